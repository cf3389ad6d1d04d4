// The channel running a program on an ideal machine (actual = setpoint): block timing, G00
// synchronisation, arcs, the rotary axis's path speed, spindle, auxiliary functions with the
// PLC's acknowledgement, events, and the errors that stop a program.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

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

TEST(ChannelTest, AuxFunctionsWaitForThePlcAcknowledgement) {
  Machine m("N1 M08 H12 G01 X10 F6000\nN2 RET\n", 0, 0,
            [](ChannelConfig& c) { c.aux_handshake = true; });
  m.channel->Start();
  for (int i = 0; i < 400; ++i) m.Tick();
  ASSERT_EQ(m.channel->aux_output().size(), 2u);
  EXPECT_EQ(m.channel->aux_output()[0].letter, 'M');
  EXPECT_EQ(m.channel->aux_output()[0].value, 8);
  EXPECT_EQ(m.channel->aux_output()[1].letter, 'H');
  EXPECT_EQ(m.channel->aux_strobe(), 1u);
  EXPECT_EQ(m.X(), 0);  // the block waits
  m.channel->AcknowledgeAux();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(m.X(), 10);
}

TEST(ChannelTest, ProgramEventsAndInstructionsOfLaterIssues) {
  // SE sets an event the program itself tests with BES; RE clears it.
  Machine m(
      "N1 SE 29\nN2 BES .SET 29\nN3 G00 X1\n.SET\nN4 RE 29\nN5 BES .BAD 29\nN6 G00 X2\n"
      "N7 RET\n.BAD\nN8 G00 X3\nN9 RET\n");
  std::vector<std::pair<int, bool>> seen;
  m.channel->SetEventSink([&](int n, bool v) { seen.emplace_back(n, v); });
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.X(), 2);
  EXPECT_EQ(seen, (std::vector<std::pair<int, bool>>{{29, true}, {29, false}}));
  // An instruction the channel does not execute yet stops the program, it is not skipped.
  Machine mtp("N1 G00 X5\nN2 MTP\nN3 G00 X9\nN4 RET\n");
  mtp.channel->Start();
  mtp.RunUntilEnd();
  EXPECT_EQ(mtp.channel->error_number(), kMsgNotAvailable);
  EXPECT_THAT(mtp.channel->error(),
              ::testing::HasSubstr("p.mtc:2:4: error: instruction MTP is not supported"));
  EXPECT_DOUBLE_EQ(mtp.X(), 5);
}

TEST(ChannelTest, EffectiveDistanceGivesTheRotaryAxisItsPathSpeed) {
  // C-axis manual 1.2: RX, RY, RZ are the tool contact point's position; the C axis (about Z)
  // moves it at the rotation times its distance from Z. C90 at RX50: 78.5 mm at 20 mm/s.
  const auto with_c = [](ChannelConfig& c) {
    ChannelAxis axis = Axis("C", 2, 3600);
    axis.rotary = true;
    axis.acceleration = 100000;
    c.axes.push_back(axis);
    c.spindle_drive = -1;
  };
  const auto seconds = [&](const std::string& block) {
    Machine m("N1 " + block + "\nN2 RET\n", 0, 0, with_c);
    m.channel->Start();
    m.RunUntilEnd();
    EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
    EXPECT_NEAR(m.channel->position(2), 90, 1e-9);
    return m.t;
  };
  const double rx = seconds("G01 C90 RX50 F1200");
  EXPECT_NEAR(rx, 50 * std::numbers::pi / 2 / 20, 0.02);
  EXPECT_NEAR(seconds("G01 C90 RX30 RY40 F1200"), rx, 1e-3);    // the same distance from Z
  EXPECT_NEAR(seconds("G01 C90 RZ50 F1200"), 90 / 20.0, 0.02);  // along Z: no distance, in deg
  EXPECT_NEAR(seconds("G01 C90 F1200"), 90 / 20.0, 0.02);       // no effective distance: deg
}

}  // namespace
}  // namespace vmt::control::channel
