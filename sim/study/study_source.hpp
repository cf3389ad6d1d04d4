#pragma once
// A study folder's record of what it was run from (study.json): the scene file, the
// interruption plan after the command line's overrides, and the share of the cases the folder
// holds (shard K of N, the first N cases). With the folder's reference run it finds every case
// again by id, and tells which of the folder's cases are still missing, without running anything.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "sim/study/study_cases.hpp"

namespace vmt::sim::study {

struct StudySource {
  std::string scene_file;  ///< absolute
  double every_ms = 0;     ///< the plan's interruptions, after --every-ms / --per-mille
  std::vector<int> per_mille;
  int shard = 1, shards = 1;        ///< the folder holds shard `shard` of `shards`
  std::optional<size_t> max_cases;  ///< ... and of that only the first N cases
};

/// The source of a study of `scene_file` with `plan` (its overrides applied), the whole study.
StudySource SourceOf(const std::string& scene_file, const StudyPlan& plan);

void WriteStudySource(const std::string& dir, const StudySource& source);

/// nullopt where `dir` has no study.json; throws std::runtime_error for a damaged one.
std::optional<StudySource> ReadStudySource(const std::string& dir);

/// Which cases of `space` a folder with this source holds, a bit per case index: its shard,
/// then of that its first N.
std::vector<bool> ShareOf(const CaseSpace& space, const StudySource& source);

/// Which cases of `space` the cases.jsonl at `jsonl_path` holds (whole lines; none where the
/// file is missing), a bit per case index, read line by line.
std::vector<bool> HeldCases(const CaseSpace& space, const std::string& jsonl_path);

/// A study folder's cases as its source and reference run give them.
struct StudyCases {
  StudySource source;
  Scene scene;
  StudyPlan plan;
  std::vector<Interruption> interruptions;
  /// Every case of the study, whatever the folder's share (valid while this lives unmoved).
  CaseSpace space() const { return CaseSpace(plan, interruptions); }
};

/// Throws std::runtime_error (`dir` has no study.json or no reference.json, or a damaged one),
/// ModelError (the scene no longer loads).
StudyCases LoadStudyCases(const std::string& dir);

}  // namespace vmt::sim::study
