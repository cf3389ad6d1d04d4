// The chuck while the spindle turns, on lathe-c1: a plunge that passes between two standing
// jaws meets the ring the jaws sweep, and so does a spindle start with the tool standing there.

#include "sim/collision/spindle_sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
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

TEST(SpindleSweep, AStartWithTheToolBetweenTheJawsIsRefused) {
  const MachineModel model = LoadMachineModel(VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml");
  std::vector<double> q(model.joints.size(), 0.0);
  q[model.links[model.LinkIndex("spindle")].parent_joint] = std::numbers::pi / 3;
  // With the part the scene adds: the tool stands clear of it (radius 30 from Z 60 on).
  MachinePathGuard guard(model, {{"workpiece", "spindle", 0.030, 0.160, 0.060}},
                         [&] { return q; });
  guard.SetSweep(SweepOf(guard.world(), "spindle"));
  std::vector<double> at(model.drives.size(), 0.0), above;
  at[model.DriveIndex("Z")] = 77.74, at[model.DriveIndex("W")] = 450;
  at[model.DriveIndex("C")] = 60, at[model.DriveIndex("X")] = 250;
  above = at;
  at[model.DriveIndex("X")] = 82;  // between jaws 1 and 2, within their sweep
  ASSERT_TRUE(guard.CheckMove(above, at).clear);  // got there past the standing jaws
  const int s1 = model.DriveIndex("S1");
  const control::PathCheck start = guard.CheckSpindleStart(at, s1);
  ASSERT_FALSE(start.clear);
  EXPECT_TRUE(start.part_a.starts_with("spindle_jaw")) << start.part_a << " " << start.part_b;
  EXPECT_TRUE(start.part_b.starts_with("turret")) << start.part_b;
  EXPECT_EQ(start.position, at);
  EXPECT_GT(std::hypot(start.point[0], start.point[1]), 60);  // out at the jaws' ends
  // The standing chuck is checked again on the next move, and from above the start is clear.
  EXPECT_TRUE(guard.CheckMove(at, above).clear);
  const control::PathCheck clear = guard.CheckSpindleStart(above, s1);
  EXPECT_TRUE(clear.clear);
  EXPECT_GT(clear.min_clearance, 10);
  EXPECT_FALSE(clear.closest_a.empty());
}

TEST(SpindleSweep, TheWorkpieceAtRestIsNoneOfTheStartsBusiness) {
  // The tool resting on the part (as a cut leaves it) touches it turning as much as standing:
  // the start checks the chuck's sweep only.
  const MachineModel model = LoadMachineModel(VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml");
  const std::vector<double> q(model.joints.size(), 0.0);
  MachinePathGuard guard(model, {{"workpiece", "spindle", 0.030, 0.160, 0.060}},
                         [&] { return q; });
  guard.SetSweep(SweepOf(guard.world(), "spindle"));
  std::vector<double> at(model.drives.size(), 0.0), to;
  at[model.DriveIndex("Z")] = 130, at[model.DriveIndex("W")] = 450;
  at[model.DriveIndex("X")] = 250;
  to = at;
  to[model.DriveIndex("X")] = 0;
  const control::PathCheck plunge = guard.CheckMove(at, to);
  ASSERT_FALSE(plunge.clear);
  EXPECT_TRUE(guard.CheckSpindleStart(plunge.position, model.DriveIndex("S1")).clear);
}

}  // namespace
}  // namespace vmt::sim
