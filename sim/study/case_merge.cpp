#include "sim/study/case_merge.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <queue>
#include <stdexcept>
#include <utility>

#include "common/output_file.hpp"
#include "sim/study/scratch_folder.hpp"

namespace vmt::sim::study {
namespace {

constexpr size_t kErrorsShown = 10;  // of a corrupt cases.jsonl's bad lines

// The lines of a file, each with whether it ended with a line break (a last line without one
// was cut short by a study stopped while writing it).
class Lines {
 public:
  explicit Lines(const std::string& path) : in_(path, std::ios::binary) {}
  bool Next(std::string& line, bool& whole) {
    if (!std::getline(in_, line)) return false;
    whole = !in_.eof();
    return true;
  }

 private:
  std::ifstream in_;
};

// Checks every line of an input is a case (throws as ReadCases, listing the bad lines) and
// tells whether its ids are in order.
bool CheckInput(const std::string& path, TornLine torn) {
  Lines lines(path);
  std::string line, errors, last_id;
  bool whole = true, sorted = true;
  size_t bad = 0, n = 0;
  const auto fault = [&](const std::string& why) {
    if (++bad <= kErrorsShown) errors += "\n" + path + ":" + std::to_string(n) + ": " + why;
  };
  while (lines.Next(line, whole)) {
    if (!whole) {
      if (torn == TornLine::kError) {
        ++n;
        fault("the last line is cut short (the study was stopped while writing it; run it again)");
      }
      break;
    }
    ++n;
    CaseResult r;
    const std::string why = LineError(line, r);
    if (!why.empty()) {
      fault(why);
      continue;
    }
    std::string id = r["case"].get<std::string>();
    if (id < last_id) sorted = false;
    last_id = std::move(id);
  }
  if (bad > kErrorsShown) errors += "\n... and " + std::to_string(bad - kErrorsShown) + " more";
  if (bad > 0)
    throw std::runtime_error(path + ": " + std::to_string(bad) + " of " + std::to_string(n) +
                             " lines are no case:" + errors);
  return sorted;
}

// Cuts an input (checked) into runs of kMergeRunCases cases sorted by id (stably), each a file
// in `scratch`; appends their paths to `runs`.
void CutIntoRuns(const std::string& path, const std::string& scratch,
                 std::vector<std::string>& runs) {
  Lines lines(path);
  std::vector<std::pair<std::string, std::string>> run;  // id, line
  const auto flush = [&] {
    if (run.empty()) return;
    std::stable_sort(run.begin(), run.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    const std::string file = scratch + "/run-" + std::to_string(runs.size()) + ".jsonl";
    std::ofstream out(file, std::ios::binary);
    for (const auto& [id, line] : run) out << line << '\n';
    out.flush();
    if (!out) throw common::WriteError(file, ENOSPC);
    runs.push_back(file);
    run.clear();
  };
  std::string line;
  bool whole = true;
  while (lines.Next(line, whole) && whole) {
    CaseResult r;
    LineError(line, r);
    run.emplace_back(r["case"].get<std::string>(), std::move(line));
    if (run.size() >= kMergeRunCases) flush();
  }
  flush();
}

// One sorted run as the merge reads it: its current case.
class Run {
 public:
  explicit Run(const std::string& path) : lines_(path) { Advance(); }
  bool done() const { return done_; }
  const std::string& id() const { return id_; }
  const CaseResult& current() const { return current_; }
  void Advance() {
    std::string line;
    bool whole = true;
    if (!lines_.Next(line, whole) || !whole) {
      done_ = true;
      return;
    }
    LineError(line, current_);
    id_ = current_["case"].get<std::string>();
  }

 private:
  Lines lines_;
  CaseResult current_;
  std::string id_;
  bool done_ = false;
};

}  // namespace

size_t MergeCaseFiles(const std::vector<std::string>& inputs, const std::string& dir, TornLine torn,
                      const std::function<void(const CaseResult&)>& each) {
  std::filesystem::create_directories(dir);
  std::vector<std::string> existing;
  std::vector<bool> sorted;
  for (const std::string& in : inputs) {
    if (!std::filesystem::exists(in)) continue;
    existing.push_back(in);
    sorted.push_back(CheckInput(in, torn));
  }
  const ScratchFolder scratch(dir + "/.merge.tmp-" + std::to_string(::getpid()));
  std::vector<std::string> run_paths;
  for (size_t i = 0; i < existing.size(); ++i) {
    if (sorted[i])
      run_paths.push_back(existing[i]);
    else
      CutIntoRuns(existing[i], scratch.path(), run_paths);
  }
  std::vector<std::unique_ptr<Run>> runs;
  for (const std::string& p : run_paths) runs.push_back(std::make_unique<Run>(p));
  // The smallest id first; among equal ids the earliest run (the first case wins).
  const auto later = [&](size_t a, size_t b) {
    const int c = runs[a]->id().compare(runs[b]->id());
    return c != 0 ? c > 0 : a > b;
  };
  std::priority_queue<size_t, std::vector<size_t>, decltype(later)> next(later);
  for (size_t i = 0; i < runs.size(); ++i)
    if (!runs[i]->done()) next.push(i);
  // Written beside and renamed: a study killed now still has its old files whole.
  common::OutputFile jsonl(dir + "/cases.jsonl");
  common::OutputFile csv(dir + "/cases.csv");
  csv.Write(CsvHeader());
  size_t written = 0;
  std::string last;
  while (!next.empty()) {
    const size_t i = next.top();
    next.pop();
    Run& run = *runs[i];
    if (written == 0 || run.id() != last) {
      jsonl.Write(CaseJsonLine(run.current()));
      csv.Write(CsvRow(run.current()));
      if (each) each(run.current());
      last = run.id();
      ++written;
    }
    run.Advance();
    if (!run.done()) next.push(i);
  }
  jsonl.Commit();
  csv.Commit();
  return written;
}

void ForEachCase(const std::string& jsonl_path,
                 const std::function<void(const CaseResult&)>& each) {
  Lines lines(jsonl_path);
  std::string line;
  bool whole = true;
  for (size_t n = 1; lines.Next(line, whole) && whole; ++n) {
    CaseResult r;
    const std::string why = LineError(line, r);
    if (!why.empty()) throw std::runtime_error(jsonl_path + ":" + std::to_string(n) + ": " + why);
    each(r);
  }
}

}  // namespace vmt::sim::study
