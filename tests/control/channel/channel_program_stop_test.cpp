// M00 and M01 (programmed_stop.hpp) and the stop conditions (HLI_SC_*, block search manual 5.6)
// the channel reports for each reason it stands: programmed stops, feed hold, a changeover
// waiting for the PLC, an axis exchange, a suspended output and a PathGuard collision.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"
#include "headstock_lathe.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing
using ::testing::HasSubstr;
namespace sc = stop_condition;

void Ticks(Machine& m, double s) {
  for (int i = 0; i < s / 250e-6; ++i) m.Tick();
}

uint32_t StopConditions(const Machine& m) { return m.channel->block_search().stop_conditions; }

/// Runs until the channel holds, and on for the drives' fine interpolation of the last cycle.
bool RunUntilHeld(Machine& m, double limit_s = 10) {
  const double end = m.t + limit_s;
  while (m.channel->state() == ChannelState::kRunning && m.t < end) m.Tick();
  Ticks(m, 0.002);
  return m.channel->state() == ChannelState::kHold;
}

constexpr const char* kProgram =
    "N1 G01 X10 F6000\n"
    "N2 G01 Z5 M00\n"
    "N3 G01 X20\n"
    "N4 G01 Z10 M01\n"
    "N5 G01 X30\n"
    "N6 RET\n";

TEST(ChannelProgramStopTest, M00HoldsAfterItsBlockUntilTheNextStart) {
  Machine m(kProgram);
  m.channel->Start();
  ASSERT_TRUE(RunUntilHeld(m)) << m.channel->error();
  // N2 ran to its end; N3 waits.
  EXPECT_EQ(m.X(), 10);
  EXPECT_EQ(m.Z(), 5);
  Ticks(m, 1);
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_EQ(m.X(), 10);
  // 5.6: M00_OR_M01 and M0_STOP, not a feed hold; the path travelled lies in the path memory,
  // so the program could be run backwards from here.
  EXPECT_EQ(StopConditions(m), sc::kM00OrM01 | sc::kM0Stop | sc::kStopReversible);
  // Without the optional-stop signal M01 does not hold: the program runs to its end.
  m.channel->Start();
  m.RunUntilEnd(m.t + 10);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_EQ(m.X(), 30);
  EXPECT_EQ(m.Z(), 10);
}

TEST(ChannelProgramStopTest, M01HoldsOnlyWithTheOptionalStopSignal) {
  Machine m(kProgram);
  m.channel->SetOptionalStop(true);
  m.channel->Start();
  ASSERT_TRUE(RunUntilHeld(m));  // M00
  m.channel->Start();
  ASSERT_TRUE(RunUntilHeld(m)) << m.channel->error();  // M01
  EXPECT_EQ(m.X(), 20);
  EXPECT_EQ(m.Z(), 10);
  Ticks(m, 0.5);
  EXPECT_EQ(m.X(), 20);
  EXPECT_EQ(StopConditions(m) & ~sc::kStopReversible, sc::kM00OrM01 | sc::kM1Stop);
  m.channel->Start();
  m.RunUntilEnd(m.t + 10);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_EQ(m.X(), 30);
}

TEST(ChannelProgramStopTest, TheStopFunctionGoesToThePlcAndTheStopFollowsItsAcknowledgement) {
  Machine m("N1 G01 X10 F6000 M00\nN2 G01 X20\nN3 RET\n", 0, 0,
            [](ChannelConfig& c) { c.aux_handshake = true; });
  m.channel->Start();
  Ticks(m, 0.1);
  ASSERT_EQ(m.channel->aux_output().size(), 1u);
  EXPECT_EQ(m.channel->aux_output()[0].letter, 'M');
  EXPECT_EQ(m.channel->aux_output()[0].value, 0);
  EXPECT_EQ(m.channel->state(), ChannelState::kRunning);
  EXPECT_EQ(StopConditions(m), sc::kPlcAcknowledge | sc::kWaitTechnoAck);
  m.channel->AcknowledgeAux();
  ASSERT_TRUE(RunUntilHeld(m));
  EXPECT_EQ(m.X(), 10);
  EXPECT_EQ(StopConditions(m) & sc::kM0Stop, sc::kM0Stop);
  m.channel->Start();
  m.RunUntilEnd(m.t + 10);
  EXPECT_EQ(m.X(), 20);
}

