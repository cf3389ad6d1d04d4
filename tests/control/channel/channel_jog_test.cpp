// Jogging on the channel in manual mode: continuous, incremental, rapid, parametric and
// handwheel jogs, a program jogged away from, and the software limits of programs and jogs.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

TEST(ChannelTest, ContinuousJogWhileTheKeyIsHeld) {
  Machine m("N1 RET\n", 50, 0);
  m.channel->Jog(0, +1);  // automatic mode: ignored
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.X(), 50);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Jog(0, +1);
  for (int i = 0; i < 4000; ++i) m.Tick();  // 1 s at 40 mm/s (a tenth of the rapid)
  EXPECT_EQ(m.channel->AxisMotion(0), 1);
  EXPECT_NEAR(m.X(), 50 + 40 - 40 * 40 / (2 * 4000.0), 0.05);
  m.channel->Jog(0, 0);
  for (int i = 0; i < 400; ++i) m.Tick();
  const double stopped = m.X();
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.X(), stopped);
  EXPECT_EQ(m.channel->AxisMotion(0), 0);
  EXPECT_EQ(m.Z(), 0);
}

TEST(ChannelTest, IncrementalJogMovesExactlyOneIncrementPerPress) {
  Machine m("N1 RET\n", 50, 20);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogIncrement(0.1);
  for (int press = 0; press < 3; ++press) {
    m.channel->Jog(1, -1);
    for (int i = 0; i < 800; ++i) m.Tick();
    m.channel->Jog(1, 0);
    for (int i = 0; i < 40; ++i) m.Tick();
  }
  EXPECT_NEAR(m.Z(), 19.7, 1e-9);
  EXPECT_EQ(m.X(), 50);
}

TEST(ChannelTest, JoggedAwayProgramDoesNotJumpBackToThePath) {
  Machine m("N1 G01 X100 F600\nN2 RET\n");
  m.channel->Start();
  for (int i = 0; i < 2000; ++i) m.Tick();
  m.channel->Stop();
  for (int i = 0; i < 400; ++i) m.Tick();
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Jog(1, +1);  // Z away from the contour
  for (int i = 0; i < 400; ++i) m.Tick();
  m.channel->Jog(1, 0);
  for (int i = 0; i < 400; ++i) m.Tick();
  const double z = m.Z();
  ASSERT_GT(z, 1);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("axis Z has left the contour"));
  EXPECT_EQ(m.Z(), z);  // nothing jumped
}

TEST(ChannelTest, JogModesRapidParametricAndHandwheel) {
  auto configure = [](ChannelConfig& c) {
    c.axes[0].jog_per_s = 20;
    c.axes[0].jog_rapid_per_s = 80;
    c.axes[0].jog_distance = 2.5;
  };
  Machine m("N1 RET\n", 0, 0, configure);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kRapid));
  m.channel->Jog(0, +1);
  for (int i = 0; i < 4000; ++i) m.Tick();
  m.channel->Jog(0, 0);
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_NEAR(m.X(), 80, 0.5);  // 1 s at 80 mm/s
  const double x0 = m.X();
  m.channel->SetJogMode(static_cast<int>(JogMode::kParametric));
  m.channel->Jog(0, -1);
  for (int i = 0; i < 4000; ++i) m.Tick();
  m.channel->Jog(0, 0);
  EXPECT_NEAR(m.X(), x0 - 2.5, 1e-9);
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement100));
  m.channel->Jog(0, +1);
  for (int i = 0; i < 400; ++i) m.Tick();
  m.channel->Jog(0, 0);
  EXPECT_NEAR(m.X(), x0 - 2.4, 1e-9);
  // Handwheel: 250 counts of 0.01 mm, the keys do nothing.
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  m.channel->Jog(1, +1);
  m.channel->Handwheel(0, 250);
  for (int i = 0; i < 4000; ++i) m.Tick();
  EXPECT_NEAR(m.X(), x0 - 2.4 + 2.5, 1e-9);
  EXPECT_EQ(m.Z(), 0);
}

// The operator selects increments right after letting a continuous jog key go: the axis
// brakes to a stop as it would have (no standstill within a cycle), and nothing of its speed
// is left over to move it when continuous jogging is selected again.
/// Jogs X from 50 in manual mode for 1 s (40 mm/s) and lets the key go: where it was let go.
/// It brakes kBrakingDistance from there.
double LetGoAJog(Machine& m) {
  EXPECT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Jog(0, +1);
  for (int i = 0; i < 4000; ++i) m.Tick();
  m.channel->Jog(0, 0);
  return m.X();
}
constexpr double kBrakingDistance = 40 * 40 / (2 * 4000.0);

