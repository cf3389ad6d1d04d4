// The turned stock: slices of the part, each the spans of radius that hold material, cut by
// turning points and by the rings a cutting part's hull sweeps, given back as cylinders and
// tubes that never leave out material that is still there.

#include "sim/collision/turned_stock.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vmt::sim {
namespace {

TEST(TurnedStock, StartsAsTheStockCylinder) {
  const TurnedStock t =
      TurnedStock::FromCylinder({"workpiece", "spindle", 0.03, 0.16, 0.06}, 0.001);
  ASSERT_EQ(t.slices.size(), 160u);
  const auto parts = t.Cylinders(1e-6);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_DOUBLE_EQ(parts[0].radius_m, 0.03);
  EXPECT_NEAR(parts[0].length_m, 0.16, 1e-12);
  EXPECT_NEAR(parts[0].z_m, 0.06, 1e-12);
  EXPECT_EQ(parts[0].name, "workpiece");
  EXPECT_EQ(parts[0].link, "spindle");
}

TEST(TurnedStock, ACutLowersOnlyItsSliceAndLeavesTheAllowance) {
  TurnedStock t = TurnedStock::FromCylinder({"w", "spindle", 0.03, 0.01, 0}, 0.001);
  EXPECT_TRUE(t.TurnDown(0.0045, 0.028, 1e-5));
  EXPECT_NEAR(t.OuterRadius(4), 0.028 - 1e-5, 1e-15);
  EXPECT_EQ(t.OuterRadius(3), 0.03);
  EXPECT_EQ(t.OuterRadius(5), 0.03);
  EXPECT_FALSE(t.TurnDown(0.0045, 0.029, 1e-5));  // above what is left: nothing to cut
  EXPECT_FALSE(t.TurnDown(-0.001, 0.0, 0));       // beside the part
  EXPECT_FALSE(t.TurnDown(0.0101, 0.0, 0));
  EXPECT_TRUE(t.TurnDown(0.0005, 0.0, 1e-5));  // through to the axis
  EXPECT_EQ(t.OuterRadius(0), 0);
}

TEST(TurnedStock, CylindersMergeRunsAndKeepTheLargestRadius) {
  TurnedStock t = TurnedStock::FromCylinder({"w", "spindle", 0.03, 0.01, 0.1}, 0.001);
  // A pass at radius 28 over slices 2..7, a slightly deeper point in slice 5, slice 0 parted.
  for (int k = 2; k <= 7; ++k) t.TurnDown(0.1 + (k + 0.5) * 0.001, 0.028, 0);
  t.TurnDown(0.1 + 5.5 * 0.001, 0.02799, 0);
  t.TurnDown(0.1005, 0.0, 0);
  const auto parts = t.Cylinders(1e-4);
  ASSERT_EQ(parts.size(), 3u);  // slice 1 at 30, slices 2..7 at 28, slices 8..9 at 30
  EXPECT_NEAR(parts[0].z_m, 0.101, 1e-12);
  EXPECT_NEAR(parts[0].length_m, 0.001, 1e-12);
  EXPECT_DOUBLE_EQ(parts[0].radius_m, 0.03);
  EXPECT_NEAR(parts[1].z_m, 0.102, 1e-12);
  EXPECT_NEAR(parts[1].length_m, 0.006, 1e-12);
  EXPECT_DOUBLE_EQ(parts[1].radius_m, 0.028);  // the run keeps its largest radius
  EXPECT_NEAR(parts[2].length_m, 0.002, 1e-12);
  // Every slice lies inside the cylinder that stands for it.
  for (size_t k = 0; k < t.slices.size(); ++k) {
    const double z = t.z0_m + (k + 0.5) * t.slice_m;
    bool covered = t.OuterRadius(k) == 0;
    for (const CylinderPart& c : parts)
      covered = covered || (z > c.z_m && z < c.z_m + c.length_m && c.radius_m >= t.OuterRadius(k));
    EXPECT_TRUE(covered) << "slice " << k;
  }
}

TEST(TurnedStock, FromAPartTheSlicesHoldItsStepsBoresAndGrooves) {
  // A stepped shaft, d 60 over 0..50 mm and d 40 over 50..80 mm, with a face groove in its
  // right face: core d 20 and ring d 40 / bore 30 over 70..80 mm (the d 40 step ends at 70).
  RevolvedPart p{"workpiece", "spindle", {}};
  p.sections = {{0.0, 0.05, 0, 0.03},
                {0.05, 0.07, 0, 0.02},
                {0.07, 0.08, 0, 0.01},
                {0.07, 0.08, 0.015, 0.02}};
  const TurnedStock t = TurnedStock::FromPart(p, 0.001);
  ASSERT_EQ(t.slices.size(), 80u);
  EXPECT_EQ(t.OuterRadius(49), 0.03);
  EXPECT_EQ(t.OuterRadius(50), 0.02);
  EXPECT_EQ(t.OuterRadius(69), 0.02);
  ASSERT_EQ(t.slices[70].size(), 2u);  // the core and the ring outside the groove
  EXPECT_EQ(t.slices[70][0].inner_m, 0.0);
  EXPECT_EQ(t.slices[70][0].outer_m, 0.01);
  EXPECT_EQ(t.slices[70][1].inner_m, 0.015);
  EXPECT_EQ(t.slices[70][1].outer_m, 0.02);
  const auto parts = t.Cylinders(1e-6);
  ASSERT_EQ(parts.size(), 4u);  // two steps, then the grooved stretch as core and ring
  EXPECT_EQ(parts[2].inner_radius_m, 0.0);
  EXPECT_DOUBLE_EQ(parts[2].radius_m, 0.01);
  EXPECT_DOUBLE_EQ(parts[3].inner_radius_m, 0.015);
  EXPECT_DOUBLE_EQ(parts[3].radius_m, 0.02);
  EXPECT_NEAR(parts[3].z_m, 0.07, 1e-15);
  EXPECT_NEAR(parts[3].length_m, 0.01, 1e-15);
  // A step off the slice grid: the slice it falls in keeps the larger radius.
  p.sections = {{0.0, 0.0505, 0, 0.03}, {0.0505, 0.06, 0, 0.02}};
  const TurnedStock u = TurnedStock::FromPart(p, 0.001);
  EXPECT_EQ(u.OuterRadius(50), 0.03);
  EXPECT_EQ(u.OuterRadius(51), 0.02);
  // A tube: a bored bar with a d 20 bore over its whole length.
  p.sections = {{0.0, 0.02, 0.01, 0.03}};
  const auto tube = TurnedStock::FromPart(p, 0.001).Cylinders(1e-6);
  ASSERT_EQ(tube.size(), 1u);
  EXPECT_EQ(tube[0].inner_radius_m, 0.01);
  EXPECT_NEAR(tube[0].length_m, 0.02, 1e-15);
}

/// A box of a cutting part's size, as its mesh's twelve triangles (spindle frame, m).
std::vector<Eigen::Vector3d> Box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<Eigen::Vector3d> c;
  const auto corner = [&](int i) {
    return Eigen::Vector3d(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(),
                           i & 4 ? hi.z() : lo.z());
  };
  // Each face as two triangles: the faces x-, x+, y-, y+, z-, z+ by their corner indices.
  const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                           {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (const auto& f : faces)
    for (const int i : {f[0], f[1], f[2], f[0], f[2], f[3]}) c.push_back(corner(i));
  return c;
}

// Everything left of a slice is inside one of the parts that stand for it.
void ExpectCovered(const TurnedStock& t, const std::vector<CylinderPart>& parts) {
  for (size_t k = 0; k < t.slices.size(); ++k)
    for (const StockSpan& s : t.slices[k]) {
      const double z = t.z0_m + (static_cast<double>(k) + 0.5) * t.slice_m;
      bool covered = false;
      for (const CylinderPart& c : parts)
        covered = covered || (z > c.z_m && z < c.z_m + c.length_m && c.radius_m >= s.outer_m &&
                              c.inner_radius_m <= s.inner_m);
      EXPECT_TRUE(covered) << "slice " << k << " span " << s.inner_m << ".." << s.outer_m;
    }
}

/// A prism over the triangle (x, z) = a, b, c, from y = -half_width to +half_width, as its
/// eight triangles (spindle frame, m): an insert seen from its side.
std::vector<Eigen::Vector3d> Wedge(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                   const Eigen::Vector2d& c, double half_width) {
  const Eigen::Vector2d xz[3] = {a, b, c};
  const auto corner = [&](int i, double y) { return Eigen::Vector3d(xz[i].x(), y, xz[i].y()); };
  std::vector<Eigen::Vector3d> t;
  for (const double y : {-half_width, half_width})
    for (int i = 0; i < 3; ++i) t.push_back(corner(i, y));
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    for (const auto& [k, y] : {std::pair{i, -1}, {j, -1}, {j, 1}, {i, -1}, {j, 1}, {i, 1}})
      t.push_back(corner(k, y * half_width));
  }
  return t;
}

