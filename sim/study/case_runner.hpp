#pragma once
// Runs a study's cases on the kinematic backend with PathGuard on every move. A case is the
// scene's program interrupted by a feed hold, the operator's retract (incremental jogs in
// manual mode), the call of repositioning or NC-block restart (PxxC.REPOS / PxxC.RESTA), AUTO
// and start: the REPOS subroutine runs; the case ends at its RTS or at an NC error.
//
// The run-up to an interruption point is the same for every case there, and the simulation is
// deterministic and single-threaded: so the program runs once per subroutine, and at each
// interruption point the process forks (POSIX fork) -- a child holds the feed and forks a
// child per retract, which appends the retract's steps to the timeline, runs them and forks a
// child per mode (REPOS or RESTA, AUTO, start). Without fork the same sharing is kept in memory:
// the run is saved at each of those points and each case goes back to it. A case run either
// way gives the same result as the case run from the start (RunCaseFromStart; a test checks it).

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/runner/runner.hpp"
#include "sim/study/case_observer.hpp"
#include "sim/study/study_cases.hpp"

namespace vmt::sim::study {

/// The scene of one subroutine: the base scene with the subroutine file appended to its
/// programs (as program 99: the main program must have no .REPOS of its own; nothing for a
/// manual order), no expectations, no snapshots, and a timeline that only starts the program.
Scene SubroutineScene(const Scene& base, const Subroutine& subroutine);
/// The same by the subroutine's file (empty: a manual order, no program appended).
Scene SubroutineScene(const Scene& base, const std::string& subroutine_file);

/// The feed hold at t (timeline step `index`).
TimelineStep HoldStep(const Scene& scene, double t_s, size_t index);
/// What a caller sees of a case's run besides its result (the study's pictures): `at_end`
/// inside the tick the case ends in, before the machine steps on; `after` once the case's run
/// is over (an NC error's number shown), with the result. Both run in the case's own process.
struct CaseWatch {
  std::function<void(const SceneRun&, const StudyCase&)> at_end;
  std::function<void(const SceneRun&, const StudyCase&, const CaseResult&)> after;
};

/// How the cases of an interruption point share the run-up to it, and a retract's cases the
/// retract. kFork: POSIX fork; a case that crashes is reported as died and the study goes on.
/// kMemory: in one process, each case going back to the shared state (SceneRun::Save). kNone:
/// every case from the program's start (slow: the check of the other two).
enum class RunUpSharing { kFork, kMemory, kNone };

/// Runs the cases of subroutine `sub` that `chosen` picks, group by group in the time order of
/// their interruption points, calling `sink` with each result as it finishes. Whatever the
/// sharing, the results are the same.
void RunSubroutineCases(const Scene& base, const StudyPlan& plan,
                        const std::vector<Interruption>& interruptions, size_t sub,
                        const std::function<bool(const StudyCase&)>& chosen, RunUpSharing sharing,
                        const std::function<void(const CaseResult&)>& sink,
                        const CaseWatch* watch = nullptr);

/// One case from the program's start, without fork.
CaseResult RunCaseFromStart(const Scene& base, const StudyPlan& plan,
                            const std::vector<Interruption>& interruptions, const StudyCase& c,
                            const CaseWatch* watch = nullptr);

/// A case's run as saved for watching it: the timeline steps it ran after the program's start
/// (as a scene writes them), the subroutine's file and the time it ended.
struct SavedCase {
  std::vector<std::string> timeline;
  std::string subroutine_file;  ///< empty: a manual order
  double until_s = 0;
  std::string trace_digest;
  CaseResult result;
};

/// One case from the program's start with the scene's own trace, its files (trace.csv,
/// events.jsonl, summary.json) written to `out_dir`. The steps it ran are the saved case's:
/// SavedCaseScene makes a scene of them that runs the same way (the same digest) with no
/// observer -- the steps the study appends while a case runs would have been appended before
/// they are due.
SavedCase SaveCaseRun(const Scene& base, const StudyPlan& plan,
                      const std::vector<Interruption>& interruptions, const StudyCase& c,
                      const std::string& out_dir);
Scene SavedCaseScene(const Scene& base, const SavedCase& saved);

}  // namespace vmt::sim::study
