// One feed axis jogged on its own: a held key reaches the jogging speed and brakes in time for
// the window's edge, an increment runs to its end once per press, PathGuard's refusal starts
// nothing, the handwheel follows its counts, and AxxC.HOME's homing ends homed.

#include "control/channel/axis_jog.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vmt::control::channel {
namespace {

constexpr double kDt = 1e-3;

axes::AxisParameters Slide() {
  axes::AxisParameters a;
  a.name = "X";
  a.rapid_per_s = 100;
  a.jog_per_s = 10;
  a.jog_rapid_per_s = 50;
  a.jog_distance = 2.5;
  a.acceleration = 1000;
  a.homing_per_s = 20;
  a.reference_position = 40;
  return a;
}

/// A context that lets every increment through and remembers where they went.
struct Checks {
  std::vector<double> asked;
  bool allow = true;
  AxisJogContext Context(JogMode mode, double increment = 0) {
    AxisJogContext c;
    c.rules = {mode, increment, 1.0};
    c.guard_increment = [this](double to) {
      asked.push_back(to);
      return allow;
    };
    return c;
  }
};

TEST(AxisJogTest, RulesGiveSpeedAndDistancePerMode) {
  const axes::AxisParameters a = Slide();
  EXPECT_DOUBLE_EQ((JogRules{JogMode::kContinuous, 0, 0.5}.Speed(a)), 5);
  EXPECT_DOUBLE_EQ((JogRules{JogMode::kRapid, 0, 1}.Speed(a)), 50);
  EXPECT_DOUBLE_EQ((JogRules{JogMode::kParametric, 0, 1}.Increment(a)), 2.5);
  EXPECT_DOUBLE_EQ((JogRules{JogMode::kIncrement100, 0.1, 1}.Increment(a)), 0.1);
  EXPECT_DOUBLE_EQ((JogRules{JogMode::kContinuous, 0, 1}.Increment(a)), 0);
  axes::AxisParameters bare = a;
  bare.jog_per_s = 0;  // no jogging speed given: a tenth of the rapid
  EXPECT_DOUBLE_EQ((JogRules{JogMode::kContinuous, 0, 1}.Speed(bare)), 10);
}

TEST(AxisJogTest, AHeldKeyReachesTheJoggingSpeedAndBrakesWhenReleased) {
  const axes::AxisParameters a = Slide();
  Checks checks;
  const AxisJogContext c = checks.Context(JogMode::kContinuous);
  JogAxis j;
  j.key = 1;
  double x = 0;
  for (int i = 0; i < 100; ++i) JogAxisCycle(j, a, c, x, kDt);
  EXPECT_DOUBLE_EQ(j.velocity, 10);
  const double released_at = x;
  j.key = 0;
  for (int i = 0; i < 100; ++i) JogAxisCycle(j, a, c, x, kDt);
  EXPECT_EQ(j.velocity, 0);
  // v^2 / 2a = 0.05 mm of braking (within a cycle's step).
  EXPECT_NEAR(x - released_at, 0.05, 0.011);
  EXPECT_TRUE(checks.asked.empty());  // continuous jogs are checked ahead by the channel
}

TEST(AxisJogTest, AContinuousJogStopsAtTheWindowEdgeWithoutPassingIt) {
  const axes::AxisParameters a = Slide();
  Checks checks;
  AxisJogContext c = checks.Context(JogMode::kRapid);
  c.window = {true, -5, 3};
  JogAxis j;
  j.key = 1;
  double x = 0, highest = 0;
  for (int i = 0; i < 2000; ++i) {
    JogAxisCycle(j, a, c, x, kDt);
    highest = std::max(highest, x);
  }
  EXPECT_DOUBLE_EQ(highest, 3);
  EXPECT_DOUBLE_EQ(x, 3);
  EXPECT_EQ(j.velocity, 0);
}

TEST(AxisJogTest, NoEnablingSignalNoBlockedDirectionNoMotion) {
  const axes::AxisParameters a = Slide();
  Checks checks;
  AxisJogContext c = checks.Context(JogMode::kContinuous);
  JogAxis j;
  j.key = -1;
  double x = 0;
  c.enabled = false;
  for (int i = 0; i < 50; ++i) JogAxisCycle(j, a, c, x, kDt);
  EXPECT_EQ(x, 0);
  c.enabled = true;
  j.blocked = -1;  // PathGuard stopped this direction
  for (int i = 0; i < 50; ++i) JogAxisCycle(j, a, c, x, kDt);
  EXPECT_EQ(x, 0);
}

TEST(AxisJogTest, AnIncrementRunsToItsEndOncePerPress) {
  const axes::AxisParameters a = Slide();
  Checks checks;
  const AxisJogContext c = checks.Context(JogMode::kIncrement1000, 1.0);
  JogAxis j;
  j.key = -1;
  double x = 10;
  JogAxisCycle(j, a, c, x, kDt);
  EXPECT_EQ(j.key, 0);  // taken: one increment per press
  EXPECT_TRUE(j.stepping);
  ASSERT_EQ(checks.asked.size(), 1u);
  EXPECT_DOUBLE_EQ(checks.asked[0], 9);  // checked whole before it starts
  for (int i = 0; i < 2000 && j.stepping; ++i) JogAxisCycle(j, a, c, x, kDt);
  EXPECT_FALSE(j.stepping);
  EXPECT_DOUBLE_EQ(x, 9);
  // A new mode while it ran does not cut it short: it was done already; nothing more moves.
  for (int i = 0; i < 100; ++i) JogAxisCycle(j, a, c, x, kDt);
  EXPECT_DOUBLE_EQ(x, 9);
}

TEST(AxisJogTest, AnIncrementIsClippedToTheWindowAndRefusedByPathGuard) {
  const axes::AxisParameters a = Slide();
  Checks checks;
  AxisJogContext c = checks.Context(JogMode::kParametric);
  c.window = {true, 0, 1};
  JogAxis j;
  j.key = 1;
  double x = 0;
  checks.allow = false;
  JogAxisCycle(j, a, c, x, kDt);
  EXPECT_FALSE(j.stepping);
  EXPECT_EQ(j.key, 0);  // the press is spent
  ASSERT_EQ(checks.asked.size(), 1u);
  EXPECT_DOUBLE_EQ(checks.asked[0], 1);  // 2.5 mm clipped to the window
  EXPECT_EQ(x, 0);
  checks.allow = true;
  j.key = 1;
  for (int i = 0; i < 2000; ++i) JogAxisCycle(j, a, c, x, kDt);
  EXPECT_DOUBLE_EQ(x, 1);
}

TEST(AxisJogTest, TheHandwheelFollowsItsCountsWithinTheWindow) {
  const axes::AxisParameters a = Slide();
  Checks checks;
  AxisJogContext c = checks.Context(JogMode::kHandwheel);
  c.window = {true, -2, 2};
  JogAxis j;
  double x = 0;
  JogAxisCycle(j, a, c, x, kDt);  // the counts start from where the axis stands
  EXPECT_TRUE(j.handwheel);
  EXPECT_EQ(j.handwheel_target, 0);
  j.handwheel_target = 1.5;
  for (int i = 0; i < 1000; ++i) JogAxisCycle(j, a, c, x, kDt);
  EXPECT_DOUBLE_EQ(x, 1.5);
  j.handwheel_target = 7;  // beyond the window: clipped
  for (int i = 0; i < 1000; ++i) JogAxisCycle(j, a, c, x, kDt);
  EXPECT_DOUBLE_EQ(x, 2);
  EXPECT_DOUBLE_EQ(j.handwheel_target, 2);
  j.key = 1;  // keys move nothing in handwheel mode
  for (int i = 0; i < 100; ++i) JogAxisCycle(j, a, c, x, kDt);
  EXPECT_DOUBLE_EQ(x, 2);
}

TEST(AxisJogTest, HomingRunsToTheReferenceAndEndsHomed) {
  const axes::AxisParameters a = Slide();
  Checks checks;
  const AxisJogContext c = checks.Context(JogMode::kContinuous);
  JogAxis j;
  j.home_requested = true;
  double x = 0;
  int homed_at = -1;
  for (int i = 0; i < 5000 && homed_at < 0; ++i)
    if (JogAxisCycle(j, a, c, x, kDt)) homed_at = i;
  ASSERT_GE(homed_at, 0);
  EXPECT_DOUBLE_EQ(x, 40);
  EXPECT_FALSE(j.homing || j.stepping || j.home_requested);
  // 40 mm at 20 mm/s: about two seconds.
  EXPECT_NEAR(homed_at * kDt, 2.0, 0.05);
  ASSERT_EQ(checks.asked.size(), 1u);
  EXPECT_DOUBLE_EQ(checks.asked[0], 40);
}

TEST(AxisJogTest, HomingWaitsForAJogToEndAndLapsesOutsideManualMode) {
  const axes::AxisParameters a = Slide();
  Checks checks;
  AxisJogContext c = checks.Context(JogMode::kContinuous);
  JogAxis j;
  j.velocity = 5;  // still braking from a jog
  j.home_requested = true;
  double x = 0;
  JogAxisCycle(j, a, c, x, kDt);
  EXPECT_FALSE(j.homing);
  EXPECT_TRUE(j.home_requested);
  c.manual = false;
  JogAxisCycle(j, a, c, x, kDt);
  EXPECT_FALSE(j.home_requested);
  // At the reference already: homed at once, without a move.
  j = JogAxis{};
  j.home_requested = true;
  c.manual = true;
  x = 40;
  EXPECT_TRUE(JogAxisCycle(j, a, c, x, kDt));
  EXPECT_FALSE(j.stepping);
}

}  // namespace
}  // namespace vmt::control::channel
