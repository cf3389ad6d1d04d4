#include "sim/runner/machine_events.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <span>
#include <utility>

#include "sim/runner/channel_events.hpp"
#include "sim/scene/steps/timeline_play.hpp"

namespace vmt::sim {

std::string TripCauses(uint32_t faults) {
  using namespace control::drive_status;
  std::string s;
  for (const auto& [bit, name] : {std::pair<uint32_t, const char*>{kOverload, "overload"},
                                  {kOverspeed, "overspeed"},
                                  {kParameterSetError, "parameter_set_error"}})
    if (faults & bit) s += (s.empty() ? "" : " and ") + std::string(name);
  return s;
}

void MachineEventWatch::Watch(double t, const control::AmplifierTelegram& at,
                              const std::vector<ClutchState>& clutches,
                              const MachineBackend& backend,
                              const control::gateway::SignalImage* image, RunRecorder& recorder) {
  if (image) WatchSignals(t, *image, recorder);
  WatchClutches(t, clutches, backend, recorder);
  // Nearly every tick changes no input: the machine's io points are visited only when one did.
  if (last_inputs_.empty() || at.inputs != last_inputs_) {
    for (size_t i = 0; i < at.inputs.size(); ++i)
      if (!m_->io[i].is_output && !m_->io[i].key &&
          (last_inputs_.empty() || at.inputs[i] != last_inputs_[i]))
        recorder.Event(
            {{"t", t}, {"event", "input"}, {"name", m_->io[i].name}, {"value", at.inputs[i]}});
    last_inputs_ = at.inputs;
  }
  WatchDrives(t, at, recorder);
  if (clutches != last_clutches_) last_clutches_ = clutches;
}

void MachineEventWatch::WatchSignals(double t, const control::gateway::SignalImage& image,
                                     RunRecorder& recorder) {
  // Only the cells that changed are read through their type: a study case runs this every
  // tick over thousands of signals, of which a handful change.
  const std::span<const int64_t> cells = image.cells();
  const bool first = last_cells_.empty();
  // Most ticks write no signal (the NC's status changes on its cycle, the PLC's on its scan).
  if (!first && image.changes() == last_changes_) return;
  last_changes_ = image.changes();
  last_signals_.resize(image.size(), std::nan(""));
  last_cells_.resize(cells.size());
  if (wanted_.size() != static_cast<size_t>(image.size())) {
    wanted_.assign(image.size(), true);
    if (signal_events_)
      for (int id = 0; id < image.size(); ++id)
        wanted_[id] = signal_events_(image.table()[id].name);
  }
  // Whole blocks of unchanged cells are passed over by memcmp (vectorised) at once; the cells
  // of a block that changed are compared one by one.
  constexpr int kBlock = 64;
  const int n = image.size();
  for (int block = 0; block < n; block += kBlock) {
    const int end = std::min(n, block + kBlock);
    if (!first && std::memcmp(&cells[block], &last_cells_[block],
                              static_cast<size_t>(end - block) * sizeof(int64_t)) == 0)
      continue;
    for (int id = block; id < end; ++id) {
      if (!first && cells[id] == last_cells_[id]) continue;
      last_cells_[id] = cells[id];
      if (!wanted_[id]) continue;
      const double v = image.Number(id);
      if (v != last_signals_[id] && !(std::isnan(v) && std::isnan(last_signals_[id]))) {
        if (!std::isnan(last_signals_[id]) || v != 0) recorder.Signal(t, image.table()[id].name, v);
        last_signals_[id] = v;
      }
    }
  }
}

void MachineEventWatch::WatchClutches(double t, const std::vector<ClutchState>& clutches,
                                      const MachineBackend& backend, RunRecorder& recorder) {
  for (size_t k = 0; k < clutches.size(); ++k)
    if (last_clutches_.empty() || clutches[k] != last_clutches_[k])
      recorder.Event({{"t", t},
                      {"event", "clutch"},
                      {"name", m_->clutches[k].name},
                      {"state", ToString(clutches[k])}});
  // A clash: the dogs pushed in while the halves turn against each other too fast (the clutch
  // refuses and ratchets), with that relative speed, deg/s on the load side.
  last_clashes_.resize(clutches.size(), 0);
  for (size_t k = 0; k < clutches.size(); ++k) {
    const DogClutchLogic& logic = backend.ClutchLogic(static_cast<int>(k));
    if (logic.clashes == last_clashes_[k]) continue;
    last_clashes_[k] = logic.clashes;
    recorder.Event(
        {{"t", t},
         {"event", "clutch"},
         {"name", m_->clutches[k].name},
         {"state", "clash"},
         {"relative_speed", std::round(logic.clash_slip_rad_s * kDegPerRad * 1e3) / 1e3},
         {"max_relative_speed",
          std::round(m_->clutches[k].max_relative_speed_rad_s * kDegPerRad * 1e3) / 1e3}});
  }
}

void MachineEventWatch::WatchDrives(double t, const control::AmplifierTelegram& at,
                                    RunRecorder& recorder) {
  // A drive's trips (overload, overspeed, missing parameter set) as they come and go.
  using namespace control::drive_status;
  last_faults_.resize(at.feedback.size(), 0);
  last_sets_.resize(at.feedback.size(), 0);
  for (size_t d = 0; d < at.feedback.size(); ++d) {
    // The drive's current parameter set as it changes (S-0-0254).
    if (at.feedback[d].parameter_set != last_sets_[d]) {
      last_sets_[d] = at.feedback[d].parameter_set;
      recorder.Event({{"t", t},
                      {"event", "drive"},
                      {"name", m_->drives[d].info.name},
                      {"parameter_set", last_sets_[d]}});
    }
    const uint32_t faults = at.feedback[d].status & (kOverload | kOverspeed | kParameterSetError);
    if (faults == last_faults_[d]) continue;
    nlohmann::ordered_json e = {{"t", t}, {"event", "drive"}, {"name", m_->drives[d].info.name}};
    e["overload"] = (faults & kOverload) != 0;
    e["overspeed"] = (faults & kOverspeed) != 0;
    e["parameter_set_error"] = (faults & kParameterSetError) != 0;
    recorder.Event(e);
    if (const uint32_t new_faults = faults & ~last_faults_[d])
      trips_.push_back({t, static_cast<int>(d), new_faults});
    last_faults_[d] = faults;
  }
  // Probe latches as the drives fill them (7.3): latched value beside the exact contact.
  last_latches_.resize(at.feedback.size(), 0);
  for (size_t d = 0; d < at.feedback.size(); ++d) {
    const control::ProbeStatus& p = at.feedback[d].probe;
    const control::ProbeEdgeLatch* latches[4] = {&p.probe1.positive, &p.probe1.negative,
                                                 &p.probe2.positive, &p.probe2.negative};
    const uint8_t now = static_cast<uint8_t>(latches[0]->latched | latches[1]->latched << 1 |
                                             latches[2]->latched << 2 | latches[3]->latched << 3);
    for (uint8_t rising = now & ~last_latches_[d]; rising != 0; rising &= rising - 1) {
      const int k = std::countr_zero(rising);
      recorder.Event(
          ProbeLatchEvent(t, m_->drives[d].info.name, k < 2 ? 4 : 5, k % 2 == 0, *latches[k]));
    }
    last_latches_[d] = now;
  }
}

}  // namespace vmt::sim
