// What the headstock shows and what the NC takes from the PLC without being asked (C-axis
// manual 2.3, 3.3, 4.2): the power-on mode, the status indication (speeds or lines, overrides
// always), and the one AxxC.READY that monitors a main spindle with rotary axis capability in
// both modes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "control/channel/channel.hpp"
#include "headstock_lathe.hpp"

namespace vmt::control::channel {
namespace {

using axes::HeadstockMode;
using headstock_test::Lathe;
using ::testing::HasSubstr;

// ---- 2.3 / 3.3 Power-On State -----------------------------------------------------------------

// "When the system is switched on, the NC assumes the mode ... that is specified by the SPS via
// ROTMOD or SPMOD": at the first NC cycle, before anything is started, and a program then runs
// C without a changeover.
TEST(ChannelHeadstockPowerOn, RotaryModePresentedAtPowerOnNeedsNoChangeover) {
  for (const bool separate : {true, false}) {
    SCOPED_TRACE(separate ? "separate servo (section 3)" : "one drive (section 2)");
    Lathe m("N1 G01 C30 F3600\nN2 RET\n", separate, {}, HeadstockMode::kRotary);
    m.Tick();
    EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);
    EXPECT_TRUE(m.hs().rotmod());
    EXPECT_FALSE(m.hs().spmod());
    EXPECT_EQ(m.channel->HeadstockAxisName(), "C");
    EXPECT_FALSE(m.channel->spindle_status().speeds_shown);
    m.Ticks(40);
    m.channel->Start();
    bool changed_over = false;
    while (m.channel->state() == ChannelState::kRunning && m.t < 5) {
      m.Tick();
      changed_over = changed_over || m.hs().busy();
    }
    m.Ticks(8);
    EXPECT_FALSE(changed_over);
    EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
    EXPECT_DOUBLE_EQ(m.at.feedback[separate ? 3 : 2].position, 30);
  }
}

// Section 2: "It also ensures that the related drive parameter record is active": the one
// drive gets the rotary set from its first setpoint on, never set 0 in between.
TEST(ChannelHeadstockPowerOn, OneDriveRunsWithTheRotarySetFromTheStart) {
  Lathe m(
      "N1 G01 C30 F3600\nN2 RET\n", false,
      [](ChannelConfig& c) { c.headstock->rotary_parameter_set = 1; }, HeadstockMode::kRotary);
  m.channel->Start();
  while (m.channel->state() == ChannelState::kRunning && m.t < 5) {
    m.Tick();
    ASSERT_EQ(m.mdt.setpoints[2].parameter_set, 1) << "at " << m.t;
  }
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

// The mode is the one presented at power-on, not one the PLC presents later: with neither then,
// "the NC specifies a new mode selection at the next possible occasion when such a mode is
// needed".
TEST(ChannelHeadstockPowerOn, NeitherModeAtPowerOnMeansAChangeoverWhenOneIsNeeded) {
  Lathe m("N1 M03 S100\nN2 G04 F0.1\nN3 RET\n", true, {}, HeadstockMode::kNone);
  m.Tick();
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kNone);
  m.plc.spmod_q = true;  // presented late, unasked
  m.Ticks(40);
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kNone);
  EXPECT_FALSE(m.hs().spmod());
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().busy(); }));
  EXPECT_EQ(m.hs().target(), HeadstockMode::kSpindle);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
}

// ---- 2.3 / 3.3 Status Indication --------------------------------------------------------------

void MaxSpeed(ChannelConfig& c) { c.spindle.max_spindle_rpm = 4000; }

// Speeds in spindle operation (programmed before the override, actual, max), lines in rotary
// axis mode, the overrides always; the switch comes with the completed changeover.
TEST(ChannelHeadstockStatus, SpeedsInSpindleModeLinesInRotaryModeOverridesAlways) {
  Lathe m("N1 M03 S1000\nN2 G04 F0.2\nN3 G01 C90 F3600\nN4 G04 F0.2\nN5 RET\n", true, MaxSpeed);
  m.channel->SetSpindleOverride(0.8);
  m.channel->SetFeedOverride(0.5);
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.t > 0.1; }));
  SpindleStatus st = m.channel->spindle_status();
  EXPECT_TRUE(st.speeds_shown);
  EXPECT_DOUBLE_EQ(st.programmed_rpm, 1000);
  EXPECT_DOUBLE_EQ(st.actual_rpm, 800);
  EXPECT_DOUBLE_EQ(st.max_rpm, 4000);
  EXPECT_DOUBLE_EQ(st.spindle_override, 0.8);
  EXPECT_DOUBLE_EQ(st.feed_override, 0.5);
  // The changeover to rotary axis mode: speeds until it has completed.
  m.acknowledge = false;
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().rotmod(); }));
  EXPECT_TRUE(m.channel->spindle_status().speeds_shown);
  m.acknowledge = true;
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().mode() == HeadstockMode::kRotary; }));
  m.Tick();
  st = m.channel->spindle_status();
  EXPECT_FALSE(st.speeds_shown);
  EXPECT_EQ(st.programmed_rpm, 0);
  EXPECT_EQ(st.actual_rpm, 0);
  EXPECT_EQ(st.max_rpm, 0);
  EXPECT_DOUBLE_EQ(st.spindle_override, 0.8);  // overrides are shown in rotary mode too
  EXPECT_DOUBLE_EQ(st.feed_override, 0.5);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

