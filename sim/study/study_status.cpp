#include "sim/study/study_status.hpp"

#include <filesystem>

#include "sim/study/case_files.hpp"
#include "sim/study/case_merge.hpp"

namespace vmt::sim::study {

StudyProgress ReadStudyProgress(const std::string& dir) {
  StudyProgress p;
  p.dir = dir;
  p.source = ReadStudySource(dir);
  if (!p.source) return p;
  p.reference = std::filesystem::exists(dir + "/reference.json");
  if (!p.reference) return p;
  const StudyCases study = LoadStudyCases(dir);
  const CaseSpace space = study.space();
  // Line by line, keeping a bit per case: a study of 100,000 cases is hundreds of MB of JSON. A
  // torn last line is a case to run again, as the study's own rerun counts it.
  const std::vector<bool> held = HeldCases(space, dir + "/cases.jsonl");
  const std::vector<bool> share = ShareOf(space, study.source);
  for (size_t k = 0; k < space.size(); ++k) {
    if (!share[k]) continue;
    ++p.expected;
    if (held[k])
      ++p.done;
    else
      p.missing.push_back(space.At(k).id);
  }
  return p;
}

std::string ProgressLine(const StudyProgress& p) {
  std::string share;
  if (p.source && p.source->shards > 1)
    share =
        " (shard " + std::to_string(p.source->shard) + "/" + std::to_string(p.source->shards) + ")";
  if (!p.source) return p.dir + ": not started (no study.json)";
  if (!p.reference) return p.dir + share + ": started, its reference run has not ended";
  std::string line = p.dir + share + ": " + std::to_string(p.done) + " of " +
                     std::to_string(p.expected) + " cases";
  if (!p.missing.empty()) line += ", " + std::to_string(p.missing.size()) + " missing";
  return line;
}

}  // namespace vmt::sim::study
