// The NC side of the headstock changeover (C-axis manual 2.3, 3.3, 4.1-4.3, figures 4-1 / 4-2),
// driven by a scripted PLC (HeadstockPlc) and scripted drives, for both machine kinds: a
// separate C servo engaged through a clutch (section 3) and one main spindle drive with a
// rotary parameter set (section 2).

#include "control/axes/headstock_changeover.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/control/axes/headstock_rig.hpp"

namespace vmt::control::axes {
namespace {

using namespace headstock_rig;

class HeadstockChangeoverKinds : public ::testing::TestWithParam<Kind> {};
INSTANTIATE_TEST_SUITE_P(Machine, HeadstockChangeoverKinds,
                         ::testing::Values(Kind::kServo, Kind::kFrameless), KindName);

// ---- Power-on (2.3, 3.3) ---------------------------------------------------------------------

TEST_P(HeadstockChangeoverKinds, PowerOnTakesTheModeThePlcAcknowledges) {
  struct Case {
    bool rotmod_q, spmod_q;
    HeadstockMode mode;
  };
  for (const Case& c :
       {Case{true, false, HeadstockMode::kRotary}, Case{false, true, HeadstockMode::kSpindle},
        Case{false, false, HeadstockMode::kNone}, Case{true, true, HeadstockMode::kNone}}) {
    SCOPED_TRACE(::testing::Message() << "ROTMOD_Q " << c.rotmod_q << " SPMOD_Q " << c.spmod_q);
    HeadstockChangeover hs(ConfigOf(GetParam()));
    HeadstockPlc plc;
    plc.rotmod_q = c.rotmod_q;
    plc.spmod_q = c.spmod_q;
    hs.TakeModeFromPlc(plc);
    EXPECT_EQ(hs.mode(), c.mode);
    EXPECT_FALSE(hs.busy());
    EXPECT_EQ(hs.target(), c.mode);
    EXPECT_EQ(hs.rotmod(), c.mode == HeadstockMode::kRotary);
    EXPECT_EQ(hs.spmod(), c.mode == HeadstockMode::kSpindle);
    // Rotary axis mode at power-on: the position command value is taken from the actual one.
    EXPECT_EQ(hs.TakeOverRotary(), c.mode == HeadstockMode::kRotary);
    EXPECT_FALSE(hs.TakeOverRotary());  // once
    EXPECT_TRUE(hs.error().empty());
  }
}

TEST_P(HeadstockChangeoverKinds, PowerOnInNeitherModeChangesOverWhenAModeIsNeeded) {
  Rig r(GetParam(), false, false);
  ASSERT_EQ(r.hs.mode(), HeadstockMode::kNone);
  r.Run(50);  // no acknowledgement to hold: no process error
  EXPECT_FALSE(r.hs.rotmod());
  EXPECT_FALSE(r.hs.spmod());
  r.hs.Request(HeadstockMode::kRotary);
  EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kInternal);
  r.RunUntil(ChangeoverPhase::kExternal);
  EXPECT_TRUE(r.hs.rotmod());
  r.Acknowledge(HeadstockMode::kRotary);
  r.RunUntil(ChangeoverPhase::kNone);
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kRotary);
}

TEST_P(HeadstockChangeoverKinds, RequestForTheCurrentModeOrNoneDoesNothing) {
  Rig r(GetParam());
  r.hs.Request(HeadstockMode::kSpindle);
  EXPECT_FALSE(r.hs.busy());
  r.hs.Request(HeadstockMode::kNone);
  EXPECT_FALSE(r.hs.busy());
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kSpindle);
  r.hs.Abandon();  // nothing to abandon
  EXPECT_FALSE(r.hs.busy());
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kSpindle);
}

// ---- The sequence of figures 4-1 / 4-2 -----------------------------------------------------

