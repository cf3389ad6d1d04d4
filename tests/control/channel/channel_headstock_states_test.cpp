// The headstock's operating states in the channel (C-axis manual 2.3, 3.3): zero offsets of the
// rotary axis in spindle mode, references (M19, encoder frequency), the manual spindle keys,
// overrides, process enabling signal and immediate stop, the position indication S1 <-> C, and
// Control-Reset acknowledging drive trips. On ideal drives (position: actual = command;
// velocity: the speed at once) and a PLC that acknowledges every changeover at once unless a
// test takes the acknowledgements in hand.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "headstock_lathe.hpp"

namespace vmt::control::channel {
namespace {

using axes::HeadstockMode;
using headstock_test::kTick;
using headstock_test::kTrips;
using headstock_test::Lathe;

void WithCOffsets(ChannelConfig& c) {
  c.zero_offsets.g54_to_g59[0] = {5, 100, 30};  // G54: X+5, Z+100, C+30
}

// 2.3 Zero Point Shifts: "Changing over to main spindle operation cancels the zero point
// shifts. Changing back to rotary axis mode automatically re-activates the zero point shifts
// (provided they have not been cleared in the meantime by G53)."
TEST(ChannelHeadstockStates, RotaryOffsetsCancelledInSpindleModeAndBackWithRotaryMode) {
  Lathe m(
      "N1 G54 G90 G00 C10\n"
      "N2 M03 S100\n"
      "N3 G00 C20\n"
      "N4 M05\n"
      "N5 G53 G00 X5\n"
      "N6 G00 C20\n"
      "N7 RET\n",
      false, WithCOffsets);
  m.channel->SetSingleBlock(true);
  m.Block();  // N1: rotary axis mode, G54 acts on C
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  EXPECT_DOUBLE_EQ(m.channel->Translation(2), 30);
  EXPECT_DOUBLE_EQ(m.at.feedback[2].position, 40);
  m.Block();  // N2: spindle mode cancels the offset of C
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  EXPECT_DOUBLE_EQ(m.channel->Translation(2), 0);
  EXPECT_DOUBLE_EQ(m.channel->Translation(1), 100);  // the other axes keep theirs
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 600);   // 100 rpm
  m.Block();                                         // N3: back in rotary axis mode, G54 acts again
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  EXPECT_DOUBLE_EQ(m.channel->Translation(2), 30);
  EXPECT_DOUBLE_EQ(m.at.feedback[2].position, 50);
  m.Block();  // N4
  m.Block();  // N5: G53 in spindle mode clears them
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  EXPECT_DOUBLE_EQ(m.at.feedback[0].position, 5);
  m.Block();  // N6: rotary axis mode without offset
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  EXPECT_DOUBLE_EQ(m.channel->Translation(2), 0);
  EXPECT_DOUBLE_EQ(m.at.feedback[2].position, 20);
  m.Block();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
}

// The manual's own example (1.2) selects G54 in a spindle block and then positions C: the
// selection made there acts once rotary axis mode comes; so does a G92 shift of C.
TEST(ChannelHeadstockStates, OffsetSelectedInSpindleModeActsInRotaryMode) {
  Lathe m(
      "N1 G00 G54 G90 X100 Z200 M03 S1000\n"
      "N2 G00 X100 Z250 C90\n"
      "N3 G92 C0\n"
      "N4 M05\n"
      "N5 G00 C10\n"
      "N6 RET\n",
      true, WithCOffsets);
  m.channel->SetSingleBlock(true);
  m.Block();
  EXPECT_DOUBLE_EQ(m.channel->Translation(2), 0);
  m.Block();
  EXPECT_DOUBLE_EQ(m.at.feedback[3].position, 120);  // the C servo: 90 + 30
  m.Block();                                         // G92 C0: C's program zero at 120
  EXPECT_DOUBLE_EQ(m.channel->Translation(2), 120);
  m.Block();
  EXPECT_DOUBLE_EQ(m.channel->Translation(2), 0);
  m.Block();
  EXPECT_DOUBLE_EQ(m.at.feedback[3].position, 130);
  EXPECT_DOUBLE_EQ(m.channel->Translation(2), 120);
}

TEST(ChannelHeadstockStates, G92OfTheRotaryAxisInSpindleModeIsRefused) {
  Lathe m("N1 M03 S100\nN2 G92 C0\nN3 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgOffsetInSpindleMode);
  EXPECT_NE(m.channel->error().find("p.mtc:2:"), std::string::npos) << m.channel->error();
}

void CNotHomed(ChannelConfig& c) { c.axes[2].homed_at_start = false; }

// 2.3 Homing: in rotary axis mode a programmed C position needs the reference; M19 establishes
// it in spindle mode (one drive, one encoder: the spindle's reference is C's).
TEST(ChannelHeadstockStates, ProgrammedCNeedsTheReferenceThatM19Establishes) {
  Lathe without("N1 G00 C10\nN2 RET\n", false, CNotHomed);
  without.channel->Start();
  without.RunUntilEnd();
  ASSERT_EQ(without.channel->state(), ChannelState::kError);
  EXPECT_EQ(without.channel->error_number(), kMsgNotHomed);
  EXPECT_EQ(without.hs().mode(), HeadstockMode::kRotary);  // the error comes in rotary mode
  EXPECT_FALSE(without.channel->spindle_homed());

  Lathe with("N1 M03 S500\nN2 G04 F0.1\nN3 M19\nN4 G00 C10\nN5 RET\n", false, CNotHomed);
  with.channel->Start();
  with.RunUntilEnd();
  ASSERT_EQ(with.channel->state(), ChannelState::kEnded) << with.channel->error();
  EXPECT_TRUE(with.channel->homed(2));
  EXPECT_TRUE(with.channel->spindle_homed());
  EXPECT_DOUBLE_EQ(with.at.feedback[2].position, 10);
}

// 2.3 / 3.3 Homing: the reference is kept while n [1/s] * periods per revolution stays within
// the limit frequency of the encoder's interface (sine signals: 150 kHz).
void CEncoder(ChannelConfig& c) {
  c.axes[2].encoder_periods_per_rev = 2048;  // 150 kHz / 2048 = 73.2 rev/s = 4394 rpm
  c.axes[2].encoder_limit_hz = 150e3;
}

TEST(ChannelHeadstockStates, ReferenceKeptBelowTheEncoderLimitLostAbove) {
  const std::string program = "N1 M03 S@1\nN2 G04 F0.1\nN3 M05\nN4 G00 C10\nN5 RET\n";
  for (int rpm : {4000, 4800}) {
    std::string p = program;
    p.replace(p.find("@1"), 2, std::to_string(rpm));
    Lathe m(p, false, CEncoder);
    m.channel->Start();
    m.RunUntilEnd();
    if (rpm == 4000) {
      EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
      EXPECT_TRUE(m.channel->homed(2));
    } else {
      EXPECT_EQ(m.channel->state(), ChannelState::kError);
      EXPECT_EQ(m.channel->error_number(), kMsgNotHomed);
      EXPECT_FALSE(m.channel->homed(2));
      EXPECT_FALSE(m.channel->spindle_homed());
    }
  }
}

// Section 3: the spindle has its own encoder and reference; the C servo's stays.
TEST(ChannelHeadstockStates, SeparateSpindleLosesItsOwnReferenceAndM19RestoresIt) {
  Lathe m("N1 M03 S3000\nN2 G04 F0.1\nN3 M19\nN4 G00 C10\nN5 RET\n", true, [](ChannelConfig& c) {
    c.spindle.encoder_periods_per_rev = 4096;  // 100 kHz: 1465 rpm
    c.spindle.encoder_limit_hz = 100e3;
  });
  m.channel->SetSingleBlock(true);
  m.Block();
  m.Block();
  EXPECT_FALSE(m.channel->spindle_homed());
  EXPECT_TRUE(m.channel->homed(2));
  m.Block();  // M19 waits for the spindle in position, and references it
  EXPECT_TRUE(m.channel->spindle_homed());
  m.Block();
  m.Block();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.at.feedback[3].position, 10);
}

// 4.2: AxxC.M3/M4/M5/M19 move the spindle in manual mode whatever the jog mode, selecting
// spindle mode; jogging the rotary axis selects rotary axis mode. The designation shown
// follows only completed changeovers (2.3 Position Indication).
TEST(ChannelHeadstockStates, ManualSpindleKeysAndJogKeysSelectTheirModes) {
  Lathe m("N1 RET\n", true, {}, HeadstockMode::kRotary);
  m.channel->Start();  // the program ends at once; the power-on mode is rotary axis mode
  m.Ticks(8);
  EXPECT_EQ(m.channel->HeadstockAxisName(), "C");
  m.channel->ManualSpindle(3);  // automatic mode: no effect
  m.Ticks(40);
  EXPECT_EQ(m.hs().target(), HeadstockMode::kRotary);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.acknowledge = false;  // hold the changeover in its external phase
  m.channel->ManualSpindle(3);
  m.Ticks(40);
  EXPECT_EQ(m.hs().target(), HeadstockMode::kSpindle);
  EXPECT_TRUE(m.hs().spmod());
  EXPECT_EQ(m.channel->HeadstockAxisName(), "C");  // not before the changeover ends
  m.acknowledge = true;
  m.Ticks(40);
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  EXPECT_EQ(m.channel->HeadstockAxisName(), "S1");
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 600);  // the spindle's jogging speed
  m.channel->ManualSpindle(4);
  m.Ticks(8);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), -600);
  m.channel->ManualSpindle(5);
  m.Ticks(8);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 0);
  m.channel->ManualSpindle(19);
  m.Ticks(8);
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kPosition);
  EXPECT_DOUBLE_EQ(m.at.feedback[2].position, 90);  // the jogging spindle position
  EXPECT_DOUBLE_EQ(m.channel->HeadstockPosition(), 90);
  // Jogging C: rotary axis mode again, and C moves there.
  m.channel->Jog(2, +1);
  m.Ticks(400);
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  EXPECT_EQ(m.channel->HeadstockAxisName(), "C");
  EXPECT_GT(m.at.feedback[3].position, 1);
  m.channel->Jog(2, 0);
}

