// Drive behaviour on the physics backend against the machine YAML's own spec.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
using testing::Bench;
using testing::Lathe;

struct StepCase {
  const char* drive;
  double step;  // mm | deg
};

void PrintTo(const StepCase& c, std::ostream* os) { *os << c.drive << " step " << c.step; }

class ServoStepTest : public ::testing::TestWithParam<StepCase> {};

// A position step from standstill: the axis must settle into its in-position window within the
// spec's settle time and overshoot no more than the spec allows.
TEST_P(ServoStepTest, SettlesWithinSpec) {
  const StepCase c = GetParam();
  const MachineModel& m = Lathe();
  const DriveParams& p = m.drives[m.DriveIndex(c.drive)];
  ASSERT_GT(p.spec_settle_time_s, 0) << c.drive << " has no spec in the machine YAML";
  const double unit = p.info.kind == control::AxisKind::kLinear ? kMmPerM : kDegPerRad;

  InitialState init;
  init.drive_positions[c.drive] = 100;
  // C reads the spindle's encoder and moves the spindle only through clutch K: rotary axis
  // mode, K engaged and the spindle drive idle (C-axis manual 4.4).
  const bool c_axis = std::string(c.drive) == "C";
  if (c_axis) init.clutch_engaged["K"] = true;
  PhysicsBackend backend(m, init);
  Bench bench(backend);
  if (c_axis) bench.Command("S1", DriveMode::kOff, 0);
  bench.Output("QTURRET_UNCLAMP", true);  // the turret moves only unclamped
  bench.Run(0.1);
  const double t0 = backend.time_s();
  const double start = bench.Feedback(c.drive).position;
  const double target = start + c.step;
  bench.Command(c.drive, DriveMode::kPosition, target);

  double overshoot = 0, last_outside = 0;
  const double window = p.in_position_window * unit;
  const double horizon = 3 * p.spec_settle_time_s + 0.5;
  bench.Run(horizon, [&] {
    const double pos = bench.Feedback(c.drive).position;
    overshoot = std::max(overshoot, pos - target);
    if (std::abs(pos - target) > window) last_outside = backend.time_s() - t0;
  });
  EXPECT_LE(overshoot, p.spec_overshoot * unit) << c.drive;
  EXPECT_LE(last_outside, p.spec_settle_time_s) << c.drive << " settles too late";
  EXPECT_NEAR(bench.Feedback(c.drive).position, target, window);
  EXPECT_TRUE(bench.Feedback(c.drive).status & control::drive_status::kInPosition);
}

INSTANTIATE_TEST_SUITE_P(LatheServos, ServoStepTest,
                         ::testing::Values(StepCase{"Z", 10}, StepCase{"X", 10}, StepCase{"W", 10},
                                           StepCase{"T", 30}, StepCase{"C", 10}),
                         [](const auto& info) { return std::string(info.param.drive); });

// Run-up 0 -> 3000 rpm is limited by the spindle's acceleration: it takes v/a, not less (the
// ramp) and not much more (the velocity loop follows the ramp).
TEST(SpindleTest, RunUpTakesTheAccelerationLimitedTime) {
  const MachineModel& m = Lathe();
  const DriveParams& p = m.drives[m.DriveIndex("S1")];
  PhysicsBackend backend(m, {});
  Bench bench(backend);
  const double rpm = 3000;
  bench.Command("S1", DriveMode::kVelocity, rpm * 6);
  const double expected_s = rpm * 6 / (p.acceleration_limit * kDegPerRad);
  const double t = bench.RunUntil(
      [&] { return bench.Feedback("S1").status & control::drive_status::kAtSpeed; }, 5);
  ASSERT_GT(t, 0) << "never at speed";
  EXPECT_GE(t, expected_s - 0.001);
  EXPECT_LE(t, expected_s * 1.05);
  bench.Run(0.5);
  EXPECT_NEAR(bench.Feedback("S1").velocity / 6, rpm, 1.0);
}

// M19: the spindle orients to an angle the short way and stops there.
TEST(SpindleTest, OrientsToAnAngle) {
  const MachineModel& m = Lathe();
  PhysicsBackend backend(m, {});
  Bench bench(backend);
  bench.Command("S1", DriveMode::kVelocity, 600);
  bench.Run(1.0);
  bench.Command("S1", DriveMode::kPosition, 45);
  const double t = bench.RunUntil(
      [&] {
        return bench.Feedback("S1").status & control::drive_status::kInPosition &&
               bench.Feedback("S1").status & control::drive_status::kStandstill;
      },
      5);
  ASSERT_GT(t, 0);
  const double angle = std::fmod(bench.Feedback("S1").position, 360.0);
  EXPECT_NEAR(angle, 45, 0.05);
}

// G64: a spindle set in position mode with `interpolated` follows the NC's cyclic position
// like a servo, over many turns, instead of orienting to it modulo 360 (M19).
TEST(SpindleTest, FollowsAnInterpolatedPositionOverManyTurns) {
  const MachineModel& m = Lathe();
  PhysicsBackend backend(m, {});
  Bench bench(backend);
  control::DriveSetpoint& sp = bench.mdt().setpoints[m.DriveIndex("S1")];
  const double start = bench.Feedback("S1").position;
  // Three turns on a triangular speed profile at 1800 deg/s^2, as the NC's G64 would send.
  const double accel = 1800, turns_deg = 3 * 360;
  double command = start, velocity = 0, worst = 0;
  bench.Run(3.0, [&] {
    const double left = turns_deg - (command - start);
    velocity = left <= velocity * velocity / (2 * accel)
                   ? std::max(0.0, velocity - accel * kDriveTickS)
                   : velocity + accel * kDriveTickS;
    command += std::min(velocity * kDriveTickS, left);
    sp = {DriveMode::kPosition, command, 0, velocity, true};
    worst = std::max(worst, std::abs(bench.Feedback("S1").following_error));
  });
  bench.Run(0.5);
  EXPECT_LT(worst, 2.0);                         // degrees, with feed-forward
  EXPECT_NEAR(command - start, turns_deg, 1.0);  // M19 would have taken the short way to it
  EXPECT_NEAR(bench.Feedback("S1").position, command, 0.05);
  EXPECT_TRUE(bench.Feedback("S1").status & control::drive_status::kInPosition);
}

// The belt is a gear: the motor turns `ratio` times the spindle, and stays in phase.
TEST(GearTest, BeltKeepsItsRatio) {
  const MachineModel& m = Lathe();
  PhysicsBackend backend(m, {});
  Bench bench(backend);
  bench.Command("S1", DriveMode::kVelocity, 3000 * 6);
  bench.Run(3.0);
  const auto q = backend.JointPositions();
  const double motor = q[m.JointIndex("s1_motor")], spindle = q[m.JointIndex("spindle")];
  ASSERT_GT(spindle, 2 * M_PI * 50);
  EXPECT_NEAR(motor - 1.5 * spindle, 0, 1e-4);
}

}  // namespace
}  // namespace vmt::sim
