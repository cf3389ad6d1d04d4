#pragma once
// report.html of a study: plain HTML with inline SVG, no scripts. First the conclusions per
// mode (study_conclusions.hpp), then how to read the report (classes, severity, clearance, the
// frame), per REPOS subroutine and mode a summary (cases by class, the worst clearance, the
// deepest contact), per subroutine the XZ plane (study_plane.hpp) and the worst cases by
// severity with their pictures.

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
