#pragma once
// What vmt golden found, as data, and its reports: JUnit XML and JSON for CI, and the page a
// failing picture leaves beside its actual, golden and difference pictures.

#include <string>
#include <vector>

namespace vmt::sim {

enum class GoldenStatus {
  kPassed,   ///< within tolerance of its baseline
  kFailed,   ///< differs beyond tolerance, or a size or a file that cannot be read
  kMissing,  ///< no baseline (check without --create-missing)
  kCreated,  ///< no baseline, written from the run (update, or check --create-missing)
  kUpdated,  ///< baseline overwritten (update)
  kStale,    ///< a baseline no snapshot of the run wrote (check)
  kRemoved,  ///< such a baseline, removed (update)
};
const char* ToString(GoldenStatus s);
bool IsFailure(GoldenStatus s);

/// One picture of a scene against its baseline.
struct GoldenPicture {
  std::string file;  ///< as the scene names it, e.g. iso_3.2s.png
  double t = 0;      ///< simulated time the picture shows, s
  GoldenStatus status = GoldenStatus::kPassed;
  std::string detail;  ///< render::DescribeComparison's line, or what went wrong
  int tolerance_levels = 0;
  double allowed_fraction = 0;
  bool compared = false;  ///< the numbers below are set
  int differing_pixels = 0, compared_pixels = 0, masked_pixels = 0, max_channel_delta = 0;
  double differing_fraction = 0;
  std::string golden, actual;  ///< paths
  std::string page;            ///< failure page (index.html), empty when none was written
};

/// One scene: its run, then its pictures.
struct GoldenScene {
  std::string name;     ///< the scene file's name without .yaml; its baselines' folder
  std::string out_dir;  ///< where its run's output is
  bool ran = false;     ///< run by this command (not an earlier run's folder)
  std::vector<std::string> run_failures;  ///< expectations, or why no picture could be compared
  std::vector<GoldenPicture> pictures;
  bool ok() const;
};

/// JUnit XML: a testsuite per scene, a testcase per picture (a failure carries the figures),
/// and a testcase "run" for a scene this command ran or could not compare.
void WriteJUnit(const std::string& path, const std::vector<GoldenScene>& scenes);
/// The same as JSON: {"passed": bool, "scenes": [{"scene", "out_dir", "run_failures",
/// "pictures": [{"file", "t", "status", ...}]}]}.
void WriteJson(const std::string& path, const std::vector<GoldenScene>& scenes);

/// index.html in `dir` (which holds golden.png, actual.png and diff.png if there is one): the
/// three side by side, what differs, and how to watch the run at the picture's time in the
/// operator station (vmt view RUN_DIR, then the page at ?t=T).
void WriteFailurePage(const std::string& dir, const GoldenPicture& picture,
                      const std::string& run_dir);

/// The replay command of a run folder, as the failure page and the console give it.
std::string ReplayCommand(const std::string& run_dir);

}  // namespace vmt::sim
