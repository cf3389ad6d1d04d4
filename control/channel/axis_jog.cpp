#include "control/channel/axis_jog.hpp"

#include <cmath>

#include "control/channel/jog_follow.hpp"

namespace vmt::control::channel {
namespace {

/// Starts a profiled move of `jog` from `commanded` to `to` at `speed`.
void StartStep(JogAxis& jog, const axes::AxisParameters& axis, double commanded, double to,
               double speed) {
  jog.stepping = true;
  jog.from = commanded;
  jog.to = to;
  jog.increment = PathProfile{};
  const double distance = std::max(std::abs(jog.to - jog.from), 1e-12);
  jog.increment.max_rate = speed / distance;
  jog.increment.max_accel = axis.acceleration / distance;
}

/// Advances the increment under way; true once it has ended.
bool AdvanceStep(JogAxis& jog, double& commanded, double dt) {
  jog.increment.Advance(dt, 1.0);
  commanded = jog.from + (jog.to - jog.from) * jog.increment.u;
  if (!jog.increment.done()) return false;
  commanded = jog.to;
  jog.stepping = false;
  return true;
}

enum class Homing { kNone, kMoving, kHomed };

/// AxxC.HOME (C-axis manual 4.2): homing as G74 homes the axis, to its reference point at its
/// homing speed; it starts once a jog or increment under way is done.
Homing HomingCycle(JogAxis& jog, const axes::AxisParameters& axis, const AxisJogContext& context,
                   double& commanded, double dt) {
  if (!context.manual) jog.home_requested = false;  // a homing begun runs to its end
  if (jog.home_requested && !jog.stepping && jog.velocity == 0) {
    jog.home_requested = false;
    if (!context.enabled || !context.guard_increment(axis.reference_position)) return Homing::kNone;
    if (std::abs(axis.reference_position - commanded) < 1e-12) {
      commanded = axis.reference_position;  // there already: homed without a move
      return Homing::kHomed;
    }
    const double speed = axis.homing_per_s > 0 ? axis.homing_per_s
                         : axis.jog_per_s > 0  ? axis.jog_per_s
                                               : axis.rapid_per_s / 10;
    StartStep(jog, axis, commanded, axis.reference_position, speed);
    jog.homing = true;
    jog.handwheel = false;
  }
  if (!jog.homing) return Homing::kNone;
  if (!AdvanceStep(jog, commanded, dt)) return Homing::kMoving;
  jog.homing = false;
  return Homing::kHomed;
}

}  // namespace

double JogRules::Speed(const axes::AxisParameters& axis) const {
  const double normal = axis.jog_per_s > 0 ? axis.jog_per_s : axis.rapid_per_s / 10;
  return (mode == JogMode::kRapid ? JogRapid(axis) : normal) * override;
}

double JogRules::Increment(const axes::AxisParameters& axis) const {
  return mode == JogMode::kParametric ? axis.jog_distance : increment;
}

bool JogAxisCycle(JogAxis& jog, const axes::AxisParameters& axis, const AxisJogContext& context,
                  double& commanded, double dt) {
  switch (HomingCycle(jog, axis, context, commanded, dt)) {
    case Homing::kHomed:
      return true;
    case Homing::kMoving:
      return false;
    case Homing::kNone:
      break;
  }
  const JogWindow& window = context.window;
  const JogRules& rules = context.rules;
  if (rules.mode == JogMode::kHandwheel && !jog.stepping) {
    // Follow the counts at most at the jogging rapid, braking so as not to pass the target.
    if (!jog.handwheel) jog.handwheel = true, jog.handwheel_target = commanded;
    jog.handwheel_target = window.Clamp(jog.handwheel_target);
    FollowTarget(commanded, jog.velocity, jog.handwheel_target, JogRapid(axis) * rules.override,
                 axis.acceleration, dt);
    return false;
  }
  const double increment = rules.Increment(axis);
  if (JogStepping(jog.stepping, increment, jog.velocity)) {
    // Incremental: a key press starts one increment, which then runs to its end.
    if (!jog.stepping && jog.key != 0 && context.enabled) {
      const double to = window.Clamp(commanded + jog.key * increment);
      const bool allowed = context.guard_increment(to);
      jog.key = 0;  // one increment per press
      if (!allowed) return false;
      StartStep(jog, axis, commanded, to, rules.Speed(axis));
    }
    if (jog.stepping) AdvanceStep(jog, commanded, dt);
    return false;
  }
  // Continuous: towards the jog speed while the key is held, braking when it is released, the
  // process enabling signal is removed (C-axis manual 2.3: axes to a standstill) or the axis
  // enabling signal (4.2), and in time for the window's edge.
  const int key = context.enabled && jog.key != jog.blocked && increment == 0 ? jog.key : 0;
  const double speed = rules.Speed(axis);
  double target = key * speed;
  if (window.limited) {
    const double room = jog.key > 0 ? window.high - commanded : commanded - window.low;
    target = key * std::min(speed, std::sqrt(2 * axis.acceleration * std::max(0.0, room)));
  }
  const double step = axis.acceleration * dt;
  jog.velocity = std::clamp(target, jog.velocity - step, jog.velocity + step);
  const double next = commanded + jog.velocity * dt;
  commanded = window.Clamp(next);
  if (commanded != next) jog.velocity = 0;
  return false;
}

}  // namespace vmt::control::channel
