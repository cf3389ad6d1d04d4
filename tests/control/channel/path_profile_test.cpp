// The path-parameter profile on its own: rest-to-rest time against the analytic time-optimal
// S-curve, acceleration and jerk limits in every cycle, arrival at u = 1 exactly and never past
// it without creeping, ending at a speed (look-ahead) and carrying it into the next block, feed
// hold on the path, override changes, the old trapezoid without a jerk limit, extreme limits and
// random profiles with override changes and holds, blocks far shorter than a cycle.

#include "control/channel/path_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace vmt::control::channel {
namespace {

constexpr double kDt = 1e-3;  // the NC cycle
constexpr double kSlack = 1e-9;

// The profile before the jerk limit, kept as the reference for max_jerk = 0.
struct OldPathProfile {
  double u = 0;
  double rate = 0;
  double max_rate = 0;
  double max_accel = 0;

  bool done() const { return u >= 1; }

  void Advance(double dt, double override) {
    if (done()) return;
    const double remaining = 1 - u;
    const double braking = std::sqrt(2 * max_accel * remaining);
    const double target = std::min(max_rate * std::max(0.0, override), braking);
    const double step = max_accel * dt;
    rate = std::clamp(target, rate - step, rate + step);
    if (rate < 0) rate = 0;
    u += rate * dt;
    if (u >= 1 || (remaining < 1e-9 && override > 0) || (rate * dt >= remaining && override > 0)) {
      u = 1;
      rate = 0;
    }
  }
};

// Time from rest to speed v (and, mirrored, from v to rest) under accel and jerk limits.
double RampTime(double v, double accel, double jerk) {
  return v * jerk >= accel * accel ? v / accel + accel / jerk : 2 * std::sqrt(v / jerk);
}

// Analytic time-optimal rest-to-rest time over `distance` (7-phase S-curve).
double SCurveTime(double distance, double rate, double accel, double jerk) {
  const double ramp = RampTime(rate, accel, jerk);
  if (rate * ramp <= distance) return 2 * ramp + (distance - rate * ramp) / rate;
  // The rate is not reached: the peak rate v with v * RampTime(v) = distance.
  double lo = 0, hi = rate;
  for (int i = 0; i < 200; ++i) {
    const double m = (lo + hi) / 2;
    (m * RampTime(m, accel, jerk) < distance ? lo : hi) = m;
  }
  return 2 * RampTime(hi, accel, jerk);
}

// Analytic acceleration-limited rest-to-rest time (trapezoid).
double TrapezoidTime(double distance, double rate, double accel) {
  if (rate * rate / accel <= distance) return rate / accel + distance / rate;
  return 2 * std::sqrt(distance / accel);
}

struct Sample {
  double u, rate, accel, override;
};

// Runs until done or max_cycles; trace[0] is the start, trace[k] the state after cycle k, run at
// trace[k].override.
std::vector<Sample> Simulate(PathProfile p, const std::function<double(int)>& override_at,
                             int max_cycles) {
  std::vector<Sample> trace{{p.u, p.rate, p.accel, 1}};
  for (int k = 1; k <= max_cycles && !p.done(); ++k) {
    const double override = override_at(k);
    p.Advance(kDt, override);
    trace.push_back({p.u, p.rate, p.accel, override});
  }
  return trace;
}

std::vector<Sample> Simulate(const PathProfile& p, int max_cycles = 10'000'000) {
  return Simulate(
      p, [](int) { return 1.0; }, max_cycles);
}

int Cycles(const std::vector<Sample>& trace) { return static_cast<int>(trace.size()) - 1; }

std::string Describe(const PathProfile& p) {
  char s[200];
  std::snprintf(s, sizeof s, "max_rate %.17g max_accel %.17g max_jerk %.17g end_rate %.17g",
                p.max_rate, p.max_accel, p.max_jerk, p.end_rate);
  return s;
}

// What the final cycle (the arrival at u = 1) did.
struct Arrival {
  double accel_step = 0;  // |accel change| in units of max_jerk * dt
  double rate_step = 0;   // |rate change| in units of max_accel * dt
};

// Checks every cycle of a trace of p: no NaN, u monotonic and never past 1, rate >= 0, the
// acceleration and jerk limits (jerk except in the final cycle), rate <= max_rate * override
// except while braking down after an override reduction (or from a carried-in speed), the end at
// rate <= end_rate. Returns an empty string if all hold, else the first violation.
std::string CheckTrace(const PathProfile& p, const std::vector<Sample>& trace,
                       Arrival* arrival = nullptr) {
  const double jerk_step = p.max_jerk * kDt * (1 + kSlack);
  const double accel_max = p.max_accel * (1 + kSlack);
  bool braking_down = trace[0].rate > p.max_rate * (1 + kSlack);
  for (size_t k = 1; k < trace.size(); ++k) {
    const Sample &s = trace[k], &prev = trace[k - 1];
    const auto fail = [&](const char* what) {
      std::ostringstream where;
      where.precision(17);
      where << what << " in cycle " << k << " (u " << s.u << " rate " << s.rate << " accel "
            << s.accel << ", before u " << prev.u << " rate " << prev.rate << " accel "
            << prev.accel << ", override " << s.override << ") of " << Describe(p);
      return where.str();
    };
    if (!std::isfinite(s.u) || !std::isfinite(s.rate) || !std::isfinite(s.accel))
      return fail("not finite");
    if (s.u < prev.u) return fail("u decreased");
    if (s.u > 1) return fail("u past 1");
    if (s.rate < -1e-12) return fail("negative rate");
    if (std::abs(s.accel) > accel_max) return fail("acceleration limit");
    const bool final = s.u >= 1;
    if (!final && std::abs(s.accel - prev.accel) > jerk_step) return fail("jerk limit");
    // The rate cannot change by more than the acceleration limit allows in one cycle.
    if (!final && std::abs(s.rate - prev.rate) > p.max_accel * kDt * (1 + kSlack))
      return fail("rate step beyond max_accel * dt");
    const double limit = p.max_rate * s.override;
    // After a reduction the rate may go on rising while the acceleration is brought down.
    if (s.override < prev.override) braking_down = true;
    if (braking_down && s.rate <= limit * (1 + kSlack) && s.accel <= 0) braking_down = false;
    if (!braking_down && s.rate > limit * (1 + kSlack) + 1e-12) return fail("rate limit");
    if (final) {
      if (s.rate > p.end_rate * (1 + kSlack) + 1e-12) return fail("above end_rate");
      if (k != trace.size() - 1) return fail("went on after the end");
      if (arrival) {
        arrival->accel_step = std::abs(s.accel - prev.accel) / (p.max_jerk * kDt);
        arrival->rate_step = std::abs(s.rate - prev.rate) / (p.max_accel * kDt);
      }
    }
  }
  return "";
}

// A block of `length` (mm) at `feed` (mm/s) with axis limits accel (mm/s^2) and jerk (mm/s^3),
// in units of u.
PathProfile Block(double length, double feed, double accel, double jerk) {
  PathProfile p;
  p.max_rate = feed / length;
  p.max_accel = accel / length;
  p.max_jerk = jerk / length;
  return p;
}

struct Case {
  double length, feed, accel, jerk;
};

// Lengths from 1 um to 1 m: long blocks that cruise, blocks that reach the acceleration but not
// the feed, blocks that reach neither, blocks shorter than one cycle, huge and small jerk.
const std::vector<Case> kCases = {
    {100, 100, 4000, 40000},   {100, 100, 4000, 4e6},    {100, 500, 2000, 20000},
    {1000, 1000, 5000, 50000}, {10, 100, 4000, 40000},   {1, 100, 4000, 40000},
    {0.1, 100, 4000, 40000},   {0.01, 100, 4000, 40000}, {0.001, 100, 4000, 40000},
    {5, 50, 1000, 1e6},        {5, 50, 1000, 100},       {20, 200, 10000, 1e5},
    {0.3, 20, 500, 5000},      {50, 33.3, 777, 12345},   {2.5, 1000, 100, 1e4},
    {100, 100, 4000, 1e12},    {0.001, 1e5, 1e5, 1e12},  {1e-6, 100, 4000, 40000},
    {1e-3, 100, 4000, 1e9},    {250, 80, 800, 8000},     {7, 300, 3000, 3e4},
    {0.05, 10, 100, 1e3},      {40, 400, 4000, 4000},    {3, 60, 30000, 3e6},
};

TEST(PathProfileTest, RestToRestTimeIsNearTheAnalyticSCurve) {
  double worst = 0, worst_ratio = 0, worst_cycles = 0;
  for (const Case& c : kCases) {
    const PathProfile p = Block(c.length, c.feed, c.accel, c.jerk);
    const auto trace = Simulate(p);
    const double t = Cycles(trace) * kDt;
    const double best = SCurveTime(1, p.max_rate, p.max_accel, p.max_jerk);
    SCOPED_TRACE(Describe(p));
    EXPECT_TRUE(trace.back().u == 1);
    EXPECT_LE(t, 1.03 * best + 2 * kDt + 1e-12) << "analytic " << best;
    // Faster than optimal only by the rounding up of the last cycle.
    EXPECT_GE(t, best - kDt) << "analytic " << best;
    worst = std::max(worst, (t - 2 * kDt) / best);
    worst_ratio = std::max(worst_ratio, t / best);
    worst_cycles = std::max(worst_cycles, (t - best) / kDt);
  }
  std::printf(
      "table: worst time / analytic S-curve time %.4f, worst excess %.2f cycles, worst (time - 2 "
      "cycles) / analytic %.4f\n",
      worst_ratio, worst_cycles, worst);
}

TEST(PathProfileTest, LimitsHoldInEveryCycleAndTheEndIsReachedExactly) {
  double worst_accel_step = 0, worst_rate_step = 0;
  for (const Case& c : kCases) {
    const PathProfile p = Block(c.length, c.feed, c.accel, c.jerk);
    const auto trace = Simulate(p);
    Arrival arrival;
    EXPECT_EQ(CheckTrace(p, trace, &arrival), "");
    EXPECT_EQ(trace.back().u, 1.0) << Describe(p);
    EXPECT_EQ(trace.back().rate, 0.0) << Describe(p);
    EXPECT_EQ(trace.back().accel, 0.0) << Describe(p);
    // From the braking curve the last step stays within the jerk limit.
    EXPECT_LE(arrival.accel_step, 1 + kSlack) << Describe(p);
    worst_accel_step = std::max(worst_accel_step, arrival.accel_step);
    worst_rate_step = std::max(worst_rate_step, arrival.rate_step);
  }
  std::printf("worst final accel step %.3g max_jerk*dt, rate step %.3g max_accel*dt\n",
              worst_accel_step, worst_rate_step);
}

TEST(PathProfileTest, ReachesTheFeedAndTheAccelerationOfLongBlocks) {
  // 100 mm at 100 mm/s, 4000 mm/s^2, 400000 mm/s^3: both limits are reached.
  const PathProfile p = Block(100, 100, 4000, 400000);
  const auto trace = Simulate(p);
  double peak_rate = 0, peak_accel = 0, peak_decel = 0;
  for (const Sample& s : trace) {
    peak_rate = std::max(peak_rate, s.rate);
    peak_accel = std::max(peak_accel, s.accel);
    peak_decel = std::min(peak_decel, s.accel);
  }
  EXPECT_DOUBLE_EQ(peak_rate, p.max_rate);
  EXPECT_DOUBLE_EQ(peak_accel, p.max_accel);
  EXPECT_DOUBLE_EQ(peak_decel, -p.max_accel);
}

TEST(PathProfileTest, FinalRampDoesNotCreep) {
  // Start on the last phase of the braking curve (jerk +J up to rest at u = 1), tau before the
  // end: it must arrive within the cycle in which the curve ends, or the next.
  for (double jerk : {10.0, 1e3, 1e5, 1e7}) {
    for (double tau_cycles : {0.1, 0.5, 1.0, 1.5, 2.3, 3.7, 10.4, 57.9}) {
      const double tau = tau_cycles * kDt;
      PathProfile p;
      p.max_rate = 1e9;
      p.max_accel = 3 * jerk * tau + 1e-9;
      p.max_jerk = jerk;
      p.u = 1 - jerk * tau * tau * tau / 6;
      if (p.u >= 1) continue;
      p.rate = jerk * tau * tau / 2;
      p.accel = -jerk * tau;
      const auto trace = Simulate(p, 1000);
      SCOPED_TRACE(Describe(p) + " tau " + std::to_string(tau_cycles) + " cycles");
      EXPECT_EQ(CheckTrace(p, trace), "");
      EXPECT_LE(Cycles(trace), std::ceil(tau_cycles - 1e-9) + 1);
    }
  }
}

// Time-optimal braking time from rate v, acceleration a to rest under jerk and accel limits,
// the distance aside: a lower bound on the time any profile needs from that state.
double BrakingTime(double v, double a, double accel, double jerk) {
  if (a < 0 && v <= a * a / (2 * jerk)) return -a / jerk;
  const double peak = std::sqrt(jerk * v + a * a / 2);
  if (peak <= accel) return (a + peak) / jerk + peak / jerk;
  return (a + accel) / jerk + (v + a * a / (2 * jerk) - accel * accel / jerk) / accel +
         accel / jerk;
}

TEST(PathProfileTest, LastCyclesOfAFullMoveDoNotCreep) {
  // In the final ramp of each table move (the acceleration rising to zero in every cycle) the
  // time left is at most the analytic braking time from the state plus two cycles.
  int checked = 0;
  for (const Case& c : kCases) {
    const PathProfile p = Block(c.length, c.feed, c.accel, c.jerk);
    const auto trace = Simulate(p);
    const int n = Cycles(trace);
    int ramp = n - 1;
    while (ramp > 1 && trace[ramp].accel > trace[ramp - 1].accel) --ramp;
    for (int k = ramp; k < n; ++k) {
      const double analytic = BrakingTime(trace[k].rate, trace[k].accel, p.max_accel, p.max_jerk);
      EXPECT_LE((n - k) * kDt, analytic + 2 * kDt + 1e-12)
          << Describe(p) << " cycle " << k << " of " << n;
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
}

TEST(PathProfileTest, BlocksShorterThanACycleFinishInTwoCycles) {
  for (double jerk : {1e3, 1e6, 1e9, 1e12, 1e15, 1e300}) {
    for (double rate : {1e3, 1e5, 1e8}) {
      for (double accel : {1e4, 1e6, 1e9}) {
        PathProfile p;
        p.max_rate = rate;
        p.max_accel = accel;
        p.max_jerk = jerk;
        const auto trace = Simulate(p, 1000);
        const double best = SCurveTime(1, rate, accel, jerk);
        if (best >= kDt) continue;
        EXPECT_LE(Cycles(trace), 2) << Describe(p);
        EXPECT_EQ(CheckTrace(p, trace), "");
      }
    }
  }
}

TEST(PathProfileTest, BlocksFarShorterThanOneCyclesJerkPulseEnd) {
  // A block of a hair (1e-15 .. 1e-6 mm at 400 mm/s, 4000 mm/s^2, 200000 mm/s^3, scaled to u)
  // asks for an acceleration far below what one cycle's jerk resolves: it still ends, at once,
  // from rest and with a look-ahead end rate, and in a hold it waits.
  for (double mm = 1e-15; mm < 1e-5; mm *= 3) {
    for (double end_share : {0.0, 0.5}) {
      PathProfile p;
      p.max_rate = 400 / mm;
      p.max_accel = 4000 / mm;
      p.max_jerk = 200000 / mm;
      p.end_rate = end_share * p.max_rate;
      SCOPED_TRACE(Describe(p));
      PathProfile held = p;
      held.Advance(kDt, 0);
      EXPECT_EQ(held.u, 0);
      const auto trace = Simulate(p, 10);
      ASSERT_EQ(trace.back().u, 1.0);
      EXPECT_LE(Cycles(trace), 2);
      EXPECT_EQ(CheckTrace(p, trace), "");
    }
  }
}

TEST(PathProfileTest, HugeJerkMovesLikeTheTrapezoid) {
  for (const Case& c : kCases) {
    PathProfile p = Block(c.length, c.feed, c.accel, 1);
    p.max_jerk = 1e9 * p.max_accel;  // 1e6 max_accel per cycle: not felt
    const auto trace = Simulate(p);
    const double trapezoid = TrapezoidTime(1, p.max_rate, p.max_accel);
    EXPECT_EQ(CheckTrace(p, trace), "");
    EXPECT_LE(Cycles(trace) * kDt, 1.03 * trapezoid + 2 * kDt) << Describe(p);
    EXPECT_GE(Cycles(trace) * kDt, trapezoid - kDt) << Describe(p);
  }
}

TEST(PathProfileTest, EndsAtEndRateWhenItBrakesToIt) {
  for (const Case& c : kCases) {
    for (double share : {0.1, 0.5, 0.9}) {
      PathProfile p = Block(c.length, c.feed, c.accel, c.jerk);
      p.end_rate = share * p.max_rate;
      const auto trace = Simulate(p);
      SCOPED_TRACE(Describe(p));
      EXPECT_EQ(CheckTrace(p, trace), "");
      ASSERT_EQ(trace.back().u, 1.0);
      double peak = 0;
      for (const Sample& s : trace) peak = std::max(peak, s.rate);
      // It braked to end_rate if it ran faster on the way; else it ends below it, accelerating.
      if (peak > p.end_rate * (1 + 1e-6)) {
        EXPECT_EQ(trace.back().rate, p.end_rate);
        EXPECT_EQ(trace.back().accel, 0.0);
      } else {
        EXPECT_LE(trace.back().rate, p.end_rate);
        EXPECT_GE(trace.back().accel, 0.0);
      }
    }
  }
}

TEST(PathProfileTest, EndsBelowEndRateWhenTheFeedIsLower) {
  PathProfile p = Block(10, 50, 4000, 40000);
  p.end_rate = 2 * p.max_rate;
  const auto trace = Simulate(p);
  EXPECT_EQ(CheckTrace(p, trace), "");
  EXPECT_EQ(trace.back().u, 1.0);
  EXPECT_DOUBLE_EQ(trace.back().rate, p.max_rate);  // at feed through the end
  EXPECT_EQ(trace.back().accel, 0.0);
  // 10 mm at 50 mm/s after accelerating to it: 0.2 s plus half the ramp.
  const double ramp = RampTime(p.max_rate, p.max_accel, p.max_jerk);
  EXPECT_NEAR(Cycles(trace) * kDt, 1 / p.max_rate + ramp / 2, 2 * kDt);
}

TEST(PathProfileTest, ArrivesAtEndRateNoEarlierThanTheAnalyticBrakingAllows) {
  // 100 mm at 100 mm/s braking to 20 mm/s: time = ramp up + cruise + ramp down to 20 mm/s.
  PathProfile p = Block(100, 100, 4000, 40000);
  p.end_rate = 0.2 * p.max_rate;
  const auto trace = Simulate(p);
  const double up = RampTime(p.max_rate, p.max_accel, p.max_jerk);
  const double down = RampTime(p.max_rate - p.end_rate, p.max_accel, p.max_jerk);
  const double cruise =
      1 - p.max_rate * up / 2 - (p.max_rate + p.end_rate) * down / 2;  // distance at max_rate
  const double best = up + down + cruise / p.max_rate;
  EXPECT_LE(Cycles(trace) * kDt, 1.03 * best + 2 * kDt);
  EXPECT_GE(Cycles(trace) * kDt, best - kDt);
}

TEST(PathProfileTest, FeedHoldStopsOnThePathAndResumes) {
  int held_on_path = 0;
  for (const Case& c : kCases) {
    const PathProfile p = Block(c.length, c.feed, c.accel, c.jerk);
    const int n = Cycles(Simulate(p));
    if (n < 20) continue;
    // Hold from a third of the move for long enough to stop, then resume.
    const int hold_from = n / 3, hold_cycles = n + 100;
    const auto override_at = [&](int k) {
      return k >= hold_from && k < hold_from + hold_cycles ? 0.0 : 1.0;
    };
    const auto trace = Simulate(p, override_at, 10 * n + 1000);
    SCOPED_TRACE(Describe(p));
    EXPECT_EQ(CheckTrace(p, trace), "");
    EXPECT_EQ(trace.back().u, 1.0);
    EXPECT_EQ(trace.back().rate, 0.0);
    // At rest from some cycle of the hold on, without moving until it ends.
    const int last_held = hold_from + hold_cycles - 1;
    ASSERT_GT(Cycles(trace), last_held);
    int rest = last_held;
    while (rest > hold_from && trace[rest - 1].rate == 0 && trace[rest - 1].accel == 0) --rest;
    const Sample& held = trace[last_held];
    EXPECT_EQ(held.rate, 0.0);
    EXPECT_EQ(held.accel, 0.0);
    EXPECT_EQ(trace[rest].u, held.u);
    if (held.u < 1) ++held_on_path;
    // Braking as fast as the limits allow, within two cycles.
    const Sample& before = trace[hold_from - 1];
    const double braking = BrakingTime(before.rate, before.accel, p.max_accel, p.max_jerk);
    EXPECT_LE((rest - hold_from + 1) * kDt, braking + 2 * kDt);
    // Resuming costs at most a restart.
    EXPECT_LE(Cycles(trace), n + hold_cycles + n);
  }
  EXPECT_GE(held_on_path, 15);
}

TEST(PathProfileTest, FeedHoldTooLateForTheBlockStopsAtItsEnd) {
  // Held 5 cycles before the end, while braking at its best anyway: feed hold brakes at the full
  // limits, harder than the braking curve with its margins, so it comes to rest on the path just
  // short of the end; on resuming it is there in a cycle or two.
  const PathProfile p = Block(100, 100, 4000, 40000);
  const int n = Cycles(Simulate(p));
  const auto trace = Simulate(
      p, [&](int k) { return k >= n - 5 && k < n + 100 ? 0.0 : 1.0; }, 10 * n);
  EXPECT_EQ(CheckTrace(p, trace), "");
  ASSERT_GT(Cycles(trace), n + 99);
  const Sample& held = trace[n + 99];
  EXPECT_EQ(held.rate, 0.0);
  EXPECT_EQ(held.accel, 0.0);
  EXPECT_GT(held.u, 1 - 1e-6);
  EXPECT_EQ(trace.back().u, 1.0);
  EXPECT_EQ(trace.back().rate, 0.0);
  EXPECT_LE(Cycles(trace), n + 100 + 2);
}

TEST(PathProfileTest, FeedHoldInTheFinalBrakingStopsOnThePathOrAtTheEnd) {
  const PathProfile p = Block(100, 100, 4000, 40000);
  const int n = Cycles(Simulate(p));
  for (int from = n - 120; from < n; from += 7) {
    const auto trace = Simulate(
        p, [&](int k) { return k >= from ? 0.0 : 1.0; }, 10 * n);
    EXPECT_EQ(CheckTrace(p, trace), "") << "hold from cycle " << from;
    EXPECT_EQ(trace.back().rate, 0.0);
    EXPECT_EQ(trace.back().accel, 0.0);
    EXPECT_LE(trace.back().u, 1.0);
  }
}

TEST(PathProfileTest, OverrideChangesActAtOnceWithinTheLimits) {
  const PathProfile p = Block(200, 100, 4000, 40000);
  const double ramp = RampTime(0.5 * p.max_rate, p.max_accel, p.max_jerk);
  const int down_at = 600, up_at = 1200;
  const auto override_at = [&](int k) { return k < down_at ? 1.0 : k < up_at ? 0.5 : 1.5; };
  const auto trace = Simulate(p, override_at, 100000);
  EXPECT_EQ(CheckTrace(p, trace), "");
  EXPECT_EQ(trace.back().u, 1.0);
  // Down: from the first cycle of the change it brakes, and is at 50 % within the analytic ramp.
  EXPECT_LT(trace[down_at].accel, 0);
  const int settled_down = down_at + static_cast<int>(std::ceil(ramp / kDt)) + 2;
  EXPECT_DOUBLE_EQ(trace[settled_down].rate, 0.5 * p.max_rate);
  // Up: it accelerates at once and reaches 150 % in the analytic ramp.
  EXPECT_GT(trace[up_at].accel, 0);
  const double ramp_up = RampTime(1.0 * p.max_rate, p.max_accel, p.max_jerk);
  const int settled_up = up_at + static_cast<int>(std::ceil(ramp_up / kDt)) + 2;
  ASSERT_LT(settled_up, Cycles(trace));
  EXPECT_DOUBLE_EQ(trace[settled_up].rate, 1.5 * p.max_rate);
}

TEST(PathProfileTest, WithoutJerkLimitMatchesTheOldTrapezoid) {
  long compared = 0;
  for (const Case& c : kCases) {
    for (int pattern = 0; pattern < 3; ++pattern) {
      const auto override_at = [&](int k) {
        if (pattern == 0) return 1.0;
        if (pattern == 1) return k % 400 < 150 ? 1.3 : k % 400 < 300 ? 0.4 : 0.0;
        return k < 50 ? 2.0 : k < 90 ? 0.0 : 0.7;
      };
      PathProfile p = Block(c.length, c.feed, c.accel, 0);
      OldPathProfile old{0, 0, p.max_rate, p.max_accel};
      int k = 0;
      for (; k < 1'000'000 && !old.done(); ++k) {
        p.Advance(kDt, override_at(k));
        old.Advance(kDt, override_at(k));
        ASSERT_EQ(p.u, old.u) << Describe(p) << " cycle " << k;
        ASSERT_EQ(p.rate, old.rate) << Describe(p) << " cycle " << k;
      }
      compared += k;
      EXPECT_TRUE(p.done());
      if (pattern == 0) {
        EXPECT_LE(k * kDt, TrapezoidTime(1, p.max_rate, p.max_accel) + 2 * kDt) << Describe(p);
      }
    }
  }
  EXPECT_GT(compared, 20000);
}

TEST(PathProfileTest, ContinueFromCarriesTheSpeedAcross) {
  // 30 mm then 10 mm at 100 mm/s; the first block ends at 60 mm/s, the second at rest.
  const double first_length = 30, second_length = 10;
  PathProfile first = Block(first_length, 100, 4000, 40000);
  first.end_rate = 60 / first_length;
  const auto first_trace = Simulate(first);
  ASSERT_EQ(first_trace.back().u, 1.0);
  first.u = first_trace.back().u;
  first.rate = first_trace.back().rate;
  first.accel = first_trace.back().accel;
  EXPECT_DOUBLE_EQ(first.rate * first_length, 60);

  PathProfile second = Block(second_length, 100, 4000, 40000);
  second.ContinueFrom(first, first_length / second_length);
  EXPECT_EQ(second.u, 0);
  EXPECT_DOUBLE_EQ(second.rate * second_length, 60);
  EXPECT_DOUBLE_EQ(second.accel * second_length, first.accel * first_length);
  const auto second_trace = Simulate(second);
  EXPECT_EQ(CheckTrace(second, second_trace), "");
  EXPECT_EQ(second_trace.back().u, 1.0);
  EXPECT_EQ(second_trace.back().rate, 0.0);
  // The path speed and acceleration (mm/s, mm/s^2) change across the join as within a block.
  const double jump = second_trace[1].accel * second_length - first.accel * first_length;
  EXPECT_LE(std::abs(jump), 40000 * kDt * (1 + kSlack));
  EXPECT_NEAR(second_trace[1].rate * second_length, 60, 4000 * kDt);
}

TEST(PathProfileTest, ContinueFromCarriesAnAccelerationAcross) {
  // A short first block ends while still accelerating below its end rate.
  const double first_length = 0.5, second_length = 50;
  PathProfile first = Block(first_length, 100, 4000, 40000);
  first.end_rate = first.max_rate;
  const auto first_trace = Simulate(first);
  ASSERT_GT(first_trace.back().accel, 0);
  first.rate = first_trace.back().rate;
  first.accel = first_trace.back().accel;

  PathProfile second = Block(second_length, 100, 4000, 40000);
  second.ContinueFrom(first, first_length / second_length);
  const auto second_trace = Simulate(second);
  EXPECT_EQ(CheckTrace(second, second_trace), "");
  EXPECT_LE(std::abs(second_trace[1].accel - second.accel), second.max_jerk * kDt * (1 + kSlack));
  // Together as fast as one 50.5 mm block, within a few cycles.
  const double best = SCurveTime(first_length + second_length, 100, 4000, 40000);
  EXPECT_LE((Cycles(first_trace) + Cycles(second_trace)) * kDt, 1.03 * best + 3 * kDt);
}

TEST(PathProfileTest, ExtremeLimitsFinishNearTheAnalyticTime) {
  // From a jerk that takes minutes to a jerk of 1e300, tiny and huge accelerations and feeds:
  // bounded time, finite, within the limits.
  int runs = 0;
  for (double jerk : {1e-3, 1.0, 1e6, 1e12, 1e300}) {
    for (double accel : {1e-3, 1.0, 1e6, 1e12}) {
      for (double rate : {1e-2, 1.0, 1e6}) {
        for (double end_share : {0.0, 0.5}) {
          PathProfile p;
          p.max_rate = rate;
          p.max_accel = accel;
          p.max_jerk = jerk;
          p.end_rate = end_share * rate;
          const double best = SCurveTime(1, rate, accel, jerk);
          const auto trace = Simulate(p, static_cast<int>(1.03 * best / kDt) + 3);
          SCOPED_TRACE(Describe(p));
          ASSERT_EQ(trace.back().u, 1.0) << "analytic " << best;
          EXPECT_EQ(CheckTrace(p, trace), "");
          EXPECT_LE(Cycles(trace) * kDt, 1.03 * best + 2 * kDt) << "analytic " << best;
          ++runs;
        }
      }
    }
  }
  EXPECT_EQ(runs, 120);
}

TEST(PathProfileTest, FeedHoldNearTheEndOfABlockWithEndRateBrakesOnInTheNext) {
  // 10 mm ending at 80 mm/s into a 20 mm block; held 3 cycles before the end of the first.
  const double first_length = 10, second_length = 20;
  PathProfile first = Block(first_length, 100, 4000, 40000);
  first.end_rate = 80 / first_length;
  const int n = Cycles(Simulate(first));
  const auto first_trace = Simulate(
      first, [&](int k) { return k >= n - 3 ? 0.0 : 1.0; }, 10 * n);
  EXPECT_EQ(CheckTrace(first, first_trace), "");
  ASSERT_EQ(first_trace.back().u, 1.0);
  EXPECT_LE(first_trace.back().rate, first.end_rate);
  EXPECT_GT(first_trace.back().rate, 0);  // too late to stop in the first block
  first.rate = first_trace.back().rate;
  first.accel = first_trace.back().accel;

  PathProfile second = Block(second_length, 100, 4000, 40000);
  second.ContinueFrom(first, first_length / second_length);
  const auto second_trace = Simulate(
      second, [](int) { return 0.0; }, 10000);
  EXPECT_EQ(CheckTrace(second, second_trace), "");
  // At rest on the second block's path.
  EXPECT_LT(second_trace.back().u, 1.0);
  EXPECT_EQ(second_trace.back().rate, 0.0);
  EXPECT_EQ(second_trace.back().accel, 0.0);
  // The path acceleration (mm/s^2) keeps to the jerk limit across the join.
  const double join = second_trace[1].accel * second_length - first.accel * first_length;
  EXPECT_LE(std::abs(join), 40000 * kDt * (1 + kSlack));
}

double LogUniform(std::mt19937_64& rng, double lo, double hi) {
  return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
}

TEST(PathProfileTest, RandomProfilesFinishWithinLimits) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> uniform(0, 1);
  int runs = 0, abrupt = 0;
  double worst_accel_step = 0, worst_rate_step = 0;
  long total_cycles = 0;
  while (runs < 3000) {
    PathProfile p;
    p.max_rate = LogUniform(rng, 0.05, 5e3);
    p.max_accel = LogUniform(rng, 0.5, 1e7);
    p.max_jerk = LogUniform(rng, 5, 1e13);
    p.end_rate = uniform(rng) < 0.5 ? 0 : 1.5 * uniform(rng) * p.max_rate;
    // Random override changes and holds in the first part of the move, then >= 0.1.
    const double slowest = 0.1;
    const double best = SCurveTime(1, slowest * p.max_rate, p.max_accel, p.max_jerk);
    if (best > 5) continue;  // keep the run time bounded
    ++runs;
    const int window = 1 + static_cast<int>(uniform(rng) * 3 * best / kDt);
    std::vector<double> override(window + 1);
    double o = uniform(rng) < 0.2 ? 0 : slowest + 1.9 * uniform(rng);
    int changes = 1;
    for (int k = 0; k <= window; ++k) {
      if (uniform(rng) < 0.01) {
        o = uniform(rng) < 0.3 ? 0 : slowest + 1.9 * uniform(rng);
        ++changes;
      }
      override[k] = o;
    }
    const double last = slowest + 1.9 * uniform(rng);
    const auto override_at = [&](int k) { return k <= window ? override[k] : last; };
    int held = 0;
    for (double v : override) held += v == 0;
    // Moving at >= 10 % and re-accelerating after each change or hold, to at most the speed
    // a rest-to-rest move over the block could reach.
    const double reachable =
        std::min({2 * p.max_rate, std::sqrt(p.max_accel), std::cbrt(p.max_jerk / 4)});
    const double ramp = RampTime(reachable, p.max_accel, p.max_jerk);
    const int bound = held + static_cast<int>((2 * best + changes * 2 * ramp) / kDt) + 10;
    const auto trace = Simulate(p, override_at, bound + 1);
    total_cycles += Cycles(trace);
    ASSERT_LE(Cycles(trace), bound) << Describe(p);
    ASSERT_EQ(trace.back().u, 1.0) << Describe(p);
    Arrival arrival;
    ASSERT_EQ(CheckTrace(p, trace, &arrival), "");
    if (arrival.accel_step > 1 + kSlack || arrival.rate_step > 1 + kSlack) ++abrupt;
    worst_accel_step = std::max(worst_accel_step, arrival.accel_step);
    worst_rate_step = std::max(worst_rate_step, arrival.rate_step);
  }
  std::printf(
      "%d random profiles, %ld cycles: final step beyond the jerk or acceleration limit in %d; "
      "worst %.3g max_jerk*dt, %.3g max_accel*dt\n",
      runs, total_cycles, abrupt, worst_accel_step, worst_rate_step);
  // The abrupt final step is rare and small.
  EXPECT_LE(abrupt, runs / 300);
  EXPECT_LE(worst_accel_step, 1.5);
  EXPECT_LE(worst_rate_step, 1.0 + kSlack);
}

TEST(PathProfileTest, RandomRestToRestMovesAreNearTimeOptimal) {
  std::mt19937_64 rng(7);
  double worst = 0, worst_ratio = 0, worst_cycles = 0;
  for (int i = 0; i < 2000; ++i) {
    PathProfile p;
    p.max_rate = LogUniform(rng, 0.1, 1e4);
    p.max_accel = LogUniform(rng, 1, 1e7);
    p.max_jerk = LogUniform(rng, 10, 1e11);
    const double best = SCurveTime(1, p.max_rate, p.max_accel, p.max_jerk);
    if (best > 5) continue;
    const auto trace = Simulate(p);
    const double t = Cycles(trace) * kDt;
    ASSERT_EQ(CheckTrace(p, trace), "");
    ASSERT_LE(t, 1.03 * best + 2 * kDt) << Describe(p) << " analytic " << best;
    ASSERT_GE(t, best - kDt) << Describe(p) << " analytic " << best;
    worst = std::max(worst, (t - 2 * kDt) / best);
    worst_ratio = std::max(worst_ratio, t / best);
    worst_cycles = std::max(worst_cycles, (t - best) / kDt);
  }
  std::printf(
      "random: worst time / analytic S-curve time %.4f, worst excess %.2f cycles, worst (time - "
      "2 cycles) / analytic %.4f\n",
      worst_ratio, worst_cycles, worst);
}

}  // namespace
}  // namespace vmt::control::channel