TEST(ChannelTest, IncrementsSelectedWhileAJogBrakesLetItBrakeToAStop) {
  Machine m("N1 RET\n", 50, 0);
  const double released = LetGoAJog(m);
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_NEAR(m.X(), released + kBrakingDistance, 0.05);
  EXPECT_EQ(m.channel->AxisMotion(0), 0);
  const double stopped = m.X();
  m.channel->SetJogMode(static_cast<int>(JogMode::kContinuous));
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.X(), stopped);
}

// The handwheel selected right after a continuous jog key was let go: the axis brakes to a
// stop as it would have, and the counts count from where it stopped.
TEST(ChannelTest, HandwheelSelectedWhileAJogBrakesLetsItBrakeToAStop) {
  Machine m("N1 RET\n", 50, 0);
  const double released = LetGoAJog(m);
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_NEAR(m.X(), released + kBrakingDistance, 0.05);
  EXPECT_EQ(m.channel->AxisMotion(0), 0);
  const double stopped = m.X();
  m.channel->Handwheel(0, 100);
  for (int i = 0; i < 4000; ++i) m.Tick();
  EXPECT_NEAR(m.X(), stopped + 1, 1e-9);
  m.channel->SetJogMode(static_cast<int>(JogMode::kContinuous));
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_NEAR(m.X(), stopped + 1, 1e-9);
}

// Automatic mode selected while the jog brakes: the axis brakes to a stop as it would have in
// manual mode (not dead within a cycle), and a start meanwhile is taken once it stands.
TEST(ChannelTest, AutomaticSelectedWhileAJogBrakesLetsItStopBeforeTheStart) {
  Machine m("N1 G01 Z10 F600\nN2 RET\n", 50, 0);
  const double released = LetGoAJog(m);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  double before = m.X();
  bool program_moved_early = false;
  while (m.channel->state() != ChannelState::kRunning && m.t < 2) {
    m.Tick();
    EXPECT_GE(m.X(), before);  // no jump back, no standstill then motion
    before = m.X();
    program_moved_early = program_moved_early || m.Z() != 0;
  }
  EXPECT_FALSE(program_moved_early);
  EXPECT_NEAR(m.X(), released + kBrakingDistance, 0.05);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), released + kBrakingDistance, 0.05);
  EXPECT_NEAR(m.Z(), 10, 1e-9);
  // Back in manual mode the jog does not go on.
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  const double stopped = m.X();
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.X(), stopped);
}

// An increment runs to its end when the handwheel is selected meanwhile, as it does when
// continuous jogging is: it neither stands still nor goes on when increments come back.
TEST(ChannelTest, AnIncrementRunsToItsEndWhenTheHandwheelIsSelected) {
  Machine m("N1 RET\n", 50, 0);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  m.channel->Jog(0, +1);
  for (int i = 0; i < 20; ++i) m.Tick();  // under way (1 mm takes some 35 ms)
  m.channel->Jog(0, 0);
  ASSERT_GT(m.X(), 50 + 1e-3);
  ASSERT_LT(m.X(), 51 - 1e-3);
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_NEAR(m.X(), 51, 1e-9);
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_NEAR(m.X(), 51, 1e-9);
  EXPECT_EQ(m.channel->AxisMotion(0), 0);
}

TEST(ChannelTest, SoftwareLimitsStopProgramsBeforeAndJogsAtTheLimit) {
  auto configure = [](ChannelConfig& c) { c.axes[0].travel_min = 0, c.axes[0].travel_max = 300; };
  Machine m("N1 G00 X100\nN2 G00 X301\nN3 RET\n", 0, 0, configure);
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->error_number(), kMsgSoftwareLimit);
  EXPECT_THAT(
      m.channel->error(),
      ::testing::HasSubstr("p.mtc:2:1: error: axis X target 301.0000 is beyond its travel"));
  EXPECT_DOUBLE_EQ(m.X(), 100);
  m.channel->Reset();
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kRapid));  // 200 mm/s
  m.channel->Jog(0, +1);
  double highest = 0;
  for (int i = 0; i < 12000; ++i) m.Tick(), highest = std::max(highest, m.X());
  EXPECT_DOUBLE_EQ(highest, 300);
  EXPECT_DOUBLE_EQ(m.X(), 300);
  m.channel->Jog(0, 0);
}

}  // namespace
}  // namespace vmt::control::channel
