// PathGuard in the channel: jogs checked ahead stop before the contact with message 507 naming
// the parts and the position, the key stays stopped until released, the other way is free;
// increments are checked whole before they start; warn records and goes on; off asks nothing.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

/// A wall: the tool (drive 0, X) touches it at X = 20; straight moves only, like the real one.
struct Wall : PathGuard {
  PathCheck CheckMove(const std::vector<double>& from, const std::vector<double>& to) override {
    ++checks;
    PathCheck c;
    c.min_clearance = std::min(from[0], to[0]) - 20;
    c.closest_a = "tool", c.closest_b = "wall";
    if (to[0] > 20 || from[0] < 20) return c;
    const double u = (from[0] - 20) / (from[0] - to[0]);
    c.clear = false;
    c.part_a = "tool", c.part_b = "wall";
    c.position = from;
    for (size_t d = 0; d < from.size(); ++d) c.position[d] = from[d] + (to[d] - from[d]) * u;
    c.point[0] = 20;
    c.distance = std::abs(from[0] - 20);
    c.min_clearance = 0;
    return c;
  }
  int checks = 0;
};

void Hold(Machine& m, double s) {
  for (int i = 0; i < s / 250e-6; ++i) m.Tick();
}

/// The channel's machine with X at `x` (Z 0), `guard` asking about its moves, switched to
/// manual mode: `manual` says whether the channel took it.
struct GuardedManualMachine : Machine {
  GuardedManualMachine(PathGuard& guard, double x,
                       const std::function<void(ChannelConfig&)>& configure = {})
      : Machine("N1 RET\n", x, 0, configure) {
    channel->SetPathGuard(&guard);
    manual = channel->SetMode(ChannelMode::kManual);
  }
  bool manual = false;
};

TEST(ChannelPathGuard, ContinuousJogStopsBeforeTheWallWithMessage507) {
  Wall wall;
  GuardedManualMachine m(wall, 60);
  ASSERT_TRUE(m.manual);
  m.channel->SetJogMode(static_cast<int>(JogMode::kRapid));  // 200 mm/s towards the wall
  m.channel->Jog(0, -1);
  Hold(m, 1.0);
  EXPECT_GT(m.X(), 20);  // stopped before it
  EXPECT_LT(m.X(), 60);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgCollision);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("tool would touch wall at X20.000"));
  // Still held: nothing moves; released and pressed again: stopped again at once.
  const double x = m.X();
  Hold(m, 0.2);
  EXPECT_EQ(m.X(), x);
  // The other way is free.
  m.channel->Jog(0, +1);
  Hold(m, 0.2);
  EXPECT_GT(m.X(), x + 1);
  m.channel->Jog(0, 0);
  Hold(m, 0.2);
  const std::vector<GuardRecord> records = m.channel->TakeGuardRecords();
  ASSERT_FALSE(records.empty());
  int stops = 0;
  for (const GuardRecord& r : records) stops += r.stopped;
  EXPECT_EQ(stops, 1);
  EXPECT_GT(wall.checks, 20);  // checked ahead all along
}

TEST(ChannelPathGuard, AnIncrementIntoTheWallDoesNotStart) {
  Wall wall;
  GuardedManualMachine m(wall, 20.5);
  ASSERT_TRUE(m.manual);
  m.channel->SetJogIncrement(1.0);
  m.channel->Jog(0, -1);
  Hold(m, 0.5);
  EXPECT_EQ(m.X(), 20.5);
  EXPECT_EQ(m.channel->error_number(), kMsgCollision);
  m.channel->Jog(0, 0);
  m.channel->Reset();
  Hold(m, 0.05);
  m.channel->SetJogIncrement(0.1);  // short of the wall: runs
  m.channel->Jog(0, -1);
  Hold(m, 0.5);
  EXPECT_NEAR(m.X(), 20.4, 1e-9);
}

TEST(ChannelPathGuard, AnIncrementIsCheckedAsItselfNotAsAContinuousRun) {
  // 0.2 mm short of the wall: a continuous run at the jog speed could not brake in time, but
  // the key starts an increment that ends 0.1 mm before it; one record, the increment's.
  Wall wall;
  GuardedManualMachine m(wall, 20.3);
  ASSERT_TRUE(m.manual);
  m.channel->SetJogIncrement(0.2);
  m.channel->Jog(0, -1);
  Hold(m, 0.5);
  m.channel->Jog(0, 0);
  EXPECT_NE(m.channel->state(), ChannelState::kError) << m.channel->error();
  EXPECT_NEAR(m.X(), 20.1, 1e-9);
  const std::vector<GuardRecord> records = m.channel->TakeGuardRecords();
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].move, "jog");
  EXPECT_NEAR(records[0].from[0], 20.3, 1e-9);
  EXPECT_NEAR(records[0].to[0], 20.1, 1e-9);
}

TEST(ChannelPathGuard, WarnRecordsAndGoesOnOffAsksNothing) {
  Wall wall;
  GuardedManualMachine warn(wall, 30,
                            [](ChannelConfig& c) { c.path_guard = GuardReaction::kWarn; });
  ASSERT_TRUE(warn.manual);
  warn.channel->Jog(0, -1);
  Hold(warn, 0.5);
  EXPECT_LT(warn.X(), 20);  // through the wall: a warning only
  EXPECT_NE(warn.channel->state(), ChannelState::kError);
  bool recorded = false;
  for (const GuardRecord& r : warn.channel->TakeGuardRecords())
    recorded = recorded || (!r.check.clear && !r.stopped);
  EXPECT_TRUE(recorded);

  Wall unused;
  GuardedManualMachine off(unused, 30,
                           [](ChannelConfig& c) { c.path_guard = GuardReaction::kOff; });
  ASSERT_TRUE(off.manual);
  off.channel->Jog(0, -1);
  Hold(off, 0.5);
  EXPECT_EQ(unused.checks, 0);
  EXPECT_LT(off.X(), 20);
}

}  // namespace
}  // namespace vmt::control::channel
