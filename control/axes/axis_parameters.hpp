#pragma once
// Axis and process parameters of one NC process, as the machine builder sets them. Parameters
// the manuals number keep the manuals' names (Cxx.020 jogging speed, Cxx.086 REPOS window,
// Bxx.036 ...); the rest (rapid, acceleration, jerk, homing) are named by what they are, since
// the manuals give them no number. Units are machine units: mm or degrees, per second.

#include <string>
#include <vector>

namespace vmt::control::axes {

struct AxisParameters {
  int number = 0;    ///< xx of Axx / Cxx, counted from 1
  std::string name;  ///< address in the program: X, Z, C (Cxx.001 axis designation)
  int drive = -1;    ///< DriveBus index
  bool rotary = false;
  double rapid_per_s = 0;                 ///< G00 speed, mm/s | deg/s
  double acceleration = 0;                ///< mm/s^2 | deg/s^2
  double jerk = 0;                        ///< mm/s^3 | deg/s^3; 0: not limited
  double jog_per_s = 0;                   ///< Cxx.020 jogging speed (0: a tenth of the rapid)
  double jog_rapid_per_s = 0;             ///< Cxx.021 jogging speed - rapid
  double jog_distance = 0;                ///< Cxx.022 parametric jogging distance (increment)
  double in_position_window = 0;          ///< Cxx.023
  double repos_window = 0.2;              ///< Cxx.086 window for repositioning and NC-block restart
  double reference_position = 0;          ///< where G74 homing ends, machine coordinates
  double homing_per_s = 0;                ///< G74 speed (0: the jogging speed)
  double travel_min = 0, travel_max = 0;  ///< software limits; equal: none (endless axis)
  bool homed_at_start = true;             ///< absolute encoder; false: G74 before the first move
};

/// Process parameters (Bxx.*), REPOS manual 6.
struct ProcessParameters {
  int number = 0;                         ///< xx of Pxx / Bxx, counted from 0
  bool reverse_program_required = false;  ///< Bxx.032 'Reverse Program Execution Required'
  bool jogging_causes_reset = false;      ///< Bxx.036 'Manual Axis Jogging causes Reset'
  bool reposition_tool_storage = false;   ///< Bxx.045 'Reposition Tool Storage Axis'
};

}  // namespace vmt::control::axes
