#include "control/channel/fictive_jog.hpp"

#include <algorithm>
#include <cmath>

#include "control/channel/jog_follow.hpp"

namespace vmt::control::channel {

std::optional<nc::FictivePoint> FictiveJogCycle(FictiveJog (&jogs)[2], nc::FictivePoint at,
                                                const FictiveJogContext& context, double dt) {
  const bool handwheel_mode = context.mode == JogMode::kHandwheel;
  const double a = context.acceleration;
  const double step = a * dt;
  double pos[2] = {at.x1, at.y1};
  bool moved = false;
  for (int k = 0; k < 2; ++k) {
    FictiveJog& j = jogs[k];
    const double low = context.low[k], high = context.high[k];
    const auto within = [&](double v) { return std::clamp(v, low, high); };
    if (handwheel_mode) j.key = 0;
    // An increment under way runs to its end at the jogging speed (below), the handwheel then
    // on from its end (the jog mode's change made that its target).
    if (handwheel_mode && !j.stepping) {
      if (!j.handwheel) {
        j.velocity = 0;
        continue;
      }
      j.handwheel_target = within(j.handwheel_target);
      if (FollowTarget(pos[k], j.velocity, j.handwheel_target, context.handwheel_speed, a, dt))
        j.handwheel = false;
      moved = true;
      continue;
    }
    if (!handwheel_mode) j.handwheel = false;
    if (JogStepping(j.stepping, context.increment, j.velocity)) {
      if (!j.stepping && j.key != 0 && context.enabled) {
        j.stepping = true;
        j.target = within(pos[k] + j.key * context.increment);
        j.key = 0;  // one increment per press
      }
      if (!j.stepping) continue;
      if (FollowTarget(pos[k], j.velocity, j.target, context.speed, a, dt)) j.stepping = false;
      moved = true;
      continue;
    }
    // A key held: towards the edge of the zone at most as fast as it can still brake there.
    const int key = context.enabled && context.increment == 0 ? j.key : 0;
    const double room = key > 0 ? high - pos[k] : pos[k] - low;
    const double target_velocity =
        key * std::min(context.speed, std::sqrt(2 * a * std::max(0.0, room)));
    j.velocity = std::clamp(target_velocity, j.velocity - step, j.velocity + step);
    if (j.velocity == 0) continue;
    const double next = within(pos[k] + j.velocity * dt);
    if (next != pos[k] + j.velocity * dt) j.velocity = 0;
    pos[k] = next;
    moved = true;
  }
  if (!moved) return std::nullopt;
  return nc::FictivePoint{pos[0], pos[1]};
}

nc::FictivePoint FictiveJogStop(const FictiveJog (&jogs)[2], JogMode mode, nc::FictivePoint next,
                                double acceleration, double interval) {
  double stop[2] = {next.x1, next.y1};
  for (int k = 0; k < 2; ++k) {
    const FictiveJog& j = jogs[k];
    if (mode == JogMode::kHandwheel) {
      if (j.handwheel) stop[k] = j.handwheel_target;
      continue;
    }
    stop[k] += j.velocity * std::abs(j.velocity) / (2 * acceleration) + j.velocity * interval;
  }
  return {stop[0], stop[1]};
}

void RestartFictiveHandwheel(FictiveJog (&jogs)[2], JogMode mode, nc::FictivePoint at,
                             double acceleration) {
  const double position[2] = {at.x1, at.y1};
  for (int k = 0; k < 2; ++k) {
    FictiveJog& f = jogs[k];
    f.handwheel = mode == JogMode::kHandwheel && (f.stepping || f.velocity != 0);
    if (!f.handwheel) continue;
    f.handwheel_target =
        f.stepping ? f.target : JogStopPoint(position[k], f.velocity, acceleration);
  }
}

}  // namespace vmt::control::channel
