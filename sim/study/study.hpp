#pragma once
// `vmt study repos`: a study folder from a scene's case plan -- the reference run, the cases
// (sharded, in worker processes), cases.jsonl / cases.csv as they finish, report.html at the
// end. A rerun into the same folder skips the cases it holds.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sim/study/case_runner.hpp"

namespace vmt::sim::study {

/// --shard K/N: at most this many shards (a cluster's cores, with room).
inline constexpr int kMaxShards = 100000;

struct StudyOptions {
  std::string scene;
  std::string out_dir;
  int jobs = 1;                    ///< worker processes
  int shard = 1, shards = 1;       ///< this process' share: groups g with g % shards == shard - 1
  std::optional<double> every_ms;  ///< overrides the plan's interruption
  std::optional<std::vector<int>> per_mille;
  /// How a group's cases share their run-up (RunUpSharing).
  RunUpSharing run_ups = RunUpSharing::kMemory;
  bool progress = false;            ///< a progress bar on stderr
  std::optional<size_t> max_cases;  ///< the first N cases of this shard only (benchmarks)
  /// Pictures of the worst cases, rendered after the study: per subroutine this many
  /// collisions and the tightest clear case (0: none).
  int snapshots = 3;
  /// Asked as the study goes: a reason to stop (a signal's name), empty to go on. Stopped, the
  /// study begins no further case or picture, ends its workers, keeps the finished cases (whole
  /// lines, in case order) and writes no report: a rerun resumes it.
  std::function<std::string()> stop;
};

struct StudySummary {
  size_t cases = 0;    ///< in this shard
  size_t skipped = 0;  ///< already in the folder
  size_t run = 0;
  double wall_s = 0;            ///< the whole study: reference run, cases, pictures, report
  double cases_per_minute = 0;  ///< run / wall time
  double cases_cpu_s = 0;       ///< CPU time (user + system) of the worker processes
  double snapshots_wall_s = 0;  ///< of wall_s, the worst cases' pictures
  size_t snapshots = 0;
  std::string text;     ///< per subroutine: cases, clear, crashes, grazes, errors, retracts refused
  std::string stopped;  ///< why the study stopped before its end (options.stop), else empty
  size_t finished = 0;  ///< of `cases`, those in the folder when it ended
};

/// Throws ModelError (scene or plan) or std::runtime_error.
StudySummary RunStudy(const StudyOptions& options);

/// `vmt study merge`: joins the case files of `dirs` (one result per case id) into `out_dir`,
/// with reference.json of the first that has one, and writes report.html. The number of cases.
size_t MergeStudies(const std::vector<std::string>& dirs, const std::string& out_dir);

}  // namespace vmt::sim::study