TEST_P(HeadstockChangeoverKinds, SpindleToRotaryAndBack) {
  Rig r(GetParam());
  const bool servo = GetParam() == Kind::kServo;
  const uint8_t rotary_set = r.config.rotary_parameter_set;
  // The spindle turns at 100 rpm (M3).
  r.spindle_cmd = {DriveMode::kVelocity, 600, 0};
  r.Run(400);
  ASSERT_NEAR(r.SpindleFb().velocity, 600, 1e-9);
  EXPECT_EQ(r.Spindle().mode, DriveMode::kVelocity);
  EXPECT_EQ(r.Spindle().parameter_set, 0);
  EXPECT_TRUE(r.hs.spmod());

  // (1) activate, (2) internal changeover: decelerate to standstill in speed control, still with
  // the spindle's parameter set (4.2: decelerate, then activate the set; the rotary set's speed
  // limit is far below the spindle's); nothing goes to the PLC yet.
  r.hs.Request(HeadstockMode::kRotary);
  EXPECT_TRUE(r.hs.busy());
  EXPECT_EQ(r.hs.target(), HeadstockMode::kRotary);
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kNone);
  EXPECT_FALSE(r.hs.rotmod());
  EXPECT_FALSE(r.hs.spmod());
  ASSERT_TRUE(r.Cycle());
  EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kInternal);
  EXPECT_EQ(r.Spindle().mode, DriveMode::kVelocity);
  EXPECT_EQ(r.Spindle().value, 0);
  EXPECT_EQ(r.Spindle().parameter_set, 0);
  if (servo) {
    EXPECT_EQ(r.Rotary().mode, DriveMode::kVelocity);
  }
  EXPECT_LT(r.SpindleFb().velocity, 600);
  // 600 deg/s at 3600 deg/s^2: about 167 cycles to standstill.
  const int braking = r.RunUntil(ChangeoverPhase::kExternal);
  EXPECT_GT(braking, 150);
  EXPECT_LT(braking, 180);
  EXPECT_TRUE(r.SpindleFb().status & drive_status::kStandstill);
  // At standstill the set of rotary axis mode is activated (section 2; the servo keeps set 0).
  EXPECT_EQ(r.Spindle().parameter_set, rotary_set);

  // (3) external changeover: ROTMOD out until the PLC acknowledges with ROTMOD_Q alone.
  EXPECT_TRUE(r.hs.rotmod());
  EXPECT_FALSE(r.hs.spmod());
  r.Run(100);
  EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kExternal);
  r.plc.rotmod_q = true;  // SPMOD_Q still applied: not yet the end of the changeover
  r.Run(20);
  EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kExternal);
  EXPECT_FALSE(r.hs.TakeOverRotary());
  // (4) deactivate, (5) position control: the rotary command value is taken over once.
  r.rotary_cmd = {DriveMode::kPosition, r.RotaryFb().position, 0};
  r.plc.spmod_q = false;
  ASSERT_TRUE(r.Cycle());
  EXPECT_FALSE(r.hs.busy());
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kRotary);
  EXPECT_TRUE(r.hs.TakeOverRotary());
  EXPECT_FALSE(r.hs.TakeOverRotary());
  EXPECT_TRUE(r.hs.rotmod());
  EXPECT_FALSE(r.hs.spmod());
  EXPECT_EQ(r.Rotary().mode, DriveMode::kPosition);
  EXPECT_EQ(r.Rotary().parameter_set, rotary_set);
  // The rotary axis follows the NC; the spindle command no longer reaches the drive.
  r.spindle_cmd = {DriveMode::kVelocity, 1200, 0};
  r.rotary_cmd = {DriveMode::kPosition, 45, 0};
  r.Run(5);
  EXPECT_EQ(r.Rotary().mode, DriveMode::kPosition);
  EXPECT_EQ(r.Rotary().value, 45);
  EXPECT_NEAR(r.RotaryFb().position, 45, 1e-12);
  if (servo) {
    EXPECT_EQ(r.Spindle().value, 0);  // the spindle drive holds still
  }

  // Back: rotary axis -> spindle mode. The internal changeover goes to speed control in set 0.
  r.spindle_cmd = {DriveMode::kVelocity, 0, 0};
  r.hs.Request(HeadstockMode::kSpindle);
  EXPECT_FALSE(r.hs.rotmod());
  ASSERT_TRUE(r.Cycle());
  EXPECT_EQ(r.Spindle().mode, DriveMode::kVelocity);
  EXPECT_EQ(r.Spindle().parameter_set, 0);
  if (servo) {
    EXPECT_EQ(r.Rotary().mode, DriveMode::kVelocity);
  }
  r.RunUntil(ChangeoverPhase::kExternal);
  EXPECT_TRUE(r.hs.spmod());
  EXPECT_FALSE(r.hs.rotmod());
  r.Run(30);  // ROTMOD_Q still applied
  EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kExternal);
  r.Acknowledge(HeadstockMode::kSpindle);
  ASSERT_TRUE(r.Cycle());
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kSpindle);
  EXPECT_FALSE(r.hs.TakeOverRotary());
  r.spindle_cmd = {DriveMode::kVelocity, -300, 0};
  r.Run(200);
  EXPECT_EQ(r.Spindle().mode, DriveMode::kVelocity);
  EXPECT_EQ(r.Spindle().value, -300);
  EXPECT_EQ(r.Spindle().parameter_set, 0);
  EXPECT_NEAR(r.SpindleFb().velocity, -300, 1e-9);
}

