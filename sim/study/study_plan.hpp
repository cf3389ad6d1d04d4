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

/// One incremental jog of the retract: the channel axis and the signed distance (mm); the
/// operator sets the increment and taps the key, the increment is completed (manual mode).
struct RetractJog {
  std::string axis;
  double mm = 0;
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

/// A REPOS subroutine to compare: the file (program 99) appended to the scene's programs.
struct Subroutine {
  std::string name;  ///< as written in the plan (nc/99.mtc), the case id's first part
  std::string file;  ///< resolved against the scene's folder
};

struct StudyPlan {
  /// Interruption: every `every_ms` of the program's run (> 0), or else every motion block of
  /// the main program at these per-mille points of its time span in the reference run.
  double every_ms = 0;
  std::vector<int> per_mille;
  std::vector<RetractPattern> retracts;
  std::vector<ReposMode> modes{ReposMode::kRepositioning};
  std::vector<Subroutine> subroutines;
  double hold_s = 0.3;      ///< feed hold to manual mode: the axes have stopped by then
  double timeout_s = 30;    ///< per case, from the start in AUTO to the REPOS subroutine's RTS
};

/// The `study:` section of the scene file `scene_path`, checked against the loaded `scene`
/// (axes, an NC without an embedded PLC). Throws ModelError with file:line:col and YAML path.
StudyPlan LoadStudyPlan(const std::string& scene_path, const Scene& scene);

}  // namespace vmt::sim::study
