// The path-parameter profile between blocks and under the operator: ending at a speed
// (look-ahead) and carrying speed and acceleration into the next block, feed hold on the path,
// override changes, and the old trapezoid without a jerk limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "control/channel/path_profile.hpp"
#include "path_profile_test_support.hpp"

namespace vmt::control::channel {
namespace {

using namespace path_profile_testing;

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

}  // namespace
}  // namespace vmt::control::channel
