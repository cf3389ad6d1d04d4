// The changeover's AXD motion functions, idents 65012..65015 (C-axis manual 2.2, 3.2, 4.2
// note): hunting, positioning and the speed specification the PLC orders while the changeover
// is in its external phase, on both machine kinds.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/control/axes/headstock_rig.hpp"

namespace vmt::control::axes {
namespace {

using namespace headstock_rig;

class HeadstockMotionFunctions : public ::testing::TestWithParam<Kind> {};
INSTANTIATE_TEST_SUITE_P(Machine, HeadstockMotionFunctions,
                         ::testing::Values(Kind::kServo, Kind::kFrameless), KindName);

TEST_P(HeadstockMotionFunctions, MotionFunctionsAreIgnoredOutsideTheChangeover) {
  Rig r(GetParam());
  r.spindle_cmd = {DriveMode::kVelocity, 120, 0};
  for (int64_t fn : {axd::kHunting, axd::kPositioning, axd::kSpeedSpec}) {
    r.plc.spindle_axd = {fn, 1000000, 10, 900000};
    r.plc.rotary_axd = r.plc.spindle_axd;
    r.Run(100);
    EXPECT_EQ(r.hs.SpindleFunctionWord(), 0);
    EXPECT_EQ(r.hs.RotaryFunctionWord(), 0);
    EXPECT_EQ(r.Spindle().value, 120);  // the NC's command, not the function's
  }
  // Nor during the internal changeover.
  r.hs.Request(HeadstockMode::kRotary);
  ASSERT_TRUE(r.Cycle());
  ASSERT_EQ(r.hs.phase(), ChangeoverPhase::kInternal);
  EXPECT_EQ(r.hs.SpindleFunctionWord(), 0);
  EXPECT_EQ(r.Spindle().value, 0);
  r.RunUntil(ChangeoverPhase::kExternal);
  r.plc.spindle_axd = {};
  r.Acknowledge(HeadstockMode::kRotary);
  r.Run(1);
  // And no more after it: the word drops, the drive is the NC's again.
  r.plc.spindle_axd = {axd::kSpeedSpec, 1000000, 10, 0};
  r.Run(20);
  EXPECT_EQ(r.hs.SpindleFunctionWord(), 0);
  EXPECT_EQ(r.Rotary().mode, DriveMode::kPosition);
}

TEST_P(HeadstockMotionFunctions, HuntingOscillatesWithoutNetRotation) {
  Rig r(GetParam());
  ToExternal(r);
  const double start = r.SpindleFb().position;
  r.plc.spindle_axd[kAxdFunction] = axd::kHunting;
  ASSERT_TRUE(r.Cycle());
  EXPECT_EQ(r.hs.SpindleFunctionWord(), axd::kHunting | axd::kHuntingAck);
  double lo = start, hi = start;
  bool forward = false, backward = false;
  for (int i = 0; i < 2000; ++i) {
    ASSERT_TRUE(r.Cycle());
    EXPECT_EQ(r.Spindle().mode, DriveMode::kVelocity);
    EXPECT_EQ(std::abs(r.Spindle().value), r.config.hunting_speed);
    forward = forward || r.Spindle().value > 0;
    backward = backward || r.Spindle().value < 0;
    lo = std::min(lo, r.SpindleFb().position);
    hi = std::max(hi, r.SpindleFb().position);
  }
  EXPECT_TRUE(forward && backward);
  // About a quarter period either side of the start, no drift.
  const double swing = r.config.hunting_speed * r.config.hunting_half_period_s / 2;
  EXPECT_NEAR(hi - start, swing, 0.2);
  EXPECT_NEAR(start - lo, swing, 0.2);
  // Switched off: the acknowledgement goes, the drive stops.
  r.plc.spindle_axd[kAxdFunction] = 0;
  r.Run(10);
  EXPECT_EQ(r.hs.SpindleFunctionWord(), 0);
  EXPECT_EQ(r.Spindle().value, 0);
}

TEST_P(HeadstockMotionFunctions, PositioningIsAcknowledgedInTheWindow) {
  Rig r(GetParam());
  ToExternal(r);
  r.plc.spindle_axd = {axd::kPositioning, 0, 0, 900000};  // 90.0000 deg
  ASSERT_TRUE(r.Cycle());
  EXPECT_EQ(r.hs.SpindleFunctionWord(), axd::kPositioning);  // not there yet
  EXPECT_GT(r.Spindle().value, 0);
  EXPECT_LE(r.Spindle().value, r.config.positioning_speed);
  int n = 0;
  while (!(r.hs.SpindleFunctionWord() & axd::kPositioningAck) && n < 20000) {
    ASSERT_TRUE(r.Cycle());
    ++n;
  }
  EXPECT_EQ(r.hs.SpindleFunctionWord(), axd::kPositioning | axd::kPositioningAck);
  EXPECT_NEAR(r.SpindleFb().position, 90, r.config.positioning_window);
  EXPECT_GT(n * kDt, 90 / r.config.positioning_speed);  // at most the positioning speed
  // The shorter way round: from 90 to 350 deg goes backwards through 0.
  r.plc.spindle_axd[kAxdAngle] = 3500000;
  r.Run(1);
  EXPECT_LT(r.Spindle().value, 0);
  r.Run(20000);
  EXPECT_NEAR(r.SpindleFb().position, -10, r.config.positioning_window);
  EXPECT_TRUE(r.hs.SpindleFunctionWord() & axd::kPositioningAck);
}

TEST_P(HeadstockMotionFunctions, SpeedSpecificationRampsAndIsLimitedTo1000Rpm) {
  Rig r(GetParam());
  ToExternal(r);
  // 65013 = 100 rpm in 0.0001 rpm, 65014 = 5 rad/s^2 (286.5 deg/s^2): 600 deg/s in 2.09 s.
  r.plc.spindle_axd = {axd::kSpeedSpec, 1000000, 5, 0};
  r.Run(1000);
  EXPECT_EQ(r.hs.SpindleFunctionWord(), axd::kSpeedSpec);  // ramping: not yet acknowledged
  EXPECT_NEAR(r.Spindle().value, 5 * 180 / M_PI * 1.0, 1e-6);
  r.Run(1100);
  EXPECT_EQ(r.hs.SpindleFunctionWord(), axd::kSpeedSpec | axd::kSpeedSpecAck);
  EXPECT_EQ(r.Spindle().value, 600);
  // "The value may also be modified while the spindle function is activated."
  r.plc.spindle_axd[kAxdSpeed] = -500000;  // -50 rpm
  r.Run(1);
  EXPECT_EQ(r.hs.SpindleFunctionWord(), axd::kSpeedSpec);
  r.Run(3500);  // 900 deg/s at 286.5 deg/s^2
  EXPECT_EQ(r.Spindle().value, -300);
  EXPECT_TRUE(r.hs.SpindleFunctionWord() & axd::kSpeedSpecAck);
  // "The maximum speed is limited to 1000 rpm."
  r.plc.spindle_axd = {axd::kSpeedSpec, 25000000, 0, 0};  // 2500 rpm, no ramp
  r.Run(1);
  EXPECT_EQ(r.Spindle().value, 6000);
  EXPECT_TRUE(r.hs.SpindleFunctionWord() & axd::kSpeedSpecAck);
  r.plc.spindle_axd = {axd::kSpeedSpec, -25000000, 0, 0};
  r.Run(1);
  EXPECT_EQ(r.Spindle().value, -6000);
}

TEST_P(HeadstockMotionFunctions, SpeedSpecificationIsAcknowledgedForAnySpeedAndAcceleration) {
  // The ramp must end exactly on the speed asked for, whatever the numbers.
  for (const auto& [speed, accel] : {std::pair<int64_t, int64_t>{333333, 3},
                                     {123457, 7},
                                     {-987654, 11},
                                     {1, 1},
                                     {9999999, 13}}) {
    SCOPED_TRACE(::testing::Message() << "65013 " << speed << " 65014 " << accel);
    Rig r(GetParam());
    ToExternal(r);
    r.plc.spindle_axd = {axd::kSpeedSpec, speed, accel, 0};
    r.Run(20000);
    EXPECT_TRUE(r.hs.SpindleFunctionWord() & axd::kSpeedSpecAck);
    EXPECT_NEAR(r.Spindle().value, speed * 1e-4 * 6, 1e-9);
  }
  // Changed while active, without a ramp (65014 = 0): the new speed at once, acknowledged.
  Rig r(GetParam());
  ToExternal(r);
  r.plc.spindle_axd = {axd::kSpeedSpec, -4326496, 0, 0};
  r.Run(1);
  ASSERT_TRUE(r.hs.SpindleFunctionWord() & axd::kSpeedSpecAck);
  r.plc.spindle_axd[kAxdSpeed] = 339343;
  r.Run(1);
  EXPECT_TRUE(r.hs.SpindleFunctionWord() & axd::kSpeedSpecAck);
  EXPECT_NEAR(r.Spindle().value, 339343 * 1e-4 * 6, 1e-9);
}

TEST(HeadstockChangeoverTest, SeparateServoRunsTheFunctionsOfBothDrives) {
  // 4.3: "the SPS may use the following motion functions during that phase for both drives".
  Rig r(Kind::kServo);
  ToExternal(r);
  r.plc.spindle_axd = {axd::kHunting, 0, 0, 0};
  r.plc.rotary_axd = {axd::kSpeedSpec, 100000, 0, 0};  // 10 rpm at once
  r.Run(2);
  EXPECT_EQ(r.hs.SpindleFunctionWord(), axd::kHunting | axd::kHuntingAck);
  EXPECT_EQ(r.hs.RotaryFunctionWord(), axd::kSpeedSpec | axd::kSpeedSpecAck);
  EXPECT_EQ(std::abs(r.Spindle().value), r.config.hunting_speed);
  EXPECT_EQ(r.Rotary().mode, DriveMode::kVelocity);
  EXPECT_EQ(r.Rotary().value, 60);
}

TEST(HeadstockChangeoverTest, OneDriveIgnoresTheRotaryAxisIdents) {
  Rig r(Kind::kFrameless);
  ToExternal(r);
  r.plc.rotary_axd = {axd::kSpeedSpec, 100000, 0, 0};
  r.Run(10);
  EXPECT_EQ(r.hs.RotaryFunctionWord(), 0);
  EXPECT_EQ(r.Spindle().value, 0);
}

}  // namespace
}  // namespace vmt::control::axes
