#pragma once
// What a jog key press leaves between NC cycles: per channel axis (continuous, increment,
// handwheel, homing by AxxC.HOME, PathGuard's block of a direction) and per fictive axis X1/Y1
// under G31. A feed axis' cycle is JogAxisCycle (axis_jog.hpp); the keys reach it through the
// channel (channel_jog.cpp); X1/Y1's cycle is FictiveJogCycle (fictive_jog.hpp), which the channel
// turns into moves of X and C (channel_fictive_jog.cpp).

#include <vector>

#include "control/channel/channel_types.hpp"
#include "control/channel/path_profile.hpp"

namespace vmt::control::channel {

struct JogAxis {
  int key = 0;            ///< key held: +1, -1, 0
  double velocity = 0;    ///< continuous jog
  PathProfile increment;  ///< incremental jog in progress when rate or u < 1
  double from = 0, to = 0;
  bool stepping = false;
  double handwheel_target = 0;  ///< kHandwheel: where the counts want the axis
  bool handwheel = false;
  int blocked = 0;  ///< PathGuard stopped the key in this direction: until it is released
  bool home_requested = false;  ///< AxxC.HOME: homing starts once the axis can move
  bool homing = false;          ///< the increment under way is homing (to the reference)
};

struct FictiveJog {
  int key = 0;
  double velocity = 0;  ///< mm/s along the fictive axis
  bool stepping = false;
  double target = 0;            ///< the increment's end
  bool handwheel = false;       ///< kHandwheel: counts given, the point not there yet
  double handwheel_target = 0;  ///< kHandwheel: where the counts want the fictive axis
};

/// The channel's jogging: every channel axis, X1/Y1 of G31, the jog mode (JOGM0..2) and the
/// increment of the continuous mode's SetJogIncrement.
struct JogData {
  std::vector<JogAxis> axes;
  FictiveJog fictive[2];
  JogMode mode = JogMode::kContinuous;
  double increment = 0;
};

}  // namespace vmt::control::channel
