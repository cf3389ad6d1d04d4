#pragma once
// Watching one case of a study: the folder records the scene and the interruption plan it was
// run with (study.json, sim/study/study_source.hpp), so any case can be run again from its id
// alone. Its run is saved on demand in the folder's cases/<id>/ as vmt run writes a run (trace,
// events, summary) with case.json, the steps the case ran, from which vmt view runs it again step
// for step.

#include <optional>
#include <stdexcept>
#include <string>

#include "sim/study/case_runner.hpp"

namespace vmt::sim::study {

/// `cases/<FileNameOf(case id)>`.
std::string CaseFolderOf(const std::string& case_id);

/// An id the study does not have.
struct UnknownCase : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The folder of case `case_id`'s saved run in the study folder `dir`, run and saved on the first
/// call. Throws UnknownCase, std::runtime_error for a folder that is not a study's (or made
/// before study.json existed), ModelError when the scene no longer loads.
std::string SaveCase(const std::string& dir, const std::string& case_id);

/// A saved case's run, to run again: its scene (the steps it ran), its end and its digest.
struct CaseReplay {
  Scene scene;
  double until_s = 0;
  std::string trace_digest;
};

/// nullopt when `run_dir` holds no case.json (a vmt run folder). Throws std::runtime_error for
/// a damaged case.json.
std::optional<CaseReplay> ReadCaseReplay(const std::string& run_dir);

}  // namespace vmt::sim::study