TEST(HeadstockChangeoverTest, OneDriveWithoutARotaryParameterSetKeepsSetZero) {
  // 2.2: "Entering 0 suppresses the changeover" of the parameter set.
  HeadstockConfig c = ConfigOf(Kind::kFrameless);
  c.rotary_parameter_set = 0;
  HeadstockChangeover hs(c);
  HeadstockPlc plc;
  plc.spmod_q = true;
  hs.TakeModeFromPlc(plc);
  AmplifierTelegram at;
  at.feedback.resize(1);
  at.feedback[0].status = drive_status::kReady | drive_status::kStandstill;
  MasterTelegram mdt;
  mdt.setpoints.resize(1);
  hs.Request(HeadstockMode::kRotary);
  ASSERT_TRUE(hs.Cycle(plc, at, kDt));
  plc = {};
  plc.rotmod_q = true;
  ASSERT_TRUE(hs.Cycle(plc, at, kDt));
  ASSERT_EQ(hs.mode(), HeadstockMode::kRotary);
  hs.WriteSetpoints({DriveMode::kVelocity, 0, 0}, {DriveMode::kPosition, 10, 0}, mdt);
  EXPECT_EQ(mdt.setpoints[0].mode, DriveMode::kPosition);
  EXPECT_EQ(mdt.setpoints[0].value, 10);
  EXPECT_EQ(mdt.setpoints[0].parameter_set, 0);
}

TEST_P(HeadstockChangeoverKinds, ModeStaysWhileTheDriveHasNotStopped) {
  Rig r(GetParam());
  r.spindle_cmd = {DriveMode::kVelocity, 600, 0};
  r.Run(400);
  r.hs.Request(HeadstockMode::kRotary);
  // A PLC that acknowledges at once still waits for the internal changeover.
  r.Acknowledge(HeadstockMode::kRotary);
  r.Run(50);
  EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kInternal);
  EXPECT_FALSE(r.hs.rotmod());
  r.RunUntil(ChangeoverPhase::kNone);
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kRotary);
}

// ---- The acknowledgement is a level (4.1) ----------------------------------------------------

TEST_P(HeadstockChangeoverKinds, AcknowledgementRemovedInItsModeIsAProcessError) {
  Rig r(GetParam(), true, false);
  ASSERT_EQ(r.hs.mode(), HeadstockMode::kRotary);
  r.plc.rotmod_q = false;
  EXPECT_FALSE(r.Cycle());
  EXPECT_THAT(r.hs.error(), ::testing::HasSubstr("ROTMOD_Q"));

  Rig s(GetParam());
  ASSERT_EQ(s.hs.mode(), HeadstockMode::kSpindle);
  s.plc.rotmod_q = true;  // the other one as well: SPMOD_Q is still there, no error
  s.Run(5);
  s.plc.spmod_q = false;
  EXPECT_FALSE(s.Cycle());
  EXPECT_THAT(s.hs.error(), ::testing::HasSubstr("SPMOD_Q"));
  // Control-Reset takes the mode from the PLC again and clears the error.
  s.hs.TakeModeFromPlc(s.plc);
  EXPECT_TRUE(s.hs.error().empty());
  EXPECT_EQ(s.hs.mode(), HeadstockMode::kRotary);
  s.Run(5);
}

