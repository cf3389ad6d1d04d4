// Look-ahead on the channel: speeds per NC cycle through collinear, tangent and cornered joins,
// over many short blocks, at reversals, under feed hold and tool nose radius compensation.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

// Speeds per NC cycle (mm/s) of a run to the end, X and Z.
std::vector<std::pair<double, double>> CycleSpeeds(Machine& m) {
  std::vector<std::pair<double, double>> v;
  double x = m.X(), z = m.Z();
  while (m.channel->state() == ChannelState::kRunning && m.t < 30) {
    for (int i = 0; i < 4; ++i) m.Tick();
    v.emplace_back((m.X() - x) / 1e-3, (m.Z() - z) / 1e-3);
    x = m.X(), z = m.Z();
  }
  return v;
}

TEST(ChannelTest, LookAheadRunsThroughCollinearAndTangentJoinsAtFeed) {
  // Two collinear G01 blocks: no stop between them; as fast as one block of the whole length.
  Machine two("N1 G01 X50 F6000\nN2 X100\nN3 RET\n"), one("N1 G01 X100 F6000\nN2 RET\n");
  two.channel->Start();
  one.channel->Start();
  const auto v = CycleSpeeds(two);
  CycleSpeeds(one);
  ASSERT_EQ(two.channel->state(), ChannelState::kEnded) << two.channel->error();
  EXPECT_DOUBLE_EQ(two.X(), 100);
  EXPECT_NEAR(two.t, one.t, 0.003);
  double slowest_inside = 1e9, worst_change = 0;
  // Between the ramps (the join at X50 is in the middle): steady 100 mm/s.
  for (size_t i = 100; i + 100 < v.size(); ++i) {
    worst_change = std::max(worst_change, std::abs(v[i].first - v[i - 1].first));
    slowest_inside = std::min(slowest_inside, v[i].first);
  }
  EXPECT_GT(slowest_inside, 99.999);
  EXPECT_LT(worst_change, 1e-6);

  // A line into a tangent arc keeps the feed too.
  Machine arc("N1 G01 X10 Z0 F3000\nN2 G01 Z-20\nN3 G02 X20 Z-30 I10 K0\nN4 RET\n", 10, 0);
  arc.channel->Start();
  const auto va = CycleSpeeds(arc);
  ASSERT_EQ(arc.channel->state(), ChannelState::kEnded) << arc.channel->error();
  double slowest = 1e9;
  for (size_t i = 50; i + 50 < va.size(); ++i)
    slowest = std::min(slowest, std::hypot(va[i].first, va[i].second));
  EXPECT_GT(slowest, 45);  // 50 mm/s, the arc's centripetal limit sqrt(4000 x 10) = 200 is above
}

