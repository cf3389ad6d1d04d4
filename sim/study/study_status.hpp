#pragma once
// `vmt study status`: how far a study folder is. The cases its share should hold (study.json
// and the reference run give them) against the whole lines of its cases.jsonl, so that a
// shard that died is rerun alone and only for what it lacks; nothing is run to find out.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "sim/study/study_source.hpp"

namespace vmt::sim::study {

struct StudyProgress {
  std::string dir;
  std::optional<StudySource> source;  ///< nullopt: the study never started in `dir`
  bool reference = false;             ///< its reference run has ended: the cases are known
  size_t expected = 0;                ///< the cases of the folder's share
  size_t done = 0;
  std::vector<std::string> missing;  ///< case ids, in the plan's order

  bool complete() const { return source && reference && missing.empty(); }
};

/// Throws std::runtime_error for a damaged study.json or cases.jsonl, ModelError when the
/// scene no longer loads.
StudyProgress ReadStudyProgress(const std::string& dir);

/// One line: "DIR: 30 of 40 cases, 10 missing" (or why none are known yet).
std::string ProgressLine(const StudyProgress& p);

}  // namespace vmt::sim::study
