// The kinematic backend is the reference the physics run is checked against: the same move
// sequence gives the same positions within a small part of the following error.

#include <gtest/gtest.h>

#include <cmath>

#include "sim/runner/timeline_player.hpp"
#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

using control::DriveMode;
using testing::Bench;
using testing::Lathe;

TEST(BackendAgreementTest, SameMovesSamePathWithinFollowingError) {
  const MachineModel& m = Lathe();
  InitialState init;
  init.drive_positions = {{"Z", 500}, {"X", 200}, {"T", 0}};
  PhysicsBackend physics(m, init);
  KinematicBackend kinematic(m, init);
  Bench bp(physics), bk(kinematic);
  bp.Output("QTURRET_UNCLAMP", true);  // unclamped within 0.08 s, before T starts at 0.5 s
  bk.Output("QTURRET_UNCLAMP", true);

  // Z and X on trapezoidal profiles at once, then the turret indexes.
  const TrapezoidProfile z{500, 250, 300, 4000, 0}, x{200, 80, 200, 4000, 0.1},
      t{0, 90, 720, 7200, 0.5};
  double worst_gap[3] = {0, 0, 0}, worst_fe[3] = {0, 0, 0};
  const char* axes[3] = {"Z", "X", "T"};
  const TrapezoidProfile* profiles[3] = {&z, &x, &t};
  for (int64_t tick = 0; tick < 6000; ++tick) {
    const double time = tick * kDriveTickS;
    for (int a = 0; a < 3; ++a) {
      bp.Command(axes[a], DriveMode::kPosition, profiles[a]->At(time));
      bk.Command(axes[a], DriveMode::kPosition, profiles[a]->At(time));
    }
    bp.Run(kDriveTickS);
    bk.Run(kDriveTickS);
    for (int a = 0; a < 3; ++a) {
      worst_gap[a] = std::max(
          worst_gap[a], std::abs(bp.Feedback(axes[a]).position - bk.Feedback(axes[a]).position));
      worst_fe[a] = std::max(worst_fe[a], std::abs(bp.Feedback(axes[a]).following_error));
    }
  }
  for (int a = 0; a < 3; ++a) {
    SCOPED_TRACE(axes[a]);
    EXPECT_GT(worst_fe[a], 0.5);  // the moves were real ones
    EXPECT_LT(worst_gap[a], 0.1 * worst_fe[a]);
    EXPECT_NEAR(bp.Feedback(axes[a]).position, bk.Feedback(axes[a]).position, 0.001);
  }
}

}  // namespace
}  // namespace vmt::sim
