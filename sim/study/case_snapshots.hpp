#pragma once
// Pictures of a study's worst cases (report.html links them): per subroutine the most severe
// collisions at their first contact (contact_picture.hpp: the two parts magenta, the point
// marked), and the clear case with the smallest clearance at its end. The study runs without
// pictures; the chosen cases run again afterwards, as the study ran them (one run-up per
// subroutine, forked at their interruption points) -- a case is deterministic, so the rerun is
// the case of cases.jsonl -- and each takes its picture in its own process.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sim/study/case_runner.hpp"

namespace vmt::sim::study {

/// The ids of the cases to picture, sorted: per subroutine the `collisions` most severe
/// collisions (MoreSevere: the deepest crashes first) and the clear case with the smallest
/// clearance (the first by id of equals).
std::vector<std::string> WorstCaseIds(const std::vector<CaseResult>& results, int collisions);

/// WorstCaseIds over cases given one at a time in id order, keeping only the picked ones.
class WorstCasePicker {
 public:
  explicit WorstCasePicker(int collisions) : collisions_(collisions) {}
  void Add(const CaseResult& r);
  /// As WorstCaseIds.
  std::vector<std::string> Ids() const;
  /// The picked cases.
  std::vector<CaseResult> Results() const;

 private:
  struct Picked {
    std::vector<CaseResult> worst;  ///< the most severe collisions, most severe first
    std::optional<CaseResult> tightest;
  };
  int collisions_;
  std::map<std::string, Picked> by_sub_;
};

/// `snapshots/<FileNameOf(case id)>.png`.
std::string SnapshotFileOf(const std::string& case_id);

/// Renders the cases `ids` (of the plan's) into dir/snapshots/ with the camera and size of the
/// scene's first snapshot (else its first camera, 320x240); a picture already there is kept.
/// Returns case id -> file relative to dir, and writes it as dir/snapshots.json. A case whose
/// rerun took no picture is left out. When `stop` says so, no further picture is begun (a
/// rerun takes the missing ones). `jobs` processes (forked) take the subroutines side by side.
std::map<std::string, std::string> SnapshotCases(
    const Scene& base, const StudyPlan& plan, const std::vector<Interruption>& interruptions,
    const std::vector<CaseResult>& results, const std::vector<std::string>& ids,
    const std::string& dir, const std::function<bool()>& stop = {}, int jobs = 1);

/// Writes `index` (case id -> file relative to dir) as dir/snapshots.json.
void WriteSnapshotIndex(const std::string& dir, const std::map<std::string, std::string>& index);

/// dir/snapshots.json, empty when there is none.
std::map<std::string, std::string> ReadSnapshotIndex(const std::string& dir);

}  // namespace vmt::sim::study