TEST(TurnedStock, ASlantedFlankLowersEverySliceItPassesToItsRadiusThere) {
  // Slices of 0.1 mm: the insert spans a hundred and fifty of them. Its tip at radius 20, z 10
  // mm; its flank rises at 45 degrees to radius 35 at z 25 mm; its leading face is z = 10 mm.
  TurnedStock t = TurnedStock::FromCylinder({"w", "spindle", 0.03, 0.03, 0}, 1e-4);
  const double allowance = 1e-5;
  const auto insert = [](double dz) {
    return Wedge({0.020, 0.010 + dz}, {0.035, 0.025 + dz}, {0.035, 0.010 + dz}, 0.0025);
  };
  ASSERT_TRUE(t.CutSolid(insert(0), allowance));
  const auto expected = [&](size_t k, double dz) {
    // The slice's lowest face, widened by the allowance, meets the flank nearest the axis.
    const double lo = static_cast<double>(k) * 1e-4 - allowance;
    const double r = 0.020 + std::max(0.0, lo - (0.010 + dz));
    return std::min(0.03, r - allowance);
  };
  for (size_t k = 0; k < t.slices.size(); ++k) {
    const bool under = (static_cast<double>(k) + 1) * 1e-4 + allowance >= 0.010;
    EXPECT_NEAR(t.OuterRadius(k), under ? expected(k, 0) : 0.03, 1e-12) << "slice " << k;
  }
  // In its own cut it takes nothing more; fed 2.35 mm along z in steps, each slice keeps the
  // lowest of the cuts that passed over it.
  EXPECT_FALSE(t.CutSolid(insert(0), allowance));
  constexpr int kSteps = 47;
  for (int step = 1; step <= kSteps; ++step) t.CutSolid(insert(step * 5e-5), allowance);
  EXPECT_FALSE(t.CutSolid(insert(kSteps * 5e-5), allowance));
  for (size_t k = 0; k < t.slices.size(); ++k) {
    double want = 0.03;
    if ((static_cast<double>(k) + 1) * 1e-4 + allowance >= 0.010)
      for (int step = 0; step <= kSteps; ++step) want = std::min(want, expected(k, step * 5e-5));
    EXPECT_NEAR(t.OuterRadius(k), want, 1e-12) << "slice " << k;
  }
}

