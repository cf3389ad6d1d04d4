#include "sim/runner/runner.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <span>
#include <nlohmann/json.hpp>
#include <utility>

#include "control/gateway/channel_gateway.hpp"
#include "control/plc/plc_programs.hpp"
#include "control/plc/plc_runtime.hpp"
#include "render/image.hpp"
#include "sim/collision/machine_path_guard.hpp"
#include "sim/collision/spindle_sweep.hpp"
#include "sim/collision/stock_cutter.hpp"
#include "sim/model/gateway_layout.hpp"
#include "sim/runner/channel_events.hpp"
#include "sim/runner/drive_program.hpp"
#include "sim/runner/event_snapshots.hpp"
#include "sim/runner/probe_glue.hpp"
#include "sim/runner/scene_renderer.hpp"

namespace vmt::sim {
namespace {

// PLC cycles a scan may be overdue before the watchdog stops the PLC.
constexpr int64_t kPlcWatchdogCycles = 2;
/// Turned stock slices whose radii differ by less make one cylinder for PathGuard: well below
/// the cut's allowance, so a merged run never stands above a tool in its cut.
constexpr double kStockTolerance = 2e-6;

// Fixed formatting: the trace bytes, and so the digest, depend only on the simulation.
void Append(std::string& row, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, ",%.6f", v == 0 ? 0.0 : v);  // no "-0.000000"
  row += buf;
}

class Fnv1a64 {
 public:
  void Add(const std::string& s) {
    for (unsigned char c : s) hash_ = (hash_ ^ c) * 0x100000001b3ull;
  }
  std::string Hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash_));
    return buf;
  }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

std::string TraceHeader(const MachineModel& m, bool nc) {
  std::string h = "t";
  for (const DriveParams& d : m.drives) {
    const std::string& n = d.info.name;
    h += "," + n + ".cmd," + n + ".pos," + n + ".vel";
    if (d.spindle || d.info.kind == control::AxisKind::kRotary) h += "," + n + ".rpm";
    if (d.parameter_sets.size() > 1) h += "," + n + ".set";  // S-0-0254, current set
  }
  for (const DogClutch& k : m.clutches) h += "," + k.name + ".state";
  if (nc) h += ",nc.state,nc.line";
  return h + "\n";
}

double Measured(const Expectation& e, const control::AmplifierTelegram& at,
                const std::vector<ClutchState>& clutches,
                const control::gateway::SignalImage* image) {
  using Q = Expectation::Quantity;
  switch (e.quantity) {
    case Q::kSignal:
      return image ? SignalNumber(*image, e.index) : std::nan("");
    case Q::kPosition:
      return at.feedback[e.index].position;
    case Q::kVelocity:
      return at.feedback[e.index].velocity;
    case Q::kRpm:
      return at.feedback[e.index].velocity / 6.0;
    case Q::kFollowingError:
      return at.feedback[e.index].following_error;
    case Q::kParameterSet:
      return at.feedback[e.index].parameter_set;
    case Q::kInput:
      return at.inputs[e.index];
    case Q::kClutch:
      return static_cast<double>(clutches[e.index]);
    case Q::kNc:
      return 0;  // a state, compared in Check
  }
  return 0;
}

ExpectationResult Check(const Expectation& e, const control::AmplifierTelegram& at,
                        const std::vector<ClutchState>& clutches,
                        const control::channel::Channel* channel,
                        const control::gateway::SignalImage* image) {
  ExpectationResult r{e.text, false, ""};
  const double got = Measured(e, at, clutches, image);
  if (e.quantity == Expectation::Quantity::kNc) {
    r.passed = channel && channel->state() == e.nc;
    r.detail = std::string("got ") + (channel ? ToString(channel->state()) : "no channel");
    if (channel && !channel->error().empty()) r.detail += ": " + channel->error();
  } else if (e.quantity == Expectation::Quantity::kClutch) {
    r.passed = clutches[e.index] == e.clutch;
    r.detail = std::string("got ") + ToString(clutches[e.index]);
  } else {
    r.passed = std::abs(got - e.value) <= e.tolerance;
    char buf[64];
    std::snprintf(buf, sizeof buf, "got %.6f", got);
    r.detail = buf;
  }
  return r;
}

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

// Everything a run holds between ticks.
struct SceneRun::State {
  State(const Scene& scene, const RunOptions& options);
  void Step();
  RunResult Finish();
  void ReadFieldBus();
  const control::AmplifierTelegram& Faulted(const control::AmplifierTelegram& raw);
  void ApplyOutputFaults();
  void ScanPlc(double t);
  void StopPlc(double t, const std::string& reason, const std::string& nc_text);

