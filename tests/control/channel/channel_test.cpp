// The channel on an ideal machine (actual = setpoint): block timing, G00 synchronisation, arcs,
// feed override and feed hold on the path.

#include "control/channel/channel.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "control/nc/parser.hpp"

namespace vmt::control::channel {
namespace {

ChannelAxis Axis(const std::string& name, int drive, double rapid_per_s) {
  ChannelAxis a;
  a.name = name;
  a.number = drive + 1;
  a.drive = drive;
  a.rapid_per_s = rapid_per_s;
  a.acceleration = 4000;
  return a;
}

struct Machine {
  explicit Machine(const std::string& program, double x = 0, double z = 0) {
    parsed = nc::ParseProgram(program, "p.mtc", nc::Dialect::kMtc200);
    EXPECT_TRUE(parsed.ok()) << nc::Format(parsed.errors[0], parsed.program.files);
    ChannelConfig config;
    config.axes = {Axis("X", 0, 400), Axis("Z", 1, 500)};
    config.spindle_drive = 2;
    channel = std::make_unique<Channel>(config, std::vector<const nc::Program*>{&parsed.program});
    at.feedback.resize(3);
    at.feedback[0].position = x;
    at.feedback[1].position = z;
    mdt.setpoints.resize(3);
  }
  // One drive tick of an ideal machine: the actual position is the setpoint.
  void Tick() {
    channel->Tick(at, mdt);
    for (int d = 0; d < 2; ++d)
      if (mdt.setpoints[d].mode == DriveMode::kPosition)
        at.feedback[d].position = mdt.setpoints[d].value;
    t += 250e-6;
  }
  double RunUntilEnd(double limit = 60) {
    while (channel->state() != ChannelState::kEnded && channel->state() != ChannelState::kError &&
           t < limit)
      Tick();
    return t;
  }
  double X() const { return at.feedback[0].position; }
  double Z() const { return at.feedback[1].position; }

  nc::ParseResult parsed;
  std::unique_ptr<Channel> channel;
  AmplifierTelegram at;
  MasterTelegram mdt;
  double t = 0;
};

TEST(ChannelTest, LinearMoveTakesFeedAndAccelerationTime) {
  Machine m("N1 G01 X100 F6000\nN2 RET\n");  // 100 mm at 100 mm/s, accel 4000 mm/s^2
  m.channel->Start();
  const double t = m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.X(), 100);
  // Trapezoid: 100/100 + 100/4000 = 1.025 s, plus a few NC cycles of block change.
  EXPECT_NEAR(t, 1.025, 0.01);
}

TEST(ChannelTest, RapidMovesEveryAxisAtItsLimitAndEndsThemTogether) {
  Machine m("N1 G00 X200 Z100\nN2 RET\n");
  m.channel->Start();
  double x_done = -1, z_done = -1;
  double max_ratio_error = 0;
  while (m.channel->state() == ChannelState::kRunning && m.t < 5) {
    m.Tick();
    if (x_done < 0 && m.X() == 200) x_done = m.t;
    if (z_done < 0 && m.Z() == 100) z_done = m.t;
    // Straight in axis space: Z/X stays 1/2.
    if (m.X() > 1) max_ratio_error = std::max(max_ratio_error, std::abs(m.Z() / m.X() - 0.5));
  }
  EXPECT_NEAR(x_done, z_done, 1e-9);
  EXPECT_LT(max_ratio_error, 1e-9);
  // X limits (200 mm at 400 mm/s, 4000 mm/s^2): 0.5 + 0.1 s.
  EXPECT_NEAR(x_done, 0.6, 0.01);
}

TEST(ChannelTest, ArcStaysOnItsCircle) {
  Machine m("N1 G18 G02 X23 Z134 I4 K0 F600\nN2 RET\n", 19, 138);
  m.channel->Start();
  double worst = 0;
  while (m.channel->state() == ChannelState::kRunning && m.t < 5) {
    m.Tick();
    worst = std::max(worst, std::abs(std::hypot(m.Z() - 138, m.X() - 23) - 4));
  }
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_LT(worst, 1e-4);
  EXPECT_DOUBLE_EQ(m.X(), 23);
  EXPECT_DOUBLE_EQ(m.Z(), 134);
}

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

TEST(ChannelTest, OverrideScalesTheFeed) {
  Machine full("N1 G01 X100 F3000\nN2 RET\n"), half("N1 G01 X100 F3000\nN2 RET\n");
  half.channel->SetFeedOverride(0.5);
  full.channel->Start();
  half.channel->Start();
  EXPECT_NEAR(half.RunUntilEnd() / full.RunUntilEnd(), 2, 0.02);
}

TEST(ChannelTest, SpindleAndErrors) {
  Machine m("N1 M03 S1200\nN2 G01 X10\nN3 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kVelocity);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 7200);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("p.mtc:2:1: error: no feed programmed"));

  Machine arc("N1 G02 X10 Z0 I3 K0 F100\nN2 RET\n");
  arc.channel->Start();
  arc.RunUntilEnd();
  EXPECT_THAT(arc.channel->error(), ::testing::HasSubstr("end point not on the arc"));
  arc.channel->Reset();
  EXPECT_EQ(arc.channel->state(), ChannelState::kIdle);
  EXPECT_EQ(arc.channel->error(), "");
}

}  // namespace
}  // namespace vmt::control::channel
