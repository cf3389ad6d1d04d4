#pragma once
// The feed along one block: the path parameter u runs from 0 to 1 with its rate limited by the
// programmed feed (times override), its second derivative by the axes' acceleration and, when a
// jerk limit is set, its third derivative by the jerk (an S-curve). Online, one NC cycle at a
// time, so that override changes and feed hold act at once and the stop of a feed hold lies on
// the path (the interruption point). With look-ahead the block may end at a speed (end_rate) at
// which the next block goes on.
//
// Without a jerk limit (max_jerk 0) the profile is the acceleration-limited trapezoid it has
// always been. With one it is a discrete-time controller that picks, each cycle, the
// acceleration at the cycle's end (see Cycle for the shape within the cycle; the state is
// integrated exactly):
//  1. Speed: the highest acceleration from which the rate, with the acceleration then brought
//     to zero at full jerk, stays at or below max_rate * override (above it, after an override
//     reduction: the lowest from which it stays at or above it). The rate lands on that
//     limiting parabola every cycle and settles on the target exactly, without overshoot.
//  2. Path end: if that acceleration leaves a state from which braking to end_rate (BrakeTo)
//     needs more than the rest of the block, the largest acceleration that lands on the
//     braking curve instead, found by a few steps of regula falsi. Braking thus follows the
//     curve, which is time-optimal up to the margin below.
//  3. End: when the braking curve ends within the cycle, u becomes exactly 1 with rate
//     end_rate and accel 0. From the curve that last step stays within the jerk limit; it
//     passes it only when the state could not follow the curve: a braking that lasts only two
//     or three cycles (seen: up to 1.15 max_jerk * dt, in under 0.1 % of random moves), or a
//     carried-in state that cannot brake in time.
// The last ramp of the braking curve is planned 0.75 cycle longer than at full jerk: the margin
// lets the discrete controller land on the curve where the continuous curve switches into it
// part-way through a cycle. With the discretisation, a rest-to-rest move takes less than 2
// cycles longer than the analytic time-optimal S-curve (worst seen in the tests: 1.9).
// Feed hold (override 0) brakes at the full limits to rest (rate 0, accel 0) on the path.

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace vmt::control::channel {

namespace path_profile_detail {

/// Distance (in u) and time (s) of one braking manoeuvre.
struct Braking {
  double distance = 0;
  double time = 0;
};

/// Braking from rate v and acceleration a down to rate `to` with the acceleration back at zero:
/// jerk -jerk down to a hold level h, h kept, then a last ramp back to zero. h is as deep as
/// needed, at most -decel, or a itself when that is already lower. The last ramp is linear and
/// takes |h| / jerk + lag seconds, shedding h^2 / (2 jerk) + |h| lag / 2 of rate: the lag leaves
/// a discrete-time controller room to start it part-way through a cycle. When the rate is
/// already too close to `to` for that ramp, the ramp is steeper, up to jerk; beyond that the rate
/// falls through `to` before the acceleration is back at zero, and the distance is that to the
/// crossing. Meaningful when the rate must come down: v + max(a, 0)^2 / (2 jerk) > to.
inline Braking BrakeTo(double v, double a, double to, double jerk, double decel, double lag) {
  // Rate shed by the last ramp from acceleration h < 0.
  const auto shed = [&](double h) { return h * h / (2 * jerk) - h * lag / 2; };
  const double dv = v - to;
  if (a < 0 && dv <= shed(a)) {
    if (dv <= 0) return {};
    const double t = 2 * dv / -a;  // the last ramp alone, ending at `to`
    if (a * a <= 2 * jerk * dv) return {t * (to + dv / 3), t};
    const double root = std::sqrt(std::max(0.0, a * a - 2 * jerk * dv));
    const double tc = 2 * dv / (root - a);
    return {tc * (v + tc * (a / 2 + tc * jerk / 6)), tc};
  }
  // Depth y = -h without a hold phase: ramp down from a to h, last ramp from h to zero:
  // dv + a^2 / (2 jerk) = y^2 / jerk + y lag / 2.
  const double c = std::max(0.0, dv + a * a / (2 * jerk));
  const double y = 2 * c / (lag / 2 + std::sqrt(lag * lag / 4 + 4 * c / jerk));
  const double deepest = std::min(-decel, a);
  const double hold = std::max(-y, deepest);
  const double t1 = (a - hold) / jerk;
  const double v1 = v + (a * a - hold * hold) / (2 * jerk);
  const double s3 = shed(hold);
  const double t2 = -y < deepest ? std::max(0.0, (v1 - to - s3) / -hold) : 0;
  const double t3 = -hold / jerk + lag;
  const double d =
      t1 * (v + t1 * (a / 2 - t1 * jerk / 6)) + t2 * (v1 + t2 * hold / 2) + t3 * (to + s3 / 3);
  return {d, t1 + t2 + t3};
}

/// Rate and distance after one cycle of dt seconds from rate v and acceleration a to
/// acceleration x (|x - a| <= jerk * dt). A falling acceleration falls at full jerk and then
/// stays at x (deceleration builds up as early as it can); a rising one rises linearly through
/// the cycle (as the last ramp of a braking does).
struct CycleEnd {
  double distance = 0;
  double rate = 0;
};

inline CycleEnd Cycle(double v, double a, double x, double jerk, double dt) {
  if (x >= a) return {dt * (v + dt * (2 * a + x) / 6), v + (a + x) * dt / 2};
  const double ramp = (a - x) / jerk, rest = dt - ramp;
  const double v_ramp = v + (a + x) / 2 * ramp;
  return {ramp * (v + ramp * (a / 2 - ramp * jerk / 6)) + rest * (v_ramp + rest * x / 2),
          v_ramp + x * rest};
}

/// Coefficients of f(x) = alpha x^2 + beta x + gamma.
struct Quadratic {
  double alpha = 0, beta = 0, gamma = 0;
  double operator()(double x) const { return (alpha * x + beta) * x + gamma; }
};

/// Root of a rising function of x on [a - jerk * dt, a + jerk * dt] that is a quadratic between
/// kinks at x = a and x = 0; piece(x) gives the quadratic at x. -infinity if the function is
/// positive all along, +infinity if it is negative all along.
template <class Piece>
double RisingRoot(double a, double jerk, double dt, const Piece& piece) {
  const auto f = [&](double x) { return piece(x)(x); };
  double left = a - jerk * dt, right = a + jerk * dt;
  if (f(left) > 0) return -std::numeric_limits<double>::infinity();
  if (f(right) < 0) return std::numeric_limits<double>::infinity();
  for (const double kink : {a, 0.0})
    if (kink > left && kink < right) (f(kink) <= 0 ? left : right) = kink;
  const Quadratic q = piece((left + right) / 2);
  const double root = std::sqrt(std::max(0.0, q.beta * q.beta - 4 * q.alpha * q.gamma));
  // Where the quadratic rises (2 alpha x + beta = root), in the form without cancellation.
  double x = left;
  if (q.beta >= 0 && q.beta + root > 0)
    x = -2 * q.gamma / (q.beta + root);
  else if (q.alpha != 0)
    x = (root - q.beta) / (2 * q.alpha);
  return std::clamp(x, left, right);
}

/// Highest acceleration x at the end of a cycle (see Cycle) such that the rate, with the
/// acceleration then brought to zero at full jerk (settle_jerk, if lower: a later block's),
/// never exceeds v + gap (the rate is v at the cycle's start; gap may be negative). +-infinity
/// as RisingRoot.
inline double CapAccel(double gap, double a, double jerk, double dt, double settle_jerk = 0) {
  const double settle = settle_jerk > 0 ? settle_jerk : jerk;
  // Highest rate ahead minus v + gap: the rate gained in the cycle plus max(x, 0)^2 / (2 jerk).
  return RisingRoot(a, jerk, dt, [&](double x) {
    const double peak = x > 0 ? 1 / (2 * settle) : 0;
    if (x >= a) return Quadratic{peak, dt / 2, a * dt / 2 - gap};
    return Quadratic{1 / (2 * jerk) + peak, dt - a / jerk, a * a / (2 * jerk) - gap};
  });
}

/// Lowest acceleration x at the end of a cycle (see Cycle) such that the rate, with the
/// acceleration then brought to zero at full jerk, never falls below v - gap. +-infinity as
/// RisingRoot.
inline double FloorAccel(double gap, double a, double jerk, double dt) {
  // Lowest rate ahead minus v - gap: the rate gained in the cycle minus min(x, 0)^2 / (2 jerk).
  return RisingRoot(a, jerk, dt, [&](double x) {
    const double dip = x < 0 ? -1 / (2 * jerk) : 0;
    if (x >= a) return Quadratic{dip, dt / 2, a * dt / 2 + gap};
    return Quadratic{1 / (2 * jerk) + dip, dt - a / jerk, a * a / (2 * jerk) + gap};
  });
}

/// Distance until the rate, braking as hard as it may, first comes down to `to`, for a limit the
/// path passes on its way down (a corner, a slower block): the deceleration need not be back at
/// zero there, only shallow enough that the rate could still come to rest from it without
/// falling below zero (at most sqrt(jerk to), with a margin). A rising acceleration is brought to
/// zero at `settle_jerk` (<= jerk: the limit of the block beyond). Meaningful when the rate must
/// come down: PeakRate(v, a, settle_jerk) > to.
inline double CrossAt(double v, double a, double to, double jerk, double decel, double settle_jerk,
                      double lag) {
  // Distance of a ramp of the acceleration from a0 at jerk js (signed) for t seconds.
  const auto ramp = [](double v0, double a0, double js, double t) {
    return t * (v0 + t * (a0 / 2 + t * js / 6));
  };
  double distance = 0;
  if (a > 0) {
    const double t = a / settle_jerk;
    distance = ramp(v, a, -settle_jerk, t);
    v += a * a / (2 * settle_jerk);
    a = 0;
  }
  // From the deceleration at `to` the rate falls by deepest^2 / (2 jerk) = to / 2 more while
  // the acceleration comes back to zero: well clear of zero, where the profile's floor would
  // make it ease off early. A discrete-time controller follows the curve a cycle at a time:
  // aim lower by the rate that deceleration sheds in `lag` seconds.
  const double deepest_at_to = std::min(decel, std::sqrt(jerk * to));
  to = std::max(0.0, to - deepest_at_to * lag);
  if (v <= to) return distance;
  const double dv = v - to;
  if (-a <= deepest_at_to) {
    // Down to -h, held, and back up to -deepest_at_to where the rate reaches `to`.
    const double h = std::sqrt((2 * jerk * dv + a * a + deepest_at_to * deepest_at_to) / 2);
    if (h <= deepest_at_to) {
      // Reaches `to` while the deceleration still builds: v + a t - jerk t^2 / 2 = to.
      const double t = (a + std::sqrt(a * a + 2 * jerk * dv)) / jerk;
      return distance + ramp(v, a, -jerk, t);
    }
    const double depth = std::min(h, decel);
    const double t1 = (depth + a) / jerk;
    const double v1 = v + (a * a - depth * depth) / (2 * jerk);
    const double shed_last = (depth * depth - deepest_at_to * deepest_at_to) / (2 * jerk);
    const double t2 = std::max(0.0, (v1 - to - shed_last) / depth);
    const double v2 = v1 - depth * t2;
    return distance + ramp(v, a, -jerk, t1) + t2 * (v1 - depth * t2 / 2) +
           ramp(v2, -depth, jerk, (depth - deepest_at_to) / jerk);
  }
  // Decelerating harder already than allowed at `to`: held, then eased off to it.
  const double shed_easing = (a * a - deepest_at_to * deepest_at_to) / (2 * jerk);
  if (shed_easing >= dv) {
    // Reaches `to` while easing off: v + a t + jerk t^2 / 2 = to.
    const double t = (-a - std::sqrt(std::max(0.0, a * a - 2 * jerk * dv))) / jerk;
    return distance + ramp(v, a, jerk, t);
  }
  const double hold = (dv - shed_easing) / -a;
  const double v1 = v + a * hold;
  return distance + hold * (v + a * hold / 2) + ramp(v1, a, jerk, (-a - deepest_at_to) / jerk);
}

/// Rate reached when the acceleration is brought to zero at full jerk, if it is rising; the
/// rate itself otherwise (the highest rate ahead).
inline double PeakRate(double v, double a, double jerk) {
  return a > 0 ? v + a * a / (2 * jerk) : v;
}

}  // namespace path_profile_detail

/// A speed limit ahead of the block (look-ahead), in the block's u: the rate must be down to
/// `rate` where u reaches `u`, braking at no more than `decel` and `jerk` (0: the profile's).
struct ProfileTarget {
  double u = 1;
  double rate = 0;
  double decel = 0;
  double jerk = 0;
  /// Passed on the way: the rate must be down to `rate` there, but may still be falling (a
  /// corner or a slower block); otherwise the path comes to rest or to a steady rate there.
  bool pass = false;
  /// Jerk of the block beyond a passed limit (0: as `jerk`): a rising acceleration must settle
  /// within it without passing `rate`.
  double settle_jerk = 0;
};

struct PathProfile {
  double u = 0;          ///< 0 at the block start, 1 at its end
  double rate = 0;       ///< du/dt, 1/s
  double max_rate = 0;   ///< du/dt at 100 % override, 1/s
  double max_accel = 0;  ///< |d2u/dt2| limit, 1/s^2
  double max_jerk = 0;   ///< |d3u/dt3| limit, 1/s^3; 0: none (acceleration-limited trapezoid)
  double accel = 0;      ///< d2u/dt2 now, 1/s^2 (state; 0 at rest)
  /// du/dt allowed when u reaches 1, 1/s (look-ahead: the next block goes on at that speed). The
  /// profile arrives at u = 1 with rate <= end_rate, exactly end_rate (and accel 0) when it had
  /// to brake to it, else with the acceleration it still has, and is then done(); it never
  /// passes u = 1. In feed hold the end is still reached at up to end_rate when the stop does not
  /// fit into the block: the caller goes on braking in the next block (ContinueFrom with
  /// override 0); with end_rate 0 the stop is at u = 1 at the latest.
  double end_rate = 0;
  /// Look-ahead: speed limits at and beyond the block's end, sorted by u, the last one at rest.
  /// With them the profile brakes for each in time, whichever block it lies in, and runs
  /// through u = 1 with the rate and acceleration it has (end_rate unused): done() with u > 1
  /// by the distance the cycle went on into the next block. The caller keeps them alive.
  std::span<const ProfileTarget> ahead;

  bool done() const { return u >= 1; }

  /// Starts this block where `previous` ended, for look-ahead: the path speed and acceleration
  /// carry over, so rate and accel scale by length_ratio = previous block length / this block
  /// length. Sets u = 0; limits and end_rate are the caller's to set.
  void ContinueFrom(const PathProfile& previous, double length_ratio) {
    u = 0;
    rate = previous.rate * length_ratio;
    accel = previous.accel * length_ratio;
  }

  /// One cycle of dt seconds at `override` (0 = hold: brake to a stop on the path).
  void Advance(double dt, double override) {
    if (done() || !(dt > 0)) return;
    // Limits ahead that brake with a jerk limit need the jerk-limited profile, even in a block
    // whose own jerk is not limited.
    const bool jerk_ahead =
        std::any_of(ahead.begin(), ahead.end(), [](const ProfileTarget& t) { return t.jerk > 0; });
    if ((max_jerk > 0 || jerk_ahead) && max_accel > 0)
      AdvanceJerkLimited(dt, override);
    else
      AdvanceTrapezoid(dt, override);
  }

  // Jerk used at most, in max_accel per cycle: beyond, the acceleration switches within a
  // quarter cycle anyway, and the cap keeps the arithmetic finite for huge limits.
  static constexpr double kJerkCap = 4;
  // Cycles by which the last ramp of braking to the block end is planned longer (see BrakeTo).
  static constexpr double kRampLag = 0.75;

 private:
  // Closer to the end than this (in u) the block counts as done once it is not held.
  static constexpr double kEndSlack = 1e-12;
  // Most steps of the search for the acceleration that lands on the braking curve (about one
  // cycle in sixteen searches; three in four searches need no step, one in two hundred all).
  static constexpr int kRootSteps = 16;

  // The acceleration-limited profile as it was before the jerk limit (end_rate added).
  void AdvanceTrapezoid(double dt, double override) {
    const double remaining = 1 - u;
    const double end = std::max(0.0, end_rate);
    // Fastest rate for this cycle from which, where the cycle ends, braking at `decel` still
    // reaches `to` within `to_go`: v^2 + 2 decel dt v <= to^2 + 2 decel to_go. Sampled at the
    // cycle's end, not its start, so that the steps land on the braking curve, not beyond.
    const auto braking_rate = [dt](double to, double decel, double to_go) {
      const double b = decel * dt;
      return std::sqrt(b * b + to * to + 2 * decel * std::max(0.0, to_go)) - b;
    };
    // Without limits ahead: the trapezoid as it always was, sampled at the cycle's start.
    double braking = std::sqrt(end * end + 2 * max_accel * remaining);
    if (!ahead.empty()) {
      braking = std::numeric_limits<double>::infinity();
      for (const ProfileTarget& t : ahead)
        if (t.u >= u)
          braking = std::min(
              braking, braking_rate(t.rate, t.decel > 0 ? std::min(t.decel, max_accel) : max_accel,
                                    t.u - u));
    }
    const double target = std::min(max_rate * std::max(0.0, override), braking);
    const double step = max_accel * dt;
    const double previous = rate;
    rate = std::clamp(target, rate - step, rate + step);
    if (rate < 0) rate = 0;
    u += rate * dt;
    accel = (rate - previous) / dt;
    if (!ahead.empty()) return;  // through the block's end at speed
    // Arrived: within the last cycle, or crawling at the end of the braking ramp.
    if (u >= 1 || (remaining < 1e-9 && override > 0) || (rate * dt >= remaining && override > 0)) {
      u = 1;
      rate = std::min(rate, end);
      accel = 0;
    }
  }

  void AdvanceJerkLimited(double dt, double override) {
    namespace d = path_profile_detail;
    struct State {
      double u, v, a;
    };
    const double max_a = max_accel;
    const double jerk =
        max_jerk > 0 ? std::min(max_jerk, kJerkCap * max_a / dt) : kJerkCap * max_a / dt;
    const double jdt = jerk * dt;
    const double lag = kRampLag * dt;
    const double end = std::max(0.0, end_rate);
    const double target = std::max(0.0, max_rate * std::max(0.0, override));
    const double remaining = 1 - u;
    const double v = std::max(0.0, rate), a = std::clamp(accel, -max_a, max_a);
    const auto arrive = [&](double end_v, double end_a) {
      u = 1;
      rate = end_v;
      accel = end_a;
    };
    // Without limits ahead: end_rate at u = 1, where the profile arrives. With them: each of
    // them, and the path runs on through u = 1.
    const bool through = !ahead.empty();
    const ProfileTarget end_target{1, end, max_a, jerk};
    const std::span<const ProfileTarget> targets =
        through ? ahead : std::span<const ProfileTarget>(&end_target, 1);
    const auto jerk_of = [&](const ProfileTarget& t) {
      return t.jerk > 0 ? std::min(t.jerk, jerk) : jerk;
    };
    const auto decel_of = [&](const ProfileTarget& t) {
      return t.decel > 0 ? std::min(t.decel, max_a) : max_a;
    };
    if (!through && remaining <= kEndSlack && override > 0) return arrive(std::min(v, end), 0);

    // How precisely a cycle lands on the braking curve (see below): a billionth of the travel
    // in the previous cycle or this one, and u's rounding.
    const double precision =
        1e-9 * (v + max_a * dt) * dt + 4 * std::numeric_limits<double>::epsilon();
    // The braking curve to end_rate ends within this cycle, and the rest of the block is no
    // longer than what the rest of the cycle could still cover within the limits (at end_rate,
    // and by speeding up towards the target and back): arrive.
    if (!through && d::PeakRate(v, a, jerk) > end) {
      const d::Braking b = d::BrakeTo(v, a, end, jerk, max_a, lag);
      const double t = dt - b.time, cruise = std::min(end, target);
      const double spare =
          cruise * t + std::min({jerk * t * t * t / 32, max_a * t * t / 4, (target - cruise) * t});
      if (t >= 0 && b.distance + spare + precision >= remaining) return arrive(end, 0);
    }
    // At rest, not held, and the rest of the block no longer than what a pulse of the
    // acceleration within the limits covers in this cycle: arrive, at rest. A block shorter than
    // such a pulse would otherwise ask the search below for an acceleration far finer than it
    // resolves, find none and never start.
    if (!through && v <= 0 && std::abs(a) <= jdt && target > 0) {
      const double pulse =
          std::min({jerk * dt * dt * dt / 32, max_a * dt * dt / 4, target * dt});
      if (pulse + precision >= remaining) return arrive(0, 0);
    }

    // Candidate states at the end of the cycle.
    const auto step = [&](double x) {
      const d::CycleEnd c = d::Cycle(v, a, x, jerk, dt);
      return State{u + c.distance, c.rate, x};
    };
    // Distance by which braking to target t from s overshoots it (<= 0: fits).
    const auto settle_jerk_of = [&](const ProfileTarget& t) {
      return t.settle_jerk > 0 ? std::min(t.settle_jerk, jerk_of(t)) : jerk_of(t);
    };
    const auto overshoot = [&](const ProfileTarget& t, const State& s) {
      const double distance =
          t.pass ? d::CrossAt(s.v, s.a, t.rate, jerk_of(t), decel_of(t), settle_jerk_of(t), lag)
                 : d::BrakeTo(s.v, s.a, t.rate, jerk_of(t), decel_of(t), lag).distance;
      return distance - (t.u - s.u);
    };
    const auto fits_one = [&](const ProfileTarget& t, const State& s) {
      return d::PeakRate(s.v, s.a, settle_jerk_of(t)) <= t.rate || overshoot(t, s) <= 0;
    };
    const auto fits = [&](const State& s) {
      return std::all_of(targets.begin(), targets.end(),
                         [&](const ProfileTarget& t) { return fits_one(t, s); });
    };

    // 1. Speed. Accelerations reachable this cycle, and the lowest that keeps the rate >= 0
    // with the acceleration then brought to zero at full jerk.
    const double x_min = std::max(a - jdt, -max_a), x_max = std::min(a + jdt, max_a);
    const double x_floor = std::clamp(d::FloorAccel(v, a, jerk, dt), x_min, x_max);
    double x;
    const double up = d::CapAccel(target - v, a, jerk, dt);
    if (up >= x_min)
      x = std::min(up, x_max);
    else if (v > target)
      x = std::clamp(d::FloorAccel(v - target, a, jerk, dt), x_min, x_max);
    else
      x = x_min;
    x = std::max(x, x_floor);
    // Settle onto the target when the acceleration can reach zero within the cycle at a rate
    // close to it (closer than an acceleration pulse within one cycle could move it).
    const double settle_t = std::abs(a) / jerk;
    const double flat_v = v + a * settle_t / 2;
    const double settle_tolerance = std::min(jdt * dt / 8, max_a * dt / 4);
    bool settle = settle_t <= dt && std::abs(flat_v - target) <= settle_tolerance;
    State next;
    if (settle) {
      const double t = settle_t, j = a > 0 ? -jerk : jerk;
      next = State{u + t * (v + t * (a / 2 + t * j / 6)) + target * (dt - t), target, 0};
      settle = fits(next);
    }

    // 2. Limits ahead: the largest acceleration from which braking to each still fits.
    if (!settle) {
      next = step(x);
      for (const ProfileTarget& t : targets) {
        if (fits_one(t, next)) continue;
        const double tj = settle_jerk_of(t);
        const auto g_of = [&](double xx) { return overshoot(t, step(xx)); };
        // At or below x_cap the rate stays <= the target's anyway; above, overshoot rises with
        // x. Lowering x for one target only helps the others.
        const double x_cap = d::CapAccel(t.rate - v, a, jerk, dt, tj);
        double lo = std::max(x_floor, x_cap), hi = x;
        if (through && lo >= hi) {
          // A limit ahead that no acceleration meets any more: brake as hard as possible.
          x = std::min(x, x_floor);
          next = step(x);
          continue;
        }
        if (lo < hi) {
          double g_lo = g_of(lo), g_hi = overshoot(t, next);
          // The overshoot has a kink where the cycle turns from falling to rising: bracket
          // the root on one side of it.
          if (g_lo <= 0 && a > lo && a < hi) {
            const double g = g_of(a);
            (g <= 0 ? lo : hi) = a;
            (g <= 0 ? g_lo : g_hi) = g;
          }
          if (g_lo > 0) {
            hi = lo;  // capped at the target's rate, or braking as hard as it can
          } else {
            // Illinois (regula falsi that halves the weight of an end kept twice), with a
            // bisection every other step unless the bracket halved since: the overshoot is
            // steep where the rate would dip below the target's.
            int kept = 0;
            const double tolerance = 1e-9 * jdt, landed = -precision;
            double width = hi - lo;
            for (int i = 0; i < kRootSteps && g_lo < landed && hi - lo > tolerance; ++i) {
              double m = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
              if (i % 2 == 1) {
                if (hi - lo > width / 2) m = (lo + hi) / 2;
                width = hi - lo;
              }
              if (!(m > lo && m < hi)) m = (lo + hi) / 2;
              const double g = g_of(m);
              if (g <= 0) {
                lo = m, g_lo = g;
                if (kept == -1) g_hi /= 2;
                kept = -1;
              } else {
                hi = m, g_hi = g;
                if (kept == 1) g_lo /= 2;
                kept = 1;
              }
            }
            hi = lo;
          }
        }
        x = std::min(hi, x);
        next = step(x);
      }
      // A deceleration turning into an acceleration within the cycle must not turn the rate
      // negative on the way (near a stop): end the cycle at zero acceleration instead, or, if
      // the rate reaches zero even so, at rest (a step within the jerk limit from a state on
      // or above FloorAccel's parabola).
      if (a < 0 && x > 0 && 2 * v * (x - a) < a * a * dt) {
        if (x_floor <= 0)
          next = step(0);
        else if (-a <= jdt)
          next = State{u + v * v / (-2 * a), 0, 0};
      }
    }

    // At rest with the path to go and a feed: a state that does not move repeats itself in every
    // cycle, so the block would never end. The search above resolves the acceleration to a
    // billionth of jerk * dt in a few steps; the one that lands on the braking curve may lie
    // below that. The overshoot is continuous in x and -(distance to go) at x = 0, so halving
    // from the largest reachable acceleration finds one that fits, and the path starts.
    if (next.u <= u && next.v <= 0 && v <= 0 && target > 0 && remaining > 0) {
      for (double xx = x_max; xx > 0 && std::isfinite(xx); xx /= 2) {
        const State s = step(xx);
        if (s.u > u && fits(s)) {
          next = s;
          break;
        }
      }
    }

    // 3. Commit. A negative rate or u going back only come from a carried-in state that
    // cannot stop in time.
    if (next.v < 0) {
      next.v = 0;
      next.a = std::max(next.a, 0.0);
    }
    next.u = std::max(next.u, u);
    if (through) {
      // Through the block's end at speed: the rest of the cycle's travel belongs to the next.
      u = next.u >= 1 - kEndSlack ? std::max(next.u, 1.0) : next.u;
      rate = next.v;
      accel = next.a;
      return;
    }
    // Arrived: past the end, or short of it by a rounding remainder, unless that last step of
    // the acceleration to zero would pass the jerk limit (the remainder is then one more cycle).
    if (next.u >= 1 || (1 - next.u <= kEndSlack && override > 0 && std::abs(a) <= jdt)) {
      // At rest for end_rate 0; above end_rate only from a carried-in state that could not
      // brake in time.
      if (next.v > end || end <= 0) return arrive(end, 0);
      // Close below end_rate (or settling at a lower target) with an acceleration that may go
      // to zero in this cycle: exactly there.
      if (std::abs(a) <= jdt) {
        const double close = std::abs(next.v - end) <= settle_tolerance ? end : target;
        if (close <= target && std::abs(next.v - close) <= settle_tolerance &&
            std::abs(close - v) <= max_a * dt)
          return arrive(close, 0);
      }
      return arrive(next.v, next.a);
    }
    u = next.u;
    rate = next.v;
    accel = next.a;
  }
};

}  // namespace vmt::control::channel
