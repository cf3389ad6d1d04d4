// Drive parameter sets (DriveSetpoint::parameter_set, SERCOS S-0-0217; C-axis manual 2.2): the
// set the setpoint names is the one the drive controls with, a switch at standstill is
// bumpless, a set the drive does not have is a fault.

#include <gtest/gtest.h>

#include <cmath>

#include "sim/runner/make_backend.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
using namespace control::drive_status;
using testing::Bench;

// lathe-c1 with a soft second set on Z: a quarter of the position gain, half the velocity gain,
// a quarter of the torque, a fifth of the speed.
const MachineModel& SoftZ() {
  static const MachineModel model = testing::EditedLathe("soft_z", [](std::string s) {
    return testing::ReplaceOnce(
        s, "    spec: {settle_time: 0.2, overshoot: 0.005}   # 10 mm step",
        "    parameter_sets:\n"
        "      - {kv: 10, velocity_kp: 65, torque_limit: 3000, velocity_limit: 100}\n"
        "    spec: {settle_time: 0.2, overshoot: 0.005}   # 10 mm step");
  });
  return model;
}

class DriveParameterSetTest : public ::testing::TestWithParam<BackendKind> {
 protected:
  std::unique_ptr<MachineBackend> Make() {
    InitialState init;
    init.drive_positions = {{"Z", 100}};
    return MakeBackend(GetParam(), SoftZ(), init);
  }
};

TEST_P(DriveParameterSetTest, TheModelHasBothSets) {
  const DriveParams& z = SoftZ().drives[SoftZ().DriveIndex("Z")];
  ASSERT_EQ(z.parameter_sets.size(), 2u);
  EXPECT_EQ(z.parameter_sets[0].kv_per_s, 40);
  EXPECT_EQ(z.parameter_sets[1].kv_per_s, 10);
  EXPECT_NEAR(z.parameter_sets[1].velocity_limit, 0.1, 1e-12);  // m/s
  // Keys the set does not name are set 0's.
  EXPECT_EQ(z.parameter_sets[1].velocity_ti_s, z.velocity_ti_s);
  EXPECT_EQ(z.parameter_sets[1].following_error_limit, z.following_error_limit);
}

// At a constant speed v the following error is v / Kv: the softer set lags four times as much.
TEST_P(DriveParameterSetTest, SofterSetLagsMore) {
  double lag[2];
  for (uint8_t set : {0, 1}) {
    auto backend = Make();
    Bench bench(*backend);
    const int z = bench.Drive("Z");
    bench.Command("Z", DriveMode::kPosition, 100, set);
    const double v = 50;  // mm/s
    bench.Run(1.0, [&] { bench.mdt().setpoints[z].value += v * kDriveTickS; });
    lag[set] = bench.Feedback("Z").following_error;
    EXPECT_FALSE(bench.Feedback("Z").status & kFollowingError);
  }
  EXPECT_NEAR(lag[0], 50.0 / 40, 0.05 * 50 / 40);
  EXPECT_NEAR(lag[1], 50.0 / 10, 0.05 * 50 / 10);
}

// At standstill a switch does not move the axis.
TEST_P(DriveParameterSetTest, SwitchAtStandstillIsBumpless) {
  auto backend = Make();
  Bench bench(*backend);
  bench.Run(0.2);
  const double before = bench.Feedback("Z").position;
  bench.Command("Z", DriveMode::kPosition, before, 1);
  double deviation = 0;
  bench.Run(0.3, [&] {
    deviation = std::max(deviation, std::abs(bench.Feedback("Z").position - before));
    EXPECT_TRUE(bench.Feedback("Z").status & kReady);
  });
  EXPECT_LE(deviation, 0.0002);  // two encoder counts
}