TEST_P(HeadstockChangeoverKinds, AcknowledgementsMayChangeDuringTheChangeover) {
  Rig r(GetParam());
  r.hs.Request(HeadstockMode::kRotary);
  r.RunUntil(ChangeoverPhase::kExternal);
  r.plc.spmod_q = false;  // the clutch has left spindle mode, not yet reached rotary
  r.Run(100);
  EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kExternal);
  r.plc.rotmod_q = true;
  r.Run(1);
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kRotary);
}

// ---- Immediate stop (2.3, 3.3) ---------------------------------------------------------------

TEST_P(HeadstockChangeoverKinds, ImmediateStopHaltsTheMotionFunctions) {
  for (int64_t fn : {axd::kHunting, axd::kPositioning, axd::kSpeedSpec}) {
    SCOPED_TRACE(::testing::Message() << "65012 " << fn);
    Rig r(GetParam());
    ToExternal(r);
    r.plc.spindle_axd = {fn, 1000000, 0, 900000};
    r.Run(50);
    ASSERT_NE(r.Spindle().value, 0);
    r.plc.stop = true;
    r.Run(1);
    EXPECT_EQ(r.Spindle().mode, DriveMode::kVelocity);
    EXPECT_EQ(r.Spindle().value, 0);
    EXPECT_EQ(r.hs.SpindleFunctionWord() & 0xff00, 0);  // no acknowledgement while stopped
    r.Run(500);
    EXPECT_TRUE(r.SpindleFb().status & drive_status::kStandstill);
    const double held = r.SpindleFb().position;
    r.Run(200);
    EXPECT_EQ(r.SpindleFb().position, held);
    EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kExternal);  // pending, not given up
    // The stop released, the function goes on.
    r.plc.stop = false;
    r.Run(100);
    EXPECT_NE(r.SpindleFb().position, held);
  }
}

TEST_P(HeadstockChangeoverKinds, ImmediateStopHoldsTheInternalSequence) {
  // 2.3: "Upon an immediate stop during a changeover process, the MTC stops the internal
  // sequence and brings the axes to a standstill. The NC causes the internal commands to be
  // pending": no ROTMOD goes out while the stop is in force.
  Rig r(GetParam());
  r.spindle_cmd = {DriveMode::kVelocity, 600, 0};
  r.Run(400);
  r.hs.Request(HeadstockMode::kRotary);
  r.plc.stop = true;
  r.Run(1000);
  EXPECT_TRUE(r.SpindleFb().status & drive_status::kStandstill);  // brought to a standstill
  EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kInternal);
  EXPECT_FALSE(r.hs.rotmod());
  r.plc.stop = false;
  r.Run(1);
  EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kExternal);
  EXPECT_TRUE(r.hs.rotmod());
}

// ---- Turning round and reverse ---------------------------------------------------------------

TEST_P(HeadstockChangeoverKinds, RequestForTheOtherModeTurnsTheChangeoverRound) {
  Rig r(GetParam());
  r.hs.Request(HeadstockMode::kRotary);
  r.RunUntil(ChangeoverPhase::kExternal);
  r.plc.spindle_axd[kAxdFunction] = axd::kHunting;
  r.Run(10);
  ASSERT_TRUE(r.hs.rotmod());
  r.hs.Request(HeadstockMode::kSpindle);
  EXPECT_EQ(r.hs.target(), HeadstockMode::kSpindle);
  EXPECT_EQ(r.hs.phase(), ChangeoverPhase::kInternal);
  EXPECT_FALSE(r.hs.rotmod());
  EXPECT_FALSE(r.hs.spmod());
  r.RunUntil(ChangeoverPhase::kExternal);
  EXPECT_TRUE(r.hs.spmod());
  ASSERT_TRUE(r.Cycle());  // the PLC still acknowledges spindle mode
  EXPECT_FALSE(r.hs.busy());
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kSpindle);
  EXPECT_FALSE(r.hs.TakeOverRotary());
}

