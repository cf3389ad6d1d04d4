#pragma once
// report.html of a study: plain HTML with inline SVG, no scripts. Per REPOS subroutine a
// summary (cases, clear, collisions, errors, the worst clearance), the XZ plane with the
// program's tool path (the contour as turned, from the reference run) and every case's approach
// path coloured by its verdict, and the worst cases.

#include <map>
#include <string>
#include <vector>

#include "sim/study/case_runner.hpp"
#include "sim/study/reference_run.hpp"

namespace vmt::sim::study {

/// `cases` sorted by id. `reference` may be null (no contour drawn).
/// `snapshots`: case id -> picture file relative to the report (the worst cases' pictures).
std::string ReportHtml(const std::string& title, const std::vector<CaseResult>& cases,
                       const Reference* reference,
                       const std::map<std::string, std::string>& snapshots = {});

/// Writes dir/report.html from dir/cases.jsonl, dir/reference.json and dir/snapshots.json (if
/// there).
void WriteReport(const std::string& dir, const std::string& title);

}  // namespace vmt::sim::study
