#pragma once
// The main spindle's program words: M3 / M4 / M5 / M19 with S, as a run and a block search
// (which keeps the spindle as the program left it) both apply them to a setpoint.

#include <cmath>

#include "control/channel/further_spindles.hpp"
#include "control/drive_bus.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

/// M3/M4/M5/M19 and S of `b` on the main spindle's setpoint `sp` (`spindle_drive` < 0: the
/// channel has none); true if M19 (orientation) came.
inline bool MainSpindleFunctions(const nc::PreparedBlock& b, int spindle_drive, DriveSetpoint& sp) {
  bool orient = false;
  for (const nc::AuxFunction& f : b.aux) {
    if (f.letter != 'M' || SpindleIndex(f.index) != 1 || spindle_drive < 0) continue;
    const int m = static_cast<int>(f.value);
    const double rpm = b.modal.spindle_speed;
    // G64 keeps the spindle in position control: M3/M4 give its direction only.
    if ((m == 3 || m == 4) && b.motion == nc::Motion::kRigidTapping) continue;
    if (m == 3) sp = {DriveMode::kVelocity, rpm * 6, 0};
    if (m == 4) sp = {DriveMode::kVelocity, -rpm * 6, 0};
    if (m == 5) sp = {DriveMode::kVelocity, 0, 0};
    if (m == 19) sp = {DriveMode::kPosition, 0, 0}, orient = true;
  }
  // An S word alone changes the speed of a running spindle.
  if (sp.mode == DriveMode::kVelocity && sp.value != 0)
    sp.value = std::copysign(b.modal.spindle_speed * 6, sp.value);
  return orient;
}

}  // namespace vmt::control::channel
