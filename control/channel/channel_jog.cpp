// Manual mode of the channel: the jog keys move the axes continuously, by increments or by
// handwheel (JogMode), braking in time at the software limits.
#include <cmath>

#include "control/channel/channel.hpp"
#include "control/channel/fictive_jog.hpp"
#include "control/channel/jog_follow.hpp"

namespace vmt::control::channel {

void Channel::SetJogIncrement(double increment) {
  jog_.increment = std::abs(increment);
  jog_.mode = JogMode::kContinuous;
}

void Channel::SetJogMode(int code) {
  jog_.mode = static_cast<JogMode>(std::clamp(code, 0, 7));
  switch (jog_.mode) {
    case JogMode::kIncrement1:
      jog_.increment = 0.001;
      break;
    case JogMode::kIncrement10:
      jog_.increment = 0.01;
      break;
    case JogMode::kIncrement100:
      jog_.increment = 0.1;
      break;
    case JogMode::kIncrement1000:
      jog_.increment = 1;
      break;
    default:
      jog_.increment = 0;
  }
  RestartHandwheel();
}

void Channel::RestartHandwheel() {
  // The handwheel's counts start afresh from where the axis comes to rest: the end of an
  // increment under way (it runs to its end, below), or where a continuous jog stops braking
  // (a target where it stands would stop it dead within a cycle).
  for (size_t a = 0; a < jog_.axes.size(); ++a) {
    JogAxis& j = jog_.axes[a];
    j.handwheel = jog_.mode == JogMode::kHandwheel;
    j.handwheel_target =
        j.stepping ? j.to
                   : JogStopPoint(out_.commanded[a], j.velocity, config_.axes[a].acceleration);
  }
  // The fictive axes' likewise (their handwheel target is there only while counts are to go).
  int x = -1, c = -1;
  if (!FictiveJogAxes(x, c)) return;
  const nc::FictivePoint p = nc::MachineToFace(out_.commanded[x] - frames_.translation[x],
                                               out_.commanded[c] - frames_.translation[c]);
  RestartFictiveHandwheel(jog_.fictive, jog_.mode, p, config_.axes[x].acceleration);
}

JogRules Channel::jog_rules() const { return {jog_.mode, jog_.increment, override_}; }

void Channel::Handwheel(size_t axis, int counts) {
  if (mode_ != ChannelMode::kManual || jog_.mode != JogMode::kHandwheel ||
      axis >= jog_.axes.size() || !enable_.process || !axis_enabled(axis))
    return;
  out_.take_over_pending = true;
  JogAxis& j = jog_.axes[axis];
  if (!j.handwheel) j.handwheel = true, j.handwheel_target = out_.commanded[axis];
  j.handwheel_target += counts * config_.handwheel_per_count;
}

void Channel::Jog(size_t axis, int direction) {
  if (mode_ != ChannelMode::kManual || axis >= jog_.axes.size()) return;
  // Bxx.036 'Manual Axis Jogging causes Reset': jogging an interrupted program away ends it
  // (REPOS manual 6.1: no repositioning then).
  if (direction != 0 && config_.process.jogging_causes_reset && state_ == ChannelState::kHold)
    Reset();
  // C-axis manual 4.2: jogging the rotary axis selects rotary axis mode; it moves once there.
  if (headstock_ && static_cast<int>(axis) == config_.rotary_axis && direction != 0 &&
      enable_.process && axis_enabled(axis))
    ManualChangeover(axes::HeadstockMode::kRotary);
  jog_.axes[axis].key = direction > 0 ? 1 : direction < 0 ? -1 : 0;
  out_.take_over_pending = true;
}

void Channel::HomeAxis(size_t axis) {
  if (mode_ != ChannelMode::kManual || axis >= jog_.axes.size()) return;
  if (!enable_.process || !axis_enabled(axis)) return;
  if (headstock_ && static_cast<int>(axis) == config_.rotary_axis)
    ManualChangeover(axes::HeadstockMode::kRotary);
  jog_.axes[axis].home_requested = true;
  out_.take_over_pending = true;
}

bool Channel::JogsMoving() const {
  for (const JogAxis& j : jog_.axes)
    if (j.velocity != 0 || j.stepping) return true;
  for (const FictiveJog& f : jog_.fictive)
    if (f.velocity != 0 || f.stepping) return true;
  return false;
}

int Channel::AxisMotion(size_t axis) const {
  const double d = out_.commanded[axis] - out_.previous[axis];
  return d > 0 ? 1 : d < 0 ? -1 : 0;
}

void Channel::Jogging(double dt) {
  GuardJog(dt);
  // REPOS manual 3.2: while repositioning or NC-block restart is called, a feed axis moves
  // between its target and where it stood when the function was called, never past the target
  // (an endless rotary axis excepted). An axis outside that zone (a zero offset edit moved its
  // target) may only come back towards it.
  const std::vector<double> repos_target =
      repos_.called() ? repos_.Target(ReposViewNow()) : std::vector<double>{};
  AxisJogContext context;
  context.rules = jog_rules();
  context.manual = mode_ == ChannelMode::kManual;
  size_t a = 0;
  context.guard_increment = [this, &a](double to) { return GuardIncrement(a, to); };
  for (; a < jog_.axes.size(); ++a) {
    JogAxis& j = jog_.axes[a];
    // Outside rotary axis mode the rotary axis follows the spindle: it has no jog to go on with.
    if (headstock_.RotaryAxisOff() && static_cast<int>(a) == config_.rotary_axis) {
      j.velocity = 0, j.stepping = j.homing = false;
      continue;
    }
    const ChannelAxis& axis = config_.axes[a];
    // Jogging stops at the software limits and the repositioning zone, braking in time.
    JogWindow& window = context.window;
    window = {axis.travel_max > axis.travel_min, axis.travel_min, axis.travel_max};
    if (!repos_target.empty()) {
      const ReposZone zone = ZoneOf(axis, repos_target[a], repos_.start()[a]);
      if (zone.limited) {
        const double zone_low = std::min(zone.low, out_.commanded[a]);
        const double zone_high = std::max(zone.high, out_.commanded[a]);
        window.low = window.limited ? std::max(window.low, zone_low) : zone_low;
        window.high = window.limited ? std::min(window.high, zone_high) : zone_high;
        window.limited = true;
      }
    }
    context.enabled = enable_.process && axis_enabled(a);
    if (JogAxisCycle(j, axis, context, out_.commanded[a], dt)) frames_.homed[a] = true;
  }
  FictiveJogging(dt);
}

}  // namespace vmt::control::channel
