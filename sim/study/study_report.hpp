#pragma once
// report.html of a study: plain HTML with inline SVG. First the conclusions per
// mode (study_conclusions.hpp), then how to read the report (classes, severity, clearance, the
// frame), per REPOS subroutine and mode a summary (cases by class, the worst clearance, the
// deepest contact), per subroutine the XZ plane (study_plane.hpp) and the worst cases by
// severity with their pictures; last all the cases, a page at a time (a small script loads
// cases-pages/N.js beside the report). Built in one pass over the cases keeping bounded state
// (counts, names, the most severe few): a study of any size makes a report of bounded size.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "sim/study/case_runner.hpp"
#include "sim/study/reference_run.hpp"

namespace vmt::sim::study {

/// Cases per page of the report's table of all cases.
constexpr size_t kCasesPerPage = 500;
/// The cases a subroutine's XZ plane draws at most (its most severe).
constexpr size_t kPlaneCases = 500;

/// The report over cases given one at a time in id order.
class ReportBuilder {
 public:
  /// `reference` (may be null) and `snapshots` must outlive the builder.
  ReportBuilder(const Reference* reference, const std::map<std::string, std::string>& snapshots);
  ~ReportBuilder();
  ReportBuilder(const ReportBuilder&) = delete;
  ReportBuilder& operator=(const ReportBuilder&) = delete;
  void Add(const CaseResult& r);
  /// The page; `pages` > 0 adds the table of all cases (cases-pages/1.js .. N.js).
  std::string Html(const std::string& title, size_t pages) const;

 private:
  struct State;
  const Reference* reference_;
  const std::map<std::string, std::string>& snapshots_;
  size_t cases_ = 0;
  std::unique_ptr<State> state_;
};

/// `cases` sorted by id; without the table of all cases. `reference` may be null (no contour
/// drawn). `snapshots`: case id -> picture file relative to the report (the worst cases' pictures).
std::string ReportHtml(const std::string& title, const std::vector<CaseResult>& cases,
                       const Reference* reference,
                       const std::map<std::string, std::string>& snapshots = {});

/// Writes dir/report.html and its pages dir/cases-pages/N.js from dir/cases.jsonl (in case id
/// order, as a study and a merge leave it; a repeated id counts once), dir/reference.json and
/// dir/snapshots.json (if there), streaming.
void WriteReport(const std::string& dir, const std::string& title);

}  // namespace vmt::sim::study
