#pragma once
// Runs a scene: machine backend + drive-level program on the one clock (drive tick 250 us,
// lockstep, no wall clock in the loop), records the trace (CSV), the events (JSON lines), the
// snapshots and a summary with the trace digest.

#include <functional>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "control/drive_bus.hpp"
#include "control/gateway/signal_image.hpp"
#include "control/plc/axd_wr.hpp"
#include "sim/collision/collision_world.hpp"
#include "sim/runner/expectation_result.hpp"
#include "sim/scene/operator_steps.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::control::channel {
class Channel;
}

namespace vmt::sim {

struct RunOptions {
  std::optional<BackendKind> backend;  ///< overrides the scene's
  std::optional<double> until_s;       ///< overrides the scene's duration
  std::string out_dir;                 ///< empty: write nothing (tests, benchmarks)
  bool snapshots = true;               ///< render the scene's snapshots
  /// Render them when the run is over, from the joint positions of their tick (vmt serve
  /// --realtime: a picture takes tens of ms, several PLC cycles of the wall clock). The files,
  /// the events and the pictures are the same.
  bool snapshots_after_run = false;
  /// The PLC is outside (vmt serve): no embedded program runs; the machine's I/O still goes
  /// through the signal image, which the external PLC reads and writes.
  bool external_plc = false;
  /// With external_plc: a `fault: {plc: client_gone}` step has run (vmt serve then drops its
  /// Modbus clients, after the Poll that is running the cycle). Called from Step.
  std::function<void()> on_plc_client_gone;
  /// Every event as events.jsonl records it (also when nothing is written), in order, from
  /// the tick that makes it: a study reads its cases' path_guard and repos events here.
  std::function<void(const nlohmann::ordered_json&)> on_event;
  /// When set and the run writes no events.jsonl: the gateway signals (by name) whose changes
  /// make events; the others make none. A study's case reads one or two signals, while the
  /// path's distance signals alone change every NC cycle of a motion.
  std::function<bool(const std::string& signal)> signal_events;
  /// The operator inputs of an earlier run (operator.yaml, vmt run --operator), taken at their
  /// ticks as SceneRun::Operate took them: the run repeats that one to the same trace digest.
  std::vector<OperatorStep> operator_steps;
};

struct RunResult {
  double simulated_s = 0;
  double wall_s = 0;
  std::string trace_digest;  ///< FNV-1a 64 of trace.csv's bytes, hex
  std::vector<ExpectationResult> expectations;
  std::vector<std::string> failures;  ///< failed expectations and timed-out waits
  std::vector<std::string> snapshot_files;
  std::vector<std::string> contact_sheets;    ///< one per snapshot series that took pictures
  std::vector<double> final_joint_positions;  ///< m | rad, at the end of the run
  /// "cannot write FILE: REASON" for each output that could not be written (a full disk): the
  /// file is missing (events.jsonl: its whole lines kept), the others are complete.
  std::vector<std::string> write_errors;
  /// Why the run stopped before its end (Finish's reason), empty when it ran to its end.
  std::string stop_reason;
  bool ok() const { return failures.empty(); }
};

/// A run one drive tick at a time, for whoever paces it (vmt serve: an external PLC's cycles).
/// Throws common::WriteError when the output folder cannot be made.
/// A run's changing state at one tick, kept in memory (SceneRun::Save).
struct SavedRun;

class SceneRun {
 public:
  SceneRun(const Scene& scene, const RunOptions& options);
  ~SceneRun();
  bool done() const;
  /// One drive tick; after the scene's last tick done() is true.
  void Step();
  /// Checks what is left, completes the files and writes summary.json last; call once, when
  /// done or stopping early. Stopped early, the tick the run is at is its last (summary.json's
  /// simulated_time_s) and summary.json says `"stopped_early": true` and `stop_reason` (given
  /// here, e.g. "SIGTERM"). A file that cannot be written does not throw: the run's other files
  /// are still written, and RunResult::write_errors names it.
  RunResult Finish(const std::string& stop_reason = {});
  /// The run as it stands, kept in memory to go back to with Restore, as often as wanted: the
  /// machine, PathGuard and the stock as turned, the channels, the signal image, the PLC's
  /// program instances, the timeline's place, the watches and the digest so far. A run on the
  /// physics backend (Bullet's world does not copy), one that writes its files as it goes
  /// (`out_dir`) and one whose PLC is an external client have none: std::runtime_error says
  /// which.
  std::shared_ptr<const SavedRun> Save() const;
  /// Back to the tick `saved` was taken at, a Save of this run (Finish too is undone): the
  /// steps from there are the ones the run took the first time, bit for bit. The scene is the
  /// caller's: timeline steps appended since stay appended.
  void Restore(const SavedRun& saved);
  /// The gateway signals, null without an nc: section.
  control::gateway::SignalImage* image();
  const control::gateway::SignalImage* image() const;
  int64_t ticks_per_plc_cycle() const;
  /// AXD_WR for an external PLC (vmt serve's Modbus AXD_WR block): the same path as the embedded
  /// PLC's (PlcScan::axd_wr), S-0-`ident` := `value` in the drive of axis number `axis`.
  /// kNoAxis without an nc: section.
  control::plc::AxdWrStatus AxdWrite(int axis, int ident, int64_t value);
  /// The PLC is lost (vmt serve: its Modbus link timed out). As when the embedded PLC's
  /// watchdog stops it: every signal only the PLC writes falls back to its preset (its valves
  /// drop), the NC stops at once with message 505 and `reason` as its text, and the event
  /// {"event":"plc","state":"stopped","reason":...} is recorded at the current time. An
  /// embedded PLC stays stopped; an external one may come back (PlcRunning).
  void PlcLost(const std::string& reason);
  /// The external PLC answers again after PlcLost: records {"event":"plc","state":"running"}.
  /// The NC stays in its error until Control-Reset, as after any immediate stop.
  void PlcRunning();
  /// Records {"t": time_s(), ...fields} in events.jsonl (vmt serve: real time not held).
  void RecordEvent(const nlohmann::ordered_json& fields);
  double time_s() const;
  /// The NC's machine data pages of fast measurement as the run has them now (what its
  /// instructions wrote); null without an nc: section.
  const control::measure::MeasuringPages* measuring_pages() const;

