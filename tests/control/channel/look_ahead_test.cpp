// The look-ahead's speed limits: braking distances as the path profile brakes, corner speeds,
// and the backward pass over the blocks read ahead.

#include "control/channel/look_ahead.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "control/channel/path_profile.hpp"

namespace vmt::control::channel {
namespace {

constexpr double kCycle = 1e-3;

TEST(LookAheadTest, BrakingDistanceWithoutJerkIsTheTrapezoidsAndGrowsWithJerk) {
  // The trapezoid's distance and one cycle at the higher speed.
  EXPECT_DOUBLE_EQ(BrakingDistance(100, 20, 4000, 0, kCycle),
                   (100 * 100 - 20 * 20) / 8000.0 + 100 * kCycle);
  EXPECT_EQ(BrakingDistance(20, 100, 4000, 0, kCycle), 0);
  const double jerky = BrakingDistance(100, 20, 4000, 200000, kCycle);
  EXPECT_GT(jerky, (100 * 100 - 20 * 20) / 8000.0);
  EXPECT_GT(jerky, BrakingDistance(100, 20, 4000, 2e6, kCycle));
  // Braking to a higher speed never takes longer.
  for (const double jerk : {0.0, 2e5, 2e6, 1e9}) {
    double previous = HUGE_VAL;
    for (double to = 0; to <= 100; to += 0.25) {
      const double d = BrakingDistance(100, to, 4000, jerk, kCycle);
      EXPECT_LE(d, previous) << jerk << " " << to;
      previous = d;
    }
  }
}

TEST(LookAheadTest, CornerSpeedFallsWithTheTurn) {
  EXPECT_TRUE(std::isinf(CornerSpeed(1, 4000)));  // tangent
  EXPECT_EQ(CornerSpeed(-1, 4000), 0);            // reversal
  const double s = std::sqrt(0.5);                // 90 degrees
  EXPECT_NEAR(CornerSpeed(0, 4000), std::sqrt(4000 * kCornerDeviation * s / (1 - s)), 1e-9);
  double previous = HUGE_VAL;
  for (int degrees = 1; degrees <= 180; ++degrees) {
    const double v = CornerSpeed(std::cos(degrees * std::numbers::pi / 180), 4000);
    EXPECT_LT(v, previous) << degrees;
    previous = v;
  }
  EXPECT_GT(CornerSpeed(std::cos(3 * std::numbers::pi / 180), 4000), 150);  // a slight turn
}

TEST(LookAheadTest, TargetsAtEachBlockEndAndAStopAtTheLast) {
  const std::vector<LookAheadLeg> legs = {{50, 3000, 0, 2, 1}, {80, 4000, 1e5, 3, 0}};
  std::vector<SpeedTarget> targets;
  PlanTargets(10, 100, 4000, 2e5, legs, targets);
  ASSERT_EQ(targets.size(), 3u);
  EXPECT_EQ(targets[0].distance, 10);
  EXPECT_TRUE(std::isinf(targets[0].corner));  // tangent
  EXPECT_EQ(targets[0].feed, 50);              // the slower side
  EXPECT_EQ(targets[0].accel, 4000);
  EXPECT_EQ(targets[1].distance, 12);
  EXPECT_NEAR(targets[1].corner, CornerSpeed(0, 3000), 1e-12);  // least acceleration so far
  EXPECT_EQ(targets[1].feed, 50);
  EXPECT_EQ(targets[1].accel, 3000);
  EXPECT_EQ(targets[1].jerk, 2e5);
  EXPECT_EQ(targets[2].distance, 15);
  EXPECT_EQ(targets[2].feed, 0);  // at rest at the end of the last block known
  EXPECT_EQ(targets[2].jerk, 1e5);
}

// Runs a chain of blocks as the channel does: a profile per block, steered at the targets of a
// window of the blocks after it, speed and acceleration carried through the block ends.
struct ChainRun {
  bool finished = false;
  double worst_junction_excess = 0;  ///< speed through a block end above its limit, mm/s
  double worst_accel_ratio = 0;      ///< |path acceleration| / the block's limit
  double worst_speed_ratio = 0;      ///< speed / the block's feed
  double end_speed = -1;
  double time = 0;
};

ChainRun RunChain(const std::vector<LookAheadLeg>& blocks, std::mt19937_64& rng, int least_window,
                  int most_window) {
  ChainRun run;
  std::uniform_int_distribution<int> window(least_window, most_window);
  double carry_v = 0, carry_a = 0, leftover = 0;
  std::vector<SpeedTarget> targets;
  std::vector<ProfileTarget> ahead;
  for (size_t b = 0; b < blocks.size(); ++b) {
    const LookAheadLeg& block = blocks[b];
    const double length = block.length;
    PathProfile p;
    p.max_rate = block.max_speed / length;
    p.max_accel = block.accel / length;
    p.max_jerk = block.jerk / length;
    if (carry_v > 0) {
      p.rate = carry_v / length;
      p.accel = carry_a / length;
      p.u = std::min(0.5, leftover / length);
    }
    const size_t last = std::min(blocks.size(), b + 1 + window(rng));
    const std::span<const LookAheadLeg> legs(blocks.data() + b + 1, last - b - 1);
    PlanTargets(length, block.max_speed, block.accel, block.jerk, legs, targets);
    const bool go_on = !legs.empty() && std::min(targets[0].corner, targets[0].feed) > 1e-9;
    carry_v = carry_a = leftover = 0;
    for (int cycle = 0; cycle < 200000; ++cycle) {
      if (go_on) ProfileTargets(targets, length, 1.0, ahead), p.ahead = ahead;
      const double u_before = p.u;
      p.Advance(kCycle, 1.0);
      run.time += kCycle;
      run.worst_accel_ratio = std::max(run.worst_accel_ratio, std::abs(p.accel) / p.max_accel);
      run.worst_speed_ratio = std::max(run.worst_speed_ratio, p.rate / p.max_rate);
      if (!p.done()) continue;
      const double v = p.rate * length;
      const double limit = go_on ? std::min(targets[0].corner, targets[0].feed) : 0;
      run.worst_junction_excess = std::max(run.worst_junction_excess, v - limit);
      if (go_on && v > 0) {
        carry_v = v;
        carry_a = p.accel * length;
        leftover =
            p.u > 1 ? (p.u - 1) * length : std::max(0.0, v * kCycle - (1 - u_before) * length);
      }
      if (b + 1 == blocks.size()) run.end_speed = v, run.finished = true;
      break;
    }
    if (!p.done()) return run;
  }
  return run;
}

TEST(LookAheadTest, RandomChainsKeepEveryLimit) {
  // Short and long blocks, corners and tangent joins, feeds that change: the path passes each
  // block end within its limit, keeps each block's acceleration and feed, and ends at rest,
  // whatever the number of blocks the look-ahead knew at each block start. The path
  // acceleration and jerk are the channel's (the least of its axes), the same in every block.
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 300; ++i) {
    std::vector<LookAheadLeg> blocks(2 + static_cast<size_t>(unit(rng) * 40));
    const bool short_blocks = unit(rng) < 0.5;
    const double accel = 1000 + unit(rng) * 5000;
    const double jerk = unit(rng) < 0.2 ? 0 : accel * (20 + unit(rng) * 200);
    for (LookAheadLeg& leg : blocks) {
      leg.max_speed = 20 + unit(rng) * 180;
      leg.accel = accel;
      leg.jerk = jerk;
      leg.length = short_blocks ? 0.05 + unit(rng) * 0.5 : 0.05 + unit(rng) * 10;
      const double turn = unit(rng) < 0.5 ? 0 : unit(rng) * unit(rng) * std::numbers::pi;
      leg.cos_turn = std::cos(turn);
    }
    const ChainRun run = RunChain(blocks, rng, 1, 8);
    ASSERT_TRUE(run.finished) << i;
    EXPECT_LE(run.worst_junction_excess, 1e-6) << i;
    EXPECT_LE(run.worst_accel_ratio, 1 + 1e-9) << i;
    EXPECT_LE(run.worst_speed_ratio, 1 + 1e-9) << i;
    EXPECT_EQ(run.end_speed, 0) << i;
  }
}

TEST(LookAheadTest, ABrakingSpansManyShortBlocks) {
  // 0.5 mm blocks at 100 mm/s, jerk-limited: a braking needs about 2.5 mm, five blocks. Each
  // block braking on its own to a junction speed at zero acceleration would need far more; the
  // targets let the braking run on through the block ends, so the chain runs at its feed.
  std::vector<LookAheadLeg> blocks(200, LookAheadLeg{100, 4000, 2e5, 0.5, 1});
  std::mt19937_64 rng(1);
  const ChainRun run = RunChain(blocks, rng, kLookAheadBlocks, kLookAheadBlocks);
  ASSERT_TRUE(run.finished);
  // One 100 mm move at 100 mm/s with these limits takes about 1.02 s.
  EXPECT_LT(run.time, 1.05);
  EXPECT_GT(run.worst_speed_ratio, 0.999);
}

}  // namespace
}  // namespace vmt::control::channel
