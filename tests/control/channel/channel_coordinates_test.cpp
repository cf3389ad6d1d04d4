// Coordinates and corrections on the channel: zero offsets, G92, G74 homing, the order of
// G codes and coordinates in a block, tool length and tool nose radius compensation.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

TEST(ChannelTest, ZeroOffsetsShiftTheProgram) {
  Machine m("N1 G54 G00 X10 Z0\nN2 G55 X10 Z0\nN3 G53 X10 Z0\nN4 RET\n", 0, 0, WithOffsetsAndTools);
  m.channel->Start();
  std::vector<std::pair<double, double>> stops;
  for (uint32_t line = 0; m.channel->state() == ChannelState::kRunning && m.t < 10;) {
    m.Tick();
    if (m.channel->line() != line) {
      if (line != 0) stops.emplace_back(m.channel->position(0), m.channel->position(1));
      line = m.channel->line();
    }
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.X(), 10);
  EXPECT_DOUBLE_EQ(m.Z(), 0);
  ASSERT_GE(stops.size(), 2u);
  EXPECT_NEAR(stops[0].first, 15, 1e-9);  // G54 reached before N2 begins
  EXPECT_NEAR(stops[0].second, 100, 1e-9);
  EXPECT_NEAR(stops[1].first, 8, 1e-9);
  EXPECT_NEAR(stops[1].second, 200, 1e-9);
}

TEST(ChannelTest, IncrementalMoveAfterAnOffsetChangeIsInProgramCoordinates) {
  // G91 X1 after G55: one mm in the G55 frame, from where the axes stand in it.
  Machine m("N1 G54 G00 X10 Z0\nN2 G55 G91 X1\nN3 RET\n", 0, 0, WithOffsetsAndTools);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 10 + 1 - 2, 1e-9);  // program X was 10, is 11, under G55's -2
}

TEST(ChannelTest, ToolLengthG48AddsAndG49SubtractsTheEdge) {
  Machine plus("N1 G48 T2 D1 G00 X10 Z0\nN2 RET\n", 0, 0, WithOffsetsAndTools);
  plus.channel->Start();
  plus.RunUntilEnd();
  ASSERT_EQ(plus.channel->state(), ChannelState::kEnded) << plus.channel->error();
  EXPECT_NEAR(plus.X(), 10 - 1.5, 1e-9);  // the tip is 1.5 mm further out than the reference
  EXPECT_NEAR(plus.Z(), 0 + 4, 1e-9);
  Machine minus("N1 G49 T2 D1 G00 X10 Z0\nN2 RET\n", 0, 0, WithOffsetsAndTools);
  minus.channel->Start();
  minus.RunUntilEnd();
  EXPECT_NEAR(minus.X(), 10 + 1.5, 1e-9);
  Machine off("N1 G47 T2 D1 G00 X10 Z0\nN2 RET\n", 0, 0, WithOffsetsAndTools);
  off.channel->Start();
  off.RunUntilEnd();
  EXPECT_NEAR(off.X(), 10, 1e-9);
}

TEST(ChannelTest, ToolMissingFromTheListIsAnError) {
  Machine m("N1 G00 X1\nN2 G48 T7 D2 X10\nN3 RET\n", 0, 0, WithOffsetsAndTools);
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgToolNotInList);
  EXPECT_STREQ(MessageText(m.channel->error_number()), "tool correction not in the tool list");
  EXPECT_THAT(m.channel->error(),
              ::testing::HasSubstr("p.mtc:2:1: error: T7 D2 is not in the tool list (G48)"));
  EXPECT_NEAR(m.X(), 1, 1e-9);
}

TEST(ChannelTest, GCodesActBeforeTheCoordinatesOfTheirBlock) {
  Machine m("N1 X40 G16 G01 F6000\nN2 X2 G91\nN3 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 21, 1e-9);  // diameter 40 -> radius 20, then +1 (incremental diameter 2)
}

TEST(ChannelTest, G92SetsTheCurrentPositionUntilReset) {
  Machine m("N1 G00 X10 Z20\nN2 G92 X0 Z0\nN3 G00 X5 Z5\nN4 M30\n", 0, 0, {}, nc::Dialect::kIsg);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 15, 1e-9);
  EXPECT_NEAR(m.Z(), 25, 1e-9);
  EXPECT_NEAR(m.channel->Translation(0), 10, 1e-9);
  m.channel->Reset();
  EXPECT_NEAR(m.channel->Translation(0), 0, 1e-9);
}