// 2.3 Feed and Spindle Override: under M3/M4 only the spindle override acts on the spindle;
// in rotary axis mode the feed override acts on C and the spindle override does not.
TEST(ChannelHeadstockStates, SpindleOverrideOnTheSpindleFeedOverrideOnTheRotaryAxis) {
  Lathe m("N1 M03 S100\nN2 G04 F0.2\nN3 G01 G91 C3600 F36000\nN4 RET\n");
  m.channel->SetFeedOverride(0.5);
  m.channel->SetSpindleOverride(0.8);
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().mode() == HeadstockMode::kSpindle && m.t > 0.1; }));
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 600 * 0.8);  // the feed override does not act
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().mode() == HeadstockMode::kRotary; }));
  m.Ticks(400);  // at speed: F36000 deg/min = 600 deg/s, halved
  const double before = m.at.feedback[2].position;
  m.Ticks(4);
  EXPECT_NEAR((m.at.feedback[2].position - before) / (4 * kTick), 300, 1e-6);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

// 2.3 Process Enabling Signal: removed during a changeover, immediate stop: the program
// stops, the PLC's motion functions halt, the request stays pending; no start without it.
TEST(ChannelHeadstockStates, ProcessEnableRemovedDuringAChangeoverStopsAtOnce) {
  Lathe m("N1 G00 C10\nN2 RET\n", true);
  m.acknowledge = false;
  m.plc.spindle_axd[axes::kAxdFunction] = axes::axd::kHunting;  // the PLC meshes the clutch
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().rotmod(); }));
  m.Ticks(40);
  EXPECT_NE(m.Drive2Velocity(), 0);  // hunting
  m.channel->SetProcessEnable(false);
  m.Ticks(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 0);
  EXPECT_TRUE(m.hs().rotmod());  // pending, as an auxiliary function
  m.channel->Start();
  m.Ticks(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);  // no start without the signal
  m.channel->SetProcessEnable(true);
  m.channel->Start();
  m.Ticks(40);
  EXPECT_NE(m.Drive2Velocity(), 0);  // the changeover goes on
  m.acknowledge = true;
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.at.feedback[3].position, 10);
}

