#pragma once
// The feed along one block: the path parameter u runs from 0 to 1 with its rate limited by the
// programmed feed (times override) and its second derivative by the axes' acceleration. Online,
// one NC cycle at a time, so that override changes and feed hold act at once and the stop of a
// feed hold lies on the path (the interruption point).

#include <algorithm>
#include <cmath>

namespace vmt::control::channel {

struct PathProfile {
  double u = 0;          ///< 0 at the block start, 1 at its end
  double rate = 0;       ///< du/dt, 1/s
  double max_rate = 0;   ///< du/dt at 100 % override, 1/s
  double max_accel = 0;  ///< d2u/dt2, 1/s^2

  bool done() const { return u >= 1; }

  /// One cycle of dt seconds at `override` (0 = hold: brake to a stop on the path).
  void Advance(double dt, double override) {
    if (done()) return;
    const double remaining = 1 - u;
    // Fastest rate from which the end can still be reached braking at max_accel.
    const double braking = std::sqrt(2 * max_accel * remaining);
    const double target = std::min(max_rate * std::max(0.0, override), braking);
    const double step = max_accel * dt;
    rate = std::clamp(target, rate - step, rate + step);
    if (rate < 0) rate = 0;
    u += rate * dt;
    // Arrived: within the last cycle, or crawling at the end of the braking ramp.
    if (u >= 1 || (remaining < 1e-9 && override > 0) || (rate * dt >= remaining && override > 0)) {
      u = 1;
      rate = 0;
    }
  }
};

}  // namespace vmt::control::channel
