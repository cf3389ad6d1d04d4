// The drive's threshold status bits (control/drive_bus.hpp; SERCOS S-0-0333 |Md| >= Mdx,
// S-0-0337 |P| >= Px, and 90 % load), which the C-axis manual's spindle signals AxxS.MD_MDX,
// P_PX and LOAD90 show (4.2): from the torque the drive gives, so on the physics backend.

#include <gtest/gtest.h>

#include <cmath>

#include "sim/runner/runner.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
using namespace control::drive_status;
using testing::Bench;
using testing::Lathe;

// S1 runs up to 3000 rpm at its 9000 deg/s^2: the ramp needs the torque of the inertia, the
// constant speed only the friction's. Mdx between the two shows the ramp; Px shows where
// torque and speed together are high, late in the ramp, not at its start.
TEST(DriveThresholdStatusTest, TorqueAndPowerThresholdsShowTheRunUp) {
  MachineModel m = Lathe();
  DriveParams& s1 = m.drives[m.DriveIndex("S1")];
  s1.torque_threshold = 30;     // N m
  s1.power_threshold_w = 5000;  // W
  PhysicsBackend backend(m, InitialState{});
  Bench bench(backend);
  bench.Command("S1", DriveMode::kVelocity, 18000);  // deg/s = 3000 rpm
  double torque_on = -1, power_on = -1, peak_torque = 0;
  double t = 0;
  bench.Run(1.0, [&] {
    t += kDriveTickS;
    const control::DriveFeedback& fb = bench.Feedback("S1");
    peak_torque = std::max(peak_torque, std::abs(fb.torque));
    const bool torque_bit = fb.status & kTorqueThreshold, power_bit = fb.status & kPowerThreshold;
    EXPECT_EQ(torque_bit, std::abs(fb.torque) >= 30) << t;
    const double power_w = std::abs(fb.torque * fb.velocity * M_PI / 180);
    // Away from the threshold by more than the deg <-> rad conversion's rounding.
    if (std::abs(power_w - 5000) > 1e-6) {
      EXPECT_EQ(power_bit, power_w >= 5000) << t;
    }
    if (torque_bit && torque_on < 0) torque_on = t;
    if (power_bit && power_on < 0) power_on = t;
  });
  ASSERT_GT(peak_torque, 30) << "the ramp needs more than the threshold";
  ASSERT_GE(torque_on, 0);
  ASSERT_GE(power_on, 0);
  EXPECT_GT(power_on, torque_on) << "power needs speed as well as torque";
  // At speed: friction only, both bits clear.
  bench.Run(1.5);
  EXPECT_TRUE(bench.Feedback("S1").status & kAtSpeed);
  EXPECT_FALSE(bench.Feedback("S1").status & kTorqueThreshold);
  EXPECT_FALSE(bench.Feedback("S1").status & kPowerThreshold);
}

// A drive without thresholds never shows them, whatever its torque.
TEST(DriveThresholdStatusTest, NoThresholdNoBit) {
  const MachineModel& m = Lathe();
  PhysicsBackend backend(m, InitialState{});
  Bench bench(backend);
  bench.Command("S1", DriveMode::kVelocity, 18000);
  bench.Run(1.0, [&] {
    EXPECT_FALSE(bench.Feedback("S1").status & (kTorqueThreshold | kPowerThreshold));
  });
}

// 90 % load: the turret pushes against its clamp at its torque limit.
TEST(DriveThresholdStatusTest, Load90AtTheTorqueLimit) {
  const MachineModel& m = Lathe();
  InitialState init;
  init.drive_positions = {{"T", 0}};
  PhysicsBackend backend(m, init);
  Bench bench(backend);
  EXPECT_FALSE(bench.Feedback("T").status & kLoad90);
  bench.Command("T", DriveMode::kPosition, 30);
  bench.Run(0.5);
  const control::DriveFeedback& fb = bench.Feedback("T");
  EXPECT_TRUE(fb.status & kTorqueLimit);
  EXPECT_TRUE(fb.status & kLoad90);
  // Released: the torque falls away, and the bit with it.
  bench.Command("T", DriveMode::kPosition, fb.position);
  bench.Run(0.3);
  EXPECT_FALSE(bench.Feedback("T").status & kLoad90);
}

}  // namespace
}  // namespace vmt::sim
