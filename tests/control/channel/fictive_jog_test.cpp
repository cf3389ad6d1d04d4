// X1/Y1 of G31 jogged on their own: a held key reaches the jogging speed and brakes in time for
// the zone's edge, an increment runs to its end once per press (the zone cuts it short), the
// handwheel follows its counts up to the zone, the stop point PathGuard checks lies where the
// jog can come to rest, and the handwheel restarts from there.

#include "control/channel/fictive_jog.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace vmt::control::channel {
namespace {

constexpr double kDt = 1e-3;

FictiveJogContext Context(JogMode mode, double increment = 0) {
  FictiveJogContext c;
  c.mode = mode;
  c.increment = increment;
  c.speed = 10;
  c.handwheel_speed = 50;
  c.acceleration = 1000;
  return c;
}

/// Runs `cycles` cycles, following the point.
nc::FictivePoint JogCycles(FictiveJog (&jogs)[2], nc::FictivePoint at, const FictiveJogContext& c,
                           int cycles) {
  for (int i = 0; i < cycles; ++i)
    if (const auto moved = FictiveJogCycle(jogs, at, c, kDt)) at = *moved;
  return at;
}

TEST(FictiveJogTest, AHeldKeyMovesOneFictiveAxisAtTheJoggingSpeed) {
  FictiveJog jogs[2];
  jogs[1].key = -1;  // Y1-
  const FictiveJogContext c = Context(JogMode::kContinuous);
  const nc::FictivePoint at = JogCycles(jogs, {20, 5}, c, 100);
  EXPECT_DOUBLE_EQ(at.x1, 20);
  EXPECT_DOUBLE_EQ(jogs[1].velocity, -10);
  // 10 cycles to reach 10 mm/s (1 + 2 + ... + 10 mm/s for 1 ms each), then 90 at it.
  EXPECT_NEAR(at.y1, 5 - (0.055 + 0.9), 1e-9);
  // Released: it brakes to a stop within 10 cycles (9 + 8 + ... + 1 mm/s) and then nothing moves.
  jogs[1].key = 0;
  const nc::FictivePoint rest = JogCycles(jogs, at, c, 20);
  EXPECT_EQ(jogs[1].velocity, 0);
  EXPECT_NEAR(rest.y1, at.y1 - 0.045, 1e-9);
  EXPECT_FALSE(FictiveJogCycle(jogs, rest, c, kDt).has_value());
}

TEST(FictiveJogTest, AKeyBrakesInTimeForTheZoneAndStaysThere) {
  FictiveJog jogs[2];
  jogs[0].key = 1;
  FictiveJogContext c = Context(JogMode::kContinuous);
  c.low[0] = 0;
  c.high[0] = 21;  // X1 may go 1 mm further
  const nc::FictivePoint at = JogCycles(jogs, {20, 0}, c, 500);
  EXPECT_DOUBLE_EQ(at.x1, 21);
  EXPECT_EQ(jogs[0].velocity, 0);
  EXPECT_FALSE(FictiveJogCycle(jogs, at, c, kDt).has_value());
  // Back out of the zone's edge it moves again.
  jogs[0].key = -1;
  EXPECT_LT(JogCycles(jogs, at, c, 10).x1, 21);
}

TEST(FictiveJogTest, AnIncrementRunsToItsEndOncePerPressAndNotPastTheZone) {
  FictiveJog jogs[2];
  FictiveJogContext c = Context(JogMode::kParametric, 0.5);
  jogs[0].key = 1;
  nc::FictivePoint at = JogCycles(jogs, {20, 0}, c, 300);
  EXPECT_DOUBLE_EQ(at.x1, 20.5);
  EXPECT_FALSE(jogs[0].stepping);
  EXPECT_EQ(jogs[0].key, 0);  // the press is used up: holding it does not step again
  EXPECT_DOUBLE_EQ(JogCycles(jogs, at, c, 300).x1, 20.5);
  // Without the enabling signals a press starts nothing.
  c.enabled = false;
  jogs[0].key = 1;
  EXPECT_FALSE(FictiveJogCycle(jogs, at, c, kDt).has_value());
  EXPECT_FALSE(jogs[0].stepping);
  // The zone ends the increment at its edge.
  c.enabled = true;
  c.high[0] = 20.7;
  jogs[0].key = 1;
  at = JogCycles(jogs, at, c, 300);
  EXPECT_DOUBLE_EQ(at.x1, 20.7);
}

TEST(FictiveJogTest, TheHandwheelFollowsItsCountsUpToTheZone) {
  FictiveJog jogs[2];
  FictiveJogContext c = Context(JogMode::kHandwheel);
  c.low[1] = -3;
  jogs[1].handwheel = true;
  jogs[1].handwheel_target = -5;  // beyond the zone: held at its edge
  jogs[1].key = -1;               // keys do nothing in handwheel mode
  const nc::FictivePoint at = JogCycles(jogs, {20, 0}, c, 1000);
  EXPECT_DOUBLE_EQ(at.y1, -3);
  EXPECT_DOUBLE_EQ(jogs[1].handwheel_target, -3);
  EXPECT_FALSE(jogs[1].handwheel);  // there: the next counts start from here
  EXPECT_EQ(jogs[1].key, 0);
  EXPECT_DOUBLE_EQ(at.x1, 20);
}

TEST(FictiveJogTest, PathGuardChecksWhereTheJogCanComeToRest) {
  FictiveJog jogs[2];
  jogs[0].velocity = 10;  // X1 at 10 mm/s: 0.05 mm braking at 1000 mm/s^2
  const nc::FictivePoint stop = FictiveJogStop(jogs, JogMode::kContinuous, {20, 0}, 1000, 0.01);
  EXPECT_NEAR(stop.x1, 20 + 0.05 + 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(stop.y1, 0);
  // The handwheel's: its target.
  jogs[1].handwheel = true;
  jogs[1].handwheel_target = 4;
  const nc::FictivePoint wheel = FictiveJogStop(jogs, JogMode::kHandwheel, {20, 0}, 1000, 0.01);
  EXPECT_DOUBLE_EQ(wheel.x1, 20);
  EXPECT_DOUBLE_EQ(wheel.y1, 4);
}

TEST(FictiveJogTest, TheHandwheelRestartsWhereAMovingAxisComesToRest) {
  FictiveJog jogs[2];
  jogs[0].velocity = -10;  // braking from here ends 0.05 mm further
  jogs[1].stepping = true;
  jogs[1].target = 3;  // an increment under way runs to its end
  RestartFictiveHandwheel(jogs, JogMode::kHandwheel, {20, 1}, 1000);
  EXPECT_TRUE(jogs[0].handwheel);
  EXPECT_DOUBLE_EQ(jogs[0].handwheel_target, 20 - 0.05);
  EXPECT_TRUE(jogs[1].handwheel);
  EXPECT_DOUBLE_EQ(jogs[1].handwheel_target, 3);
  // At rest, or outside handwheel mode, there is no target.
  FictiveJog still[2];
  RestartFictiveHandwheel(still, JogMode::kHandwheel, {20, 1}, 1000);
  EXPECT_FALSE(still[0].handwheel);
  RestartFictiveHandwheel(jogs, JogMode::kContinuous, {20, 1}, 1000);
  EXPECT_FALSE(jogs[0].handwheel);
  EXPECT_FALSE(jogs[1].handwheel);
}

}  // namespace
}  // namespace vmt::control::channel
