// The chuck while the spindle turns, on lathe-c1: a plunge that passes between two standing
// jaws meets the ring the jaws sweep.

#include "sim/collision/spindle_sweep.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "sim/collision/machine_path_guard.hpp"

namespace vmt::sim {
namespace {

TEST(SpindleSweep, AMoveBetweenStandingJawsMeetsTheTurningChuck) {
  const MachineModel model = LoadMachineModel(VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml");
  std::vector<double> q(model.joints.size(), 0.0);
  // Jaw 1 points along +x at angle 0, towards the turret: turned by 60 deg, the X plunge runs
  // between jaws 1 and 2.
  q[model.links[model.LinkIndex("spindle")].parent_joint] = std::numbers::pi / 3;
  MachinePathGuard guard(model, {}, [&] { return q; });
  std::vector<double> from(model.drives.size(), 0.0), to;
  from[model.DriveIndex("Z")] = 77.74, from[model.DriveIndex("W")] = 450;
  from[model.DriveIndex("C")] = 60;
  to = from;
  from[model.DriveIndex("X")] = 250, to[model.DriveIndex("X")] = 82;
  const control::PathCheck standing = guard.CheckMove(from, to);
  EXPECT_TRUE(standing.clear) << standing.part_a << " " << standing.part_b;

  const SpindleSweep sweep = SweepOf(guard.world(), "spindle");
  ASSERT_EQ(sweep.joint, model.links[model.LinkIndex("spindle")].parent_joint);
  ASSERT_EQ(sweep.parts.size(), sweep.swept.size());
  ASSERT_GE(sweep.parts.size(), 3u);  // at least the three jaws
  guard.world().SetAdded(sweep.swept);
  for (const int p : sweep.parts) guard.world().SetAside(p, true);
  const control::PathCheck turning = guard.CheckMove(from, to);
  ASSERT_FALSE(turning.clear);
  EXPECT_TRUE(turning.part_a.starts_with("spindle_jaw") ||
              turning.part_b.starts_with("spindle_jaw"))
      << turning.part_a << " " << turning.part_b;
  // Set back, the standing chuck is checked again.
  guard.world().SetAdded({});
  for (const int p : sweep.parts) guard.world().SetAside(p, false);
  EXPECT_TRUE(guard.CheckMove(from, to).clear);
}

}  // namespace
}  // namespace vmt::sim
