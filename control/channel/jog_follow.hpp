#pragma once
// One coordinate of a manual move following its target (a handwheel's counts, a jog
// increment of a fictive axis): towards the target at most at `speed`, braking in time so as
// not to pass it, the velocity changing by at most `acceleration` per second. The real axes'
// handwheel and the fictive axes X1/Y1 (increments and handwheel) share it, so they brake alike;
// the jog mode's rules for switching while an axis moves are shared below for the same reason.
#include <algorithm>
#include <cmath>

#include "control/axes/axis_parameters.hpp"

namespace vmt::control::channel {

/// Cxx.021 jogging speed - rapid of `axis`, half its rapid if not given.
inline double JogRapid(const axes::AxisParameters& axis) {
  return axis.jog_rapid_per_s > 0 ? axis.jog_rapid_per_s : axis.rapid_per_s / 2;
}

/// Whether a jogged axis runs an increment this cycle, or may start one: an increment under
/// way runs to its end whatever the jog mode becomes, and a continuous jog (or a handwheel's
/// move) still at `velocity` when increments are selected brakes to a stop first; else it
/// would stand still within a cycle and keep its speed for the next continuous jog.
inline bool JogStepping(bool stepping, double increment, double velocity) {
  return stepping || (increment > 0 && velocity == 0);
}

/// Where an axis moving at `velocity` comes to rest braking at `acceleration`: the handwheel
/// selected while a continuous jog brakes counts from there, so the jog brakes as it would have.
inline double JogStopPoint(double position, double velocity, double acceleration) {
  return velocity == 0 ? position : position + velocity * std::abs(velocity) / (2 * acceleration);
}

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
