#pragma once
// The scene's `snapshots:` (docs/scene-format.md): pictures at a time, at even steps of time (a
// series, with a contact sheet), or on an event (a collision, a probe latch, an NC error) for
// its first occurrences; each with what a golden comparison ignores and tolerates.

#include <vector>

#include "sim/scene/scene.hpp"

namespace vmt::sim {

class YamlNode;

/// Pictures a series may have (`every:`, `from:`, `to:`): a mistyped step stays a few files.
inline constexpr int kMaxSeriesPictures = 200;

/// Reads the list under `snapshots:` into scene.snapshots and scene.snapshot_series; the
/// scene's cameras must be known. Throws ModelError with the YAML path of the fault.
void ReadSnapshots(const YamlNode& list, Scene& scene);

}  // namespace vmt::sim
