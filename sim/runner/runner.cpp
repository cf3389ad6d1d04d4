#include "sim/runner/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <utility>

#include "common/output_file.hpp"
#include "sim/backend/stylus.hpp"
#include "sim/collision/stock_cutter.hpp"
#include "sim/runner/channel_events.hpp"
#include "sim/runner/contact_sheets.hpp"
#include "sim/runner/expectation_watch.hpp"
#include "sim/runner/make_backend.hpp"
#include "sim/runner/runner_state.hpp"
#include "sim/runner/timeline_player.hpp"
#include "sim/runner/trace_rows.hpp"

namespace vmt::sim {
namespace {

// The main spindle's status indication as a user interface shows it (C-axis manual 2.3 / 3.3):
// the designation, the speeds or -- in rotary axis mode -- lines (null), the overrides always.
nlohmann::ordered_json SpindleStatusJson(const control::channel::Channel& ch,
                                         const std::string& spindle_name) {
  const control::channel::SpindleStatus st = ch.spindle_status();
  const std::string axis = ch.headstock() ? ch.HeadstockAxisName() : spindle_name;
  auto speed = [&](double rpm) {
    return st.speeds_shown ? nlohmann::ordered_json(rpm) : nlohmann::ordered_json(nullptr);
  };
  return {{"axis", axis},
          {"speeds", st.speeds_shown ? "shown" : "lines"},
          {"programmed_rpm", speed(st.programmed_rpm)},
          {"actual_rpm", speed(st.actual_rpm)},
          {"max_rpm", speed(st.max_rpm)},
          {"spindle_override_percent", st.spindle_override * 100},
          {"feed_override_percent", st.feed_override * 100}};
}

}  // namespace

SceneRun::State::State(const Scene& scene_, const RunOptions& options_)
    : scene(scene_), options(options_), m(*scene_.model) {
  recorder.AddObserver([this](const nlohmann::ordered_json& e) { snapshots.NoteEvent(e); }, false);
  recorder.AddObserver([this](const nlohmann::ordered_json& e) { NoteProbeLatch(e); }, false);
  if (options.on_event) recorder.AddObserver(options.on_event);
  if (options.signal_events && options.out_dir.empty())
    machine_events.SetSignalEvents(options.signal_events);
  backend = MakeBackend(options.backend.value_or(scene.backend), m, scene.initial);
  if (scene.workpiece.present) backend->SetWorkpiece(scene.workpiece.part);
  backend->SetProbeSamplingPhase(scene.probe_sampling);
  if (scene.nc.present && scene.nc.channel.path_guard != control::GuardReaction::kOff) {
    // The machine's collision geometry with the scene's workpiece, posed where the backend
    // stands; the channels ask it before their approach moves.
    path_guard = std::make_unique<RunPathGuard>(m, scene.workpiece, *backend);
  }
  control_stage = std::make_unique<ControlStage>(scene, options.external_plc,
                                                 path_guard ? &path_guard->guard() : nullptr);
  timeline = std::make_unique<TimelinePlayer>(scene, backend->Read(), control_stage->channel(),
                                              control_stage->image());
  for (size_t d = 0; d < m.drives.size(); ++d)
    if (control_stage->MayWriteDrive(d)) timeline->LeaveEnableToChannel(d);
  if (control_stage->ReadsInputsAt(0))  // the first PLC cycle's
    control_stage->ReadInputs(fault_filter.In(backend->Read(), timeline->faults()));

  last_tick = std::llround(options.until_s.value_or(scene.duration_s) / kDriveTickS);
  trace_every = std::max<int64_t>(1, std::llround(scene.trace_period_s / kDriveTickS));
  if (!options.out_dir.empty()) recorder.Open(options.out_dir);
  recorder.Trace(TraceHeader(m, control_stage->channel() != nullptr));

  clutches.resize(m.clutches.size());
}

void SceneRun::State::Step() {
  const double t = tick * kDriveTickS;
  // An operator input of a recorded run is taken where the station took it: before the tick.
  if (next_operator_step < options.operator_steps.size()) ReplayOperatorSteps();
  const control::AmplifierTelegram& at = fault_filter.In(backend->Read(), timeline->faults());
  for (size_t k = 0; k < clutches.size(); ++k) clutches[k] = backend->Clutch(static_cast<int>(k));

  // The PLC scans at the start of its cycle, on the machine's inputs as they stand then (the
  // field bus copied them at the end of the last tick); an external PLC has scanned just before
  // this tick, on the same inputs, so both see and act alike.
  control_stage->ReadStatus(at);
  if (std::string text = control_stage->ScanPlc(tick, timeline->faults()); !text.empty())
    StopPlc(t, "watchdog", text);
  events.clear();
  timeline->Tick(t, at, clutches, mdt, events);
  // An external PLC's client is gone: vmt serve drops the connections (an embedded PLC misses
  // its scans instead, ScanPlc).
  for (InjectedFaults& f = timeline->faults(); plc_client_gone_told < f.plc_client_gone;) {
    ++plc_client_gone_told;
    if (options.external_plc && options.on_plc_client_gone) options.on_plc_client_gone();
  }
  control_stage->WriteOutputs(mdt);
  if (control_stage->channel())
    StepChannel(t, at);
  else
    timeline->WriteSetpoints(mdt, [](size_t) { return false; });
  for (const ProgramEvent& e : events)
    recorder.Event({{"t", e.t_s}, {"event", e.kind}, {"text", e.text}});
  machine_events.Watch(t, at, clutches, *backend, control_stage->image(), recorder);
  if (tick % trace_every == 0 || tick == last_tick)
    recorder.Trace(trace_rows.Row(t, m, at, mdt, clutches, control_stage->channel()));
  CheckExpectations(t, at);
  snapshots.TakeDue(t,
                    {*backend, path_guard ? path_guard->cutter() : nullptr,
                     path_guard ? path_guard->stock_cuts() : 0},
                    recorder, result.snapshot_files);

  if (tick == last_tick) {
    finished = true;
    return;
  }
  FaultFilter::Out(timeline->faults(), mdt);
  backend->Write(mdt);
  backend->Step();
  for (const StylusOverTravel& o : backend->TakeStylusOverTravels())
    recorder.Event(StylusOverTravelEvent(o));
  ++tick;
  if (control_stage->ReadsInputsAt(tick))
    control_stage->ReadInputs(fault_filter.In(backend->Read(), timeline->faults()));
}

void SceneRun::State::StepChannel(double t, const control::AmplifierTelegram& at) {
  const bool nc_cycle = control_stage->NcCycle(tick);
  control_stage->ReadControls(nc_cycle);
  if (path_guard && nc_cycle)
    path_guard->FollowSpindle(t, control_stage->channel()->ticks_per_cycle() * kDriveTickS);
  // Each drive has one writer: the timeline's steps for those no channel writes this tick.
  timeline->WriteSetpoints(mdt, [this](size_t d) { return control_stage->WritesDrive(d); });
  control_stage->Tick(nc_cycle, at, mdt);
  channel_events.Watch(t, nc_cycle, at, *control_stage->channel(), control_stage->jog_of_path(),
                       recorder);
}

// The PLC is no longer there, whoever noticed it: the event records why.
void SceneRun::State::StopPlc(double t, const std::string& reason, const std::string& nc_text) {
  control_stage->StopPlc(nc_text);
  recorder.Event({{"t", t}, {"event", "plc"}, {"state", "stopped"}, {"reason", reason}});
}

void SceneRun::State::CheckExpectations(double t, const control::AmplifierTelegram& at) {
  if (!expectations.Due(t, tick == last_tick)) return;
  expectations.Check(
      t, tick == last_tick,
      {at, clutches, control_stage->channel(), control_stage->image(), machine_events.trips()},
      recorder);
}

RunResult SceneRun::State::Finish(const std::string& stop_reason) {
  // A run stopped early (vmt serve, a study's case, a signal) ends with the tick it is at, as a
  // run to that time does (its last tick's trace row, no step beyond): so vmt view, running to
  // the time in summary.json, runs the same ticks and gives the same digest.
  const bool stopped_early = !finished;
  if (stopped_early)
    result.stop_reason = stop_reason.empty() ? "stopped before its end" : stop_reason;
  if (!finished) {
    last_tick = tick;
    Step();
  }
  snapshots.RenderPending(recorder, result.snapshot_files);
  if (options.snapshots && recorder.writing()) {
    try {
      result.contact_sheets = WriteContactSheets(scene, options.out_dir, result.snapshot_files);
    } catch (const common::WriteError& e) {
      recorder.AddWriteError(e.what());
    }
  }
  result.simulated_s = last_tick * kDriveTickS;
  result.final_joint_positions = backend->JointPositions();
  result.trace_digest = recorder.DigestHex();
  result.expectations = expectations.Close();
  for (std::string& f : expectations.NotHeld()) result.failures.push_back(std::move(f));
  for (const std::string& f : timeline->failures()) result.failures.push_back(f);
  for (std::string& f : expectations.Unexpected(
           machine_events.trips(),
           control_stage->channel() ? control_stage->channel()->error() : std::string()))
    result.failures.push_back(std::move(f));
  result.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  // The files are complete now, whether or not the run object lives on.
  recorder.Close();
  WriteOperatorSteps();

  if (recorder.writing()) {
    nlohmann::ordered_json summary;
    summary["scene"] = scene.name;
    // vmt view replays the run from here: the scene, the backend and the operator's inputs.
    summary["scene_file"] = std::filesystem::absolute(scene.file).lexically_normal().string();
    summary["backend"] = ToString(options.backend.value_or(scene.backend));
    summary["simulated_time_s"] = result.simulated_s;
    if (stopped_early) {
      summary["stopped_early"] = true;
      summary["stop_reason"] = result.stop_reason;
    }
    summary["wall_time_s"] = result.wall_s;
    summary["real_time_factor"] = result.wall_s > 0 ? result.simulated_s / result.wall_s : 0.0;
    summary["trace_digest"] = result.trace_digest;
    summary["expectations_passed"] =
        result.expectations.size() - std::count_if(result.expectations.begin(),
                                                   result.expectations.end(),
                                                   [](const auto& c) { return !c.passed; });
    summary["expectations_failed"] =
        std::count_if(result.expectations.begin(), result.expectations.end(),
                      [](const auto& c) { return !c.passed; });
    auto& list = summary["expectations"] = nlohmann::ordered_json::array();
    for (const ExpectationResult& c : result.expectations)
      list.push_back({{"text", c.text}, {"passed", c.passed}, {"detail", c.detail}});
    summary["failures"] = result.failures;
    summary["snapshots"] = result.snapshot_files;
    if (!result.contact_sheets.empty()) summary["contact_sheets"] = result.contact_sheets;
    // The NC's message list over the run (NC errors, PLC messages MSG_WR): the operator's log.
    summary["messages"] = channel_events.messages_seen();
    if (control_stage->channel() && scene.nc.data.spindle_drive >= 0)
      summary["spindle_status"] = SpindleStatusJson(
          *control_stage->channel(), m.drives[scene.nc.data.spindle_drive].info.name);
    // Last: a summary.json says the run's files are complete (events.jsonl, written as the run
    // goes, may lack its end without it). A file that failed is named in it.
    if (!recorder.write_errors().empty()) summary["write_errors"] = recorder.write_errors();
    WriteOutput(
        options.out_dir + "/summary.json",
        summary.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + '\n');
  }
  result.write_errors = recorder.write_errors();
  return result;
}

SceneRun::SceneRun(const Scene& scene, const RunOptions& options)
    : state_(std::make_unique<State>(scene, options)) {}
SceneRun::~SceneRun() = default;
bool SceneRun::done() const { return state_->finished; }
bool SceneRun::State::WriteOutput(const std::string& path, std::string_view text) {
  try {
    common::WriteFileAtomically(path, text);
    return true;
  } catch (const common::WriteError& e) {
    recorder.AddWriteError(e.what());
    return false;
  }
}

void SceneRun::Step() { state_->Step(); }
RunResult SceneRun::Finish(const std::string& stop_reason) { return state_->Finish(stop_reason); }
control::gateway::SignalImage* SceneRun::image() { return state_->control_stage->image(); }
const control::measure::MeasuringPages* SceneRun::measuring_pages() const {
  const ControlStage& stage = *state_->control_stage;
  return stage.channel() ? &stage.measuring_pages() : nullptr;
}
int64_t SceneRun::ticks_per_plc_cycle() const { return state_->control_stage->plc_every(); }
control::plc::AxdWrStatus SceneRun::AxdWrite(int axis, int ident, int64_t value) {
  ProbeGlue* glue = state_->control_stage->probe_glue();
  return glue ? glue->Write(axis, ident, value) : control::plc::AxdWrStatus::kNoAxis;
}
double SceneRun::time_s() const { return state_->tick * kDriveTickS; }
void SceneRun::PlcLost(const std::string& reason) { state_->StopPlc(time_s(), reason, reason); }
void SceneRun::PlcRunning() {
  state_->recorder.Event({{"t", time_s()}, {"event", "plc"}, {"state", "running"}});
}
void SceneRun::RecordEvent(const nlohmann::ordered_json& fields) {
  nlohmann::ordered_json event = {{"t", time_s()}};
  for (const auto& [key, value] : fields.items()) event[key] = value;
  state_->recorder.Event(std::move(event));
}
// A latch event comes in the tick after the backend step whose contact the drive latched, so
// the machine stands where that step left it: the sphere is in the part by the pre-travel and
// at most one tick's travel, and the part's surface point nearest it is where it touched.
void SceneRun::State::NoteProbeLatch(const nlohmann::ordered_json& event) {
  if (event.value("event", "") != "probe_latch") return;
  probe_latch_point.reset();
  const int part_link = scene.workpiece.present ? m.LinkIndex(scene.workpiece.part.link) : -1;
  if (part_link < 0) return;
  const bool pin5 = event.value("input", "") == "PIN5";
  const auto stylus = std::find_if(m.probes.begin(), m.probes.end(),
                                   [pin5](const ProbeStylus& s) { return s.pin5 == pin5; });
  if (stylus == m.probes.end() || stylus->spheres.empty()) return;
  const std::vector<Eigen::Isometry3d> X_W = LinkPoses(m, backend->JointPositions());
  const std::vector<Eigen::Vector3d> centres =
      SphereCentres(*stylus, X_W[part_link].inverse() * X_W[stylus->link]);
  double deepest = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < centres.size(); ++i) {
    const RevolvedDistance d = SignedDistance(scene.workpiece.part, centres[i]);
    const double depth = stylus->spheres[i].radius_m - d.distance_m;
    if (depth > deepest) deepest = depth, probe_latch_point = X_W[part_link] * d.point_m;
  }
}

std::optional<Eigen::Vector3d> SceneRun::ToolTip() const {
  const StockCutter* cutter = state_->path_guard ? state_->path_guard->cutter() : nullptr;
  if (!cutter) return std::nullopt;
  return cutter->CuttingPoint(state_->backend->JointPositions());
}
std::optional<Eigen::Vector3d> SceneRun::ProbeLatchPoint() const {
  return state_->probe_latch_point;
}

RunResult RunScene(const Scene& scene, const RunOptions& options,
                   const std::function<std::string()>& stop) {
  SceneRun run(scene, options);
  if (!stop) {
    while (!run.done()) run.Step();
    return run.Finish();
  }
  std::string reason;
  while (!run.done() && (reason = stop()).empty()) run.Step();
  return run.Finish(reason);
}

}  // namespace vmt::sim
