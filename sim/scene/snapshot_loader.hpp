#pragma once
// The scene's `snapshots:` (docs/scene-format.md): pictures at a time, or on an event (a
// collision, a probe latch, an NC error) for its first occurrences.

#include <vector>

#include "sim/scene/scene.hpp"

namespace vmt::sim {

class YamlNode;

/// The list under `snapshots:`; the scene's cameras must be known. Throws ModelError with the
/// YAML path of the fault.
std::vector<SnapshotSpec> ReadSnapshots(const YamlNode& list, const Scene& scene);

}  // namespace vmt::sim