TEST(TurnedStock, ATurningToolAboveTheSurfaceLowersIt) {
  TurnedStock t = TurnedStock::FromCylinder({"w", "spindle", 0.03, 0.02, 0}, 0.001);
  // An insert from radius 28 to 42 over z 2..6 mm, beside the axis at y -2.5..2.5 mm.
  EXPECT_TRUE(t.CutSolid(Box({0.028, -0.0025, 0.002}, {0.042, 0.0025, 0.006}), 1e-5));
  EXPECT_NEAR(t.OuterRadius(3), 0.028 - 1e-5, 1e-12);
  ASSERT_EQ(t.slices[3].size(), 1u);
  EXPECT_EQ(t.slices[3][0].inner_m, 0.0);
  EXPECT_EQ(t.OuterRadius(0), 0.03);  // beyond the allowance
  EXPECT_EQ(t.OuterRadius(7), 0.03);
  // Again at the same place: nothing more; beside the part: nothing.
  EXPECT_FALSE(t.CutSolid(Box({0.028, -0.0025, 0.002}, {0.042, 0.0025, 0.006}), 1e-5));
  EXPECT_FALSE(t.CutSolid(Box({0.0, -0.0025, 0.03}, {0.01, 0.0025, 0.04}), 1e-5));
}

TEST(TurnedStock, ADrillAtTheAxisBoresTheCore) {
  TurnedStock t = TurnedStock::FromCylinder({"w", "spindle", 0.03, 0.02, 0}, 0.001);
  // A d 8 drill (as a square of its size) 8 mm into the right face: no triangle of its flanks
  // crosses the axis inside the part, yet the slices it passes through lose their core.
  EXPECT_TRUE(t.CutSolid(Box({-0.004, -0.004, 0.012}, {0.004, 0.004, 0.05}), 1e-5));
  ASSERT_EQ(t.slices[5].size(), 1u);  // ahead of the drill: solid
  EXPECT_EQ(t.slices[5][0].inner_m, 0.0);
  ASSERT_EQ(t.slices[15].size(), 1u);
  // The bore is the corners' distance, the square's diagonal, widened by the allowance.
  EXPECT_NEAR(t.slices[15][0].inner_m, 0.004 * std::sqrt(2.0) + 1e-5, 1e-12);
  EXPECT_EQ(t.OuterRadius(15), 0.03);  // the outside stays
  const auto parts = t.Cylinders(1e-6);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].inner_radius_m, 0.0);
  EXPECT_NEAR(parts[0].length_m, 0.011, 1e-12);  // the drill's point cuts a slice early
  EXPECT_NEAR(parts[1].inner_radius_m, 0.004 * std::sqrt(2.0) + 1e-5, 1e-12);
  EXPECT_EQ(parts[1].radius_m, 0.03);
  EXPECT_NEAR(parts[1].z_m + parts[1].length_m, 0.02, 1e-12);
  ExpectCovered(t, parts);
  // Turning the outside afterwards keeps the bore; turning down into it parts the slice off.
  EXPECT_TRUE(t.TurnDown(0.0165, 0.02, 0));
  ASSERT_EQ(t.slices[16].size(), 1u);
  EXPECT_NEAR(t.slices[16][0].inner_m, 0.004 * std::sqrt(2.0) + 1e-5, 1e-12);
  EXPECT_EQ(t.slices[16][0].outer_m, 0.02);
  EXPECT_TRUE(t.TurnDown(0.0175, 0.003, 0));
  EXPECT_TRUE(t.slices[17].empty());
  EXPECT_EQ(t.OuterRadius(17), 0.0);
}