// A switch while moving acts at once: the lag settles to the new set's, the axis stays under
// control, the torque within the new set's limit.
TEST_P(DriveParameterSetTest, SwitchWhileMovingSettlesToTheNewLag) {
  auto backend = Make();
  Bench bench(*backend);
  const int z = bench.Drive("Z");
  const double v = 50;
  bench.Run(0.5, [&] { bench.mdt().setpoints[z].value += v * kDriveTickS; });
  bench.mdt().setpoints[z].parameter_set = 1;
  double torque = 0;
  bench.Run(1.0, [&] {
    bench.mdt().setpoints[z].value += v * kDriveTickS;
    torque = std::max(torque, std::abs(bench.Feedback("Z").torque));
  });
  EXPECT_NEAR(bench.Feedback("Z").following_error, v / 10, 0.05 * v / 10);
  EXPECT_TRUE(bench.Feedback("Z").status & kReady);
  EXPECT_LE(torque, 3000);
}

// A set the drive does not have: the drive trips (not ready, power stage off) and stays so
// until the master removes the controller enable and names a set it has.
TEST_P(DriveParameterSetTest, UnknownSetFaults) {
  auto backend = Make();
  Bench bench(*backend);
  bench.Command("Z", DriveMode::kPosition, 110, 3);
  bench.Run(0.3);
  const uint32_t status = bench.Feedback("Z").status;
  EXPECT_TRUE(status & kParameterSetError);
  EXPECT_FALSE(status & kReady);
  EXPECT_FALSE(status & kEnabled);
  EXPECT_NEAR(bench.Feedback("Z").position, 100, 0.01);  // it did not move
  bench.Command("Z", DriveMode::kOff, 0, 3);
  bench.Run(0.01);
  EXPECT_TRUE(bench.Feedback("Z").status & kParameterSetError) << "the set is still missing";
  bench.Command("Z", DriveMode::kOff, 0, 0);
  bench.Run(0.01);
  EXPECT_EQ(bench.Feedback("Z").status & (kParameterSetError | kReady), kReady);
  bench.Command("Z", DriveMode::kPosition, 110, 0);
  bench.Run(0.6);
  EXPECT_NEAR(bench.Feedback("Z").position, 110, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Backends, DriveParameterSetTest,
                         ::testing::Values(BackendKind::kPhysics, BackendKind::kKinematic),
                         [](const auto& info) { return std::string(ToString(info.param)); });

// The velocity loop's integral is torque: it carries over a switch, but into the new torque
// limit -- so that a drive that was pushing hard lets go at once under a weaker set.
TEST(DriveControllerTest, SwitchClampsTheIntegralIntoTheNewTorqueLimit) {
  DriveParams p;
  p.kv_per_s = 30;
  p.velocity_kp = 10;
  p.velocity_ti_s = 0.01;
  p.torque_limit = 400;
  p.velocity_limit = 10;
  p.acceleration_limit = 100;
  p.in_position_window = 1e-4;
  p.standstill_window = 1e-3;
  p.following_error_limit = 1;
  p.encoder_resolution = 1e-6;
  p.info.kind = control::AxisKind::kRotary;
  p.parameter_sets = {p, p};
  p.parameter_sets[1].torque_limit = 50;
  DriveController c(p);
  const double dt = kDriveTickS;
  // Pushing against a stop: the error stays, the integral winds up to the limit.
  for (int i = 0; i < 2000; ++i) {
    c.VelocityReference({DriveMode::kPosition, 0.1, 0}, 0, 0, dt);
    c.Torque(1.0, 0, dt);
  }
  EXPECT_DOUBLE_EQ(c.Torque(1.0, 0, dt), 400);
  // The weaker set: at zero error the torque is what the integral holds -- not beyond 50.
  c.VelocityReference({DriveMode::kPosition, 0, 1}, 0, 0, dt);
  EXPECT_DOUBLE_EQ(c.Torque(0, 0, dt), 50);
  EXPECT_FALSE(c.saturated());
  // A small opposite error takes it off the limit at once.
  EXPECT_LT(c.Torque(-0.01, 0, dt), 50);
  EXPECT_EQ(c.faults(), 0u);
}

}  // namespace
}  // namespace vmt::sim
