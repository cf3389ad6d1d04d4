// The turned stock: slices of the stock cylinder, lowered by the cutting edge's points, given
// back as cylinders that never leave out material that is still there.

#include "sim/collision/turned_stock.hpp"

#include <gtest/gtest.h>

namespace vmt::sim {
namespace {

TEST(TurnedStock, StartsAsTheStockCylinder) {
  const TurnedStock t =
      TurnedStock::FromCylinder({"workpiece", "spindle", 0.03, 0.16, 0.06}, 0.001);
  ASSERT_EQ(t.radius_m.size(), 160u);
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
  EXPECT_TRUE(t.Cut(0.0045, 0.028, 1e-5));
  EXPECT_NEAR(t.radius_m[4], 0.028 - 1e-5, 1e-15);
  EXPECT_EQ(t.radius_m[3], 0.03);
  EXPECT_EQ(t.radius_m[5], 0.03);
  EXPECT_FALSE(t.Cut(0.0045, 0.029, 1e-5));  // above what is left: nothing to cut
  EXPECT_FALSE(t.Cut(-0.001, 0.0, 0));       // beside the part
  EXPECT_FALSE(t.Cut(0.0101, 0.0, 0));
  EXPECT_TRUE(t.Cut(0.0005, 0.0, 1e-5));  // through to the axis
  EXPECT_EQ(t.radius_m[0], 0);
}

TEST(TurnedStock, CylindersMergeRunsAndKeepTheLargestRadius) {
  TurnedStock t = TurnedStock::FromCylinder({"w", "spindle", 0.03, 0.01, 0.1}, 0.001);
  // A pass at radius 28 over slices 2..7, a slightly deeper point in slice 5, slice 0 parted.
  for (int k = 2; k <= 7; ++k) t.Cut(0.1 + (k + 0.5) * 0.001, 0.028, 0);
  t.Cut(0.1 + 5.5 * 0.001, 0.02799, 0);
  t.Cut(0.1005, 0.0, 0);
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
  for (size_t k = 0; k < t.radius_m.size(); ++k) {
    const double z = t.z0_m + (k + 0.5) * t.slice_m;
    bool covered = t.radius_m[k] == 0;
    for (const CylinderPart& c : parts)
      covered = covered || (z > c.z_m && z < c.z_m + c.length_m && c.radius_m >= t.radius_m[k]);
    EXPECT_TRUE(covered) << "slice " << k;
  }
}

TEST(TurnedStock, FromAPartTheCoreIsSlicedAndTheRingsStay) {
  // A stepped shaft, d 60 over 0..50 mm and d 40 over 50..80 mm, with a face groove in its
  // right face: core d 20 and ring d 40 / bore 30 over 70..80 mm (the d 40 step ends at 70).
  RevolvedPart p{"workpiece", "spindle", {}};
  p.sections = {{0.0, 0.05, 0, 0.03},
                {0.05, 0.07, 0, 0.02},
                {0.07, 0.08, 0, 0.01},
                {0.07, 0.08, 0.015, 0.02}};
  const TurnedStock t = TurnedStock::FromPart(p, 0.001);
  ASSERT_EQ(t.radius_m.size(), 80u);
  EXPECT_EQ(t.radius_m[49], 0.03);
  EXPECT_EQ(t.radius_m[50], 0.02);
  EXPECT_EQ(t.radius_m[69], 0.02);
  EXPECT_EQ(t.radius_m[70], 0.01);
  ASSERT_EQ(t.rings.size(), 1u);
  const auto parts = t.Cylinders(1e-6);
  ASSERT_EQ(parts.size(), 4u);  // three steps of the core, then the ring as it was
  EXPECT_DOUBLE_EQ(parts[3].inner_radius_m, 0.015);
  EXPECT_DOUBLE_EQ(parts[3].radius_m, 0.02);
  EXPECT_NEAR(parts[3].z_m, 0.07, 1e-15);
  EXPECT_NEAR(parts[3].length_m, 0.01, 1e-15);
  // A step off the slice grid: the slice it falls in keeps the larger radius.
  p.sections = {{0.0, 0.0505, 0, 0.03}, {0.0505, 0.06, 0, 0.02}};
  const TurnedStock u = TurnedStock::FromPart(p, 0.001);
  EXPECT_EQ(u.radius_m[50], 0.03);
  EXPECT_EQ(u.radius_m[51], 0.02);
}

}  // namespace
}  // namespace vmt::sim
