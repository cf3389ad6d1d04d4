// Turning for PathGuard on lathe-c1: the turning tool's insert cuts the stock while the
// spindle turns, and a tool standing in its own cut is clear of what is left. On a lathe with
// axial tools, a drill at the axis bores the part and a grooving blade in the end face cuts a
// face groove.

#include "sim/collision/stock_cutter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "render/mesh_primitives.hpp"
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
  EXPECT_NEAR(s.OuterRadius(tip), 0.028 - kCutAllowanceM, 1e-6);
  // Far from the tool the stock is untouched; again at the same place nothing more is cut.
  EXPECT_EQ(s.OuterRadius(0), 0.030);
  EXPECT_EQ(s.OuterRadius(s.slices.size() - 1), 0.030);
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

/// A lathe with axial tools only: the spindle (joint 0) and a slide along the spindle axis
/// (joint 1) that carries a d 8 drill (a square bar of 8 mm) at the axis and a 3 mm grooving
/// blade from radius 20 to 24 mm 10 mm behind it, each 100 mm long along +z.
MachineModel AxialLathe() {
  MachineModel m;
  m.name = "axial";
  m.links.resize(3);
  m.links[0].name = "bed", m.links[1].name = "spindle", m.links[2].name = "slide";
  m.joints.resize(2);
  m.joints[0].name = "spindle", m.joints[0].type = JointType::kContinuous;
  m.joints[1].name = "slide", m.joints[1].type = JointType::kPrismatic;
  for (int j = 0; j < 2; ++j) m.joints[j].parent_link = 0, m.joints[j].child_link = j + 1;
  m.links[1].parent_joint = 0, m.links[2].parent_joint = 1;
  const auto bar = [&](const char* name, Eigen::Vector3d lo, Eigen::Vector3d hi) {
    Visual v;
    v.name = name;
    v.mesh = std::make_shared<const render::Mesh>(render::MakeBox(lo, hi));
    m.links[2].collisions.push_back(v);
    m.cutting_parts.push_back({2, static_cast<int>(m.links[2].collisions.size()) - 1});
  };
  bar("drill", {-0.004, -0.004, 0}, {0.004, 0.004, 0.1});
  bar("blade", {0.020, -0.0015, 0.01}, {0.024, 0.0015, 0.11});
  return m;
}

TEST(StockCutter, AxialToolsBoreThePartAndCutAFaceGroove) {
  const MachineModel m = AxialLathe();
  // A bar d 60 from z 0 to 100 mm; the drill's tip comes in from z 120 down to 80 (20 mm
  // deep) and the blade 10 mm into the face, at 1500 rpm, 0.1 mm per turn.
  StockCutter cutter(m, {"workpiece", "spindle", {{0.0, 0.1, 0, 0.03}}});
  double t = 0, angle = 0;
  EXPECT_FALSE(cutter.Cut({0, 0.08}, t));  // not turning: a crash for PathGuard, no cut
  for (double z = 0.12; z >= 0.08 - 1e-12; z -= 4e-6)
    cutter.Cut({angle += 2 * M_PI / 25, z}, t += 0.04 / 25);
  const TurnedStock& s = cutter.stock();
  const auto slice = [&](double z_m) { return static_cast<size_t>((z_m - s.z0_m) / s.slice_m); };
  const double bore = 0.004 * std::sqrt(2.0) + kCutAllowanceM;  // the drill's corners
  const double groove_in = 0.02 - kCutAllowanceM, groove_out = std::hypot(0.024, 0.0015);
  // Between the groove's floor (z 90) and the face: a core with the bore, and a ring outside.
  const std::vector<StockSpan>& grooved = s.slices[slice(0.095)];
  ASSERT_EQ(grooved.size(), 2u);
  EXPECT_NEAR(grooved[0].inner_m, bore, 1e-7);
  EXPECT_NEAR(grooved[0].outer_m, groove_in, 1e-7);
  EXPECT_NEAR(grooved[1].inner_m, groove_out + kCutAllowanceM, 1e-7);
  EXPECT_EQ(grooved[1].outer_m, 0.03);
  // Below the groove's floor the bore goes on to the drill's tip; deeper the bar is solid.
  const std::vector<StockSpan>& bored = s.slices[slice(0.085)];
  ASSERT_EQ(bored.size(), 1u);
  EXPECT_NEAR(bored[0].inner_m, bore, 1e-7);
  ASSERT_EQ(s.slices[slice(0.075)].size(), 1u);
  EXPECT_EQ(s.slices[slice(0.075)][0].inner_m, 0.0);
  // The tools standing in their cuts are clear of what is left; each part stands in the
  // cylinders and tubes PathGuard and the pictures take.
  EXPECT_FALSE(cutter.Cut({angle += 2 * M_PI / 25, 0.08}, t += 0.04 / 25));
  const std::vector<CylinderPart> parts = s.Cylinders(2e-6);
  int tubes = 0;
  for (const CylinderPart& c : parts) tubes += c.inner_radius_m > 0;
  // The bored core and the ring outside the groove, then the bore below the groove's floor.
  EXPECT_EQ(tubes, 3);
}

}  // namespace
}  // namespace vmt::sim