TEST(ChannelProgramStopTest, FeedHoldAndControlResetLeaveNoProgrammedStop) {
  Machine m(kProgram);
  m.channel->Start();
  Ticks(m, 0.02);
  m.channel->Stop();
  Ticks(m, 0.2);
  ASSERT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_EQ(StopConditions(m), sc::kFeedhold);
  m.channel->Start();
  ASSERT_TRUE(RunUntilHeld(m));
  EXPECT_EQ(StopConditions(m) & sc::kM0Stop, sc::kM0Stop);
  m.channel->Reset();
  Ticks(m, 0.01);
  EXPECT_EQ(StopConditions(m), 0u);
}

TEST(ChannelProgramStopTest, OverrideZeroDwellAndSingleBlockAreTheirOwnStopConditions) {
  Machine m("N1 G01 X10 F6000\nN2 G00 X20\nN3 G04 F0.5\nN4 RET\n");
  m.channel->Start();
  Ticks(m, 0.05);
  m.channel->SetFeedOverride(0);
  Ticks(m, 0.01);
  EXPECT_EQ(StopConditions(m), sc::kOverrideZero);
  m.channel->SetFeedOverride(1);
  while (m.X() < 12 && m.t < 5) m.Tick();
  m.channel->SetFeedOverride(0);
  Ticks(m, 0.01);
  EXPECT_EQ(StopConditions(m), sc::kOverrideRapidZero);
  m.channel->SetFeedOverride(1);
  while (m.X() < 20 && m.t < 5) m.Tick();
  Ticks(m, 0.1);
  EXPECT_EQ(StopConditions(m), sc::kDelayTime);
  m.channel->SetSingleBlock(true);
  ASSERT_TRUE(RunUntilHeld(m));
  EXPECT_EQ(StopConditions(m), sc::kSingleBlock);
}

TEST(ChannelProgramStopTest, AnAxisExchangeAndASuspendedOutputAreStopConditions) {
  // Block search 4.2.1: the axes change hands at standstill only; meanwhile the channel waits
  // for the exchange it asked for. Then, lent, its program reads no blocks.
  Machine m("N1 G01 X100 F6000\nN2 RET\n");
  m.channel->Start();
  Ticks(m, 0.2);
  m.channel->Stop();
  m.channel->SetSuspendOutput(true);
  Ticks(m, 0.001);
  EXPECT_EQ(StopConditions(m) & sc::kWaitForAxes, sc::kWaitForAxes);
  Ticks(m, 0.5);
  EXPECT_EQ(StopConditions(m) & (sc::kWaitForAxes | sc::kIpoInputDisabled),
            sc::kIpoInputDisabled);
  m.channel->SetSuspendOutput(false);
  Ticks(m, 0.01);
  EXPECT_EQ(StopConditions(m) & (sc::kWaitForAxes | sc::kIpoInputDisabled), 0u);
}

TEST(ChannelProgramStopTest, AChangeoverWaitingForThePlcLeavesTheInterpolatorEmpty) {
  headstock_test::Lathe m("N1 G00 C90\nN2 RET\n");
  m.acknowledge = false;  // the PLC does not acknowledge ROTMOD
  m.channel->Start();
  m.Ticks(40);
  ASSERT_EQ(m.channel->state(), ChannelState::kRunning);
  EXPECT_EQ(m.channel->block_search().stop_conditions, sc::kWaitTechnoAck | sc::kIpoInputEmpty);
  m.acknowledge = true;
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

/// The tool touches a wall at X = 20.
struct Wall : PathGuard {
  PathCheck CheckMove(const std::vector<double>& from, const std::vector<double>& to) override {
    PathCheck c;
    c.min_clearance = std::min(from[0], to[0]) - 20;
    if (to[0] <= 20) return c;
    c.clear = false;
    c.part_a = "tool", c.part_b = "wall";
    c.position = from;
    c.position[0] = 20;
    c.min_clearance = 0;
    return c;
  }
};

TEST(ChannelProgramStopTest, APathGuardCollisionIsAnErrorAfterADetectedCollision) {
  Machine m("N1 G00 X30\nN2 RET\n", 0, 0, [](ChannelConfig& c) { c.approach_program = true; });
  Wall wall;
  m.channel->SetPathGuard(&wall);
  m.channel->Start();
  Ticks(m, 0.01);
  ASSERT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_THAT(m.channel->error(), HasSubstr("collision ahead"));
  EXPECT_EQ(StopConditions(m), sc::kChannelError | sc::kWaitContinueAfterCollision);
}

}  // namespace
}  // namespace vmt::control::channel
