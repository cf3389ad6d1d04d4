#pragma once
// Runs a scene: machine backend + drive-level program on the one clock (drive tick 250 us,
// lockstep, no wall clock in the loop), records the trace (CSV), the events (JSON lines), the
// snapshots and a summary with the trace digest.

#include <optional>
#include <string>
#include <vector>

#include "sim/scene/scene.hpp"

namespace vmt::sim {

struct RunOptions {
  std::optional<BackendKind> backend;  ///< overrides the scene's
  std::optional<double> until_s;       ///< overrides the scene's duration
  std::string out_dir;                 ///< empty: write nothing (tests, benchmarks)
  bool snapshots = true;               ///< render the scene's snapshots
};

struct ExpectationResult {
  std::string text;
  bool passed = false;
  std::string detail;  ///< "got 249.9876"
};

struct RunResult {
  double simulated_s = 0;
  double wall_s = 0;
  std::string trace_digest;  ///< FNV-1a 64 of trace.csv's bytes, hex
  std::vector<ExpectationResult> expectations;
  std::vector<std::string> failures;  ///< failed expectations and timed-out waits
  std::vector<std::string> snapshot_files;
  std::vector<double> final_joint_positions;  ///< m | rad, at the end of the run
  bool ok() const { return failures.empty(); }
};

/// Throws std::runtime_error when an output file cannot be written.
RunResult RunScene(const Scene& scene, const RunOptions& options);

}  // namespace vmt::sim