TEST_P(HeadstockChangeoverKinds, AbandonRestoresTheOriginalMode) {
  for (const bool from_rotary : {false, true}) {
    SCOPED_TRACE(from_rotary ? "from rotary" : "from spindle");
    Rig r(GetParam(), from_rotary, !from_rotary);
    const HeadstockMode original = from_rotary ? HeadstockMode::kRotary : HeadstockMode::kSpindle;
    const HeadstockMode other = from_rotary ? HeadstockMode::kSpindle : HeadstockMode::kRotary;
    r.hs.TakeOverRotary();
    r.hs.Request(other);
    r.RunUntil(ChangeoverPhase::kExternal);
    r.Run(10);
    r.hs.Abandon();
    EXPECT_EQ(r.hs.target(), original);
    r.RunUntil(ChangeoverPhase::kNone);
    EXPECT_EQ(r.hs.mode(), original);
    EXPECT_EQ(r.hs.rotmod(), from_rotary);
    EXPECT_EQ(r.hs.spmod(), !from_rotary);
    EXPECT_EQ(r.hs.TakeOverRotary(), from_rotary);
  }
  // Abandoned during the internal changeover, too.
  Rig r(GetParam());
  r.hs.Request(HeadstockMode::kRotary);
  ASSERT_TRUE(r.Cycle());
  r.hs.Abandon();
  r.RunUntil(ChangeoverPhase::kNone);
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kSpindle);
}

TEST_P(HeadstockChangeoverKinds, AbandonAfterTurningRoundStillRestoresTheFirstMode) {
  Rig r(GetParam());
  r.hs.Request(HeadstockMode::kRotary);
  r.RunUntil(ChangeoverPhase::kExternal);
  r.hs.Request(HeadstockMode::kSpindle);
  r.hs.Request(HeadstockMode::kRotary);
  r.hs.Abandon();
  EXPECT_EQ(r.hs.target(), HeadstockMode::kSpindle);
  r.RunUntil(ChangeoverPhase::kNone);
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kSpindle);
}

TEST_P(HeadstockChangeoverKinds, AbandonFromNeitherModeEndsInNeither) {
  Rig r(GetParam(), false, false);
  r.hs.Request(HeadstockMode::kRotary);
  r.RunUntil(ChangeoverPhase::kExternal);
  r.hs.Abandon();
  EXPECT_FALSE(r.hs.busy());
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kNone);
  EXPECT_FALSE(r.hs.rotmod());
  EXPECT_FALSE(r.hs.spmod());
  r.Run(10);
}

TEST_P(HeadstockChangeoverKinds, ControlResetAbandonsTheChangeoverForThePlcsMode) {
  Rig r(GetParam());
  r.hs.Request(HeadstockMode::kRotary);
  r.RunUntil(ChangeoverPhase::kExternal);
  r.plc.spindle_axd[kAxdFunction] = axd::kHunting;
  r.Run(10);
  ASSERT_NE(r.hs.SpindleFunctionWord(), 0);
  r.hs.TakeModeFromPlc(r.plc);  // SPMOD_Q still applied
  EXPECT_FALSE(r.hs.busy());
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kSpindle);
  EXPECT_EQ(r.hs.SpindleFunctionWord(), 0);
  r.Run(10);
  EXPECT_EQ(r.hs.SpindleFunctionWord(), 0);
}

// ---- Controller enables, AxxC.READY (4.3) ----------------------------------------------------

