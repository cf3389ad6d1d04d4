// The main spindle's jog keys AxxC.JGPOS / JGNEG (C-axis manual 2.3, 3.3, 4.3, 4.4): they select
// spindle mode, turn or step the spindle as the jog mode says, and abort a changeover an
// immediate stop interrupted. On the ideal drives of headstock_lathe.hpp.

#include <gtest/gtest.h>

#include "control/channel/channel.hpp"
#include "headstock_lathe.hpp"

namespace vmt::control::channel {
namespace {

using axes::HeadstockMode;
using headstock_test::Lathe;

TEST(ChannelSpindleJog, KeysSelectSpindleModeAndTurnTheSpindleWhileHeld) {
  Lathe m("N1 RET\n", true, {}, HeadstockMode::kRotary);
  m.channel->Start();
  m.Ticks(8);
  m.channel->JogSpindle(+1);  // automatic mode: no effect
  m.Ticks(40);
  EXPECT_EQ(m.hs().target(), HeadstockMode::kRotary);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 0);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.acknowledge = false;  // hold the changeover in its external phase
  m.channel->JogSpindle(+1);
  m.Ticks(40);
  EXPECT_EQ(m.hs().target(), HeadstockMode::kSpindle);
  EXPECT_TRUE(m.hs().spmod());
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 0);  // not before spindle mode is there
  m.acknowledge = true;
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().mode() == HeadstockMode::kSpindle; }));
  m.Ticks(8);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 600);  // the main spindle's jogging speed
  m.channel->JogSpindle(0);
  m.Ticks(8);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 0);
  m.channel->JogSpindle(-1);
  m.Ticks(8);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), -600);
  m.channel->JogSpindle(0);
  m.Ticks(8);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 0);
}

TEST(ChannelSpindleJog, RapidIncrementAndHandwheelModes) {
  Lathe m("N1 RET\n", true, [](ChannelConfig& c) {
    c.spindle.jog_rapid_per_s = 1800;
    c.spindle.jog_distance = 30;
  });
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.Ticks(8);
  m.channel->SetJogMode(static_cast<int>(JogMode::kRapid));
  m.channel->JogSpindle(+1);
  m.Ticks(8);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 1800);
  m.channel->JogSpindle(0);
  m.Ticks(8);
  // One increment per press, from where the spindle stands, in position control.
  const double from = m.at.feedback[2].position;
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  m.channel->JogSpindle(-1);
  m.Ticks(8);
  m.channel->JogSpindle(0);
  m.Ticks(8);
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kPosition);
  EXPECT_NEAR(m.at.feedback[2].position, from - 1, 1e-9);
  m.channel->SetJogMode(static_cast<int>(JogMode::kParametric));
  m.channel->JogSpindle(+1);
  m.Ticks(8);
  m.channel->JogSpindle(0);
  m.Ticks(8);
  EXPECT_NEAR(m.at.feedback[2].position, from + 29, 1e-9);
  // Handwheel mode: the keys move nothing.
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  m.channel->JogSpindle(+1);
  m.Ticks(8);
  m.channel->JogSpindle(0);
  m.Ticks(8);
  EXPECT_NEAR(m.at.feedback[2].position, from + 29, 1e-9);
}

// 2.3 / 3.3 Jogging Movements: AxxCJGPOS / JGNEG of the main spindle abort a changeover an
// immediate stop interrupted and command their own; the program, started again, commands its
// changeover anew.
TEST(ChannelSpindleJog, JogKeyAbortsAnInterruptedChangeover) {
  Lathe m("N1 G00 C10\nN2 RET\n", true);
  m.acknowledge = false;
  m.plc.spindle_axd[axes::kAxdFunction] = axes::axd::kHunting;
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().rotmod(); }));
  m.channel->Stop();  // immediate stop in the external changeover
  m.Ticks(8);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->JogSpindle(-1);
  m.Ticks(8);
  EXPECT_EQ(m.hs().target(), HeadstockMode::kSpindle);
  m.acknowledge = true;
  m.plc.spindle_axd[axes::kAxdFunction] = 0;
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().mode() == HeadstockMode::kSpindle; }));
  m.Ticks(8);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), -600);
  m.channel->JogSpindle(0);
  m.Ticks(8);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  EXPECT_DOUBLE_EQ(m.at.feedback[3].position, 10);
}

}  // namespace
}  // namespace vmt::control::channel
