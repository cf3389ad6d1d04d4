// A load-side (external) encoder (`encoder: load`): a C servo that closes its position loop on
// the spindle's encoder (C-axis manual 3.1), its velocity loop on the motor. With clutch K open
// a C move turns the motor but not the spindle: C lags until its following error faults the NC
// -- the C-axis manual's consequence of a wrong PLC sequence. Both backends behave alike here:
// the kinematic one moves the motor joint at the velocity reference, and the spindle, in
// another coupled group, stays.
//
// lathe-c1's C has this encoder (machine.yaml `encoder: load`, `load_joint: spindle`, modulo
// 360): its enable is off in spindle mode, as the changeover sequence (4.3, 4.4) switches it.

#include <gtest/gtest.h>

#include <cmath>

#include "sim/runner/make_backend.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
using namespace control::drive_status;
using testing::Bench;

using testing::Lathe;

class LoadEncoderTest : public ::testing::TestWithParam<BackendKind> {};

TEST(LoadEncoderModelTest, CReadsTheSpindle) {
  const MachineModel& m = Lathe();
  const DriveParams& c = m.drives[m.DriveIndex("C")];
  EXPECT_EQ(c.load_joint, m.JointIndex("spindle"));
  EXPECT_EQ(c.motor_joint, m.JointIndex("c_motor"));
}

TEST_P(LoadEncoderTest, ClutchOpenTheMotorTurnsTheSpindleDoesNot) {
  const MachineModel& m = Lathe();
  auto backend = MakeBackend(GetParam(), m, {});
  Bench bench(*backend);
  bench.Command("S1", DriveMode::kOff, 0);  // the spindle idles, as in rotary axis mode
  bench.Command("C", DriveMode::kPosition, 90);
  const double t = bench.RunUntil([&] { return bench.Feedback("C").status & kFollowingError; }, 1);
  ASSERT_GT(t, 0) << "C never reported its following error";
  // The position loop asks for all the speed it may have: the motor runs, the spindle stands.
  bench.Run(0.1);
  const control::DriveFeedback& fb = bench.Feedback("C");
  EXPECT_NEAR(fb.position, 0, 0.001);
  EXPECT_NEAR(fb.following_error, 90, 0.001);
  EXPECT_NEAR(fb.velocity, 1200, 30);  // deg/s at the spindle: the motor at its limit
  EXPECT_TRUE(fb.status & kReady) << "a following error is the NC's to act on, not a trip";
  const std::vector<double> q = backend->JointPositions();
  EXPECT_NEAR(q[m.JointIndex("spindle")], 0, 1e-6);
  EXPECT_GT(q[m.JointIndex("c_motor")] / 8 * kDegPerRad, 90);
}

// Why C's enable belongs off in spindle mode: a C left in position control while the spindle
// turns sees its encoder run away, drives its motor back towards its command (the motor turns,
// the spindle encoder it reads runs on) and lags into its following error limit.
TEST_P(LoadEncoderTest, EnabledCLagsWhileTheSpindleTurns) {
  auto backend = MakeBackend(GetParam(), Lathe(), {});
  Bench bench(*backend);
  bench.Command("C", DriveMode::kPosition, 0);
  bench.Command("S1", DriveMode::kVelocity, 300 * 6);
  const double t = bench.RunUntil([&] { return bench.Feedback("C").status & kFollowingError; }, 1);
  ASSERT_GT(t, 0) << "C never reported its following error";
  EXPECT_LT(bench.Feedback("C").velocity, -600) << "C drives back towards its command";
}

// Modulo 360: the feedback stays within one turn, however far the spindle has turned, and a
// command a turn away is the same position (the shorter way round).
TEST_P(LoadEncoderTest, ModuloPositionWithinOneTurn) {
  const MachineModel& m = Lathe();
  auto backend = MakeBackend(GetParam(), m, {});
  Bench bench(*backend);
  bench.Command("C", DriveMode::kOff, 0);
  bench.Command("S1", DriveMode::kVelocity, 300 * 6);
  bench.Run(1.0);
  bench.Command("S1", DriveMode::kVelocity, 0);
  bench.Run(0.5);
  const double spindle_deg = backend->JointPositions()[m.JointIndex("spindle")] * kDegPerRad;
  ASSERT_GT(spindle_deg, 720);
  const double c = bench.Feedback("C").position;
  EXPECT_GE(c, 0);
  EXPECT_LT(c, 360);
  EXPECT_NEAR(c, std::fmod(spindle_deg, 360.0), 0.001);
  // Engaged, a command 720 deg + 10 deg away moves the spindle by 10 deg, not two turns.
  bench.Command("S1", DriveMode::kOff, 0);
  bench.Output("QROTMODE", true);
  bench.Command("C", DriveMode::kVelocity, 6);  // hunting
  ASSERT_GT(bench.RunUntil([&] { return bench.Input("IROTMODE"); }, 4), 0);
  const double before = backend->JointPositions()[m.JointIndex("spindle")] * kDegPerRad;
  bench.Command("C", DriveMode::kPosition, bench.Feedback("C").position + 730);
  bench.Run(1.0);
  const double after = backend->JointPositions()[m.JointIndex("spindle")] * kDegPerRad;
  EXPECT_NEAR(after - before, 10, 0.05);
  EXPECT_FALSE(bench.Feedback("C").status & kFollowingError);
}

TEST_P(LoadEncoderTest, ClutchEngagedCPositionsOnTheSpindleEncoder) {
  const MachineModel& m = Lathe();
  InitialState init;
  init.clutch_engaged = {{"K", true}};
  auto backend = MakeBackend(GetParam(), m, init);
  Bench bench(*backend);
  bench.Command("S1", DriveMode::kOff, 0);
  bench.Command("C", DriveMode::kPosition, 90);
  const double t = bench.RunUntil(
      [&] {
        return (bench.Feedback("C").status & kInPosition) &&
               (bench.Feedback("C").status & kStandstill);
      },
      2);
  ASSERT_GT(t, 0);
  bench.Run(0.2);
  EXPECT_FALSE(bench.Feedback("C").status & kFollowingError);
  // The feedback is the spindle's angle (to the encoder's resolution), not the motor's / 8.
  const double spindle_deg = backend->JointPositions()[m.JointIndex("spindle")] * kDegPerRad;
  EXPECT_NEAR(bench.Feedback("C").position, spindle_deg, 0.0001);
  EXPECT_NEAR(spindle_deg, 90, 0.005);
}

INSTANTIATE_TEST_SUITE_P(Backends, LoadEncoderTest,
                         ::testing::Values(BackendKind::kPhysics, BackendKind::kKinematic),
                         [](const auto& info) { return std::string(ToString(info.param)); });

}  // namespace
}  // namespace vmt::sim
