#pragma once
// The main spindle's state in the channel, and the channel's watch over its drives.

#include <vector>

#include "control/drive_bus.hpp"

namespace vmt::control::channel {

struct MainSpindleState {
  DriveSetpoint command;     ///< M3/M4/M5/M19 and S, or a key's (before the headstock)
  double override = 1.0;     ///< AxxC.SOVR
  bool enable = true;        ///< AxxC.ENABL of the main spindle
  bool jogging = false;      ///< the spindle turns because a jog key is held
  bool homed = true;         ///< a separate spindle's reference (C-axis manual section 3)
  bool referencing = false;  ///< M19 runs: the reference comes when it is in position
  /// The block waits for the spindle: M19's positioning to end, G77 S1=0's speed to be reached.
  bool orienting = false;
  double position = 0;      ///< the actual position at the last NC cycle
  double rpm = 0;           ///< and the actual speed
  double previous_deg = 0;  ///< G64: the command at the last NC cycle
};

/// What the channel keeps of its drives between cycles.
struct DriveWatch {
  std::vector<double> encoder_last;  ///< per drive: position at the last NC cycle
  bool trip_reset_pending = false;   ///< Control-Reset: acknowledge the drives' trips
  std::vector<int> trip_reset;       ///< the drives being acknowledged
  int trip_reset_ticks = 0;
};

}  // namespace vmt::control::channel