  void emit_trace(const std::string& row) {
    digest.Add(row);
    if (writing) trace_file << row;
  }
  void emit_event(nlohmann::ordered_json event) {
    // Times on the tick grid, without binary noise (3.4995, not 3.4995000000000003).
    event["t"] = std::round(event["t"].get<double>() * 1e6) / 1e6;
    if (writing) events_file << event.dump() << '\n';
    NoteSnapshotEvent(event);
    if (options.on_event) options.on_event(event);
  }
  void NoteSnapshotEvent(const nlohmann::ordered_json& event);
  void TakeSnapshot(const SnapshotSpec& s, const std::string& file, nlohmann::ordered_json event);
  /// A picture as taken: the joint positions of its tick, what to render, where it goes.
  struct PendingSnapshot {
    std::vector<double> joints;
    const SnapshotSpec* spec;
    std::string path;
  };
  void RenderSnapshot(const PendingSnapshot& shot);
  void RenderPendingSnapshots();
  /// RunOptions::snapshots_after_run: the pictures taken, rendered at Finish.
  std::vector<PendingSnapshot> pending_snapshots;

  const Scene& scene;
  const RunOptions options;
  const MachineModel& m;
  const std::chrono::steady_clock::time_point wall_start = std::chrono::steady_clock::now();
  std::unique_ptr<MachineBackend> backend;
  std::unique_ptr<MachinePathGuard> path_guard;  ///< before the channel, which asks it
  /// The workpiece as turned and the chuck as it sweeps while the spindle turns, for
  /// PathGuard; its added parts are rebuilt before a check after either changed.
  std::unique_ptr<StockCutter> cutter;
  SpindleSweep sweep;
  bool spindle_turning = false;
  double spindle_angle = 0;
  bool guard_parts_stale = false;
  void FollowSpindle(double t);
  /// The machine data pages of fast measurement: the channel's MTD(...) and the probe block's
  /// MTD_RD read and write the same ones.
  control::measure::MeasuringPages measuring_pages;
  std::unique_ptr<control::channel::Channel> channel;
  std::unique_ptr<control::gateway::SignalImage> image;
  std::unique_ptr<control::gateway::ChannelGateway> gateway;
  std::unique_ptr<control::plc::PlcRuntime> plc;
  bool field_bus = false;  ///< the machine's I/O goes through the image (a PLC is there)
  int64_t plc_every = 16;  ///< drive ticks per PLC cycle
  std::vector<std::pair<int, int>> plc_inputs, plc_outputs;  // I/O point, signal id
  std::unique_ptr<ProbeGlue> probe_glue;  ///< the SERCOS side of the PLC's probe block
  std::unique_ptr<DriveProgram> program;
  std::vector<double> last_signals;
  std::vector<int64_t> last_cells;  ///< the image's cells when last_signals was taken
  control::channel::ChannelState nc_state = control::channel::ChannelState::kIdle;
  int64_t tick = 0, last_tick = 0, trace_every = 1;
  bool writing = false, finished = false;
  std::ofstream trace_file, events_file;
  Fnv1a64 digest;
  RunResult result;
  std::unique_ptr<SceneRenderer> renderer;
  std::vector<bool> snapped, checked;
  std::vector<int> event_shots;  ///< per snapshot: occurrences of its event so far
  /// Event snapshots due at this tick's pictures: snapshot index and occurrence (1, 2, ...).
  std::vector<std::pair<size_t, int>> pending_shots;
  std::vector<ExpectationResult> checks;
  std::vector<ClutchState> clutches, last_clutches;
  std::vector<int> last_clashes;  ///< clashes of each clutch reported so far
  std::vector<uint8_t> last_inputs;
  std::vector<uint32_t> last_faults;  ///< per drive: its fault bits at the last tick
  std::vector<uint8_t> last_sets;     ///< per drive: its current parameter set at the last tick
  std::vector<uint8_t> last_latches;  ///< per drive: its probe latched flags at the last tick
  control::MasterTelegram mdt;
  std::vector<ProgramEvent> events;
  control::AmplifierTelegram faulted_at;  ///< the machine as the control sees it, faults applied
  int64_t plc_overdue = 0;                ///< scans in a row the PLC has missed
  /// Without a PLC the runner acknowledges the headstock changeover at once, as a PLC does
  /// when no mechanical changeover is needed (C-axis manual 4.2), reports spindle mode at
  /// power-on and enables the drives (AxxC.READY); a timeline that writes ROTMOD_Q / SPMOD_Q
  /// itself turns this off.
  bool default_headstock_plc = false;
  void AcknowledgeHeadstock();
  void StartHeadstockPlc();
  control::axes::HeadstockMode headstock_mode = control::axes::HeadstockMode::kNone;
  control::axes::HeadstockMode headstock_target = control::axes::HeadstockMode::kNone;
  std::string repos_key;         ///< the REPOS screen last emitted (ReposEventKey)
  control::channel::BlockSearchState block_search_state =
      control::channel::BlockSearchState::kInactive;
  size_t block_search_warnings = 0;  ///< warnings of the block search already emitted
  int plc_client_gone_told = 0;  ///< client_gone steps passed to the callback
};