TEST(ChannelTest, G74HomesTheAxesInTheirOrder) {
  auto configure = [](ChannelConfig& c) {
    c.axes[0].reference_position = 200;
    c.axes[1].reference_position = 400;
    c.axes[0].homing_per_s = 100;
    c.axes[1].homing_per_s = 100;
    c.axes[0].homed_at_start = c.axes[1].homed_at_start = false;
  };
  // ISG: G74 X1 Z2 homes X first, then Z.
  Machine m("N10 G74 X1 Z2\nN20 G00 X150 Z300\nN30 M30\n", 50, 100, configure, nc::Dialect::kIsg);
  EXPECT_FALSE(m.channel->homed(0));
  m.channel->Start();
  bool z_moved_before_x_home = false, x_home = false;
  while (m.channel->state() == ChannelState::kRunning && m.t < 20) {
    m.Tick();
    x_home = x_home || m.X() == 200;
    if (!x_home && m.Z() != 100) z_moved_before_x_home = true;
  }
  EXPECT_TRUE(x_home);
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_FALSE(z_moved_before_x_home);
  EXPECT_TRUE(m.channel->homed(0));
  EXPECT_TRUE(m.channel->homed(1));
  EXPECT_DOUBLE_EQ(m.X(), 150);
  EXPECT_DOUBLE_EQ(m.Z(), 300);

  // Without homing a move is refused.
  Machine unhomed("N1 G00 X10\nN2 RET\n", 0, 0, configure);
  unhomed.channel->Start();
  unhomed.RunUntilEnd();
  EXPECT_EQ(unhomed.channel->error_number(), kMsgNotHomed);
  EXPECT_THAT(unhomed.channel->error(), ::testing::HasSubstr("axis X has no reference"));
}

TEST(ChannelTest, ToolNoseRadiusCompensationPutsTheTipOnTheContour) {
  // Turning tool T1 D1: nose radius 0.8, edge position 3; G42 on an outside diameter.
  Machine m(
      "N1 G00 X30 Z110\nN2 G42 T1 D1 G01 X20 Z100 F6000\nN3 Z50\nN4 G02 X25 Z45 I5 K0\n"
      "N5 G01 Z30\nN6 G40 G00 X40\nN7 RET\n",
      30, 110, WithOffsetsAndTools);
  m.channel->Start();
  double worst_n3 = 0, worst_n5 = 0, worst_arc = 0;
  bool saw_n3 = false, saw_arc = false;
  while (m.channel->state() == ChannelState::kRunning && m.t < 20) {
    m.Tick();
    const double x = m.channel->position(0), z = m.channel->position(1);
    if (m.channel->line() == 3) saw_n3 = true, worst_n3 = std::max(worst_n3, std::abs(x - 20));
    // N4 ends going +X, N5 goes -Z: an outer corner, its arc (tagged N5) ends at Z44.2.
    if (m.channel->line() == 5 && z < 44.2 - 1e-9) worst_n5 = std::max(worst_n5, std::abs(x - 25));
    if (m.channel->line() == 4) {
      // G02 from (Z50, X20) to (Z45, X25) about (Z50, X25) (I5 K0): the nose centre (tip +
      // (0.8, 0.8)) runs on the inside, at radius 5 - 0.8.
      saw_arc = true;
      const double r = std::hypot(z + 0.8 - 50, x + 0.8 - 25);
      worst_arc = std::max(worst_arc, std::abs(r - (5 - 0.8)));
    }
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_TRUE(saw_n3);
  EXPECT_TRUE(saw_arc);
  EXPECT_LT(worst_n3, 1e-9);
  EXPECT_LT(worst_n5, 1e-9);
  EXPECT_LT(worst_arc, 1e-6);
  EXPECT_NEAR(m.X(), 40, 1e-9);  // G40: back on the programmed point
  EXPECT_NEAR(m.Z(), 30, 1e-9);
}

TEST(ChannelTest, ToolNoseRadiusCompensationReportsAGouge) {
  // A 1 mm groove is narrower than the 1.6 mm nose: a contour violation before it is cut.
  Machine m(
      "N1 G00 X30 Z110\nN2 G42 T1 D1 G01 X20 Z100 F6000\nN3 Z60\nN4 X15\nN5 Z59\nN6 X20\n"
      "N7 Z40\nN8 G40 G00 X40\nN9 RET\n",
      30, 110, WithOffsetsAndTools);
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgGouge);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("contour violation (gouge)"));
  // One block of look-ahead: N4 runs down the groove's first wall (nose centre Z59.2, tip
  // Z58.4); N5 is found too short for the nose when N6 arrives, before N5 runs.
  EXPECT_GE(m.channel->position(1), 58.4 - 1e-9);
  EXPECT_GE(m.channel->position(0), 15 - 1e-9);
  EXPECT_LE(m.channel->line(), 5u);
}

}  // namespace
}  // namespace vmt::control::channel