  /// The operator's input, taken now, before the next Step (vmt serve --http: at the start of
  /// a PLC cycle): a machine key of the model's io or, with an external PLC, a signal the PLC
  /// writes. Recorded as the event {"event":"operator",...} and in operated(); at Finish the
  /// steps are written to operator.yaml. Returns why it is refused (nothing changes then), or "".
  std::string Operate(const std::string& signal, double value);
  /// The operator turns the handwheel of `axis` (a channel axis, or X1 / Y1 of G31) by `counts`,
  /// as the timeline's `handwheel:` does; recorded like Operate. Returns why it is refused, or "".
  std::string OperateHandwheel(const std::string& axis, int counts);
  /// Why Operate would refuse `signal` (the value aside), or "". Reads only the scene.
  std::string OperateError(const std::string& signal) const;
  /// Why Operate would refuse `signal` = `value` (its type's range, a selector's positions), or "".
  std::string OperateError(const std::string& signal, double value) const;
  const std::vector<OperatorStep>& operated() const;

  // What the run shows as it goes (the operator station reads these between steps).
  const Scene& scene() const;
  /// The NC channel, null without an nc: section.
  const control::channel::Channel* channel() const;
  /// The drives' feedback as the control saw it at the last tick.
  const control::AmplifierTelegram& feedback() const;
  /// The machine's joint positions now (m | rad, one per joint of the model).
  std::vector<double> joint_positions() const;
  int64_t tick() const;
  /// Where the run ends (s): the scene's duration or RunOptions::until_s.
  double end_s() const;
  /// The workpiece as turned so far (its solid of revolution as cylinders in its link's frame,
  /// the rings included), and how many ticks have cut it: a new count, a new shape. Empty
  /// without a workpiece that PathGuard turns.
  std::vector<CylinderPart> TurnedStockCylinders() const;
  int64_t stock_cuts() const;
  /// Where the tool in work cuts now (world, m; StockCutter::CuttingPoint): none without a
  /// workpiece that PathGuard turns, or when no cutting tool faces the spindle.
  std::optional<Eigen::Vector3d> ToolTip() const;
  /// Where a stylus touched the workpiece at the last probe latch (world, m): the part's
  /// surface point nearest the sphere pushed deepest, the stylus on the latching drive's probe
  /// input posed as the machine stood in the latch's tick. None before a latch or without one
  /// (no stylus on that input, no workpiece).
  std::optional<Eigen::Vector3d> ProbeLatchPoint() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Runs the scene to its end, or until `stop` (checked once a tick) says to stop early: then
/// Finish gets `stop()`'s text as the reason. Throws common::WriteError when the output folder
/// cannot be made; a file that fails later is in RunResult::write_errors.
RunResult RunScene(const Scene& scene, const RunOptions& options,
                   const std::function<std::string()>& stop = {});

}  // namespace vmt::sim