SceneRun::State::State(const Scene& scene_, const RunOptions& options_)
    : scene(scene_), options(options_), m(*scene_.model) {
  backend = MakeBackend(options.backend.value_or(scene.backend), m, scene.initial);
  if (scene.workpiece.present) backend->SetWorkpiece(scene.workpiece.part);
  // The NC channel, if the scene has one: its axes move at the drives' rapid and acceleration.
  if (scene.nc.present) {
    control::channel::ChannelConfig config;
    config.axes = scene.nc.data.axes;
    config.process = scene.nc.data.process;
    config.spindle_drive = scene.nc.data.spindle_drive;
    config.spindle = scene.nc.data.spindle;
    if (config.spindle_drive >= 0) {
      // The spindle's limits bound G64's interpolation of it (its spindle set 0).
      const DriveParams& d = m.drives[config.spindle_drive];
      config.spindle.name = d.info.name;
      config.spindle.rapid_per_s = d.parameter_sets.at(0).velocity_limit * kDegPerRad;
      config.spindle.acceleration = d.parameter_sets.at(0).acceleration_limit * kDegPerRad;
    }
    config.zero_offsets = scene.nc.data.zero_offsets;
    config.tools = scene.nc.data.tools;
    config.initial = scene.nc.initial;
    config.aux_handshake = scene.nc.aux_handshake;
    config.tick_s = kDriveTickS;
    if (scene.nc.data.rotary_axis >= 0 && scene.nc.data.spindle_drive >= 0) {
      control::axes::HeadstockConfig h;
      h.spindle_drive = scene.nc.data.spindle_drive;
      h.rotary_drive = scene.nc.data.axes[scene.nc.data.rotary_axis].drive;
      h.rotary_parameter_set = static_cast<uint8_t>(scene.nc.data.rotary_parameter_set);
      config.headstock = h;
      config.rotary_axis = scene.nc.data.rotary_axis;
    }
    std::vector<const control::nc::Program*> programs;
    for (const auto& parsed : scene.nc.programs) programs.push_back(&parsed->program);
    config.path_guard = scene.nc.data.path_guard;
    config.tool_storage_drive = scene.nc.data.tool_storage_drive;
    config.tool_storage = scene.nc.data.tool_storage;
    config.tool_storage_stations = scene.nc.data.tool_storage_stations;
    config.tool_storage_nc = scene.nc.tool_storage_nc;
    channel = std::make_unique<control::channel::Channel>(config, programs);
    channel->SetFeedOverride(scene.nc.override);
    measuring_pages = scene.nc.measuring_pages;
    channel->SetMeasuringPages(&measuring_pages);
    if (config.path_guard != control::GuardReaction::kOff) {
      // The machine's collision geometry with the scene's workpiece, posed where the backend
      // stands; the channel asks it before its approach moves.
      std::vector<CylinderPart> parts;
      if (scene.workpiece.present) {
        cutter = std::make_unique<StockCutter>(m, scene.workpiece.part);
        parts = cutter->stock().Cylinders(kStockTolerance);
      }
      MachineBackend* b = backend.get();
      path_guard =
          std::make_unique<MachinePathGuard>(m, parts, [b] { return b->JointPositions(); });
      sweep = SweepOf(path_guard->world(),
                      scene.workpiece.present ? scene.workpiece.part.link : std::string("spindle"));
      path_guard->before_check = [this](CollisionWorld& world) {
        if (!guard_parts_stale) return;
        std::vector<CylinderPart> added;
        if (cutter) added = cutter->stock().Cylinders(kStockTolerance);
        if (spindle_turning) added.insert(added.end(), sweep.swept.begin(), sweep.swept.end());
        world.SetAdded(added);
        for (const int part : sweep.parts) world.SetAside(part, spindle_turning);
        guard_parts_stale = false;
      };
      channel->SetPathGuard(path_guard.get());
    }
  }
  // The gateway: the channel reads its control signals and writes its status each NC cycle.
  if (channel && scene.nc.signals) {
    image = std::make_unique<control::gateway::SignalImage>(*scene.nc.signals);
    std::vector<int> numbers;
    for (const auto& a : scene.nc.data.axes) numbers.push_back(a.number);
    int spindle_number = -1;
    const int sd = scene.nc.data.spindle_drive;
    for (const auto& a : GatewayLayoutOf(m).axes)
      if (a.spindle_capable && sd >= 0 &&
          (a.name == m.drives[sd].info.name || scene.nc.data.spindle_number == a.number))
        spindle_number = a.number;
    const int ra = scene.nc.data.rotary_axis;
    gateway = std::make_unique<control::gateway::ChannelGateway>(
        *image, scene.nc.data.process.number, numbers, spindle_number, sd,
        ra >= 0 ? numbers[ra] : -1);
    control::gateway::ChannelGateway* gw = gateway.get();
    channel->SetEventSource([gw](int n) { return gw->Event(n); });
    channel->SetEventSink([gw](int n, bool v) { gw->SetEvent(n, v); });
  }
  // The embedded PLC: scanned at its period against the gateway; the machine's sensors reach
  // it through the image (as over a field bus) and its valves go out to the machine.
  // An external PLC (vmt serve) takes the embedded program's place.
  plc_every = std::llround(scene.plc.period_s / kDriveTickS);
  if (image && scene.plc.present && !options.external_plc) {
    auto made = control::plc::MakePlcProgram(scene.plc.program, *image, &measuring_pages);
    if (!made) throw std::runtime_error("no PLC program '" + scene.plc.program + "'");
    plc = std::make_unique<control::plc::PlcRuntime>(*image, std::move(*made),
                                                     control::plc::PlcTime(plc_every * 250));
    for (const auto& [id, value] : scene.plc.constants) SetSignalNumber(*image, id, value);
  }
  if (image)
    for (const NcSetup::SignalPreset& p : scene.nc.presets) {
      if (image->table()[p.id].type == control::gateway::SignalType::kString)
        image->SetString(p.id, p.text);
      else
        SetSignalNumber(*image, p.id, p.number);
    }
  if (image) {
    probe_glue = std::make_unique<ProbeGlue>(m, *image);
    ProbeGlue* glue = probe_glue.get();
    if (plc)
      plc->SetAxdWriter([glue](int axis, int ident, int64_t value) {
        return glue->Write(axis, ident, value);
      });
  }
  field_bus = image && (plc || options.external_plc);
  if (field_bus) {
    for (size_t i = 0; i < m.io.size(); ++i) {
      const int id = image->Find(m.io[i].name);
      if (id < 0 || m.io[i].key) continue;  // keys are the operator's, not the machine's
      (m.io[i].is_output ? plc_outputs : plc_inputs).emplace_back(static_cast<int>(i), id);
    }
  }
  if (image && !field_bus && channel && channel->headstock()) {
    default_headstock_plc = true;
    for (const TimelineStep& step : scene.timeline) {
      if (step.kind != TimelineStep::Kind::kSignal) continue;
      const std::string& name = image->table()[step.signal].name;
      if (name.ends_with(".ROTMOD_Q") || name.ends_with(".SPMOD_Q")) default_headstock_plc = false;
    }
    if (default_headstock_plc && channel->headstock()->config().separate_servo())
      StartHeadstockPlc();
  }
  program = std::make_unique<DriveProgram>(scene, backend->Read(), channel.get(), image.get());
  if (field_bus) ReadFieldBus();

  last_tick = std::llround(options.until_s.value_or(scene.duration_s) / kDriveTickS);
  trace_every = std::max<int64_t>(1, std::llround(scene.trace_period_s / kDriveTickS));
  writing = !options.out_dir.empty();

  if (writing) {
    std::filesystem::create_directories(options.out_dir);
    trace_file.open(options.out_dir + "/trace.csv", std::ios::binary);
    events_file.open(options.out_dir + "/events.jsonl", std::ios::binary);
    if (!trace_file || !events_file)
      throw std::runtime_error("cannot write to output folder " + options.out_dir);
  }
  emit_trace(TraceHeader(m, channel != nullptr));

  snapped.assign(scene.snapshots.size(), false);
  event_shots.assign(scene.snapshots.size(), 0);
  checked.assign(scene.expectations.size(), false);
  checks.resize(scene.expectations.size());
  clutches.resize(m.clutches.size());
}

