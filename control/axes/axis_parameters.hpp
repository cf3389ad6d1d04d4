#pragma once
// Axis and process parameters of one NC process, as the machine builder sets them. Parameters
// the manuals number keep the manuals' names (Cxx.020 jogging speed, Cxx.086 REPOS window,
// Bxx.036 ...); the rest (rapid, acceleration, jerk, homing) are named by what they are, since
// the manuals give them no number. Units are machine units: mm or degrees, per second.

#include <array>
#include <limits>
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
  /// Main spindle mode (C-axis manual 2.2, a parameter "provided with a new parameter number"
  /// the manual does not print): "Jogging spindle position", where AxxC.M19 positions the
  /// spindle, deg. The spindle's "Jogging speed" (AxxC.M3/M4) is jog_per_s, in deg/s.
  double jog_spindle_position = 0;
  /// Main spindle mode: Cxx.049 "Max. programmable spindle speed", rpm (C-axis manual 2.2), the
  /// maximum the status indication shows (2.3). 0: not set.
  double max_spindle_rpm = 0;
  /// The reference is kept while the position encoder's signal frequency stays within the limit
  /// frequency of its interface (C-axis manual 2.3 and 3.3 Homing):
  ///   n_max [1/s] * impulses or oscillations per revolution <= limit frequency [1/s].
  /// The manual names these quantities but gives them no parameter numbers. 0: not monitored
  /// (e.g. the INDRAMAT gear-type encoder, good up to 24000 rpm: reference lost only at power-off).
  double encoder_periods_per_rev = 0;  ///< impulses (square) or oscillations (sine) per rev
  /// Limit frequency of the encoder interface, Hz: DDS and main spindle units 150 kHz for sine,
  /// 1 MHz for square-wave signals (3.3); the main spindle interface for incremental encoders
  /// 100 kHz (2.3).
  double encoder_limit_hz = 0;
  /// Cxx.025..Cxx.032 waypoints 0..7 (C-axis manual 2.2), mm | deg in machine coordinates; a
  /// rotary axis' or spindle's within [0, 360). kNoWaypoint: not set, AxxS.WPn stays 0.
  static constexpr double kNoWaypoint = std::numeric_limits<double>::quiet_NaN();
  std::array<double, 8> waypoints{kNoWaypoint, kNoWaypoint, kNoWaypoint, kNoWaypoint,
                                  kNoWaypoint, kNoWaypoint, kNoWaypoint, kNoWaypoint};
};

/// Process parameters (Bxx.*), REPOS manual 6.
struct ProcessParameters {
  int number = 0;                         ///< xx of Pxx / Bxx, counted from 0
  bool reverse_program_required = false;  ///< Bxx.032 'Reverse Program Execution Required'
  bool jogging_causes_reset = false;      ///< Bxx.036 'Manual Axis Jogging causes Reset'
  bool reposition_tool_storage = false;   ///< Bxx.045 'Reposition Tool Storage Axis'
};

}  // namespace vmt::control::axes
