#pragma once
// The channel's small vocabulary for those who watch it rather than run it: the scene, the
// gateway and the runner name its state, mode and jog mode, show its spindle status and record
// its PathGuard checks without the Channel class (channel.hpp), which is declared here for
// those that only pass a channel on.

#include <cstdint>
#include <string>
#include <vector>

#include "control/path_guard.hpp"

namespace vmt::control::channel {

class Channel;

enum class ChannelState { kIdle, kRunning, kHold, kEnded, kError };
const char* ToString(ChannelState s);

/// Operating modes. Automatic runs the program (single block makes it semi-automatic); manual
/// moves the axes with the jog keys, continuously, by increments or by handwheel; MDI runs
/// blocks typed in by the operator.
enum class ChannelMode { kAutomatic, kManual, kMdi };
const char* ToString(ChannelMode m);

/// Jog modes, selected by the code on PxxC.JOGM0..2 (JOGM0 the lowest bit). The manuals name
/// the signals, not their codes; these are vmt's.
enum class JogMode : uint8_t {
  kContinuous = 0,     ///< Cxx.020 jogging speed while the key is held
  kRapid = 1,          ///< Cxx.021 jogging speed - rapid
  kParametric = 2,     ///< one Cxx.022 parametric jogging distance per key press
  kIncrement1 = 3,     ///< 0.001 mm | deg per press
  kIncrement10 = 4,    ///< 0.01
  kIncrement100 = 5,   ///< 0.1
  kIncrement1000 = 6,  ///< 1
  kHandwheel = 7,      ///< the handwheel counts move the axis, keys do nothing
};

/// One PathGuard check the channel made: which move, from where to where (per drive), and the
/// answer. A continuous jog is checked many times: its clear checks are summed up in one record
/// when it ends (`checks`, the smallest clearance of all).
struct GuardRecord {
  std::string move;  ///< "jog", "G77", "repositioning" (the closing move)
  std::vector<double> from, to;
  PathCheck check;
  int checks = 1;
  bool stopped = false;  ///< the reaction stopped the move
};

/// The main spindle in the status indication (C-axis manual 2.3 / 3.3 Status Indication): in
/// main spindle operation the programmed, current and maximum speed as for any main spindle;
/// with its headstock in rotary axis mode lines instead of the three speeds (the manual's "in
/// main spindle mode" there is a slip: it says the opposite a sentence before). The override
/// values are always shown.
struct SpindleStatus {
  /// False: the display shows lines instead of the speeds, which are then 0. It switches with
  /// the axis designation, when a changeover has completed (2.3 Position Indication).
  bool speeds_shown = true;
  double programmed_rpm = 0;    ///< commanded speed before the override, M4 negative; 0 for M19
  double actual_rpm = 0;        ///< the spindle's actual speed, signed
  double max_rpm = 0;           ///< Cxx.049 max. programmable spindle speed
  double spindle_override = 1;  ///< fraction (AxxC.SOVR / 100), always shown
  double feed_override = 1;     ///< fraction (PxxC.FOVR / 100), always shown
};

}  // namespace vmt::control::channel