void SceneRun::State::Step() {
  const double t = tick * kDriveTickS;
  const control::AmplifierTelegram& at = Faulted(backend->Read());
  for (size_t k = 0; k < clutches.size(); ++k) clutches[k] = backend->Clutch(static_cast<int>(k));

  // The PLC scans at the start of its cycle, on the machine's inputs as they stand then (the
  // field bus copied them at the end of the last tick); an external PLC has scanned just before
  // this tick, on the same inputs, so both see and act alike.
  if (probe_glue) probe_glue->ReadStatus(at);
  if (plc && tick % plc_every == 0) ScanPlc(t);
  events.clear();
  program->Tick(t, at, clutches, mdt, events);
  // An external PLC's client is gone: vmt serve drops the connections (an embedded PLC misses
  // its scans instead, ScanPlc).
  for (InjectedFaults& f = program->faults(); plc_client_gone_told < f.plc_client_gone;) {
    ++plc_client_gone_told;
    if (options.external_plc && options.on_plc_client_gone) options.on_plc_client_gone();
  }
  if (field_bus)
    for (const auto& [io, id] : plc_outputs) mdt.outputs[io] = image->Bool(id) ? 1 : 0;
  if (channel) {
    const bool nc_cycle = tick % channel->ticks_per_cycle() == 0;
    if (gateway && nc_cycle && default_headstock_plc) AcknowledgeHeadstock();
    if (gateway && nc_cycle) gateway->ReadControls(*channel);
    if (path_guard && nc_cycle) FollowSpindle(t);
    channel->Tick(at, mdt);
    if (probe_glue) probe_glue->WriteSetpoints(mdt);
    if (gateway && nc_cycle) gateway->WriteStatus(*channel, at);
    if (const auto* hs = channel->headstock(); hs && hs->target() != headstock_target) {
      // The operator's display: the axis designation of the mode (S1 <-> C, 2.3 position
      // indication) once the changeover is complete.
      headstock_target = hs->target();
      emit_event({{"t", t},
                  {"event", "headstock"},
                  {"mode", ToString(hs->mode())},
                  {"target", ToString(hs->target())}});
    }
    if (const auto* hs = channel->headstock(); hs && hs->mode() != headstock_mode) {
      headstock_mode = hs->mode();
      // The status indication switches with it: speeds in spindle mode, lines in rotary mode.
      emit_event({{"t", t},
                  {"event", "headstock"},
                  {"mode", ToString(headstock_mode)},
                  {"axis", channel->HeadstockAxisName()},
                  {"speeds", channel->spindle_status().speeds_shown ? "shown" : "lines"}});
    }
    for (const control::channel::GuardRecord& r : channel->TakeGuardRecords())
      emit_event(GuardEvent(t, r, m));
    if (nc_cycle) {
      // The REPOS screen (repositioning manual 2.2) when its function, status or an adjust
      // symbol changes.
      const control::channel::ReposStatus rs = channel->repos_status(&at);
      std::string key = ReposEventKey(rs);
      if (key != repos_key) {
        if (!repos_key.empty() || rs.allowed) emit_event(ReposEvent(t, rs));
        repos_key = std::move(key);
      }
    }
    if (nc_cycle) {
      // Block search: its state as the PLC sees it change, and each warning once.
      const control::channel::BlockSearchStatus& bs = channel->block_search();
      if (bs.state != block_search_state) {
        block_search_state = bs.state;
        emit_event(BlockSearchEvent(t, *channel));
      }
      if (bs.warnings.size() < block_search_warnings) block_search_warnings = 0;  // a new run
      for (; block_search_warnings < bs.warnings.size(); ++block_search_warnings)
        emit_event(BlockSearchEvent(t, *channel, bs.warnings[block_search_warnings]));
    }
    if (channel->state() != nc_state) {
      nc_state = channel->state();
      nlohmann::ordered_json e = {{"t", t}, {"event", "nc"}, {"state", ToString(nc_state)}};
      if (!channel->error().empty()) e["error"] = channel->error();
      emit_event(e);
    }
  }
  for (const ProgramEvent& e : events)
    emit_event({{"t", e.t_s}, {"event", e.kind}, {"text", e.text}});
  if (image) {
    // Every change of a gateway signal, either direction, as the PLC engineer traces it.
    // Only the cells that changed are read through their type: a study case runs this every
    // tick over thousands of signals, of which a handful change.
    const std::span<const int64_t> cells = image->cells();
    const bool first = last_cells.empty();
    last_signals.resize(image->size(), std::nan(""));
    last_cells.resize(cells.size());
    for (int id = 0; id < image->size(); ++id) {
      if (!first && cells[id] == last_cells[id]) continue;
      last_cells[id] = cells[id];
      const double v = SignalNumber(*image, id);
      if (v != last_signals[id] && !(std::isnan(v) && std::isnan(last_signals[id]))) {
        if (!std::isnan(last_signals[id]) || v != 0)
          emit_event(
              {{"t", t}, {"event", "signal"}, {"name", image->table()[id].name}, {"value", v}});
        last_signals[id] = v;
      }
    }
  }
  for (size_t k = 0; k < clutches.size(); ++k)
    if (last_clutches.empty() || clutches[k] != last_clutches[k])
      emit_event({{"t", t},
                  {"event", "clutch"},
                  {"name", m.clutches[k].name},
                  {"state", ToString(clutches[k])}});
  // A clash: the dogs pushed in while the halves turn against each other too fast (the clutch
  // refuses and ratchets), with that relative speed, deg/s on the load side.
  last_clashes.resize(clutches.size(), 0);
  for (size_t k = 0; k < clutches.size(); ++k) {
    const DogClutchLogic& logic = backend->ClutchLogic(static_cast<int>(k));
    if (logic.clashes == last_clashes[k]) continue;
    last_clashes[k] = logic.clashes;
    emit_event({{"t", t},
                {"event", "clutch"},
                {"name", m.clutches[k].name},
                {"state", "clash"},
                {"relative_speed", std::round(logic.clash_slip_rad_s * kDegPerRad * 1e3) / 1e3},
                {"max_relative_speed",
                 std::round(m.clutches[k].max_relative_speed_rad_s * kDegPerRad * 1e3) / 1e3}});
  }
  for (size_t i = 0; i < at.inputs.size(); ++i)
    if (!m.io[i].is_output && !m.io[i].key &&
        (last_inputs.empty() || at.inputs[i] != last_inputs[i]))
      emit_event({{"t", t}, {"event", "input"}, {"name", m.io[i].name}, {"value", at.inputs[i]}});
  // A drive's trips (overload, overspeed, missing parameter set) as they come and go.
  using namespace control::drive_status;
  last_faults.resize(at.feedback.size(), 0);
  last_sets.resize(at.feedback.size(), 0);
  for (size_t d = 0; d < at.feedback.size(); ++d) {
    // The drive's current parameter set as it changes (S-0-0254).
    if (at.feedback[d].parameter_set != last_sets[d]) {
      last_sets[d] = at.feedback[d].parameter_set;
      emit_event({{"t", t},
                  {"event", "drive"},
                  {"name", m.drives[d].info.name},
                  {"parameter_set", last_sets[d]}});
    }
    const uint32_t faults = at.feedback[d].status & (kOverload | kOverspeed | kParameterSetError);
    if (faults == last_faults[d]) continue;
    nlohmann::ordered_json e = {{"t", t}, {"event", "drive"}, {"name", m.drives[d].info.name}};
    e["overload"] = (faults & kOverload) != 0;
    e["overspeed"] = (faults & kOverspeed) != 0;
    e["parameter_set_error"] = (faults & kParameterSetError) != 0;
    emit_event(e);
    last_faults[d] = faults;
  }
  // Probe latches as the drives fill them (7.3): latched value beside the exact contact.
  last_latches.resize(at.feedback.size(), 0);
  for (size_t d = 0; d < at.feedback.size(); ++d) {
    const control::ProbeStatus& p = at.feedback[d].probe;
    const control::ProbeEdgeLatch* latches[4] = {&p.probe1.positive, &p.probe1.negative,
                                                 &p.probe2.positive, &p.probe2.negative};
    uint8_t now = 0;
    for (int k = 0; k < 4; ++k)
      if (latches[k]->latched) now |= static_cast<uint8_t>(1u << k);
    for (int k = 0; k < 4; ++k)
      if ((now >> k & 1) && !(last_latches[d] >> k & 1))
        emit_event(ProbeLatchEvent(t, m.drives[d].info.name, k < 2 ? 4 : 5, k % 2 == 0,
                                   *latches[k]));
    last_latches[d] = now;
  }
  last_clutches = clutches;
  last_inputs = at.inputs;

  if (tick % trace_every == 0 || tick == last_tick) {
    std::string row;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6f", t);
    row = buf;
    for (size_t d = 0; d < m.drives.size(); ++d) {
      const control::DriveFeedback& fb = at.feedback[d];
      Append(row, mdt.setpoints[d].mode == control::DriveMode::kOff ? 0.0 : mdt.setpoints[d].value);
      Append(row, fb.position);
      Append(row, fb.velocity);
      if (m.drives[d].spindle || m.drives[d].info.kind == control::AxisKind::kRotary)
        Append(row, fb.velocity / 6.0);
      if (m.drives[d].parameter_sets.size() > 1) Append(row, fb.parameter_set);
    }
    for (ClutchState c : clutches) Append(row, static_cast<int>(c));
    if (channel) {
      Append(row, static_cast<int>(channel->state()));
      Append(row, channel->line());
    }
    emit_trace(row + "\n");
  }

  for (size_t i = 0; i < scene.expectations.size(); ++i) {
    const Expectation& e = scene.expectations[i];
    const bool due = e.at_s < 0 ? tick == last_tick : t >= e.at_s - 1e-9;
    if (checked[i] || !due) continue;
    checked[i] = true;
    checks[i] = Check(e, at, clutches, channel.get(), image.get());
    emit_event({{"t", t},
                {"event", "expectation"},
                {"text", e.text},
                {"passed", checks[i].passed},
                {"detail", checks[i].detail}});
  }

  for (size_t i = 0; i < scene.snapshots.size(); ++i) {
    const SnapshotSpec& s = scene.snapshots[i];
    if (s.on != SnapshotEvent::kNone || snapped[i] || t < s.at_s - 1e-9) continue;
    snapped[i] = true;
    TakeSnapshot(s, s.file, {{"t", t}, {"event", "snapshot"}, {"camera", s.camera}});
  }
  // Events recorded since the last pictures (this tick's, and a stylus' over-travel found in
  // the last physics step), in the order they came.
  for (const auto& [i, n] : std::exchange(pending_shots, {})) {
    const SnapshotSpec& s = scene.snapshots[i];
    TakeSnapshot(s, EventSnapshotFile(s, n, t),
                 {{"t", t}, {"event", "snapshot"}, {"on", ToString(s.on)}, {"n", n},
                  {"camera", s.camera}});
  }

  if (tick == last_tick) {
    finished = true;
    return;
  }
  ApplyOutputFaults();
  backend->Write(mdt);
  backend->Step();
  for (const StylusOverTravel& o : backend->TakeStylusOverTravels())
    emit_event(StylusOverTravelEvent(o));
  ++tick;
  if (field_bus && tick % plc_every == 0) ReadFieldBus();
}

