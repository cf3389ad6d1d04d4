// The PLC's part of a scene run: its scans and watchdog, the field bus between the machine's
// I/O and the signal image, the headstock changeover PLC a scene without one gets.
#include <stdexcept>

#include "control/plc/plc_programs.hpp"
#include "sim/runner/runner_state.hpp"

namespace vmt::sim {
namespace {

// PLC cycles a scan may be overdue before the watchdog stops the PLC.
constexpr int64_t kPlcWatchdogCycles = 2;

}  // namespace

// A headstock with a separate C servo needs its clutch switched before the PLC may acknowledge
// (C-axis manual 4.4): without a PLC of the scene's own, the manual's typical program runs as the
// machine's PLC for it. It sees every sensor, as a PLC does, and drives the clutch valves alone:
// the timeline keeps the other valves.
void SceneRun::State::StartHeadstockPlc() {
  auto made = control::plc::MakePlcProgram("c_axis_changeover", *image);
  if (!made) return;
  plc = std::make_unique<control::plc::PlcRuntime>(*image, std::move(*made),
                                                   control::plc::PlcTime(plc_every * 250));
  field_bus.Connect();
  default_headstock_plc = false;
  for (size_t i = 0; i < m.io.size(); ++i) {
    const std::string& name = m.io[i].name;
    const int id = image->Find(name);
    if (id < 0 || m.io[i].key) continue;
    if (!m.io[i].is_output) {
      field_bus.AddInput(static_cast<int>(i), id);
      continue;
    }
    if (name != "QROTMODE" && name != "QSPMODE") continue;
    for (const TimelineStep& step : scene.timeline)
      if (step.kind == TimelineStep::Kind::kOutput && step.io == static_cast<int>(i))
        throw std::runtime_error(step.text + ": valve " + name +
                                 " is switched by the headstock changeover PLC (C-axis manual "
                                 "4.4) in a scene with an NC and no plc:");
    field_bus.AddOutput(static_cast<int>(i), id);
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

// The PLC scans unless an overrun makes it miss its cycles or its link is gone; after two missed
// cycles its watchdog stops it (its outputs drop) and the NC stops with "PLC not running".
void SceneRun::State::ScanPlc(double t) {
  InjectedFaults& f = timeline->faults();
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
  recorder.Event({{"t", t}, {"event", "plc"}, {"state", "stopped"}, {"reason", reason}});
}

void SceneRun::State::ReadFieldBus() {
  field_bus.ReadInputs(fault_filter.In(backend->Read(), timeline->faults()), *image);
}

}  // namespace vmt::sim
