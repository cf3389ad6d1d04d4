#pragma once
// The operator station's JSON (docs/station.md): the model a page builds its 3D view and panel
// from once, and the frames it polls (state, signals). Built on the simulation's thread from
// the run between two steps; the HTTP threads only hand the text out.

#include <map>
#include <string>
#include <vector>

#include "sim/runner/runner.hpp"

namespace vmt::sim::station {

/// Marks the page draws from the run's events: the last PathGuard refusal (the two parts and
/// the contact point) and the probe's latches.
struct StationMarks {
  /// The latches the state lists: a measurement latches every measuring axis at one edge,
  /// and the operator compares a few measurements.
  static constexpr size_t kLatchesKept = 12;
  std::string guard;  ///< {"parts":[..],"point":[x,y,z] m} of the last refusal, or empty
  std::string probe;  ///< {"drive":..,"value":..,"t":..} of the last latch, or empty
  std::vector<std::string> latches;  ///< the last kLatchesKept latches as `probe`, oldest first
  std::map<std::string, std::string> clutches;  ///< each dog clutch's last state (clutch events)
  /// Takes what an event says about the marks (a refusal, a clear check after it, a latch).
  void Note(const nlohmann::ordered_json& event);
};

/// GET /api/model: scene, pace, links with their meshes (metres, link frame, the visual's origin
/// applied; the workpiece as a visual of its link), cameras (metres), machine keys, axes, and
/// the main program's text.
std::string ModelJson(const SceneRun& run, const std::string& pace);

/// GET /api/state: time, PLC cycle, run state, each link's world pose, where the tool in work
/// cuts (SceneRun::ToolTip), the NC's state, mode, line and modal state, axes, messages, the
/// event count and the marks (the last probe latch with where the stylus touched the part,
/// SceneRun::ProbeLatchPoint, and the latches before it); the REPOS screen
/// (repositioning manual 2.2), the headstock (C-axis manual 2.3: mode, changeover, ROTMOD/SPMOD
/// and their acknowledgements, clutches) and block search (its HLI state and figures).
std::string StateJson(const SceneRun& run, int64_t plc_cycle, const std::string& run_state,
                      size_t events, const StationMarks& marks);

/// GET /api/stock: the workpiece as turned, `cylinders` of [z0, length, radius, inner radius]
/// (metres, along the z axis of `link`), and `version` (StateJson's `stock`: a new one, a new
/// shape).
std::string StockJson(const SceneRun& run);

/// GET /api/signals: every gateway signal with its value and whether the page may write it.
std::string SignalsJson(SceneRun& run);

}  // namespace vmt::sim::station