// An event snapshot is due for each of the scene's `on:` snapshots of this event that has not
// reached its limit.
void SceneRun::State::NoteSnapshotEvent(const nlohmann::ordered_json& event) {
  if (!options.snapshots) return;
  const SnapshotEvent kind = SnapshotEventOf(event);
  if (kind == SnapshotEvent::kNone) return;
  for (size_t i = 0; i < scene.snapshots.size(); ++i)
    if (scene.snapshots[i].on == kind && event_shots[i] < scene.snapshots[i].limit)
      pending_shots.emplace_back(i, ++event_shots[i]);
}

// The machine as it stands at this tick, written to `file` with its `snapshot` event.
void SceneRun::State::TakeSnapshot(const SnapshotSpec& s, const std::string& file,
                                   nlohmann::ordered_json event) {
  if (!options.snapshots) return;
  PendingSnapshot shot{backend->JointPositions(), &s, options.out_dir + "/" + file};
  if (!options.snapshots_after_run)
    RenderSnapshot(shot);
  else if (writing)
    pending_snapshots.push_back(std::move(shot));
  if (!writing) return;
  result.snapshot_files.push_back(options.out_dir + "/" + file);
  event["file"] = file;
  emit_event(std::move(event));
}

void SceneRun::State::RenderSnapshot(const PendingSnapshot& shot) {
  if (!renderer) renderer = std::make_unique<SceneRenderer>(m, scene.workpiece);
  const SnapshotSpec& s = *shot.spec;
  const render::Image picture =
      renderer->Render(shot.joints, *scene.Camera(s.camera), s.width, s.height);
  if (writing) render::WritePng(shot.path, picture);
}