TEST(ChannelHeadstockStates, ProcessEnableRemovedBrakesJoggingAxes) {
  Lathe m("N1 RET\n");
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Jog(0, +1);
  m.Ticks(2000);
  m.channel->SetProcessEnable(false);
  m.Ticks(400);
  const double stopped = m.at.feedback[0].position;
  m.Ticks(400);
  EXPECT_EQ(m.at.feedback[0].position, stopped);
  m.channel->ManualSpindle(3);  // nothing starts
  m.Ticks(40);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 0);
}

// 2.3 Jogging Movements: the spindle keys abort a changeover an immediate stop interrupted
// and command their own; the program, started again, commands its changeover anew.
TEST(ChannelHeadstockStates, ManualKeyAbortsAnInterruptedChangeover) {
  Lathe m("N1 G00 C10\nN2 RET\n", true);
  m.acknowledge = false;
  m.plc.spindle_axd[axes::kAxdFunction] = axes::axd::kHunting;
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().rotmod(); }));
  m.channel->Stop();  // immediate stop in the external changeover
  m.Ticks(8);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 0);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->ManualSpindle(3);
  m.Ticks(8);
  EXPECT_EQ(m.hs().target(), HeadstockMode::kSpindle);
  m.acknowledge = true;
  m.plc.spindle_axd[axes::kAxdFunction] = 0;
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().mode() == HeadstockMode::kSpindle; }));
  m.Ticks(8);
  EXPECT_DOUBLE_EQ(m.Drive2Velocity(), 600);
  m.channel->ManualSpindle(5);
  m.Ticks(8);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  EXPECT_DOUBLE_EQ(m.at.feedback[3].position, 10);
}

