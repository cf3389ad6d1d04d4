#pragma once
// Snapshots on events (scene `snapshots: - {on: ...}`): which recorded events count as a
// collision, a probe latch or an NC error, and the files their pictures go to. The runner
// renders a picture at the end of the tick in which the event was recorded.

#include <nlohmann/json.hpp>
#include <string>

#include "sim/scene/scene.hpp"

namespace vmt::sim {

/// The snapshot event an events.jsonl record is, kNone for most: a PathGuard check that found a
/// contact (`path_guard`, clear false) and a stylus beyond its over-travel are collisions, a
/// drive's `probe_latch` a probe latch, the NC entering its error state (`nc`, state error) an
/// error.
SnapshotEvent SnapshotEventOf(const nlohmann::ordered_json& event);

/// `<event>_<n>_<t>s_<camera>.png`: the event, its occurrence (1, 2, ...), the time of the
/// picture to the drive tick (4 decimals: the same scene names the same files) and the camera.
std::string EventSnapshotFile(const SnapshotSpec& spec, int occurrence, double t);

}  // namespace vmt::sim
