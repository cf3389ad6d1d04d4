#pragma once
// A study folder's results: cases.jsonl (one JSON object per case) and cases.csv (the same,
// one row per case). Each case is appended with a single write() to files opened O_APPEND, so
// the workers of one study write side by side without tearing lines, and a study stopped
// half-way keeps every case it finished.

#include <functional>
#include <string>
#include <vector>

#include "sim/study/case_runner.hpp"

namespace vmt::sim::study {

std::string CsvHeader();
std::string CsvRow(const CaseResult& r);

/// What to do with a last line that has no line break (a study killed while writing it).
enum class TornLine {
  kLeftOut,  ///< the study resuming in its own folder runs that case again
  kError,    ///< merge, compare: the shard was not finished
};

/// Why a line of cases.jsonl (without its line break) is no case, or "" (r is the case).
std::string LineError(const std::string& line, CaseResult& r);

/// A case as its line of cases.jsonl.
std::string CaseJsonLine(const CaseResult& r);

/// The cases of a cases.jsonl; none if the file is not there. Every line must be a case (a JSON
/// object with a "case" id): otherwise throws std::runtime_error listing the bad lines as
/// "FILE:LINE: REASON", so that a corrupt file is never taken for a study of fewer cases.
/// Read line by line; `keep`, when given, makes of each case what is held of it (a reader of a
/// few fields of 100,000 cases holds those, not the cases).
std::vector<CaseResult> ReadCases(const std::string& jsonl_path, TornLine torn = TornLine::kLeftOut,
                                  const std::function<CaseResult(CaseResult&&)>& keep = {});

/// One result per id (the first), sorted by id.
std::vector<CaseResult> Deduplicated(std::vector<CaseResult> cases);

/// A case id as a file name: every character but A-Z a-z 0-9 - as _ (a `../` of a
/// subroutine's path would make a hidden file or leave the folder).
std::string FileNameOf(const std::string& case_id);

/// Writes dir/cases.jsonl and dir/cases.csv anew from `cases`, in their order.
void RewriteCaseFiles(const std::string& dir, const std::vector<CaseResult>& cases);

class CaseFiles {
 public:
  /// Opens (creates) dir/cases.jsonl and dir/cases.csv for appending; the CSV gets its header
  /// when empty. Throws std::runtime_error if they cannot be opened.
  explicit CaseFiles(const std::string& dir);
  ~CaseFiles();
  CaseFiles(const CaseFiles&) = delete;
  CaseFiles& operator=(const CaseFiles&) = delete;
  void Write(const CaseResult& r);

 private:
  std::string jsonl_path_, csv_path_;
  int jsonl_ = -1, csv_ = -1;
};

}  // namespace vmt::sim::study
