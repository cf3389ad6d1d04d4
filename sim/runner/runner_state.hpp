#pragma once
// What a scene run holds between ticks (SceneRun::State): private to sim/runner/, whose files
// each take one part of a tick - runner.cpp the tick and the run's end, runner_channel.cpp the
// NC channel's part, runner_plc.cpp the PLC and the field bus.

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

#include "control/channel/channel.hpp"
#include "control/gateway/channel_gateway.hpp"
#include "control/plc/plc_runtime.hpp"
#include "sim/runner/channel_event_watch.hpp"
#include "sim/runner/expectation_watch.hpp"
#include "sim/runner/fault_filter.hpp"
#include "sim/runner/field_bus.hpp"
#include "sim/runner/machine_events.hpp"
#include "sim/runner/probe_glue.hpp"
#include "sim/runner/run_path_guard.hpp"
#include "sim/runner/run_recorder.hpp"
#include "sim/runner/run_snapshots.hpp"
#include "sim/runner/runner.hpp"
#include "sim/runner/timeline_player.hpp"

namespace vmt::sim {

// Everything a run holds between ticks.
struct SceneRun::State {
  State(const Scene& scene, const RunOptions& options);
  // The construction's parts, in this order: the NC channels with PathGuard, the gateway, the
  // embedded PLC with the signals it starts from and the field bus.
  void MakeChannels();
  void MakeGateway();
  void MakePlc();
  void Step();
  RunResult Finish(const std::string& stop_reason);
  void ReadFieldBus();
  void ScanPlc(double t);
  /// The channel's NC cycle work of a tick: gateway, PathGuard's stock, the channel, events.
  void StepChannel(double t, const control::AmplifierTelegram& at);
  void StopPlc(double t, const std::string& reason, const std::string& nc_text);
  /// The scene's expectations due at `t`, checked and recorded.
  void CheckExpectations(double t, const control::AmplifierTelegram& at);

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
  /// The machine data pages of fast measurement: the channel's MTD(...) and the probe block's
  /// MTD_RD read and write the same ones.
  control::measure::MeasuringPages measuring_pages;
  std::unique_ptr<control::channel::Channel> channel;
  /// The JogOfPath channel of `nc: jog_of_path:` (block search 4.2.1): on the channel's feed
  /// axes while the PLC lends them; its events are the channel's, tagged "jog_of_path".
  std::unique_ptr<control::channel::Channel> jog_of_path;
  std::unique_ptr<control::gateway::SignalImage> image;
  std::unique_ptr<control::gateway::ChannelGateway> gateway;
  std::unique_ptr<control::plc::PlcRuntime> plc;
  FieldBus field_bus;      ///< the machine's I/O through the image, where a PLC is there
  int64_t plc_every = 16;  ///< drive ticks per PLC cycle
  std::unique_ptr<ProbeGlue> probe_glue;  ///< the SERCOS side of the PLC's probe block
  std::unique_ptr<TimelinePlayer> timeline;
  /// Per drive: a channel may write it (its own, or the one it lends); the timeline writes
  /// the others every tick.
  std::vector<uint8_t> channel_drive;
  /// The machine's changes (signals, clutches, inputs, drives, probe latches) as events.
  MachineEventWatch machine_events{m};
  /// The channel's changes (headstock, PathGuard, REPOS screen, block search, messages, state).
  ChannelEventWatch channel_events{m};
  int64_t tick = 0, last_tick = 0, trace_every = 1;
  bool finished = false;
  /// Trace, events and their observers: the event snapshots first, then RunOptions::on_event.
  RunRecorder recorder;
  RunResult result;
  /// The scene's expectations, checked as they fall due.
  ExpectationWatch expectations{scene.expectations, m};
  /// The scene's pictures, taken as they fall due.
  RunSnapshots snapshots{scene, {options.snapshots, options.snapshots_after_run, options.out_dir}};
  std::vector<ClutchState> clutches;  ///< the backend's, this tick
  control::MasterTelegram mdt;
  std::vector<ProgramEvent> events;
  FaultFilter fault_filter;               ///< the injected faults between machine and control
  int64_t plc_overdue = 0;                ///< scans in a row the PLC has missed
  /// Without a PLC the runner acknowledges the headstock changeover at once, as a PLC does
  /// when no mechanical changeover is needed (C-axis manual 4.2), reports spindle mode at
  /// power-on and enables the drives (AxxC.READY); a timeline that writes ROTMOD_Q / SPMOD_Q
  /// itself turns this off.
  bool default_headstock_plc = false;
  void AcknowledgeHeadstock();
  void StartHeadstockPlc();
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
