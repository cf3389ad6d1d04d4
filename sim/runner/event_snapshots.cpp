#include "sim/runner/event_snapshots.hpp"

#include <cmath>
#include <cstdio>

namespace vmt::sim {

SnapshotEvent SnapshotEventOf(const nlohmann::ordered_json& event) {
  const std::string kind = event.value("event", "");
  if (kind == "path_guard" && !event.value("clear", true)) return SnapshotEvent::kCollision;
  if (kind == "stylus" && event.value("state", "") == "over_travel")
    return SnapshotEvent::kCollision;
  if (kind == "probe_latch") return SnapshotEvent::kProbeLatch;
  if (kind == "nc" && event.value("state", "") == "error") return SnapshotEvent::kError;
  return SnapshotEvent::kNone;
}

std::string EventSnapshotFile(const SnapshotSpec& spec, int occurrence, double t) {
  char time[32];
  std::snprintf(time, sizeof time, "%.4f", std::round(t * 1e4) / 1e4 + 0.0);
  return std::string(ToString(spec.on)) + "_" + std::to_string(occurrence) + "_" + time + "s_" +
         spec.camera + ".png";
}

}  // namespace vmt::sim
