#include "sim/backend/probe_wiring.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vmt::sim {

double ActualPosition(const DriveParams& p, double encoder_position_si) {
  const double unit = p.info.kind == control::AxisKind::kLinear ? kMmPerM : kDegPerRad;
  const double wrapped =
      p.modulo > 0 ? encoder_position_si - p.modulo * std::floor(encoder_position_si / p.modulo)
                   : encoder_position_si;
  return wrapped * unit;
}

ProbeWiring::ProbeWiring(const MachineModel& model)
    : model_(&model),
      settable_(model.io.size(), 1),
      set_(model.io.size(), 0),
      switches_(model.io.size()),
      latches_(model.drives.size()),
      positions_before_(model.drives.size(), 0.0) {
  for (size_t d = 0; d < model.drives.size(); ++d) {
    const DriveParams& p = model.drives[d];
    if (p.probe_inputs[0] >= 0 || p.probe_inputs[1] >= 0) wired_.push_back(static_cast<int>(d));
  }
  any_ = !wired_.empty();
  // What a device shows on an input (MachineInputs) would overwrite a switch set here.
  for (size_t i = 0; i < model.io.size(); ++i)
    if (model.io[i].is_output || model.io[i].key) settable_[i] = 0;
  for (const DogClutch& k : model.clutches) settable_[k.sensor_engaged] = 0;
  for (const DogClutch& k : model.clutches) settable_[k.sensor_released] = 0;
  for (const Actuator& a : model.actuators) {
    if (a.on_switch >= 0) settable_[a.on_switch] = 0;
    if (a.off_switch >= 0) settable_[a.off_switch] = 0;
  }
  for (const PositionSwitch& s : model.position_switches) settable_[s.input] = 0;
}

void ProbeWiring::SetSamplingPhase(const ProbeSamplingPhase& phase) {
  phase_ = phase;
  phase_state_ = phase.seed;
}

double ProbeWiring::NextPhase() {
  // SplitMix64: the same sequence on every platform and standard library, unlike the
  // distributions of <random>.
  uint64_t z = (phase_state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

void ProbeWiring::SetSwitch(int io_input, bool level, double tick_fraction) {
  if (io_input < 0 || static_cast<size_t>(io_input) >= switches_.size())
    throw std::invalid_argument("SetProbeSwitch: no I/O point " + std::to_string(io_input));
  if (!settable_[io_input])
    throw std::invalid_argument("SetProbeSwitch: '" + model_->io[io_input].name +
                                "' is not a machine input a switch may set (an output, a key, or "
                                "the switch of a clutch, actuator or cam)");
  Switch& s = switches_[io_input];
  if (!set_[io_input]) set_points_.push_back(io_input);
  set_[io_input] = 1;
  if (s.level == level) return;
  s.level = level;
  if (!s.changed) changed_.push_back(io_input);
  s.changed = true;
  // NaN counts as the tick's end: the drive then sees the change at its sample, no earlier.
  s.fraction = tick_fraction >= 0 ? std::min(tick_fraction, 1.0) : tick_fraction < 0 ? 0.0 : 1.0;
  if (phase_.seeded) s.sample_wait = NextPhase();
}

void ProbeWiring::ShowInputs(std::vector<uint8_t>& inputs) const {
  for (const int i : set_points_) inputs[i] = switches_[i].level;
}

void ProbeWiring::Step(const std::vector<control::DriveSetpoint>& setpoints,
                       const std::vector<uint8_t>& inputs, const std::vector<double>& positions,
                       std::vector<control::DriveFeedback>& feedback) {
  for (const int d : wired_) {
    const DriveParams& p = model_->drives[d];
    // Only an active function latches, i.e. reads the exact position (most ticks it is off).
    const bool active =
        setpoints[d].probe.probe_cycle_command == control::probe_control::kProbeCycleActive;
    std::array<ProbeInputSample, 2> pins;
    for (int k = 0; k < 2; ++k) {
      const int io = p.probe_inputs[k];
      if (io < 0) continue;
      pins[k].level = inputs[io] != 0;
      if (!active) continue;
      // The axis moves nearly uniformly within 250 us: the position at the change lies on the
      // line between the two ticks' (a modulo drive's the shorter way round).
      const Switch& s = switches_[io];
      const double before = positions_before_[d];
      double step = positions[d] - before;
      const double modulo = p.modulo * kDegPerRad;  // only a rotary drive has one
      if (modulo > 0) step -= modulo * std::round(step / modulo);
      double exact = s.changed ? before + s.fraction * step : positions[d];
      if (s.changed) {
        // 7.3: the position value is acquired kLatchPositionLeadS before the input sample that
        // sees the change, on the same line (a sample a little into the next tick extrapolates
        // it). Off, that sample is this tick's end; seeded, it lies sample_wait after the change.
        const double wait = phase_.seeded ? s.sample_wait : 1 - s.fraction;
        double acquired = exact + (wait - kLatchPositionLeadS / kProbeSamplePeriodS) * step;
        // Quantised by the encoder as DriveController::Feedback quantises the tick's position.
        const double unit = p.info.kind == control::AxisKind::kLinear ? kMmPerM : kDegPerRad;
        acquired = std::floor(acquired / unit / p.encoder_resolution + 0.5) *
                   p.encoder_resolution * unit;
        if (modulo > 0) acquired -= modulo * std::floor(acquired / modulo);
        pins[k].acquired_position = acquired;
      }
      if (modulo > 0) exact -= modulo * std::floor(exact / modulo);
      pins[k].exact_position = exact;
    }
    // Nothing else writes DriveFeedback::probe (DriveController::Feedback leaves it), so an
    // unchanged status need not be copied again.
    if (latches_[d].Step(setpoints[d].probe, pins, feedback[d].position))
      feedback[d].probe = latches_[d].status();
    positions_before_[d] = positions[d];
  }
  for (const int i : changed_) switches_[i].changed = false;
  changed_.clear();
}

}  // namespace vmt::sim
