#include "control/channel/look_ahead.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vmt::control::channel {

double BrakingDistance(double from, double to, double accel, double jerk, double cycle_s) {
  if (from <= to) return 0;
  if (!(accel > 0)) return std::numeric_limits<double>::infinity();
  // The profile plans its last ramp a little longer (PathProfile::kRampLag) and lands on its
  // braking curve a cycle at a time: covered by the travel at the higher speed for that long.
  if (jerk <= 0) return (from * from - to * to) / (2 * accel) + from * cycle_s;
  // Jerk-limited, braking to a higher speed can take longer: the ramps take as long, at a
  // higher speed. The distance taken is the most over all speeds from `to` up, found where the
  // braking with a hold phase (speeds below the knee) and the one without have their maxima.
  const double j = std::min(jerk, PathProfile::kJerkCap * accel / cycle_s);
  const auto distance = [&](double t) {
    return path_profile_detail::BrakeTo(from, 0, t, j, accel, 0).distance;
  };
  const double knee = from - accel * accel / j;
  double most = distance(to);
  if (knee > to) most = std::max(most, distance(std::clamp(accel * accel / (2 * j), to, knee)));
  most = std::max(most, distance(std::clamp(from / 3, std::max(to, knee), from)));
  return most + from * PathProfile::kRampLag * cycle_s;
}

double CornerSpeed(double cos_turn, double accel) {
  if (cos_turn >= 1 - 1e-10) return std::numeric_limits<double>::infinity();
  // Junction deviation: the corner is rounded by an arc tangent to both directions whose
  // closest point lies kCornerDeviation from the corner; s = cos(turn / 2).
  const double s = std::sqrt(std::max(0.0, (1 + cos_turn) / 2));
  if (s <= 0) return 0;
  return std::sqrt(accel * kCornerDeviation * s / (1 - s));
}

void PlanTargets(double length, double max_speed, double accel, double jerk,
                 std::span<const LookAheadLeg> legs, std::vector<SpeedTarget>& out) {
  out.clear();
  double distance = length, feed = max_speed, least_accel = accel;
  double least_jerk = jerk > 0 ? jerk : HUGE_VAL;
  for (const LookAheadLeg& leg : legs) {
    const double corner = CornerSpeed(leg.cos_turn, std::min(leg.accel, least_accel));
    out.push_back({distance, corner, std::min(feed, leg.max_speed), least_accel,
                   std::isfinite(least_jerk) ? least_jerk : 0, leg.jerk});
    distance += leg.length;
    feed = leg.max_speed;
    least_accel = std::min(least_accel, leg.accel);
    if (leg.jerk > 0) least_jerk = std::min(least_jerk, leg.jerk);
  }
  out.push_back({distance, 0, 0, least_accel, std::isfinite(least_jerk) ? least_jerk : 0});
}

void ProfileTargets(std::span<const SpeedTarget> targets, double length, double override,
                    std::vector<ProfileTarget>& out) {
  out.clear();
  const double feed_scale = std::max(1.0, override);
  for (const SpeedTarget& t : targets)
    out.push_back({t.distance / length, std::min(t.corner, t.feed * feed_scale) / length,
                   t.accel / length, t.jerk / length, &t != &targets.back(),
                   t.settle_jerk / length});
}

}  // namespace vmt::control::channel