TEST(ChannelHeadstockStatus, M4IsNegativeAndM19HasNoProgrammedSpeed) {
  Lathe m("N1 M04 S200\nN2 G04 F0.1\nN3 M19\nN4 RET\n", false, MaxSpeed);
  m.channel->SetSingleBlock(true);
  m.Block();
  m.Block();
  EXPECT_DOUBLE_EQ(m.channel->spindle_status().programmed_rpm, -200);
  EXPECT_DOUBLE_EQ(m.channel->spindle_status().actual_rpm, -200);
  m.Block();
  EXPECT_TRUE(m.channel->spindle_status().speeds_shown);
  EXPECT_EQ(m.channel->spindle_status().programmed_rpm, 0);
}

// ---- 4.2 Axis ready of a main spindle with rotary axis capability -----------------------------

// Section 2's HeadstockPlc from the gateway carries the one signal in both fields; a caller
// that fills in only one is read by the axis' (the spindle's) signal.
void NotReady(Lathe& m) {
  m.plc.spindle_ready = false;
  m.plc.rotary_ready = false;
}

// Rotary axis mode: removing A03C.READY while a program moves C is an error, not a lost move.
TEST(ChannelHeadstockReady, OneDriveInRotaryModeStopsWith503) {
  Lathe m("N1 G01 C3600 F3600\nN2 RET\n", false, {}, HeadstockMode::kRotary);
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.t > 0.2; }));
  ASSERT_EQ(m.channel->state(), ChannelState::kRunning);
  NotReady(m);
  m.Ticks(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgDriveFault);
  EXPECT_THAT(m.channel->error(), HasSubstr("axis C: not ready (A03C.READY removed)"));
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kOff);  // powerless
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);     // READY does not change the mode
}

// Spindle mode: the same signal monitors the spindle turning under M3.
TEST(ChannelHeadstockReady, OneDriveInSpindleModeStopsWith503AndTheSpindleStaysStopped) {
  Lathe m("N1 M03 S500\nN2 G04 F10\nN3 RET\n");
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.t > 0.2; }));
  ASSERT_DOUBLE_EQ(m.Drive2Velocity(), 3000);
  NotReady(m);
  m.Ticks(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgDriveFault);
  EXPECT_THAT(m.channel->error(), HasSubstr("axis S1: not ready (A03C.READY removed)"));
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kOff);
  // READY back: the spindle does not start again by itself.
  m.plc.spindle_ready = m.plc.rotary_ready = true;
  m.Ticks(40);
  EXPECT_EQ(m.Drive2Velocity(), 0);
}

// At rest and not needed, READY removed makes the drive powerless without a message; its
// command follows the actual position (4.2: "In a powerless state, the NC corrects the actual
// values and assigns them to the command values"), so READY back does not jump.
TEST(ChannelHeadstockReady, OneDriveAtRestFollowsUpWithoutAMessage) {
  for (const HeadstockMode mode : {HeadstockMode::kSpindle, HeadstockMode::kRotary}) {
    SCOPED_TRACE(axes::ToString(mode));
    Lathe m("N1 G04 F0.01\nN2 RET\n", false, {}, mode);
    m.channel->Start();
    m.RunUntilEnd();
    ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
    NotReady(m);
    m.Ticks(40);
    EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kOff);
    m.at.feedback[2].position = 77;  // turned by hand while powerless
    m.Ticks(40);
    EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
    EXPECT_EQ(m.channel->position(2), 77);
    m.plc.spindle_ready = m.plc.rotary_ready = true;
    m.Ticks(40);
    EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
    EXPECT_NE(m.mdt.setpoints[2].mode, DriveMode::kOff);
    EXPECT_DOUBLE_EQ(m.at.feedback[2].position, 77);
  }
}

// Which signal: on one drive the axis' own READY (the spindle's, A03C.READY); a rotary_ready
// alone is no signal of this axis and changes nothing.
TEST(ChannelHeadstockReady, OneDriveReadsTheAxisReadyOnly) {
  Lathe m("N1 G01 C360 F3600\nN2 RET\n", false, {}, HeadstockMode::kRotary);
  m.plc.rotary_ready = false;
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.at.feedback[2].position, 360);
}

// Section 3 keeps its two READY as the PLC's controller enables (4.3): the spindle's removed in
// rotary axis mode is what the manual's PLC does, no message.
TEST(ChannelHeadstockReady, SeparateServoSpindleReadyOffInRotaryModeIsNoError) {
  Lathe m("N1 G01 C90 F3600\nN2 RET\n", true, {}, HeadstockMode::kRotary);
  m.plc.spindle_ready = false;
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.at.feedback[3].position, 90);
}

}  // namespace
}  // namespace vmt::control::channel
