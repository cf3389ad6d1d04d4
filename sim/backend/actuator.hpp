#pragma once
// Valve-driven devices and cam switches of the machine's I/O map (machine.yaml `actuators:`,
// `position_switches:`), shared by both backends: the stroke and what the switches show. The
// backends hold a clamped drive's joint (physics: a joint motor up to the hold torque;
// kinematic: the joint does not move).

#include <cstdint>
#include <vector>

#include "control/drive_bus.hpp"
#include "sim/backend/dog_clutch.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

struct ActuatorLogic {
  double stroke = 0;  ///< 0 = off end, 1 = on end; between them while the valve moves it

  void Step(const Actuator& a, bool valve, double dt_s);
  bool OnSwitch() const { return stroke >= 1; }
  bool OffSwitch() const { return stroke <= 0; }
  /// A clamp holds its drive unless it is fully released.
  bool Holds(const Actuator& a) const { return a.holds_drive >= 0 && !OnSwitch(); }
};

/// Is the drive at a multiple of the switch's pitch (within its window)?
bool PositionSwitchOn(const PositionSwitch& p, double drive_position);

/// The digital inputs the machine shows: outputs read back, clutch end-position switches,
/// actuator end switches, cam switches on the drives' actual positions. Keys stay 0: they are
/// the operator's, set on the control side.
class MachineInputs {
 public:
  explicit MachineInputs(const MachineModel& model);

  /// Every I/O point's input as the machine shows it this tick (`outputs`: one per I/O point,
  /// as the master wrote them).
  void Read(const std::vector<uint8_t>& outputs, const std::vector<DogClutchLogic>& clutches,
            const std::vector<ActuatorLogic>& actuators,
            const std::vector<control::DriveFeedback>& feedback,
            std::vector<uint8_t>& inputs) const;

 private:
  const MachineModel* model_;
  /// Per I/O point 0xff for an output (read back), else 0: every tick reads every point, and a
  /// mask over the bytes is a few vector instructions where testing IoInfo::is_output point by
  /// point was a loop of loads.
  std::vector<uint8_t> read_back_;
};

}  // namespace vmt::sim