TEST(HeadstockChangeoverTest, SeparateServoDriveWithoutItsEnableIsOff) {
  Rig r(Kind::kServo, true, false);
  r.rotary_cmd = {DriveMode::kPosition, 30, 0};
  // Rotary axis mode, the PLC has switched the spindle's enable off (4.4: it idles).
  r.plc.spindle_ready = false;
  r.Run(2);
  EXPECT_EQ(r.Spindle().mode, DriveMode::kOff);
  EXPECT_EQ(r.Rotary().mode, DriveMode::kPosition);
  EXPECT_EQ(r.Rotary().value, 30);
  // Spindle mode, the servo's enable off: it is in follow-up, torque-free.
  Rig s(Kind::kServo);
  s.spindle_cmd = {DriveMode::kVelocity, 600, 0};
  s.plc.rotary_ready = false;
  s.Run(2);
  EXPECT_EQ(s.Rotary().mode, DriveMode::kOff);
  EXPECT_EQ(s.Spindle().mode, DriveMode::kVelocity);
  EXPECT_EQ(s.Spindle().value, 600);
  // During the changeover the enables are the PLC's too (3.1 of figure 4-2).
  s.hs.Request(HeadstockMode::kRotary);
  s.RunUntil(ChangeoverPhase::kExternal);
  s.plc.rotary_axd = {axd::kHunting, 0, 0, 0};
  s.Run(5);
  EXPECT_EQ(s.Rotary().mode, DriveMode::kOff);
  s.plc.rotary_ready = true;
  s.plc.spindle_ready = false;
  s.Run(5);
  EXPECT_EQ(s.Spindle().mode, DriveMode::kOff);
  EXPECT_EQ(s.Rotary().mode, DriveMode::kVelocity);
  EXPECT_EQ(std::abs(s.Rotary().value), s.config.hunting_speed);
}

TEST(HeadstockChangeoverTest, OneDriveWithoutItsEnableIsOffInEveryMode) {
  for (const bool rotary : {false, true}) {
    Rig r(Kind::kFrameless, rotary, !rotary);
    r.plc.spindle_ready = false;
    r.Run(2);
    EXPECT_EQ(r.Spindle().mode, DriveMode::kOff);
    r.plc.spindle_ready = true;
    r.Run(1);
    EXPECT_EQ(r.Spindle().mode, rotary ? DriveMode::kPosition : DriveMode::kVelocity);
  }
}

// A changeover the PLC does not acknowledge is reported after stall_message_s, with what the
// PLC's AXD idents leave undone; the report goes with the acknowledgement.
TEST(HeadstockChangeoverTest, AStalledChangeoverSaysWhy) {
  Rig r(Kind::kServo);
  r.hs.Request(HeadstockMode::kRotary);
  r.RunUntil(ChangeoverPhase::kExternal);
  const int cycles = static_cast<int>(r.config.stall_message_s / kDt);
  r.Run(cycles - 2);
  EXPECT_EQ(r.hs.Stalled(), "");
  r.Run(4);
  EXPECT_EQ(r.hs.Stalled(),
            "changeover to rotary axis mode: no ROTMOD_Q from the PLC within 5.0 s; no AXD "
            "motion function is requested (65012 = 0): a clutch whose dogs meet tooth on tooth "
            "does not mesh unless a drive turns");
  // A speed specification left at speed 0 turns nothing either.
  r.plc.rotary_axd = {axd::kSpeedSpec, 0, 100, 0};
  r.Run(1);
  EXPECT_NE(r.hs.Stalled().find("the rotary drive's speed specification has speed 0 (AXD 65013)"),
            std::string::npos)
      << r.hs.Stalled();
  r.plc.rotary_axd = {axd::kSpeedSpec, 100000, 0, 0};
  r.Run(1);
  EXPECT_NE(r.hs.Stalled().find("acceleration 0 (AXD 65014)"), std::string::npos) << r.hs.Stalled();
  r.Acknowledge(HeadstockMode::kRotary);
  r.Run(2);
  EXPECT_EQ(r.hs.mode(), HeadstockMode::kRotary);
  EXPECT_EQ(r.hs.Stalled(), "");
}

}  // namespace
}  // namespace vmt::control::axes
