// The operator's control of a program on the channel: feed hold, single block, feed override,
// mode change, program selection, MDI and the reverse program.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

TEST(ChannelTest, FeedHoldStopsOnThePathAndResumes) {
  Machine m("N1 G01 X100 Z50 F6000\nN2 RET\n");
  m.channel->Start();
  while (m.t < 0.3) m.Tick();
  m.channel->Stop();
  for (int i = 0; i < 1000; ++i) m.Tick();
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  const double x = m.X(), z = m.Z();
  EXPECT_GT(x, 10);
  EXPECT_LT(x, 100);
  EXPECT_NEAR(z, x / 2, 1e-9);  // the stop point lies on the programmed line
  for (int i = 0; i < 100; ++i) m.Tick();
  EXPECT_EQ(m.X(), x);  // standing
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(m.X(), 100);
}

TEST(ChannelTest, SingleBlockHoldsAfterEachBlock) {
  Machine m("N1 G01 X10 F6000\nN2 X20\nN3 X30\nN4 RET\n");
  m.channel->SetSingleBlock(true);
  std::vector<double> stops;
  for (int start = 0; start < 10 && m.channel->state() != ChannelState::kEnded; ++start) {
    m.channel->Start();
    for (int i = 0; i < 4000 && m.channel->state() == ChannelState::kRunning; ++i) m.Tick();
    for (int i = 0; i < 8; ++i) m.Tick();  // fine interpolation trails the NC cycle by one cycle
    stops.push_back(m.X());
  }
  EXPECT_EQ(stops, (std::vector<double>{10, 20, 30, 30}));
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
}

TEST(ChannelTest, ModeChangeWaitsForTheProgramToStop) {
  Machine m("N1 G01 X100 F600\nN2 RET\n");
  m.channel->Start();
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_FALSE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Stop();
  for (int i = 0; i < 400; ++i) m.Tick();
  // Interrupted: jog away in manual, come back, continue the program.
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(m.X(), 100);
}

TEST(ChannelTest, OverrideScalesTheFeed) {
  Machine full("N1 G01 X100 F3000\nN2 RET\n"), half("N1 G01 X100 F3000\nN2 RET\n");
  half.channel->SetFeedOverride(0.5);
  full.channel->Start();
  half.channel->Start();
  EXPECT_NEAR(half.RunUntilEnd() / full.RunUntilEnd(), 2, 0.02);
}

TEST(ChannelTest, SelectedProgramRunsAtTheNextStartAndTheOthersStayCallable) {
  Machine m(std::vector<std::string>{"N1 G01 X10 F6000\nN2 RET\n",
                                     "N1 G01 X20 F6000\nN2 JSR .SUB\nN3 RET\n.SUB\nN4 Z5\nN5 RTS\n",
                                     "N1 G01 X30 F6000\nN2 RET\n"});
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_DOUBLE_EQ(m.X(), 10);
  ASSERT_TRUE(m.channel->SelectProgram(1));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(m.X(), 20);
  EXPECT_DOUBLE_EQ(m.Z(), 5);
  // The first program is still in the store: index 1 now that the second is in front.
  ASSERT_TRUE(m.channel->SelectProgram(1));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_DOUBLE_EQ(m.X(), 10);
  EXPECT_FALSE(m.channel->SelectProgram(3));  // no such program
}

TEST(ChannelTest, ProgramSelectionIsRefusedWhileAProgramIsActiveOrInterrupted) {
  Machine m(std::vector<std::string>{"N1 G01 X100 F600\nN2 RET\n", "N1 G01 X5 F600\nN2 RET\n"});
  m.channel->Start();
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_FALSE(m.channel->SelectProgram(1));  // running
  m.channel->Stop();
  for (int i = 0; i < 400; ++i) m.Tick();
  ASSERT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_FALSE(m.channel->SelectProgram(1));  // interrupted: the interruption point would be lost
  m.channel->Reset();
  for (int i = 0; i < 8; ++i) m.Tick();
  ASSERT_TRUE(m.channel->SelectProgram(1));  // Control-Reset ended it
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(m.X(), 5);
}

TEST(ChannelTest, MdiRunsTypedBlocksInTheModalStateOfTheLastProgram) {
  Machine m("N1 G91 G01 X10 F6000\nN2 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kMdi));
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);
  ASSERT_TRUE(m.channel->Mdi("X5 Z-3\nX1 Z1\n"));
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 16, 1e-9);  // G91 carried over: 10 + 5 + 1
  EXPECT_NEAR(m.Z(), -2, 1e-9);
  // A text that does not parse is refused with its message; Control-Reset clears it.
  EXPECT_FALSE(m.channel->Mdi("X5 Z-3 Y"));
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgMdiSyntax);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("MDI:1:"));
  m.channel->Reset();
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);
  // Back in automatic, start runs the program again from its top.
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_NEAR(m.X(), 26, 1e-9);  // G91 X10 from 16
}

TEST(ChannelTest, ReverseContinuesAtHome) {
  Machine m("N1 G01 X100 F600\nN2 X0\nN3 RET\n.HOME\nN10 G00 Z50\nN11 G00 X-20\nN12 RET\n");
  m.channel->Start();
  for (int i = 0; i < 2000; ++i) m.Tick();
  EXPECT_FALSE(m.channel->Reverse());  // only when interrupted
  m.channel->Stop();
  for (int i = 0; i < 800; ++i) m.Tick();
  const double x = m.X();
  ASSERT_GT(x, 1);
  ASSERT_LT(x, 99);
  ASSERT_TRUE(m.channel->Reverse());
  EXPECT_TRUE(m.channel->reversing());
  bool x_still_while_z = true;
  while (m.channel->state() == ChannelState::kRunning && m.t < 20) {
    m.Tick();
    if (m.Z() > 0 && m.Z() < 50 && std::abs(m.X() - x) > 1e-9) x_still_while_z = false;
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_FALSE(m.channel->reversing());
  EXPECT_TRUE(x_still_while_z);
  EXPECT_DOUBLE_EQ(m.Z(), 50);
  EXPECT_DOUBLE_EQ(m.X(), -20);

  Machine none("N1 G01 X100 F600\nN2 RET\n");
  none.channel->Start();
  for (int i = 0; i < 400; ++i) none.Tick();
  none.channel->Stop();
  for (int i = 0; i < 400; ++i) none.Tick();
  EXPECT_FALSE(none.channel->Reverse());
  EXPECT_EQ(none.channel->error_number(), kMsgNoHomeLabel);
}

}  // namespace
}  // namespace vmt::control::channel
