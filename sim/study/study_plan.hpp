#pragma once
// The case plan of a REPOS study (scene key `study:`, docs/scene-format.md): where the program is
// interrupted, how the operator leaves the contour, which function brings the tool back
// (repositioning or NC-block restart, repositioning manual 2.3 / 4.1) and which REPOS
// subroutines (program 99 variants) are compared. Plain data; every case is one combination.

#include <optional>
#include <string>
#include <vector>

#include "sim/scene/scene.hpp"

namespace vmt::sim::study {

/// One incremental jog of the retract: the channel axis and the signed distance (mm), or the
/// drive position `to` (a tool change point: the distance is taken where the axis stands);
/// the operator sets the increment and taps the key, the increment is completed (manual mode).
struct RetractJog {
  std::string axis;
  double mm = 0;
  std::optional<double> to;
};

/// How the operator leaves the contour after the feed hold, e.g. "X+ then Z+".
struct RetractPattern {
  std::string name;
  std::vector<RetractJog> jogs;
};

/// Repositioning returns to the interruption point; NC-block restart to the start of the
/// interrupted block (repositioning manual 1, 4.1). Both run the REPOS subroutine in AUTO.
enum class ReposMode { kRepositioning, kRestart };
const char* ToString(ReposMode m);

/// A way back to the contour that the study compares: a REPOS subroutine (the file, program
/// 99, appended to the scene's programs; program-driven, 4.1) or, with `manual_order` set, the
/// operator in manual mode (3): the function called, the spindle restored by its key (3.3),
/// then each feed axis jogged toward its target in this order, where the NC stops it (3.2).
struct Subroutine {
  std::string
      name;  ///< nc/99.mtc as written in the plan, or "manual X,Z"; the case id's first part
  std::string file;  ///< resolved against the scene's folder; empty for a manual order
  std::vector<std::string> manual_order;  ///< NC axis names; empty: a REPOS subroutine
  bool manual() const { return !manual_order.empty(); }
};

/// The interruption period (`every_ms:`, --every-ms), ms: from 1 ms (a control cycle's order)
/// to 10^7 ms (2.8 h of a program's run, a single interruption for any real program).
inline constexpr double kMinEveryMs = 1;
inline constexpr double kMaxEveryMs = 1e7;
/// Per-mille points (`per_mille:`, --per-mille): 0..1000, at most one of each.
inline constexpr size_t kMaxPerMillePoints = 1001;

struct StudyPlan {
  /// Interruption: every `every_ms` of the program's run (> 0), or else every motion block of
  /// the main program at these per-mille points of its time span in the reference run.
  double every_ms = 0;
  std::vector<int> per_mille;
  std::vector<RetractPattern> retracts;
  std::vector<ReposMode> modes{ReposMode::kRepositioning};
  std::vector<Subroutine> subroutines;  ///< the plan's `subroutines:`, then its `manual:` orders
  double hold_s = 0.3;                  ///< feed hold to manual mode: the axes have stopped by then
  double timeout_s = 30;  ///< per case, from the start in AUTO to the REPOS subroutine's RTS
};

/// The `study:` section of the scene file `scene_path`, checked against the loaded `scene`
/// (axes, an NC without an embedded PLC). Throws ModelError with file:line:col and YAML path.
StudyPlan LoadStudyPlan(const std::string& scene_path, const Scene& scene);

}  // namespace vmt::sim::study
