// Valve-driven devices and cam switches of lathe-c1 (machine.yaml actuators:,
// position_switches:) on both backends: stroke times, end switches, the turret clamp.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "sim/kinematic/kinematic_backend.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
using testing::Bench;
using testing::Lathe;

std::unique_ptr<MachineBackend> Make(BackendKind kind, const InitialState& init) {
  if (kind == BackendKind::kPhysics) return std::make_unique<PhysicsBackend>(Lathe(), init);
  return std::make_unique<KinematicBackend>(Lathe(), init);
}

class ActuatorTest : public ::testing::TestWithParam<BackendKind> {};

// The quill reaches its forward switch after time_on (not before), and the back switch opens
// as soon as it leaves; spring return takes time_off.
TEST_P(ActuatorTest, QuillStrokeTimesAndEndSwitches) {
  auto backend = Make(GetParam(), {});
  Bench bench(*backend);
  EXPECT_TRUE(bench.Input("ITAILSTOCK_BACK"));
  EXPECT_FALSE(bench.Input("ITAILSTOCK_FWD"));
  bench.Output("QTAILSTOCK", true);
  bench.Run(kDriveTickS);
  EXPECT_FALSE(bench.Input("ITAILSTOCK_BACK"));  // left the back end at once
  const double t_fwd = bench.RunUntil([&] { return bench.Input("ITAILSTOCK_FWD"); }, 2);
  EXPECT_NEAR(t_fwd + kDriveTickS, 0.6, 2 * kDriveTickS);
  bench.Output("QTAILSTOCK", false);
  const double t_back = bench.RunUntil([&] { return bench.Input("ITAILSTOCK_BACK"); }, 2);
  EXPECT_NEAR(t_back, 0.5, 2 * kDriveTickS);
  EXPECT_FALSE(bench.Input("ITAILSTOCK_FWD"));
}

// Coolant pressure and probe ready: devices with an on switch only.
TEST_P(ActuatorTest, PressureSwitchAndProbeReady) {
  auto backend = Make(GetParam(), {});
  Bench bench(*backend);
  bench.Output("QCOOLANT", true);
  bench.Output("QPROBE_ON", true);
  EXPECT_NEAR(bench.RunUntil([&] { return bench.Input("ICOOLANT_PRESSURE"); }, 2), 0.4,
              2 * kDriveTickS);
  EXPECT_NEAR(bench.RunUntil([&] { return bench.Input("IPROBE_READY"); }, 2), 0.1,
              2 * kDriveTickS);
  bench.Output("QPROBE_ON", false);
  EXPECT_NEAR(bench.RunUntil([&] { return !bench.Input("IPROBE_READY"); }, 2), kDriveTickS,
              kDriveTickS / 2);
  EXPECT_FALSE(bench.Input("IPROBE_CONTACT"));
}

// The door's safety switch opens the moment the door starts to open.
TEST_P(ActuatorTest, DoorSwitches) {
  auto backend = Make(GetParam(), {});
  Bench bench(*backend);
  EXPECT_TRUE(bench.Input("IDOOR_CLOSED"));
  bench.Output("QDOOR_OPEN", true);
  bench.Run(0.01);
  EXPECT_FALSE(bench.Input("IDOOR_CLOSED"));
  EXPECT_FALSE(bench.Input("IDOOR_OPEN"));
  EXPECT_GT(bench.RunUntil([&] { return bench.Input("IDOOR_OPEN"); }, 2), 1.1);
}

// Clamped, the turret does not move: the T drive pushes at its torque limit, lags beyond its
// following-error limit and says so. Unclamped it indexes and the cam switch shows the station.
TEST_P(ActuatorTest, ClampedTurretDoesNotIndex) {
  InitialState init;
  init.drive_positions = {{"T", 0}};
  auto backend = Make(GetParam(), init);
  Bench bench(*backend);
  EXPECT_TRUE(bench.Input("ITURRET_CLAMPED"));
  EXPECT_TRUE(bench.Input("ITURRET_INPOS"));
  bench.Command("T", DriveMode::kPosition, 60);  // beyond the 45 degree following-error limit
  bench.Run(0.3);
  EXPECT_NEAR(bench.Feedback("T").position, 0, 0.01);
  EXPECT_TRUE(bench.Feedback("T").status & control::drive_status::kFollowingError);
  EXPECT_TRUE(bench.Input("ITURRET_INPOS"));  // still at station 1

  bench.Command("T", DriveMode::kPosition, 0);
  bench.Run(0.05);
  bench.Output("QTURRET_UNCLAMP", true);
  EXPECT_NEAR(bench.RunUntil([&] { return bench.Input("ITURRET_UNCLAMPED"); }, 1), 0.08,
              2 * kDriveTickS);
  EXPECT_FALSE(bench.Input("ITURRET_CLAMPED"));
  bench.Command("T", DriveMode::kPosition, 30);
  bench.Run(0.05);
  EXPECT_FALSE(bench.Input("ITURRET_INPOS"));  // between stations
  bench.Run(0.6);
  EXPECT_NEAR(bench.Feedback("T").position, 30, 0.01);
  EXPECT_TRUE(bench.Input("ITURRET_INPOS"));
  bench.Output("QTURRET_UNCLAMP", false);
  bench.Run(0.1);
  EXPECT_TRUE(bench.Input("ITURRET_CLAMPED"));
  EXPECT_NEAR(bench.Feedback("T").position, 30, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Backends, ActuatorTest,
                         ::testing::Values(BackendKind::kPhysics, BackendKind::kKinematic),
                         [](const auto& info) { return std::string(ToString(info.param)); });

TEST(PositionSwitchTest, WindowAroundEveryMultipleOfThePitch) {
  const PositionSwitch p{0, 0, 30, 0.05};
  EXPECT_TRUE(PositionSwitchOn(p, 0));
  EXPECT_TRUE(PositionSwitchOn(p, 330.04));
  EXPECT_TRUE(PositionSwitchOn(p, -59.96));
  EXPECT_FALSE(PositionSwitchOn(p, 15));
  EXPECT_FALSE(PositionSwitchOn(p, 30.06));
  EXPECT_TRUE(PositionSwitchOn(p, 7200.0));
}

}  // namespace
}  // namespace vmt::sim
