// PathGuard in machine units on lathe-c1: drive positions (mm, deg) in, named parts, the
// contact point and the distance along the path out.

#include "sim/collision/machine_path_guard.hpp"

#include <gtest/gtest.h>

namespace vmt::sim {
namespace {

struct Guarded {
  Guarded()
      : model(LoadMachineModel(VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml")),
        guard(model, {{"workpiece", "spindle", 0.030, 0.160, 0.060}},
              [this] { return std::vector<double>(model.joints.size(), 0.0); }) {}
  std::vector<double> Drives(double z, double x, double w) const {
    std::vector<double> d(model.drives.size(), 0.0);
    d[model.DriveIndex("Z")] = z, d[model.DriveIndex("X")] = x, d[model.DriveIndex("W")] = w;
    return d;
  }
  MachineModel model;
  MachinePathGuard guard;
};

TEST(MachinePathGuard, PlungingXIntoTheWorkpieceNamesThePartsAndWhere) {
  Guarded g;
  const control::PathCheck c = g.guard.CheckMove(g.Drives(130, 250, 450), g.Drives(130, 0, 450));
  ASSERT_FALSE(c.clear);
  EXPECT_TRUE(c.part_a == "workpiece" || c.part_b == "workpiece") << c.part_a << " " << c.part_b;
  const int x = g.model.DriveIndex("X"), z = g.model.DriveIndex("Z");
  // Along the path = the X travel to the contact; the drives stand there.
  EXPECT_NEAR(c.distance, 250 - c.position[x], 1e-9);
  EXPECT_GT(c.distance, 0);
  EXPECT_LT(c.distance, 250);
  EXPECT_EQ(c.position[z], 130);
  // The contact lies on the workpiece's surface (radius 30 mm about the spindle axis, z).
  EXPECT_NEAR(std::hypot(c.point[0], c.point[1]), 30, 0.01);
  EXPECT_EQ(c.min_clearance, 0);
}

TEST(MachinePathGuard, AMoveInTheOpenIsClearWithItsSmallestClearance) {
  Guarded g;
  const control::PathCheck c = g.guard.CheckMove(g.Drives(500, 250, 650), g.Drives(450, 200, 650));
  EXPECT_TRUE(c.clear);
  EXPECT_GT(c.min_clearance, 0);
  EXPECT_FALSE(c.closest_a.empty());
  EXPECT_FALSE(c.closest_b.empty());
}

}  // namespace
}  // namespace vmt::sim
