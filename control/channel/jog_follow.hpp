#pragma once
// One coordinate of a manual move following its target (a handwheel's counts, a jog
// increment of a fictive axis): towards the target at most at `speed`, braking in time so as
// not to pass it, the velocity changing by at most `acceleration` per second. The real axes'
// handwheel and the fictive axes X1/Y1 (increments and handwheel) share it, so they brake alike.
#include <algorithm>
#include <cmath>

namespace vmt::control::channel {

/// Advances `position` by one cycle `dt` towards `target`; true once it is there (velocity 0).
inline bool FollowTarget(double& position, double& velocity, double target, double speed,
                         double acceleration, double dt) {
  const double to_go = target - position;
  const double braking = std::sqrt(2 * acceleration * std::abs(to_go));
  const double wanted = std::copysign(std::min(speed, braking), to_go);
  const double step = acceleration * dt;
  velocity = std::clamp(wanted, velocity - step, velocity + step);
  if (std::abs(to_go) <= std::abs(velocity * dt) || std::abs(to_go) < 1e-9) {
    position = target;
    velocity = 0;
    return true;
  }
  position += velocity * dt;
  return false;
}

}  // namespace vmt::control::channel