void SceneRun::State::RenderPendingSnapshots() {
  for (const PendingSnapshot& shot : pending_snapshots) RenderSnapshot(shot);
  pending_snapshots.clear();
}

// A headstock with a separate C servo needs its clutch switched before the PLC may acknowledge
// (C-axis manual 4.4): without a PLC of the scene's own, the manual's typical program runs as the
// machine's PLC for it. It sees every sensor, as a PLC does, and drives the clutch valves alone:
// the timeline keeps the other valves.
void SceneRun::State::StartHeadstockPlc() {
  auto made = control::plc::MakePlcProgram("c_axis_changeover", *image);
  if (!made) return;
  plc = std::make_unique<control::plc::PlcRuntime>(*image, std::move(*made),
                                                   control::plc::PlcTime(plc_every * 250));
  field_bus = true;
  default_headstock_plc = false;
  for (size_t i = 0; i < m.io.size(); ++i) {
    const std::string& name = m.io[i].name;
    const int id = image->Find(name);
    if (id < 0 || m.io[i].key) continue;
    if (!m.io[i].is_output) {
      plc_inputs.emplace_back(static_cast<int>(i), id);
      continue;
    }
    if (name != "QROTMODE" && name != "QSPMODE") continue;
    for (const TimelineStep& step : scene.timeline)
      if (step.kind == TimelineStep::Kind::kOutput && step.io == static_cast<int>(i))
        throw std::runtime_error(step.text + ": valve " + name +
                                 " is switched by the headstock changeover PLC (C-axis manual "
                                 "4.4) in a scene with an NC and no plc:");
    plc_outputs.emplace_back(static_cast<int>(i), id);
  }
}

