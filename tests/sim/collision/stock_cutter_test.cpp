// Turning for PathGuard on lathe-c1: the turning tool's insert cuts the stock while the
// spindle turns, and a tool standing in its own cut is clear of what is left.

#include "sim/collision/stock_cutter.hpp"

#include <gtest/gtest.h>

#include "sim/collision/machine_path_guard.hpp"

namespace vmt::sim {
namespace {

struct Lathe {
  Lathe() : model(LoadMachineModel(VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml")) {}
  /// Joint positions with the drives at Z, X (mm), turret T at station 1, spindle at `deg`.
  std::vector<double> Joints(MachinePathGuard& g, double z, double x, double deg) const {
    std::vector<double> d(model.drives.size(), 0.0);
    d[model.DriveIndex("Z")] = z, d[model.DriveIndex("X")] = x, d[model.DriveIndex("W")] = 450;
    // The spindle's angle as C's load encoder reads it (S1 turns it through its belt).
    d[model.DriveIndex("C")] = deg;
    return g.JointPositions(std::vector<double>(model.joints.size(), 0.0), d,
                            std::vector<char>(d.size(), 1));
  }
  MachineModel model;
  RevolvedPart stock{"workpiece", "spindle", {{0.060, 0.220, 0, 0.030}}};
};

TEST(StockCutter, TheInsertCutsOnlyWhileTheSpindleTurns) {
  Lathe l;
  MachinePathGuard g(l.model, {}, [&] { return std::vector<double>(l.model.joints.size(), 0); });
  StockCutter cutter(l.model, l.stock);
  // Standing in the stock (tip at radius 28, Z 130 -> z 190 mm on the spindle) without
  // turning: nothing is cut, that would be a crash for PathGuard to see.
  EXPECT_FALSE(cutter.Cut(l.Joints(g, 130, 28, 0), 0.000));
  EXPECT_FALSE(cutter.Cut(l.Joints(g, 130, 28, 0.01), 0.001));  // 1.7 rpm: positioning
  // Turning at 1500 rpm (9 deg per ms): the slice under the tip falls to 28 less the allowance.
  EXPECT_TRUE(cutter.Cut(l.Joints(g, 130, 28, 9.01), 0.002));
  const TurnedStock& s = cutter.stock();
  const size_t tip = static_cast<size_t>((0.190 - s.z0_m) / s.slice_m);
  EXPECT_NEAR(s.radius_m[tip], 0.028 - kCutAllowanceM, 1e-6);
  // Far from the tool the stock is untouched; again at the same place nothing more is cut.
  EXPECT_EQ(s.radius_m[0], 0.030);
  EXPECT_EQ(s.radius_m[s.radius_m.size() - 1], 0.030);
  EXPECT_FALSE(cutter.Cut(l.Joints(g, 130, 28, 18.01), 0.003));
}

TEST(StockCutter, AToolInItsCutIsClearAndAnApproachMeetsWhatIsLeft) {
  Lathe l;
  MachinePathGuard g(l.model, {}, [&] { return std::vector<double>(l.model.joints.size(), 0); });
  StockCutter cutter(l.model, l.stock);
  // A pass at radius 28 from Z 158 to Z 120 at 1500 rpm, 0.1 mm per revolution (the holder
  // would reach the chuck jaws further on).
  double t = 0, deg = 0;
  cutter.Cut(l.Joints(g, 158, 28, deg), t);
  for (int k = 1; k <= 38 * 250; ++k)  // 25 steps per revolution, 0.004 mm each
    cutter.Cut(l.Joints(g, 158 - k * 0.004, 28, deg += 360.0 / 25), t += 0.04 / 25);
  g.world().SetAdded(cutter.stock().Cylinders(2e-6));
  std::vector<double> at(l.model.drives.size(), 0.0), away = at;
  at[l.model.DriveIndex("Z")] = 120, at[l.model.DriveIndex("X")] = 28;
  at[l.model.DriveIndex("W")] = away[l.model.DriveIndex("W")] = 450;
  away[l.model.DriveIndex("Z")] = 120, away[l.model.DriveIndex("X")] = 60;
  // Out of the cut and back into it: clear.
  const control::PathCheck out = g.CheckMove(at, away);
  EXPECT_TRUE(out.clear) << out.part_a << " " << out.part_b << " at " << out.distance << " point "
                         << out.point[0] << " " << out.point[1] << " " << out.point[2] << " "
                         << out.min_clearance;
  EXPECT_TRUE(g.CheckMove(away, at).clear);
  // Along the finished pass back to its start: clear; beyond the pass's end at Z 158 the
  // stock's end (radius 30 up to Z 160) is still there.
  std::vector<double> start = at;
  start[l.model.DriveIndex("Z")] = 157.5;
  const control::PathCheck back = g.CheckMove(at, start);
  EXPECT_TRUE(back.clear) << back.part_a << " " << back.part_b << " at " << back.distance
                          << " point " << back.point[0] << " " << back.point[1] << " "
                          << back.point[2];
  std::vector<double> beyond = at;
  beyond[l.model.DriveIndex("Z")] = 175;
  const control::PathCheck c = g.CheckMove(at, beyond);
  ASSERT_FALSE(c.clear);
  EXPECT_TRUE(c.part_a == "workpiece" || c.part_b == "workpiece");
  // Deeper than the cut, the plunge meets the material left at radius 28.
  std::vector<double> deeper = at;
  deeper[l.model.DriveIndex("X")] = 20;
  const control::PathCheck d = g.CheckMove(at, deeper);
  ASSERT_FALSE(d.clear);
  EXPECT_LT(d.distance, 0.05);
}

}  // namespace
}  // namespace vmt::sim