TEST(ChannelTest, LookAheadSlowsForCornersAndStopsWhereItMust) {
  // A right-angle corner: the path passes the corner slowly but without a stop. The cycle that
  // passes it commands a point before and one after it: the straight line between them (the
  // fine interpolation) cuts the corner by less than the corner deviation.
  Machine m("N1 G01 X50 F6000\nN2 Z50\nN3 RET\n");
  m.channel->Start();
  double cut = 1e9, min_speed = 1e9;
  while (m.channel->state() == ChannelState::kRunning && m.t < 10) {
    const double x = m.channel->position(0), z = m.channel->position(1);
    for (int i = 0; i < 4; ++i) m.Tick();
    const double x1 = m.channel->position(0), z1 = m.channel->position(1);
    const double speed = std::hypot(x1 - x, z1 - z) / 1e-3;
    // Distance of the corner (50, 0) from this cycle's chord.
    const double len2 = (x1 - x) * (x1 - x) + (z1 - z) * (z1 - z);
    const double f =
        len2 > 0 ? std::clamp(((50 - x) * (x1 - x) + (0 - z) * (z1 - z)) / len2, 0.0, 1.0) : 0.0;
    cut = std::min(cut, std::hypot(x + f * (x1 - x) - 50, z + f * (z1 - z)));
    if (x1 > 49 && z1 < 1) min_speed = std::min(min_speed, speed);
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_LT(cut, kCornerDeviation);
  EXPECT_LT(min_speed, 20);  // slow at the corner ...
  EXPECT_GT(min_speed, 1);   // ... but not stopped
  // A block with an M function, single block, and rapid moves still stop.
  Machine aux("N1 G01 X50 F6000\nN2 X100 M08\nN3 RET\n");
  aux.channel->Start();
  const auto v = CycleSpeeds(aux);
  double slowest_mid = 1e9;
  for (size_t i = 100; i + 100 < v.size(); ++i) slowest_mid = std::min(slowest_mid, v[i].first);
  EXPECT_LT(slowest_mid, 5);  // at rest at X50 (one cycle's start-up at most)
}

TEST(ChannelTest, FeedHoldJustBeforeABlendedJoinBrakesIntoTheNextBlock) {
  Machine m("N1 G01 X50 F6000\nN2 X100\nN3 RET\n");
  m.channel->Start();
  while (m.channel->position(0) < 49.9 && m.t < 5) m.Tick();
  m.channel->Stop();
  for (int i = 0; i < 2000; ++i) m.Tick();
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  const double x = m.X();
  EXPECT_GT(x, 49.9);
  EXPECT_LT(x, 49.9 + 100 * 100 / (2 * 4000.0) + 0.2);  // the braking distance from 100 mm/s
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.X(), x);  // at rest
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.X(), 100);
}

