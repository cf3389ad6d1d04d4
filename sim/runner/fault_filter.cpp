#include "sim/runner/fault_filter.hpp"

namespace vmt::sim {

const control::AmplifierTelegram& FaultFilter::In(const control::AmplifierTelegram& raw,
                                                  const InjectedFaults& f) {
  if (!f.any) return raw;
  filtered_ = raw;
  for (size_t i = 0; i < f.sensor.size(); ++i)
    if (f.sensor[i] >= 0) filtered_.inputs[i] = static_cast<uint8_t>(f.sensor[i]);
  for (size_t d = 0; d < f.drive.size(); ++d)
    if (f.drive[d])
      filtered_.feedback[d].status &=
          ~(control::drive_status::kReady | control::drive_status::kEnabled);
  return filtered_;
}

void FaultFilter::Out(const InjectedFaults& f, control::MasterTelegram& mdt) {
  if (!f.any) return;
  for (size_t i = 0; i < f.valve.size(); ++i)
    if (f.valve[i] >= 0) mdt.outputs[i] = static_cast<uint8_t>(f.valve[i]);
  for (size_t d = 0; d < f.drive.size(); ++d)
    if (f.drive[d]) mdt.setpoints[d] = {control::DriveMode::kOff, 0, 0};
}

}  // namespace vmt::sim
