// Clutch K on both backends: it refuses to engage at a speed mismatch or with the teeth on
// each other, and meshes when they line up slowly enough (C-axis manual 4.4).

#include <gtest/gtest.h>

#include "sim/runner/make_backend.hpp"
#include "sim/scene/scene.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
using testing::Bench;
using testing::Lathe;

class DogClutchTest : public ::testing::TestWithParam<BackendKind> {
 protected:
  std::unique_ptr<MachineBackend> Make(const InitialState& init = {}) {
    return MakeBackend(GetParam(), Lathe(), init);
  }
};

TEST_P(DogClutchTest, RefusesWhileTheSpindleTurns) {
  auto backend = Make();
  Bench bench(*backend);
  // Spindle mode: C's enable is off (C-axis manual 4.3), else its position loop, which reads
  // the spindle's encoder, would chase the spindle.
  bench.Command("C", DriveMode::kOff, 0);
  bench.Command("S1", DriveMode::kVelocity, 100 * 6);  // 100 rpm against a C servo at rest
  bench.Run(1.0);
  bench.Output("QROTMODE", true);
  bench.Run(0.5);
  EXPECT_EQ(backend->Clutch(0), ClutchState::kBlocked);
  EXPECT_FALSE(bench.Input("IROTMODE"));
  EXPECT_FALSE(bench.Input("ISPMODE"));
  // The spindle is not dragged by a clutch that did not mesh.
  EXPECT_NEAR(bench.Feedback("S1").velocity / 6, 100, 1);
}

TEST_P(DogClutchTest, StaysBlockedToothOnToothThenMeshesWhileHunting) {
  auto backend = Make();
  Bench bench(*backend);
  bench.Command("C", DriveMode::kOff, 0);  // spindle mode: C idles
  // Orient the spindle to half a tooth pitch (7.5 deg): the dogs sit on each other.
  bench.Command("S1", DriveMode::kPosition, 7.5);
  ASSERT_GT(bench.RunUntil(
                [&] {
                  return (bench.Feedback("S1").status & control::drive_status::kInPosition) &&
                         (bench.Feedback("S1").status & control::drive_status::kStandstill);
                },
                5),
            0);
  bench.Command("S1", DriveMode::kOff, 0);
  bench.Output("QROTMODE", true);
  bench.Run(0.3);
  EXPECT_EQ(backend->Clutch(0), ClutchState::kBlocked);
  EXPECT_FALSE(bench.Input("IROTMODE"));

  // Hunting: the C servo creeps (1 rpm at the spindle) until the teeth find their gaps.
  bench.Command("C", DriveMode::kVelocity, 6);
  const double t = bench.RunUntil([&] { return bench.Input("IROTMODE"); }, 3);
  ASSERT_GT(t, 0) << "never engaged";
  EXPECT_EQ(backend->Clutch(0), ClutchState::kEngaged);
  EXPECT_FALSE(bench.Input("ISPMODE"));
  // 7.5 deg less the 1 deg tolerance at 6 deg/s: about a second of hunting.
  EXPECT_NEAR(t, (7.5 - 1.0) / 6.0, 0.1);

  // Engaged, the C servo turns the spindle (after the dogs' chamfers have pulled the last
  // fraction of a degree of phase error in).
  bench.Run(0.05);
  const auto& m = backend->model();
  const double spindle_before = backend->JointPositions()[m.JointIndex("spindle")];
  const double c_before = bench.Feedback("C").position;
  bench.Command("C", DriveMode::kPosition, c_before + 90);
  bench.Run(1.5);
  const double spindle_after = backend->JointPositions()[m.JointIndex("spindle")];
  EXPECT_NEAR((spindle_after - spindle_before) * kDegPerRad, 90, 0.05);

  // Release: the switches follow the stroke.
  bench.Output("QROTMODE", false);
  bench.Output("QSPMODE", true);
  bench.Run(0.2);
  EXPECT_EQ(backend->Clutch(0), ClutchState::kReleased);
  EXPECT_TRUE(bench.Input("ISPMODE"));
  EXPECT_FALSE(bench.Input("IROTMODE"));
}

TEST_P(DogClutchTest, MeshesAtOnceWhenAlignedAndStill) {
  auto backend = Make();
  Bench bench(*backend);
  bench.Command("S1", DriveMode::kOff, 0);
  bench.Output("QROTMODE", true);
  const double t = bench.RunUntil([&] { return bench.Input("IROTMODE"); }, 1);
  ASSERT_GT(t, 0);
  EXPECT_NEAR(t, Lathe().clutches[0].engage_time_s, 2 * kDriveTickS);
}

// A clash is a spell of ratcheting: pushed in (blocked) while the halves turn against each other
// faster than max_relative_speed. It is counted once per spell, with the speed it began at.
TEST(DogClutchLogicTest, CountsEachSpellOfRatchetingAsOneClash) {
  const DogClutch& k = Lathe().clutches[0];
  DogClutchLogic logic;
  const double fast = 10 * k.max_relative_speed_rad_s, slow = 0.5 * k.max_relative_speed_rad_s;
  const double off_phase = k.phase_tolerance_rad * 3;
  auto step = [&](double slip) { logic.Step(k, true, false, off_phase, slip, kDriveTickS); };
  step(fast);
  double travel_s = 0;
  while (logic.state == ClutchState::kEngaging && travel_s < 1) {
    EXPECT_EQ(logic.clashes, 0) << "the dogs are still travelling";
    step(fast);
    travel_s += kDriveTickS;
  }
  EXPECT_NEAR(travel_s, k.engage_time_s, 1.5 * kDriveTickS);
  EXPECT_EQ(logic.state, ClutchState::kBlocked);
  EXPECT_EQ(logic.clashes, 1);
  EXPECT_DOUBLE_EQ(logic.clash_slip_rad_s, fast);
  for (int i = 0; i < 100; ++i) step(fast);
  EXPECT_EQ(logic.clashes, 1) << "one spell, one clash";
  step(slow);  // tooth on tooth, slowly: no clash
  EXPECT_FALSE(logic.ratcheting);
  step(-fast);
  EXPECT_EQ(logic.clashes, 2);
  EXPECT_DOUBLE_EQ(logic.clash_slip_rad_s, -fast);
  EXPECT_EQ(logic.state, ClutchState::kBlocked);
}

INSTANTIATE_TEST_SUITE_P(Backends, DogClutchTest,
                         ::testing::Values(BackendKind::kPhysics, BackendKind::kKinematic),
                         [](const auto& info) { return std::string(ToString(info.param)); });

}  // namespace
}  // namespace vmt::sim