TEST(ChannelTest, LookAheadUnderToolNoseRadiusCompensation) {
  // The tip path of N3 - fillet N4 - corner arc - N5 is tangent throughout: no stop on it.
  Machine m(
      "N1 G00 X30 Z110\nN2 G42 T1 D1 G01 X20 Z100 F6000\nN3 Z50\nN4 G02 X25 Z45 I5 K0\n"
      "N5 G01 Z30\nN6 G40 G00 X40\nN7 RET\n",
      30, 110, WithOffsetsAndTools);
  m.channel->Start();
  double slowest = 1e9;
  while (m.channel->state() == ChannelState::kRunning && m.t < 20) {
    const double x = m.channel->position(0), z = m.channel->position(1);
    for (int i = 0; i < 4; ++i) m.Tick();
    const double speed = std::hypot(m.channel->position(0) - x, m.channel->position(1) - z) / 1e-3;
    if (z < 60 && z > 35) slowest = std::min(slowest, speed);
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_GT(slowest, 40);  // the 0.8 mm corner arc allows sqrt(4000 x 0.8) = 57 mm/s
}

std::string Program(const std::vector<std::string>& blocks) {
  std::string text;
  for (size_t i = 0; i < blocks.size(); ++i)
    text += "N" + std::to_string(i + 1) + " " + blocks[i] + "\n";
  return text;
}

TEST(ChannelTest, LookAheadPlansOverManyShortBlocks) {
  // 200 collinear blocks of 0.5 mm at 100 mm/s: stopping from the feed takes 1.25 mm, more
  // than two blocks, so the feed is only reached when the look-ahead sees several blocks.
  std::vector<std::string> blocks = {"G01 X0.5 F6000"};
  for (int i = 2; i <= 200; ++i) blocks.push_back("X" + std::to_string(i * 0.5));
  blocks.push_back("RET");
  Machine many(Program(blocks)), one("N1 G01 X100 F6000\nN2 RET\n");
  many.channel->Start();
  one.channel->Start();
  const auto v = CycleSpeeds(many);
  CycleSpeeds(one);
  ASSERT_EQ(many.channel->state(), ChannelState::kEnded) << many.channel->error();
  EXPECT_DOUBLE_EQ(many.X(), 100);
  double slowest_inside = 1e9;
  for (size_t i = 100; i + 100 < v.size(); ++i)
    slowest_inside = std::min(slowest_inside, v[i].first);
  EXPECT_GT(slowest_inside, 99.99);
  EXPECT_NEAR(many.t, one.t, 0.003);

  // The same with jerk-limited axes: a braking takes about 2.5 mm, five blocks, and runs on
  // through their ends, so the feed is kept between the ramps here too.
  const auto jerk_limited = [](ChannelConfig& c) {
    for (ChannelAxis& a : c.axes) a.jerk = 200000;
  };
  Machine smooth(Program(blocks), 0, 0, jerk_limited),
      smooth_one("N1 G01 X100 F6000\nN2 RET\n", 0, 0, jerk_limited);
  smooth.channel->Start();
  smooth_one.channel->Start();
  const auto vs = CycleSpeeds(smooth);
  CycleSpeeds(smooth_one);
  ASSERT_EQ(smooth.channel->state(), ChannelState::kEnded) << smooth.channel->error();
  EXPECT_DOUBLE_EQ(smooth.X(), 100);
  double slowest_smooth = 1e9;
  for (size_t i = 100; i + 100 < vs.size(); ++i)
    slowest_smooth = std::min(slowest_smooth, vs[i].first);
  EXPECT_GT(slowest_smooth, 99.99);
  EXPECT_NEAR(smooth.t, smooth_one.t, 0.003);

  // A polyline turning by 3 degrees per 0.5 mm block (a finely segmented arc of 9.5 mm radius,
  // whose centripetal limit sqrt(4000 x 9.5) = 195 mm/s is above the feed) runs at the feed.
  std::vector<std::string> arc = {"G01 F6000"};
  double x = 0, z = 0;
  for (int i = 0; i < 60; ++i) {
    const double angle = i * 3 * std::numbers::pi / 180;
    x += 0.5 * std::sin(angle), z -= 0.5 * std::cos(angle);
    char block[64];
    std::snprintf(block, sizeof block, "X%.6f Z%.6f", x, z);
    arc.push_back(block);
  }
  arc.push_back("RET");
  Machine polyline(Program(arc));
  polyline.channel->Start();
  const auto vp = CycleSpeeds(polyline);
  ASSERT_EQ(polyline.channel->state(), ChannelState::kEnded) << polyline.channel->error();
  double slowest = 1e9;
  for (size_t i = 60; i + 60 < vp.size(); ++i)
    slowest = std::min(slowest, std::hypot(vp[i].first, vp[i].second));
  EXPECT_GT(slowest, 95);
}

TEST(ChannelTest, LookAheadStopsAtAReversal) {
  // Back along the same line: the path comes to rest at X50 before it turns back (jerk-limited
  // axes: no step in the speed anywhere), and the reversal of an acute zigzag is slow too.
  const auto jerk_limited = [](ChannelConfig& c) {
    for (ChannelAxis& a : c.axes) a.jerk = 200000;
  };
  Machine m("N1 G01 X50 F6000\nN2 X0\nN3 RET\n", 0, 0, jerk_limited);
  m.channel->Start();
  const auto v = CycleSpeeds(m);
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  double worst_change = 0;
  for (size_t i = 1; i < v.size(); ++i)
    worst_change = std::max(worst_change, std::abs(v[i].first - v[i - 1].first));
  EXPECT_LE(worst_change, 4000 * 1e-3 + 1e-6);  // the axis' acceleration, no jump
  Machine zigzag("N1 G01 X50 Z0 F6000\nN2 X0 Z5\nN3 RET\n");
  zigzag.channel->Start();
  const auto vz = CycleSpeeds(zigzag);
  ASSERT_EQ(zigzag.channel->state(), ChannelState::kEnded) << zigzag.channel->error();
  double slowest_mid = 1e9;
  for (size_t i = 100; i + 100 < vz.size(); ++i)
    slowest_mid = std::min(slowest_mid, std::hypot(vz[i].first, vz[i].second));
  EXPECT_LT(slowest_mid, 5);
}

}  // namespace
}  // namespace vmt::control::channel
