// PathGuard in machine units on lathe-c1: drive positions (mm, deg) in, named parts, the
// contact point and the distance along the path out.

#include "sim/collision/machine_path_guard.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/collision/turned_stock.hpp"

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

TEST(MachinePathGuard, ThePartAsTurnedReplacesTheStock) {
  Guarded g;
  // The same plunge as above finds the stock's surface at radius 30 ...
  const control::PathCheck before =
      g.guard.CheckMove(g.Drives(130, 250, 450), g.Drives(130, 0, 450));
  ASSERT_FALSE(before.clear);
  // ... and, once the part is turned down to radius 25 over its whole length, that surface.
  TurnedStock stock =
      TurnedStock::FromCylinder({"workpiece", "spindle", 0.030, 0.160, 0.060}, 0.0005);
  for (std::vector<StockSpan>& s : stock.slices) s = {{0, 0.025}};
  g.guard.world().SetAdded(stock.Cylinders(1e-6));
  const control::PathCheck after =
      g.guard.CheckMove(g.Drives(130, 250, 450), g.Drives(130, 0, 450));
  ASSERT_FALSE(after.clear);
  EXPECT_TRUE(after.part_a == "workpiece" || after.part_b == "workpiece");
  EXPECT_NEAR(std::hypot(after.point[0], after.point[1]), 25, 0.01);
  EXPECT_NEAR(after.distance - before.distance, 5, 0.01);
  // A tool standing 10 µm above what is left is clear of it.
  const int x = g.model.DriveIndex("X");
  const double standing = after.position[x] + 0.01;
  const control::PathCheck away =
      g.guard.CheckMove(g.Drives(130, standing, 450), g.Drives(130, 250, 450));
  EXPECT_TRUE(away.clear);
}

// Saved and restored (a run's in-memory copy), the guard answers as it did when saved: the
// stock as it was then, and the clearance proof of its last check.
TEST(MachinePathGuard, RestoredGuardAnswersAsWhenSaved) {
  Guarded g;
  const control::PathCheck plunge =
      g.guard.CheckMove(g.Drives(130, 250, 450), g.Drives(130, 0, 450));
  const control::PathCheck open =
      g.guard.CheckMove(g.Drives(500, 250, 650), g.Drives(450, 200, 650));
  ASSERT_TRUE(open.clear);
  const MachinePathGuard::Saved saved = g.guard.Save();
  control::PathCheck proven;
  ASSERT_TRUE(g.guard.Proves(g.Drives(500, 249.5, 650), g.Drives(450, 199.5, 650), proven));

  g.guard.SetAdded({{"workpiece", "spindle", 0.025, 0.160, 0.060}});
  const control::PathCheck turned =
      g.guard.CheckMove(g.Drives(130, 250, 450), g.Drives(130, 0, 450));
  ASSERT_NE(turned.distance, plunge.distance);

  g.guard.Restore(saved);
  control::PathCheck proven_again;
  ASSERT_TRUE(g.guard.Proves(g.Drives(500, 249.5, 650), g.Drives(450, 199.5, 650), proven_again));
  EXPECT_EQ(proven_again.min_clearance, proven.min_clearance);
  EXPECT_EQ(proven_again.closest_a, proven.closest_a);
  const control::PathCheck again =
      g.guard.CheckMove(g.Drives(130, 250, 450), g.Drives(130, 0, 450));
  EXPECT_EQ(again.distance, plunge.distance);
  EXPECT_EQ(again.part_a, plunge.part_a);
  EXPECT_EQ(again.part_b, plunge.part_b);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(again.point[i], plunge.point[i]);
}

TEST(MachinePathGuard, ARingIsMaterialOnlyBetweenItsRadii) {
  Guarded g;
  const control::PathCheck solid =
      g.guard.CheckMove(g.Drives(130, 250, 450), g.Drives(130, 0, 450));
  ASSERT_FALSE(solid.clear);
  // The stock replaced by a tube, bore 15, outer 30 mm: a plunge meets its outer wall where it
  // met the solid stock's, or a little before (the polygon circumscribes the circle: never
  // after).
  g.guard.world().SetAdded({{"workpiece", "spindle", 0.030, 0.160, 0.060, 0.015}});
  const control::PathCheck c = g.guard.CheckMove(g.Drives(130, 250, 450), g.Drives(130, 0, 450));
  ASSERT_FALSE(c.clear);
  EXPECT_TRUE(c.part_a == "workpiece" || c.part_b == "workpiece");
  EXPECT_LE(c.distance, solid.distance + 0.01);
  EXPECT_GE(c.distance, solid.distance - 30 * (1 / std::cos(std::numbers::pi / 64) - 1) - 0.01);
  // A ring of the bore's size (radius 15) is missed by the same plunge down to X 16.
  g.guard.world().SetAdded({{"workpiece", "spindle", 0.015, 0.160, 0.060, 0.010}});
  const control::PathCheck above =
      g.guard.CheckMove(g.Drives(130, 250, 450), g.Drives(130, 16, 450));
  EXPECT_TRUE(above.clear);
}

