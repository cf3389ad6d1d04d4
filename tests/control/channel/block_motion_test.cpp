// Planning one block's motion on its own: the path (line, arc, helix), its length and the limits
// of its profile, and the errors a block gets before it moves.
#include "control/channel/block_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "control/channel/channel_messages.hpp"

namespace vmt::control::channel {
namespace {

constexpr double kPi = std::numbers::pi;

// X (radius), Z and C of a lathe, as the channel's axis list.
std::vector<axes::AxisParameters> Axes() {
  axes::AxisParameters x, z, c;
  x.name = "X";
  x.rapid_per_s = 400;
  x.acceleration = 4000;
  x.travel_min = 0;
  x.travel_max = 300;
  z = x;
  z.name = "Z";
  z.rapid_per_s = 500;
  z.acceleration = 2000;
  z.travel_max = 650;
  c.name = "C";
  c.rotary = true;
  c.rapid_per_s = 3600;
  c.acceleration = 36000;
  return {x, z, c};
}

nc::PreparedBlock Block(nc::Motion motion, std::vector<double> target, double feed = 0) {
  nc::PreparedBlock b;
  b.motion = motion;
  b.target = std::move(target);
  b.modal.motion = motion;
  b.modal.feed = feed;
  return b;
}

TEST(BlockMotion, ARapidMovesAtTheSlowestAxisShare) {
  BlockMotion m;
  // X 40 at 400 mm/s takes 0.1 s, Z 100 at 500 mm/s 0.2 s: Z sets the pace, du/dt = 5/s.
  ASSERT_FALSE(PlanBlockMotion(Block(nc::Motion::kRapid, {60, 200, 0}), {20, 100, 0}, {0, 0, 0},
                               Axes(), 0, m));
  ASSERT_TRUE(m.moves);
  EXPECT_NEAR(m.max_rate, 5, 1e-12);
  EXPECT_NEAR(m.max_accel, std::min(4000 / 40.0, 2000 / 100.0), 1e-12);
  EXPECT_NEAR(m.length, std::hypot(40, 100), 1e-9);
  std::vector<double> p;
  m.PointAt(0.25, p);
  EXPECT_NEAR(p[0], 30, 1e-12);
  EXPECT_NEAR(p[1], 125, 1e-12);
}

TEST(BlockMotion, FeedAlongThePathAndPerRevolution) {
  BlockMotion m;
  // F600 mm/min = 10 mm/s along a 50 mm line.
  ASSERT_FALSE(PlanBlockMotion(Block(nc::Motion::kLinear, {50, 140, 0}, 600), {20, 100, 0},
                               {0, 0, 0}, Axes(), 0, m));
  EXPECT_NEAR(m.max_rate * m.length, 10, 1e-9);
  // G95: 0.2 mm/rev at 10 rev/s is 2 mm/s.
  nc::PreparedBlock per_rev = Block(nc::Motion::kLinear, {50, 140, 0}, 0.2);
  per_rev.modal.feed_per_revolution = true;
  ASSERT_FALSE(PlanBlockMotion(per_rev, {20, 100, 0}, {0, 0, 0}, Axes(), 10, m));
  EXPECT_NEAR(m.max_rate * m.length, 2, 1e-9);
  // G95 on a standing spindle, or no F at all: no feed, an error before the move.
  const auto standing = PlanBlockMotion(per_rev, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m);
  ASSERT_TRUE(standing);
  EXPECT_EQ(standing->number, kMsgNoFeed);
  const auto none = PlanBlockMotion(Block(nc::Motion::kLinear, {50, 140, 0}), {20, 100, 0},
                                    {0, 0, 0}, Axes(), 0, m);
  ASSERT_TRUE(none);
  EXPECT_EQ(none->number, kMsgNoFeed);
  // A feed beyond the axes' rapid is held to it.
  ASSERT_FALSE(PlanBlockMotion(Block(nc::Motion::kLinear, {20, 600, 0}, 1e6), {20, 100, 0},
                               {0, 0, 0}, Axes(), 0, m));
  EXPECT_NEAR(m.max_rate * m.length, 500, 1e-9);
}

TEST(BlockMotion, TheTranslationTakesTheTargetToTheAxesAndTheTravelIsChecked) {
  BlockMotion m;
  ASSERT_FALSE(PlanBlockMotion(Block(nc::Motion::kRapid, {10, 20, 0}), {0, 0, 0}, {5, 300, 0},
                               Axes(), 0, m));
  EXPECT_EQ(m.end[0], 15);
  EXPECT_EQ(m.end[1], 320);
  const auto beyond = PlanBlockMotion(Block(nc::Motion::kRapid, {10, 400, 0}), {0, 0, 0},
                                      {5, 300, 0}, Axes(), 0, m);
  ASSERT_TRUE(beyond);
  EXPECT_EQ(beyond->number, kMsgSoftwareLimit);
  EXPECT_NE(beyond->text.find("axis Z target 700.0000 is beyond its travel 0.0000 .. 650.0000"),
            std::string::npos)
      << beyond->text;
  // An endless axis (no travel) goes anywhere.
  ASSERT_FALSE(PlanBlockMotion(Block(nc::Motion::kRapid, {0, 0, 7200}), {0, 0, 0}, {0, 0, 0},
                               Axes(), 0, m));
}

TEST(BlockMotion, AFollowUpAxisIsNoMoveOfTheBlock) {
  BlockMotion m;
  // C in follow-up (its spindle in spindle mode): it stays at its actual position, and a block
  // that programs only C does not move.
  ASSERT_FALSE(PlanBlockMotion(Block(nc::Motion::kRapid, {20, 100, 90}), {20, 100, 33.3},
                               {0, 0, 0}, Axes(), 0, m, 0b100));
  EXPECT_FALSE(m.moves);
  EXPECT_EQ(m.end[2], 33.3);
}

TEST(BlockMotion, ArcsByCentreAndByRadius) {
  BlockMotion m;
  // G18 (Z first, X second): a half circle of radius 10 about Z110 X20, from Z100 to Z120.
  nc::PreparedBlock arc = Block(nc::Motion::kArcCw, {20, 120, 0}, 600);
  arc.has_centre = true;
  arc.centre[2] = 10;  // K: along Z from the start
  ASSERT_FALSE(PlanBlockMotion(arc, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m));
  EXPECT_EQ(m.arc_axes[0], 1);  // Z
  EXPECT_EQ(m.arc_axes[1], 0);  // X
  EXPECT_NEAR(m.arc_radius, 10, 1e-12);
  EXPECT_NEAR(m.arc_sweep, -kPi, 1e-12);  // clockwise
  EXPECT_NEAR(m.length, 10 * kPi, 1e-9);
  std::vector<double> p;
  m.PointAt(0.5, p);  // clockwise in the ZX plane from Z100: through X30
  EXPECT_NEAR(p[1], 110, 1e-9);
  EXPECT_NEAR(p[0], 30, 1e-9);
  // R > 0 takes the short way, R < 0 the long one (over 180 degrees).
  nc::PreparedBlock quarter = Block(nc::Motion::kArcCcw, {30, 110, 0}, 600);
  quarter.radius = 10;
  ASSERT_FALSE(PlanBlockMotion(quarter, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m));
  EXPECT_NEAR(m.arc_sweep, kPi / 2, 1e-9);
  quarter.radius = -10;
  ASSERT_FALSE(PlanBlockMotion(quarter, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m));
  EXPECT_NEAR(m.arc_sweep, 3 * kPi / 2, 1e-9);
}

TEST(BlockMotion, ArcsThatDoNotFitAreErrors) {
  BlockMotion m;
  nc::PreparedBlock arc = Block(nc::Motion::kArcCw, {20, 150, 0}, 600);
  arc.radius = 10;  // a chord of 50 under R10
  auto e = PlanBlockMotion(arc, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->number, kMsgArcGeometry);
  arc.radius = 0;
  arc.has_centre = true;
  arc.centre[2] = 10;  // the end lies 40 from the centre, the start 10
  e = PlanBlockMotion(arc, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m);
  ASSERT_TRUE(e);
  EXPECT_NE(e->text.find("end point not on the arc"), std::string::npos);
  arc.has_centre = false;
  e = PlanBlockMotion(arc, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m);
  ASSERT_TRUE(e);
  EXPECT_NE(e->text.find("needs a centre (I/J/K) or a radius R"), std::string::npos);
  // G17 needs Y, which the lathe has not.
  nc::PreparedBlock g17 = Block(nc::Motion::kArcCw, {20, 120, 0}, 600);
  g17.modal.plane = nc::Plane::kXY;
  g17.radius = 10;
  e = PlanBlockMotion(g17, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->number, kMsgArcPlane);
}

TEST(BlockMotion, ASmallArcIsSlowedByItsCentripetalAcceleration) {
  BlockMotion m;
  nc::PreparedBlock arc = Block(nc::Motion::kArcCcw, {20, 101, 0}, 60000);  // 1000 mm/s asked
  arc.has_centre = true;
  arc.centre[2] = 0.5;  // radius 0.5 mm
  ASSERT_FALSE(PlanBlockMotion(arc, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m));
  // v^2 / r within the lesser axis acceleration (Z 2000): v = sqrt(2000 x 0.5) = 31.6 mm/s.
  EXPECT_NEAR(m.max_rate * m.length, std::sqrt(2000 * 0.5), 1e-9);
}

TEST(BlockMotion, ARotaryAxisCountsWithItsEffectiveDistance) {
  BlockMotion m;
  // C 90 deg at F600 (10 mm/s) with the tool 20 mm off the axis (RX20): the path is 31.4 mm.
  nc::PreparedBlock c = Block(nc::Motion::kLinear, {20, 100, 90}, 600);
  c.effective_distance[0] = 20;
  c.has_effective_distance = 1;
  ASSERT_FALSE(PlanBlockMotion(c, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m));
  EXPECT_NEAR(m.max_rate, 10 / (20 * kPi / 2), 1e-12);  // 90 deg in 3.14 s
  // Without it the degrees are the path: F600 is 10 deg/s.
  c.has_effective_distance = 0;
  ASSERT_FALSE(PlanBlockMotion(c, {20, 100, 0}, {0, 0, 0}, Axes(), 0, m));
  EXPECT_NEAR(m.max_rate, 10.0 / 90, 1e-12);
}

}  // namespace
}  // namespace vmt::control::channel
