#pragma once
// Jogging one feed axis for one NC cycle: a key held (continuous), one increment per press, the
// handwheel's counts, or homing by AxxC.HOME, braking in time at the edge of the window the
// axis may move in. The axis' jog state is plain data (JogAxis); the channel gives the rest as
// a narrow context, so each rule can be tested without a channel.
#include <algorithm>
#include <functional>

#include "control/axes/axis_parameters.hpp"
#include "control/channel/channel_types.hpp"
#include "control/channel/jog_state.hpp"

namespace vmt::control::channel {

/// Where a jogged axis may go: its software limits, narrowed by the repositioning zone while
/// repositioning is called (REPOS manual 3.2). Unlimited when `limited` is false.
struct JogWindow {
  bool limited = false;
  double low = 0, high = 0;
  double Clamp(double x) const { return limited ? std::clamp(x, low, high) : x; }
};

/// The jog mode's speeds and distances, as the channel's mode and feed override give them.
struct JogRules {
  JogMode mode = JogMode::kContinuous;
  double increment = 0;  ///< the fixed increment of kIncrement1..1000 (SetJogIncrement's)
  double override = 1;   ///< the feed override: jogging speeds scale with it

  /// Cxx.020 jogging speed (Cxx.021 in kRapid) with the override, a tenth of the rapid where
  /// the machine data give no jogging speed.
  double Speed(const axes::AxisParameters& axis) const;
  /// One key press' distance: Cxx.022 in kParametric, the fixed increment in kIncrement1..1000;
  /// 0 where a key jogs continuously (or, kHandwheel, not at all).
  double Increment(const axes::AxisParameters& axis) const;
};

/// What one axis' jog needs of the channel in a cycle.
struct AxisJogContext {
  JogRules rules;
  bool manual = true;   ///< manual mode: outside it a homing request lapses
  bool enabled = true;  ///< the process and the axis' enabling signals: keys start nothing
  JogWindow window;
  /// PathGuard's check of a whole increment (or homing move) to `to`: false refuses it.
  std::function<bool(double to)> guard_increment;
};

/// Advances `axis`' jog by one cycle `dt`, moving its command value `commanded`. Returns true
/// when homing brought the axis to its reference point this cycle (the axis is then homed).
bool JogAxisCycle(JogAxis& jog, const axes::AxisParameters& axis, const AxisJogContext& context,
                  double& commanded, double dt);

}  // namespace vmt::control::channel