void SceneRun::State::AcknowledgeHeadstock() {
  const control::axes::HeadstockChangeover& hs = *channel->headstock();
  for (int id = 0; id < image->size(); ++id) {
    const std::string& pattern = image->table()[id].pattern;
    if (pattern == "AxxC.READY") image->SetBool(id, true);  // every drive enabled
    if (pattern == "Axx.ROTMOD_Q") image->SetBool(id, hs.rotmod());
    if (pattern == "Axx.SPMOD_Q")
      image->SetBool(
          id, hs.spmod() || (!hs.busy() && hs.mode() == control::axes::HeadstockMode::kNone));
  }
}

// Faults between the machine and the control (timeline `fault:` steps): a stuck sensor reads
// its stuck level, a faulted drive reports itself not ready.
const control::AmplifierTelegram& SceneRun::State::Faulted(const control::AmplifierTelegram& raw) {
  InjectedFaults& f = program->faults();
  if (!f.any) return raw;
  faulted_at = raw;
  for (size_t i = 0; i < f.sensor.size(); ++i)
    if (f.sensor[i] >= 0) faulted_at.inputs[i] = static_cast<uint8_t>(f.sensor[i]);
  for (size_t d = 0; d < f.drive.size(); ++d)
    if (f.drive[d])
      faulted_at.feedback[d].status &=
          ~(control::drive_status::kReady | control::drive_status::kEnabled);
  return faulted_at;
}

// A stuck valve stays where it is whatever the PLC commands; a faulted drive's power stage is
// off, so its axis coasts.
void SceneRun::State::ApplyOutputFaults() {
  InjectedFaults& f = program->faults();
  if (!f.any) return;
  for (size_t i = 0; i < f.valve.size(); ++i)
    if (f.valve[i] >= 0) mdt.outputs[i] = static_cast<uint8_t>(f.valve[i]);
  for (size_t d = 0; d < f.drive.size(); ++d)
    if (f.drive[d]) mdt.setpoints[d] = {control::DriveMode::kOff, 0, 0};
}

// The PLC scans unless an overrun makes it miss its cycles or its link is gone; after two missed
// cycles its watchdog stops it (its outputs drop) and the NC stops with "PLC not running".
// Each NC cycle, before the channel may ask PathGuard: cut the stock where the tools stand and
// note whether the spindle turns (the chuck is then checked as it sweeps).
void SceneRun::State::FollowSpindle(double t) {
  const std::vector<double> q = backend->JointPositions();
  if (cutter && cutter->Cut(q, t)) guard_parts_stale = true;
  if (sweep.joint < 0) return;
  const double cycle_s = channel->ticks_per_cycle() * kDriveTickS;
  const bool turning = std::abs(q[sweep.joint] - spindle_angle) >= kTurningSpeedRadS * cycle_s;
  spindle_angle = q[sweep.joint];
  if (turning != spindle_turning) guard_parts_stale = true;
  spindle_turning = turning;
}

