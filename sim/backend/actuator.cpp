#include "sim/backend/actuator.hpp"

#include <algorithm>
#include <cmath>

namespace vmt::sim {

void ActuatorLogic::Step(const Actuator& a, bool valve, double dt_s) {
  // At the end the valve drives it to (most ticks) the stroke stays: times are > 0, so the
  // clamp below would return the end itself, after a division.
  if (valve ? stroke >= 1 : stroke <= 0) return;
  stroke = valve ? std::min(1.0, stroke + dt_s / a.time_on_s)
                 : std::max(0.0, stroke - dt_s / a.time_off_s);
}

bool PositionSwitchOn(const PositionSwitch& p, double drive_position) {
  const double off = drive_position - p.pitch * std::round(drive_position / p.pitch);
  return std::abs(off) <= p.window;
}

MachineInputs::MachineInputs(const MachineModel& model)
    : model_(&model), read_back_(model.io.size(), 0) {
  for (size_t i = 0; i < model.io.size(); ++i)
    if (model.io[i].is_output) read_back_[i] = 0xff;
}

void MachineInputs::Read(const std::vector<uint8_t>& outputs,
                         const std::vector<DogClutchLogic>& clutches,
                         const std::vector<ActuatorLogic>& actuators,
                         const std::vector<control::DriveFeedback>& feedback,
                         std::vector<uint8_t>& inputs) const {
  const MachineModel& model = *model_;
  const size_t n = read_back_.size();
  const uint8_t* mask = read_back_.data();
  const uint8_t* out = outputs.data();
  uint8_t* in = inputs.data();
  for (size_t i = 0; i < n; ++i) in[i] = out[i] & mask[i];
  for (size_t k = 0; k < clutches.size(); ++k) {
    const DogClutch& c = model.clutches[k];
    inputs[c.sensor_engaged] = clutches[k].EngagedSwitch();
    inputs[c.sensor_released] = clutches[k].ReleasedSwitch();
  }
  for (size_t k = 0; k < actuators.size(); ++k) {
    const Actuator& a = model.actuators[k];
    if (a.on_switch >= 0) inputs[a.on_switch] = actuators[k].OnSwitch();
    if (a.off_switch >= 0) inputs[a.off_switch] = actuators[k].OffSwitch();
  }
  for (const PositionSwitch& p : model.position_switches)
    inputs[p.input] = PositionSwitchOn(p, feedback[p.drive].position);
}

}  // namespace vmt::sim