// A turret index swings every station's tools round. Over the part (Z 130) at X 6, stations 8
// and 9 each stand clear of it (their holders reach it at X 5), but between them a holder's
// corner dips into it: the index from 8 to 9 is refused, from 1 to 2 above the part it is clear.
// The check is the turn of the T drive alone.
TEST(MachinePathGuard, ATurretIndexSweepsItsToolsThroughThePart) {
  Guarded g;
  const int t = g.model.DriveIndex("T"), x = g.model.DriveIndex("X");
  auto at = [&](double turret, double x_mm) {
    std::vector<double> d = g.Drives(130, x_mm, 450);
    d[t] = turret;
    return d;
  };
  EXPECT_TRUE(g.guard.CheckMove(at(210, 7), at(210, 6)).clear);
  EXPECT_TRUE(g.guard.CheckMove(at(240, 7), at(240, 6)).clear);
  const control::PathCheck c = g.guard.CheckMove(at(210, 6), at(240, 6));
  ASSERT_FALSE(c.clear);
  EXPECT_TRUE(c.part_a.starts_with("turret_st08") || c.part_b.starts_with("turret_st08"))
      << c.part_a << " " << c.part_b;
  EXPECT_TRUE(c.part_a == "workpiece" || c.part_b == "workpiece") << c.part_a << " " << c.part_b;
  EXPECT_GT(c.position[t], 210);  // on the way
  EXPECT_LT(c.position[t], 240);
  EXPECT_EQ(c.position[x], 6);
  EXPECT_EQ(c.distance, 0);  // no linear drive moved
  EXPECT_TRUE(g.guard.CheckMove(at(0, 31), at(30, 31)).clear);
}

// A jog checked ahead every millimetre as X plunges towards the part: a check the last clear
// one proves is clear to a query as well, and its clearance is as exact as a query's (it may
// be up to the tolerance more than there is, and a query says at least what there is). Near
// the part the proofs run out and the query finds the contact.
TEST(MachinePathGuard, AJogCheckedAheadIsProvenClearOnlyWhereAQueryFindsItClear) {
  Guarded g, reference;
  int proven = 0, queried = 0;
  bool contact = false;
  for (double x = 250; x > 0 && !contact; x -= 1) {
    const std::vector<double> from = g.Drives(130, x, 450), to = g.Drives(130, x - 5, 450);
    control::PathCheck c;
    if (g.guard.Proves(from, to, c)) {
      ++proven;
      const control::PathCheck r = reference.guard.CheckMove(from, to);
      ASSERT_TRUE(r.clear) << "X " << x;
      EXPECT_TRUE(c.clear);
      EXPECT_GT(c.min_clearance, 0);
      // The proven move's tolerance (10 % of its clearance, which is at most 1/0.9 of this).
      const double tolerance = std::max(0.01, c.min_clearance / 9);
      EXPECT_LE(c.min_clearance - tolerance, r.min_clearance) << "X " << x;
    } else {
      ++queried;
      contact = !g.guard.CheckMove(from, to).clear;
    }
  }
  EXPECT_TRUE(contact);
  EXPECT_GT(proven, 150);
  EXPECT_GT(queried, 5);
}

// What the last check did not measure, it proves nothing of: a slide it held still (the pairs
// that slide moves against each other), a world changed since.
TEST(MachinePathGuard, ACheckProvesNothingOfWhatItDidNotMeasure) {
  Guarded g;
  ASSERT_TRUE(g.guard.CheckMove(g.Drives(300, 250, 450), g.Drives(300, 240, 450)).clear);
  control::PathCheck c;
  EXPECT_TRUE(g.guard.Proves(g.Drives(300, 249, 450), g.Drives(300, 239, 450), c));
  EXPECT_FALSE(g.guard.Proves(g.Drives(300, 249, 450), g.Drives(299, 239, 450), c));
  g.guard.SetAdded({{"workpiece", "spindle", 0.020, 0.160, 0.060}});
  EXPECT_FALSE(g.guard.Proves(g.Drives(300, 249, 450), g.Drives(300, 239, 450), c));
}

// A rotation moves a part by as much as it is wide: the turret turning beside a proven move
// has its tools' pairs queried. Over the part at X 6 a holder's corner dips into it between
// stations 8 and 9: no proof; above the part the turn is clear, as the whole query says.
TEST(MachinePathGuard, TheTurretTurningBesideAProvenMoveIsQueried) {
  Guarded g, reference;
  const int t = g.model.DriveIndex("T");
  auto at = [&](double turret, double x_mm) {
    std::vector<double> d = g.Drives(130, x_mm, 450);
    d[t] = turret;
    return d;
  };
  control::PathCheck c;
  ASSERT_TRUE(g.guard.CheckMove(at(210, 6.001), at(210, 6)).clear);
  EXPECT_FALSE(g.guard.Proves(at(210, 6.001), at(240, 6), c));
  ASSERT_TRUE(g.guard.CheckMove(at(0, 31.001), at(0, 31)).clear);
  ASSERT_TRUE(g.guard.Proves(at(0, 31.001), at(30, 31), c));
  const control::PathCheck r = reference.guard.CheckMove(at(0, 31.001), at(30, 31));
  ASSERT_TRUE(r.clear);
  EXPECT_NEAR(c.min_clearance, r.min_clearance, 0.1 * r.min_clearance + 0.01);
}

}  // namespace
}  // namespace vmt::sim