TEST(TurnedStock, AGroovingToolInTheEndFaceCutsAFaceGroove) {
  TurnedStock t = TurnedStock::FromCylinder({"w", "spindle", 0.03, 0.02, 0}, 0.001);
  // A 4 mm wide blade from radius 20 to 24, plunged 4 mm into the right face (z 20 mm).
  EXPECT_TRUE(t.CutSolid(Box({0.02, -0.0015, 0.016}, {0.024, 0.0015, 0.06}), 1e-5));
  ASSERT_EQ(t.slices[17].size(), 2u);
  EXPECT_EQ(t.slices[17][0].inner_m, 0.0);
  EXPECT_NEAR(t.slices[17][0].outer_m, 0.02 - 1e-5, 1e-12);
  // The blade's far corners stand farthest from the axis.
  EXPECT_NEAR(t.slices[17][1].inner_m, std::hypot(0.024, 0.0015) + 1e-5, 1e-12);
  EXPECT_EQ(t.slices[17][1].outer_m, 0.03);
  const auto parts = t.Cylinders(1e-6);
  ASSERT_EQ(parts.size(), 3u);  // the solid part, then core and ring of the grooved slices
  EXPECT_EQ(parts[0].radius_m, 0.03);
  EXPECT_EQ(parts[1].inner_radius_m, 0.0);
  EXPECT_NEAR(parts[1].radius_m, 0.02 - 1e-5, 1e-12);
  EXPECT_GT(parts[2].inner_radius_m, 0.024);
  EXPECT_EQ(parts[2].radius_m, 0.03);
  EXPECT_EQ(parts[1].z_m, parts[2].z_m);
  ExpectCovered(t, parts);
  // Inside the groove nothing more is cut; turning above it keeps it, turning down into it
  // leaves the core.
  EXPECT_FALSE(t.CutSolid(Box({0.021, -0.001, 0.018}, {0.023, 0.001, 0.019}), 1e-5));
  EXPECT_TRUE(t.TurnDown(0.0185, 0.027, 0));
  EXPECT_EQ(t.slices[18].size(), 2u);
  EXPECT_EQ(t.OuterRadius(18), 0.027);
  EXPECT_TRUE(t.TurnDown(0.0195, 0.022, 0));
  ASSERT_EQ(t.slices[19].size(), 1u);
  EXPECT_NEAR(t.OuterRadius(19), 0.02 - 1e-5, 1e-12);
}

TEST(TurnedStock, ABoringBarWidensABore) {
  // A tube d 60 / bore d 20 over 0..30 mm; a bar from radius 8 to 14 reaches 10 mm in.
  RevolvedPart p{"workpiece", "spindle", {{0.0, 0.03, 0.01, 0.03}}};
  TurnedStock t = TurnedStock::FromPart(p, 0.001);
  EXPECT_TRUE(t.CutSolid(Box({0.008, -0.003, 0.02}, {0.014, 0.003, 0.1}), 1e-5));
  ASSERT_EQ(t.slices[25].size(), 1u);
  EXPECT_NEAR(t.slices[25][0].inner_m, std::hypot(0.014, 0.003) + 1e-5, 1e-12);
  EXPECT_EQ(t.slices[25][0].outer_m, 0.03);
  EXPECT_EQ(t.slices[10][0].inner_m, 0.01);  // deeper in, the bore as it was
  // A bar wholly inside the bore cuts nothing.
  EXPECT_FALSE(t.CutSolid(Box({0.002, -0.002, 0.0}, {0.008, 0.002, 0.1}), 1e-5));
}

}  // namespace
}  // namespace vmt::sim
