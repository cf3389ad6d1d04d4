// The channel's PathGuard bookkeeping on its own: clear checks and contacts recorded in order,
// what stops a move under each reaction, and a continuous move checked ahead at its start and
// then every few NC cycles, summed up as one record until it rests or meets a contact.

#include "control/channel/path_guard_client.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace vmt::control::channel {
namespace {

PathCheck Clear(double clearance) {
  PathCheck c;
  c.min_clearance = clearance;
  return c;
}

PathCheck Contact() {
  PathCheck c;
  c.clear = false;
  c.part_a = "tool";
  c.part_b = "chuck";
  return c;
}

const std::vector<double> kFrom{0, 0}, kTo{10, 0};

TEST(PathGuardClientTest, WithoutAGuardOrWithReactionOffNothingIsChecked) {
  PathGuardClient off(GuardReaction::kOff, 8);
  EXPECT_FALSE(off.active());
  PathGuardClient none(GuardReaction::kStop, 8);
  EXPECT_FALSE(none.active());
}

TEST(PathGuardClientTest, ContactsStopUnderStopAndAreOnlyRecordedUnderWarn) {
  PathGuardClient stop(GuardReaction::kStop, 8);
  stop.Clear("G77", kFrom, kTo, Clear(3));
  EXPECT_TRUE(stop.Contact("repositioning", kFrom, kTo, Contact()));
  std::vector<GuardRecord> records = stop.TakeRecords();
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].move, "G77");
  EXPECT_FALSE(records[0].stopped);
  EXPECT_EQ(records[1].move, "repositioning");
  EXPECT_TRUE(records[1].stopped);
  EXPECT_TRUE(stop.TakeRecords().empty());

  PathGuardClient warn(GuardReaction::kWarn, 8);
  EXPECT_FALSE(warn.Contact("jog", kFrom, kTo, Contact()));
  records = warn.TakeRecords();
  ASSERT_EQ(records.size(), 1u);
  EXPECT_FALSE(records[0].stopped);
  EXPECT_FALSE(records[0].check.clear);
}

TEST(PathGuardClientTest, AJogIsCheckedAtItsStartThenEveryNCyclesAsOneRecord) {
  PathGuardClient g(GuardReaction::kStop, 4);
  int checks = 0;
  for (int cycle = 0; cycle < 12; ++cycle) {
    if (!g.Due(ContinuousMove::kJog, true)) continue;
    ++checks;
    std::vector<double> to{10.0 + cycle, 0};
    EXPECT_FALSE(g.Ahead(ContinuousMove::kJog, "jog", kFrom, to, Clear(5 - cycle * 0.1)));
  }
  EXPECT_EQ(checks, 3);                              // cycles 0, 4, 8
  EXPECT_TRUE(g.TakeRecords().empty());              // still running: no record yet
  EXPECT_FALSE(g.Due(ContinuousMove::kJog, false));  // at rest: the record closes
  const std::vector<GuardRecord> records = g.TakeRecords();
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].checks, 3);
  EXPECT_DOUBLE_EQ(records[0].check.min_clearance, 5 - 8 * 0.1);  // the smallest
  EXPECT_EQ(records[0].to, (std::vector<double>{18, 0}));         // the last check's
  EXPECT_TRUE(g.Due(ContinuousMove::kJog, true));                 // a new jog is checked at once
}

TEST(PathGuardClientTest, AContactAheadClosesTheRecordAndStops) {
  PathGuardClient g(GuardReaction::kStop, 4);
  ASSERT_TRUE(g.Due(ContinuousMove::kTurretJog, true));
  EXPECT_FALSE(g.Ahead(ContinuousMove::kTurretJog, "turret index MGPOS", kFrom, kTo, Clear(2)));
  // The jog of the feed axes is another record.
  ASSERT_TRUE(g.Due(ContinuousMove::kJog, true));
  for (int i = 0; i < 3; ++i) ASSERT_FALSE(g.Due(ContinuousMove::kTurretJog, true));
  ASSERT_TRUE(g.Due(ContinuousMove::kTurretJog, true));
  EXPECT_TRUE(g.Ahead(ContinuousMove::kTurretJog, "turret index MGPOS", kFrom, kTo, Contact()));
  const std::vector<GuardRecord> records = g.TakeRecords();
  ASSERT_EQ(records.size(), 2u);
  EXPECT_FALSE(records[0].stopped);  // the clear part, closed
  EXPECT_TRUE(records[1].stopped);   // the contact
}

TEST(PathGuardClientTest, XYJogIsDueEveryNCycles) {
  PathGuardClient g(GuardReaction::kStop, 3);
  int due = 0;
  for (int i = 0; i < 9; ++i) due += g.FictiveDue();
  EXPECT_EQ(due, 3);
}

}  // namespace
}  // namespace vmt::control::channel
