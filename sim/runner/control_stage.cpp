#include "sim/runner/control_stage.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "control/channel/jog_of_path.hpp"
#include "control/plc/plc_programs.hpp"
#include "sim/model/gateway_layout.hpp"

namespace vmt::sim {
namespace {

// PLC cycles a scan may be overdue before the watchdog stops the PLC.
constexpr int64_t kPlcWatchdogCycles = 2;

}  // namespace

ControlStage::ControlStage(const Scene& scene, bool external_plc, control::PathGuard* guard)
    : m_(*scene.model) {
  if (scene.nc.present) MakeChannels(scene, guard);
  if (channel_ && scene.nc.signals) MakeGateway(scene);
  MakePlc(scene, external_plc);
  channel_drive_.assign(m_.drives.size(), 0);
  for (const control::channel::Channel* c : {channel_.get(), jog_of_path_.get()})
    for (size_t d = 0; c && d < channel_drive_.size(); ++d)
      if (c->MayWriteDrive(d)) channel_drive_[d] = 1;
}

// The NC channel (and the JogOfPath channel): its axes move at the drives' rapid and
// acceleration; with PathGuard they ask it before their approach moves.
void ControlStage::MakeChannels(const Scene& scene, control::PathGuard* guard) {
  const control::channel::ChannelConfig& config = scene.nc.channel;
  std::vector<const control::nc::Program*> programs;
  for (const auto& parsed : scene.nc.programs) programs.push_back(&parsed->program);
  channel_ = std::make_unique<control::channel::Channel>(config, programs);
  channel_->SetFeedOverride(scene.nc.override);
  if (scene.nc.jog_of_path) {
    jog_of_path_ = std::make_unique<control::channel::Channel>(
        control::channel::JogOfPathConfig(config),
        std::vector<const control::nc::Program*>{&scene.nc.jog_of_path->program});
    jog_of_path_->SetFeedOverride(scene.nc.override);
  }
  measuring_pages_ = scene.nc.measuring_pages;
  channel_->SetMeasuringPages(&measuring_pages_);
  if (guard) {
    channel_->SetPathGuard(guard);
    if (jog_of_path_) jog_of_path_->SetPathGuard(guard);
  }
}

// The gateway: the channel reads its control signals and writes its status each NC cycle.
void ControlStage::MakeGateway(const Scene& scene) {
  image_ = std::make_unique<control::gateway::SignalImage>(*scene.nc.signals);
  std::vector<int> numbers;
  for (const auto& a : scene.nc.data.axes) numbers.push_back(a.number);
  int spindle_number = -1;
  const int sd = scene.nc.data.spindle_drive;
  for (const auto& a : GatewayLayoutOf(m_).axes)
    if (a.spindle_capable && sd >= 0 &&
        (a.name == m_.drives[sd].info.name || scene.nc.data.spindle_number == a.number))
      spindle_number = a.number;
  const int ra = scene.nc.data.rotary_axis;
  gateway_ = std::make_unique<control::gateway::ChannelGateway>(
      *image_, scene.nc.data.process.number, numbers, spindle_number, sd,
      ra >= 0 ? numbers[ra] : -1);
  control::gateway::ChannelGateway* gw = gateway_.get();
  channel_->SetEventSource([gw](int n) { return gw->Event(n); });
  channel_->SetEventSink([gw](int n, bool v) { gw->SetEvent(n, v); });
}

// The embedded PLC: scanned at its period against the gateway; the machine's sensors reach it
// through the image (as over a field bus) and its valves go out to the machine. An external PLC
// (vmt serve) takes the embedded program's place.
void ControlStage::MakePlc(const Scene& scene, bool external_plc) {
  plc_every_ = std::llround(scene.plc.period_s / kDriveTickS);
  if (gateway_) {
    const int64_t nc = channel_->ticks_per_cycle();
    gateway_->SetPlcScan(static_cast<int>((plc_every_ + nc - 1) / nc));
  }
  if (image_ && scene.plc.present && !external_plc) {
    auto made = control::plc::MakePlcProgram(scene.plc.program, *image_, &measuring_pages_);
    if (!made) throw std::runtime_error("no PLC program '" + scene.plc.program + "'");
    plc_ = std::make_unique<control::plc::PlcRuntime>(*image_, std::move(*made),
                                                      control::plc::PlcTime(plc_every_ * 250));
    for (const auto& [id, value] : scene.plc.constants) image_->SetNumber(id, value);
  }
  if (!image_) return;
  for (const NcSetup::SignalPreset& p : scene.nc.presets) {
    if (image_->table()[p.id].type == control::gateway::SignalType::kString)
      image_->SetString(p.id, p.text);
    else
      image_->SetNumber(p.id, p.number);
  }
  probe_glue_ = std::make_unique<ProbeGlue>(m_, *image_);
  ProbeGlue* glue = probe_glue_.get();
  if (plc_)
    plc_->SetAxdWriter(
        [glue](int axis, int ident, int64_t value) { return glue->Write(axis, ident, value); });
  if (plc_ || external_plc) field_bus_.ConnectAll(m_, *image_);
  if (field_bus_.connected() || !channel_->headstock()) return;
  default_headstock_plc_ = true;
  for (const TimelineStep& step : scene.timeline) {
    if (step.kind != TimelineStep::Kind::kSignal) continue;
    const std::string& name = image_->table()[step.signal].name;
    if (name.ends_with(".ROTMOD_Q") || name.ends_with(".SPMOD_Q")) default_headstock_plc_ = false;
  }
  if (default_headstock_plc_ && channel_->headstock()->config().separate_servo())
    StartHeadstockPlc(scene);
}

// A headstock with a separate C servo needs its clutch switched before the PLC may acknowledge
// (C-axis manual 4.4): without a PLC of the scene's own, the manual's typical program runs as the
// machine's PLC for it. It sees every sensor, as a PLC does, and drives the clutch valves alone:
// the timeline keeps the other valves.
void ControlStage::StartHeadstockPlc(const Scene& scene) {
  auto made = control::plc::MakePlcProgram("c_axis_changeover", *image_);
  if (!made) return;
  plc_ = std::make_unique<control::plc::PlcRuntime>(*image_, std::move(*made),
                                                    control::plc::PlcTime(plc_every_ * 250));
  field_bus_.Connect();
  default_headstock_plc_ = false;
  for (size_t i = 0; i < m_.io.size(); ++i) {
    const std::string& name = m_.io[i].name;
    const int id = image_->Find(name);
    if (id < 0 || m_.io[i].key) continue;
    if (!m_.io[i].is_output) {
      field_bus_.AddInput(static_cast<int>(i), id);
      continue;
    }
    if (name != "QROTMODE" && name != "QSPMODE") continue;
    for (const TimelineStep& step : scene.timeline)
      if (step.kind == TimelineStep::Kind::kOutput && step.io == static_cast<int>(i))
        throw std::runtime_error(step.text + ": valve " + name +
                                 " is switched by the headstock changeover PLC (C-axis manual "
                                 "4.4) in a scene with an NC and no plc:");
    field_bus_.AddOutput(static_cast<int>(i), id);
  }
}

void ControlStage::AcknowledgeHeadstock() {
  const control::axes::HeadstockChangeover& hs = *channel_->headstock();
  for (int id = 0; id < image_->size(); ++id) {
    const std::string& pattern = image_->table()[id].pattern;
    if (pattern == "AxxC.READY") image_->SetBool(id, true);  // every drive enabled
    if (pattern == "Axx.ROTMOD_Q") image_->SetBool(id, hs.rotmod());
    if (pattern == "Axx.SPMOD_Q")
      image_->SetBool(
          id, hs.spmod() || (!hs.busy() && hs.mode() == control::axes::HeadstockMode::kNone));
  }
}

void ControlStage::ReadStatus(const control::AmplifierTelegram& at) {
  if (probe_glue_) probe_glue_->ReadStatus(at);
}

// The PLC scans unless an overrun makes it miss its cycles or its link is gone; after two missed
// cycles its watchdog stops it (its outputs drop) and the NC stops with "PLC not running".
std::string ControlStage::ScanPlc(int64_t tick, InjectedFaults& f) {
  if (!plc_ || tick % plc_every_ != 0 || plc_->stopped()) return "";
  if (f.plc_missed_scans > 0 || f.plc_client_gone > 0) {
    if (f.plc_missed_scans > 0) --f.plc_missed_scans;
    if (++plc_overdue_ <= kPlcWatchdogCycles) return "";
    std::string text =
        "PLC watchdog: " + std::to_string(plc_overdue_) + " scans missed, the PLC has stopped";
    StopPlc(text);
    return text;
  }
  plc_overdue_ = 0;
  plc_->Scan();
  return "";
}

// The reaction of the manuals to a PLC that is no longer there, whoever notices it: its outputs
// drop and the NC stops at once with message 505.
void ControlStage::StopPlc(const std::string& nc_text) {
  if (plc_)
    plc_->Stop();
  else if (image_)
    control::plc::DropPlcOutputs(*image_);
  if (channel_) channel_->MachineFault(nc_text, control::channel::kMsgPlcFault);
}

void ControlStage::WriteOutputs(control::MasterTelegram& mdt) {
  if (field_bus_.connected()) field_bus_.WriteOutputs(*image_, mdt);
}

void ControlStage::ReadControls(bool nc_cycle) {
  if (!nc_cycle) return;
  if (gateway_ && default_headstock_plc_) AcknowledgeHeadstock();
  if (gateway_) gateway_->ReadControls(*channel_);
  if (jog_of_path_ && gateway_) gateway_->ReadJogOfPath(*jog_of_path_);
  if (jog_of_path_) control::channel::HandOverAxes(*channel_, *jog_of_path_);
}

void ControlStage::Tick(bool nc_cycle, const control::AmplifierTelegram& at,
                        control::MasterTelegram& mdt) {
  // The channel holding the axes writes their setpoints last; the other holds them where the
  // holder commanded them, which also covers the cycle in which both have let them go.
  const bool jog_of_path_holds = jog_of_path_ && !jog_of_path_->output_suspended();
  if (jog_of_path_ && !jog_of_path_holds) jog_of_path_->Tick(at, mdt);
  channel_->Tick(at, mdt);
  if (jog_of_path_holds) jog_of_path_->Tick(at, mdt);
  if (probe_glue_) probe_glue_->WriteSetpoints(mdt);
  if (gateway_ && nc_cycle) gateway_->WriteStatus(*channel_, at);
  if (jog_of_path_ && gateway_ && nc_cycle) gateway_->WriteJogOfPath(*jog_of_path_);
}

ControlStage::Saved ControlStage::Save() const {
  Saved saved{measuring_pages_, {}, {}, {}, {}, {}, {}, plc_overdue_, default_headstock_plc_};
  if (channel_) saved.channel = channel_->data();
  if (jog_of_path_) saved.jog_of_path = jog_of_path_->data();
  if (image_) saved.image = *image_;
  if (gateway_) saved.gateway = *gateway_;
  if (plc_) saved.plc = plc_->Save();
  if (probe_glue_) saved.probe_glue = *probe_glue_;
  return saved;
}

// The stage's objects stay where they are (the channel points at the pages and PathGuard, the
// gateway and the PLC at the image): their values are put back.
void ControlStage::Restore(const Saved& saved) {
  measuring_pages_ = saved.measuring_pages;
  if (channel_) channel_->Restore(*saved.channel);
  if (jog_of_path_) jog_of_path_->Restore(*saved.jog_of_path);
  if (image_) *image_ = *saved.image;
  if (gateway_) *gateway_ = *saved.gateway;
  if (plc_) plc_->Restore(*saved.plc);
  if (probe_glue_) *probe_glue_ = *saved.probe_glue;
  plc_overdue_ = saved.plc_overdue;
  default_headstock_plc_ = saved.default_headstock_plc;
}

}  // namespace vmt::sim
