#pragma once
// The cases of one or more cases.jsonl files merged into a study folder's cases.jsonl and
// cases.csv in case id order, one case per id, streaming: a study of any size is merged with
// the memory of a few cases per input, not of all its cases. A study's own files (written by its
// workers side by side, so out of order) and the shards of `vmt study merge` go the same way.

#include <functional>
#include <string>
#include <vector>

#include "sim/study/case_files.hpp"

namespace vmt::sim::study {

/// Cases an unsorted input is cut into, each run sorted in memory and kept in a scratch file.
constexpr size_t kMergeRunCases = 20000;

/// Writes dir/cases.jsonl and dir/cases.csv anew from `inputs` (missing files count as empty;
/// one of them may be dir/cases.jsonl itself): in case id order, one case per id, the first
/// (of the earliest input, its earliest line): the bytes RewriteCaseFiles(dir,
/// Deduplicated(all cases read)) writes. Every case written is given to `each` in that order.
/// Returns how many were written. A corrupt input throws as ReadCases does and leaves dir's
/// files as they were.
size_t MergeCaseFiles(const std::vector<std::string>& inputs, const std::string& dir, TornLine torn,
                      const std::function<void(const CaseResult&)>& each = {});

/// Each case of a study folder's cases.jsonl in file order (whole lines only), without
/// holding them. Throws as ReadCases does for a line that is no case.
void ForEachCase(const std::string& jsonl_path, const std::function<void(const CaseResult&)>& each);

}  // namespace vmt::sim::study
