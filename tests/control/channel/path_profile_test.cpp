// The path-parameter profile from rest to rest: time against the analytic time-optimal S-curve,
// acceleration and jerk limits in every cycle, arrival at u = 1 exactly and never past it
// without creeping, blocks far shorter than a cycle, a huge jerk like the trapezoid.
#include "control/channel/path_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "path_profile_test_support.hpp"

namespace vmt::control::channel {
namespace {

using namespace path_profile_testing;

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

}  // namespace
}  // namespace vmt::control::channel