void SceneRun::State::ScanPlc(double t) {
  InjectedFaults& f = program->faults();
  if (plc->stopped()) return;
  if (f.plc_missed_scans > 0 || f.plc_client_gone > 0) {
    if (f.plc_missed_scans > 0) --f.plc_missed_scans;
    if (++plc_overdue > kPlcWatchdogCycles)
      StopPlc(
          t, "watchdog",
          "PLC watchdog: " + std::to_string(plc_overdue) + " scans missed, the PLC has stopped");
    return;
  }
  plc_overdue = 0;
  plc->Scan();
}

// The reaction of the manuals to a PLC that is no longer there, whoever notices it: its outputs
// drop, the NC stops at once with message 505, and the event records why.
void SceneRun::State::StopPlc(double t, const std::string& reason, const std::string& nc_text) {
  if (plc)
    plc->Stop();
  else if (image)
    control::plc::DropPlcOutputs(*image);
  if (channel) channel->MachineFault(nc_text, control::channel::kMsgPlcFault);
  emit_event({{"t", t}, {"event", "plc"}, {"state", "stopped"}, {"reason", reason}});
}

void SceneRun::State::ReadFieldBus() {
  const control::AmplifierTelegram& at = Faulted(backend->Read());
  for (const auto& [io, id] : plc_inputs) image->SetBool(id, at.inputs[io] != 0);
}

RunResult SceneRun::State::Finish() {
  RenderPendingSnapshots();
  // A run stopped early (vmt serve) has simulated only up to where it stopped.
  result.simulated_s = (finished ? last_tick : tick) * kDriveTickS;
  result.final_joint_positions = backend->JointPositions();
  result.trace_digest = digest.Hex();
  for (size_t i = 0; i < checks.size(); ++i) {
    if (!checked[i]) {
      checks[i] = {scene.expectations[i].text, false, "not reached: the run ended first"};
    }
    if (!checks[i].passed)
      result.failures.push_back(checks[i].text + " (" + checks[i].detail + ")");
  }
  for (const std::string& f : program->failures()) result.failures.push_back(f);
  // An NC error fails the run unless the scene expects it.
  if (channel && !channel->error().empty()) {
    bool expected = false;
    for (const Expectation& e : scene.expectations)
      expected = expected || (e.quantity == Expectation::Quantity::kNc &&
                              e.nc == control::channel::ChannelState::kError);
    if (!expected) result.failures.push_back("NC error: " + channel->error());
  }
  result.expectations = checks;
  result.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  // The files are complete now, whether or not the run object lives on.
  trace_file.flush();
  events_file.flush();

  if (writing) {
    nlohmann::ordered_json summary;
    summary["scene"] = scene.name;
    summary["backend"] = ToString(options.backend.value_or(scene.backend));
    summary["simulated_time_s"] = result.simulated_s;
    summary["wall_time_s"] = result.wall_s;
    summary["real_time_factor"] = result.wall_s > 0 ? result.simulated_s / result.wall_s : 0.0;
    summary["trace_digest"] = result.trace_digest;
    summary["expectations_passed"] =
        result.expectations.size() -
        std::count_if(checks.begin(), checks.end(), [](const auto& c) { return !c.passed; });
    summary["expectations_failed"] =
        std::count_if(checks.begin(), checks.end(), [](const auto& c) { return !c.passed; });
    auto& list = summary["expectations"] = nlohmann::ordered_json::array();
    for (const ExpectationResult& c : checks)
      list.push_back({{"text", c.text}, {"passed", c.passed}, {"detail", c.detail}});
    summary["failures"] = result.failures;
    summary["snapshots"] = result.snapshot_files;
    if (channel && scene.nc.data.spindle_drive >= 0)
      summary["spindle_status"] =
          SpindleStatusJson(*channel, m.drives[scene.nc.data.spindle_drive].info.name);
    std::ofstream(options.out_dir + "/summary.json") << summary.dump(2) << '\n';
  }
  return result;
}

SceneRun::SceneRun(const Scene& scene, const RunOptions& options)
    : state_(std::make_unique<State>(scene, options)) {}
SceneRun::~SceneRun() = default;
bool SceneRun::done() const { return state_->finished; }
void SceneRun::Step() { state_->Step(); }
RunResult SceneRun::Finish() { return state_->Finish(); }
control::gateway::SignalImage* SceneRun::image() { return state_->image.get(); }
int64_t SceneRun::ticks_per_plc_cycle() const { return state_->plc_every; }
control::plc::AxdWrStatus SceneRun::AxdWrite(int axis, int ident, int64_t value) {
  if (!state_->probe_glue) return control::plc::AxdWrStatus::kNoAxis;
  return state_->probe_glue->Write(axis, ident, value);
}
double SceneRun::time_s() const { return state_->tick * kDriveTickS; }
void SceneRun::PlcLost(const std::string& reason) { state_->StopPlc(time_s(), reason, reason); }
void SceneRun::PlcRunning() {
  state_->emit_event({{"t", time_s()}, {"event", "plc"}, {"state", "running"}});
}

RunResult RunScene(const Scene& scene, const RunOptions& options) {
  SceneRun run(scene, options);
  while (!run.done()) run.Step();
  return run.Finish();
}

}  // namespace vmt::sim
