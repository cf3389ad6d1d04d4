#pragma once
// What a scene run holds between ticks (SceneRun::State): private to sim/runner/. runner.cpp
// takes the tick through its stages and ends the run; runner_operator.cpp takes the operator
// station's inputs.

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/runner/channel_event_watch.hpp"
#include "sim/runner/control_stage.hpp"
#include "sim/runner/expectation_watch.hpp"
#include "sim/runner/fault_filter.hpp"
#include "sim/runner/machine_events.hpp"
#include "sim/runner/run_path_guard.hpp"
#include "sim/runner/run_recorder.hpp"
#include "sim/runner/run_snapshots.hpp"
#include "sim/runner/runner.hpp"
#include "sim/runner/timeline_player.hpp"
#include "sim/runner/trace_rows.hpp"

namespace vmt::sim {

// The values of a run's changing state at one tick (saved_run.cpp). The objects they belong
// to stay where they are in the run, pointing at each other, and take these values back.
struct SavedRun {
  std::unique_ptr<MachineBackend> backend;
  std::optional<RunPathGuard::Saved> path_guard;
  ControlStage::Saved control_stage;
  TimelinePlayer timeline;
  MachineEventWatch machine_events;
  ChannelEventWatch channel_events;
  int64_t tick, last_tick;
  bool finished;
  RunRecorder::Saved recorder;
  RunResult result;
  ExpectationWatch expectations;
  RunSnapshots::Saved snapshots;
  std::vector<ClutchState> clutches;
  control::MasterTelegram mdt;
  std::vector<ProgramEvent> events;
  FaultFilter fault_filter;
  int plc_client_gone_told;
  std::optional<Eigen::Vector3d> probe_latch_point;
  std::vector<OperatorStep> operated;
  size_t next_operator_step;
};

// Everything a run holds between ticks.
struct SceneRun::State {
  State(const Scene& scene, const RunOptions& options);
  void Step();
  RunResult Finish(const std::string& stop_reason);
  /// The channel's part of a tick: the control stage's inputs, PathGuard's stock, the
  /// timeline's setpoints of the drives no channel writes, the channels' tick, their events.
  void StepChannel(double t, const control::AmplifierTelegram& at);
  /// The PLC is gone: the control stage's reaction and the event of it.
  void StopPlc(double t, const std::string& reason, const std::string& nc_text);
  /// The scene's expectations due at `t`, checked and recorded.
  void CheckExpectations(double t, const control::AmplifierTelegram& at);
  /// The run's changing state as it stands (SceneRun::Save), or why it has no copy.
  std::shared_ptr<const SavedRun> Save() const;
  void Restore(const SavedRun& saved);

  const Scene& scene;
  const RunOptions options;
  const MachineModel& m;
  const std::chrono::steady_clock::time_point wall_start = std::chrono::steady_clock::now();
  std::unique_ptr<MachineBackend> backend;
  /// PathGuard with the stock as turned; before the channel, which asks it. Null: no PathGuard.
  std::unique_ptr<RunPathGuard> path_guard;
  /// SceneRun::ProbeLatchPoint, taken from each probe_latch event as it is recorded.
  std::optional<Eigen::Vector3d> probe_latch_point;
  void NoteProbeLatch(const nlohmann::ordered_json& event);
  /// The channels, gateway, PLC and field bus; after PathGuard, which the channels ask.
  std::unique_ptr<ControlStage> control_stage;
  std::unique_ptr<TimelinePlayer> timeline;
  /// The machine's changes (signals, clutches, inputs, drives, probe latches) as events.
  MachineEventWatch machine_events{m};
  /// The channel's changes (headstock, PathGuard, REPOS screen, block search, messages, state).
  ChannelEventWatch channel_events{m};
  int64_t tick = 0, last_tick = 0, trace_every = 1;
  bool finished = false;
  /// Trace, events and their observers: the event snapshots first, then RunOptions::on_event.
  RunRecorder recorder;
  /// The trace's rows; what it keeps is the last row's text, the same after any Restore.
  TraceRowWriter trace_rows;
  RunResult result;
  /// The scene's expectations, checked as they fall due.
  ExpectationWatch expectations{scene.expectations, m};
  /// The scene's pictures, taken as they fall due.
  RunSnapshots snapshots{scene, {options.snapshots, options.snapshots_after_run, options.out_dir}};
  std::vector<ClutchState> clutches;  ///< the backend's, this tick
  control::MasterTelegram mdt;
  std::vector<ProgramEvent> events;
  FaultFilter fault_filter;      ///< the injected faults between machine and control
  int plc_client_gone_told = 0;  ///< client_gone steps passed to the callback

  // The operator station's inputs (runner_operator.cpp).
  std::string OperateError(const std::string& signal) const;
  std::string ValueError(const std::string& signal, double value) const;
  std::string Operate(const std::string& signal, double value);
  std::string OperateHandwheel(const std::string& axis, int counts);
  /// RunOptions::operator_steps due at this tick, taken before anything else of it.
  void ReplayOperatorSteps();
  void WriteOperatorSteps();
  /// Writes one of the run's files whole (common::OutputFile); a failure is kept in the
  /// recorder's write errors and the run goes on. Returns whether it was written.
  bool WriteOutput(const std::string& path, std::string_view text);
  std::vector<OperatorStep> operated;
  size_t next_operator_step = 0;
};

}  // namespace vmt::sim