// 2.3 Position Indication: S1 until the changeover to rotary axis mode has completed, then C
// with its position in program coordinates.
TEST(ChannelHeadstockStates, PositionIndicationSwitchesAfterTheChangeover) {
  Lathe m("N1 G54 G00 C10\nN2 RET\n", false, WithCOffsets);
  m.acknowledge = false;
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().rotmod(); }));
  EXPECT_EQ(m.channel->HeadstockAxisName(), "S1");
  m.acknowledge = true;
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->HeadstockAxisName(), "C");
  EXPECT_DOUBLE_EQ(m.channel->HeadstockPosition(), 10);
  EXPECT_DOUBLE_EQ(m.at.feedback[2].position, 40);
}

// Drive trips latch until the drive's controller enable is removed; Control-Reset does that
// for one NC cycle to a tripped drive, and the channel names the trip in its message.
TEST(ChannelHeadstockStates, ControlResetAcknowledgesADriveTrip) {
  Lathe m("N1 G01 X50 F3000\nN2 RET\n");
  m.channel->Start();
  m.Ticks(400);
  m.Trip(0, drive_status::kOverload);
  m.Ticks(4);
  ASSERT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgDriveFault);
  EXPECT_NE(m.channel->error().find("axis X: drive error: overload"), std::string::npos)
      << m.channel->error();
  m.Ticks(40);
  EXPECT_TRUE(m.at.feedback[0].status & drive_status::kOverload);  // latched
  m.channel->Reset();
  std::vector<DriveMode> modes;
  for (int i = 0; i < 8; ++i) m.Tick(), modes.push_back(m.mdt.setpoints[0].mode);
  EXPECT_EQ(modes[0], DriveMode::kOff);
  EXPECT_EQ(modes[3], DriveMode::kOff);
  EXPECT_EQ(modes[4], DriveMode::kPosition);
  EXPECT_EQ(m.mdt.setpoints[1].mode, DriveMode::kPosition);  // untripped drives untouched
  EXPECT_EQ(m.at.feedback[0].status & kTrips, 0u);
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);
  // The coasting axis did not jump back: its command followed it.
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.at.feedback[0].position, 50);
}

TEST(ChannelHeadstockStates, ATripWhoseCausePersistsIsReportedAgainAfterReset) {
  Lathe m("N1 M03 S100\nN2 RET\n");
  m.channel->Start();
  m.Ticks(400);
  m.Trip(2, drive_status::kOverspeed, /*persist=*/true);
  m.Ticks(4);
  ASSERT_EQ(m.channel->state(), ChannelState::kError);
  // Spindle and C are one drive (section 2): named as the display shows it in spindle mode.
  EXPECT_NE(m.channel->error().find("axis S1: drive error: overspeed"), std::string::npos)
      << m.channel->error();
  m.channel->Reset();
  m.Ticks(2);
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);
  m.Ticks(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  m.persisting[2] = false;
  m.channel->Reset();
  m.Ticks(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);
  EXPECT_EQ(m.at.feedback[2].status & kTrips, 0u);
}

TEST(ChannelHeadstockStates, ControlResetWithoutATripKeepsTheDrivesOn) {
  Lathe m("N1 G01 X50 F3000\nN2 RET\n");
  m.channel->Start();
  m.Ticks(400);
  m.channel->Reset();
  for (int i = 0; i < 8; ++i) {
    m.Tick();
    EXPECT_NE(m.mdt.setpoints[0].mode, DriveMode::kOff);
  }
}

// 2.3 Errors: a drive failing during a changeover: as at power-on, the mode is the PLC's.
TEST(ChannelHeadstockStates, DriveFaultDuringAChangeoverTakesTheModeFromThePlc) {
  Lathe m("N1 G00 C10\nN2 RET\n", true);
  m.acknowledge = false;
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().rotmod(); }));
  m.Trip(3, drive_status::kParameterSetError);
  m.Ticks(4);
  ASSERT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_NE(m.channel->error().find("parameter set error"), std::string::npos);
  EXPECT_FALSE(m.hs().busy());
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);  // SPMOD_Q is what the PLC still gives
}

}  // namespace
}  // namespace vmt::control::channel
