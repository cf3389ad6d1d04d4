#include "tests/support/ideal_drive_bus.hpp"

#include <gtest/gtest.h>

namespace vmt::test_support {
namespace {

using control::DriveMode;
namespace status = control::drive_status;

TEST(IdealDriveBus, NewDrivesAreReadyAtZeroAndLeftAlone) {
  IdealDriveBus bus(2);
  bus.mdt.setpoints[0] = {DriveMode::kPosition, 5};
  bus.Answer();
  EXPECT_EQ(bus.at.feedback[0].position, 0);  // kNone: the test answers itself
  EXPECT_EQ(bus.at.feedback[1].status, status::kReady);
  bus.Resize(3, status::kReady | status::kStandstill);
  EXPECT_EQ(bus.at.feedback[2].status, status::kReady | status::kStandstill);
  EXPECT_EQ(bus.at.feedback[1].status, status::kReady);
  EXPECT_EQ(bus.drives.size(), 3u);
  EXPECT_EQ(bus.mdt.setpoints.size(), 3u);
}

TEST(IdealDriveBus, FollowTakesThePositionAndIntegratesAVelocityOnly) {
  IdealDriveBus bus(1);
  bus.drives[0] = IdealDrive::Follow();
  bus.mdt.setpoints[0] = {DriveMode::kPosition, 12.5};
  bus.Answer();
  EXPECT_EQ(bus.at.feedback[0].position, 12.5);
  EXPECT_EQ(bus.at.feedback[0].velocity, 0);
  EXPECT_EQ(bus.at.feedback[0].status, status::kReady);
  bus.mdt.setpoints[0] = {DriveMode::kVelocity, 4000};
  bus.Answer();
  EXPECT_DOUBLE_EQ(bus.at.feedback[0].position, 13.5);
  bus.mdt.setpoints[0] = {DriveMode::kOff, 0};
  bus.Answer();
  EXPECT_DOUBLE_EQ(bus.at.feedback[0].position, 13.5);
}

TEST(IdealDriveBus, AServoStepsOntoItsPositionAndRampsItsVelocity) {
  IdealDriveBus bus(1);
  bus.drives[0] = IdealDrive::Servo(7200);  // 1.8 deg/s per tick
  bus.mdt.setpoints[0] = {DriveMode::kPosition, 1};
  bus.Answer();
  const control::DriveFeedback& f = bus.at.feedback[0];
  EXPECT_EQ(f.position, 1);
  EXPECT_DOUBLE_EQ(f.velocity, 4000);
  EXPECT_EQ(f.status, status::kReady | status::kInPosition);
  bus.Answer();
  EXPECT_EQ(f.status, status::kReady | status::kStandstill | status::kInPosition);
  bus.mdt.setpoints[0] = {DriveMode::kVelocity, 3.6};
  bus.Answer();
  EXPECT_DOUBLE_EQ(f.velocity, 1.8);
  EXPECT_DOUBLE_EQ(f.position, 1 + 1.8 * 250e-6);
  EXPECT_EQ(f.status, status::kReady);  // no at-speed bit unless asked for
  bus.drives[0].at_speed = true;
  bus.Answer();
  EXPECT_DOUBLE_EQ(f.velocity, 3.6);
  EXPECT_EQ(f.status, status::kReady | status::kAtSpeed);
  bus.mdt.setpoints[0] = {DriveMode::kOff, 0};
  bus.Answer();
  bus.Answer();
  EXPECT_EQ(f.velocity, 0);  // kOff coasts down at the same ramp
  EXPECT_EQ(f.status, status::kReady | status::kStandstill);
}

TEST(IdealDriveBus, AServoWithoutAccelerationIsAtItsCommandAtOnce) {
  IdealDriveBus bus(1);
  bus.drives[0] = IdealDrive::Servo();
  bus.drives[0].enabled = true;
  bus.drives[0].standstill_window = 1e-9;
  bus.mdt.setpoints[0] = {DriveMode::kVelocity, 600};
  bus.Answer();
  EXPECT_EQ(bus.at.feedback[0].velocity, 600);
  EXPECT_DOUBLE_EQ(bus.at.feedback[0].position, 0.15);
  EXPECT_EQ(bus.at.feedback[0].status, status::kReady | status::kEnabled);
  bus.mdt.setpoints[0] = {DriveMode::kOff, 0};
  bus.Answer();
  EXPECT_EQ(bus.at.feedback[0].status, status::kReady | status::kStandstill);
}

TEST(IdealDriveBus, AnOrientingSpindleReportsNoVelocityUnlessInterpolated) {
  IdealDriveBus bus(1);
  bus.drives[0] = IdealDrive::Servo(7200);
  bus.drives[0].orients = true;
  bus.mdt.setpoints[0] = {DriveMode::kPosition, 90};  // M19
  bus.Answer();
  EXPECT_EQ(bus.at.feedback[0].position, 90);
  EXPECT_EQ(bus.at.feedback[0].velocity, 0);
  bus.mdt.setpoints[0].value = 91;
  bus.mdt.setpoints[0].interpolated = true;  // G64
  bus.Answer();
  EXPECT_DOUBLE_EQ(bus.at.feedback[0].velocity, 4000);
}

TEST(IdealDriveBus, AnInstantSpindleIsAtSpeedOrInPositionAtOnce) {
  IdealDriveBus bus(1);
  bus.drives[0] = IdealDrive::InstantSpindle();
  const control::DriveFeedback& f = bus.at.feedback[0];
  bus.mdt.setpoints[0] = {DriveMode::kVelocity, 6000};
  bus.Answer();
  EXPECT_EQ(f.velocity, 6000);
  EXPECT_EQ(f.position, 0);  // a turning spindle's position is not followed
  EXPECT_EQ(f.status, status::kReady | status::kAtSpeed);
  bus.mdt.setpoints[0] = {DriveMode::kVelocity, 0};
  bus.Answer();
  EXPECT_EQ(f.status, status::kReady | status::kStandstill);
  bus.mdt.setpoints[0] = {DriveMode::kPosition, 45};
  bus.Answer();
  EXPECT_EQ(f.position, 45);
  EXPECT_EQ(f.velocity, 0);
  EXPECT_EQ(f.status, status::kReady | status::kStandstill | status::kInPosition);
  bus.mdt.setpoints[0] = {DriveMode::kOff, 0};
  bus.Answer();
  EXPECT_EQ(f.position, 45);
  EXPECT_EQ(f.status, status::kReady | status::kStandstill);
}

TEST(IdealDriveBus, OneDriveAnswersAsAnotherDescriptionSays) {
  IdealDriveBus bus(2);
  bus.mdt.setpoints[1] = {DriveMode::kPosition, 30};
  bus.Answer(1, IdealDrive::Follow());  // e.g. a turret the test lets follow only at times
  EXPECT_EQ(bus.at.feedback[1].position, 30);
  EXPECT_EQ(bus.drives[1].answer, IdealDrive::Answer::kNone);
}

TEST(IdealDriveBus, ItsTickIsTheRigs) {
  IdealDriveBus bus(1, control::drive_status::kReady, 1e-3);  // one NC cycle
  bus.drives[0] = IdealDrive::Servo(3600);
  bus.mdt.setpoints[0] = {DriveMode::kVelocity, 100};
  bus.Answer();
  EXPECT_DOUBLE_EQ(bus.at.feedback[0].velocity, 3.6);
  EXPECT_DOUBLE_EQ(bus.at.feedback[0].position, 3.6e-3);
}

}  // namespace
}  // namespace vmt::test_support
