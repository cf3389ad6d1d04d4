// The probe in CollisionWorld on lathe-c1, with the MachinePathGuard tests' rig (a stock
// cylinder r 30 from z 60 to 220 on the spindle): the ruby touching the workpiece is the
// measurement (machine.yaml probe: sphere_parts), the shank, band and body touching it, and
// the ruby touching the machine's own parts, are collisions.

#include <gtest/gtest.h>

#include <cmath>

#include "sim/collision/machine_path_guard.hpp"
#include "sim/collision/turned_stock.hpp"

namespace vmt::sim {
namespace {

const CylinderPart kStock{"workpiece", "spindle", 0.030, 0.160, 0.060};

struct Guarded {
  explicit Guarded(bool with_probe_section = true)
      : model(Load(with_probe_section)),
        guard(model, {kStock}, [this] { return std::vector<double>(model.joints.size(), 0.0); }) {}
  static MachineModel Load(bool with_probe_section) {
    MachineModel m = LoadMachineModel(VMT_SOURCE_DIR "/models/lathe-c1/machine.yaml");
    if (!with_probe_section) m.probes.clear();
    return m;
  }
  // The turret at station 3 (the probe towards the spindle), X and Z in mm.
  std::vector<double> Drives(double z, double x) const {
    std::vector<double> d(model.drives.size(), 0.0);
    d[model.DriveIndex("Z")] = z, d[model.DriveIndex("X")] = x;
    d[model.DriveIndex("T")] = 60;
    d[model.DriveIndex("W")] = 650;  // tailstock out of the way
    return d;
  }
  int Part(const std::string& name) {
    for (int i = 0; i < guard.world().size(); ++i)
      if (guard.world().part(i).name == name) return i;
    ADD_FAILURE() << "no part " << name;
    return 0;
  }
  MachineModel model;
  MachinePathGuard guard;
};

bool Names(const control::PathCheck& c, const std::string& a, const std::string& b) {
  return (c.part_a == a && c.part_b == b) || (c.part_a == b && c.part_b == a);
}

TEST(ProbeContact, TheRubyStandsWhereTheToolTipIs) {
  // Station 3's ruby (r 3) touches the tip point (X, Z + 60): its centre is 3 mm beyond it.
  Guarded g;
  const std::vector<double> q =
      g.guard.JointPositions(std::vector<double>(g.model.joints.size(), 0.0), g.Drives(140, 40),
                             std::vector<char>(g.model.drives.size(), 1));
  const std::vector<Eigen::Isometry3d> X_W = LinkPoses(g.model, q);
  const ProbeStylus& s = g.model.probes.at(0);
  const Eigen::Vector3d centre = X_W[s.link] * s.spheres[0].centre_m;
  // To the URDF's 9 decimals of the probe mount.
  EXPECT_NEAR((centre - Eigen::Vector3d(0.043, 0, 0.200)).norm(), 0, 1e-8) << centre.transpose();
}

TEST(ProbeContact, TheRubyInTheWorkpieceIsAMeasurementOnlyOnTheMeasuringPath) {
  // Radially onto the stock (r 30) at Z 140 until the ruby is 1.5 mm in: on the measuring path
  // its shank, 3 mm behind its front, stays 1.5 mm clear.
  Guarded g;
  const control::PathCheck c = g.guard.CheckMeasuringPath(g.Drives(140, 250), g.Drives(140, 28.5));
  EXPECT_TRUE(c.clear) << c.part_a << " / " << c.part_b << " at X "
                       << c.position[g.model.DriveIndex("X")];
  // Any other move (an approach, a jog) that takes the ruby into the part is a collision.
  const control::PathCheck a = g.guard.CheckMove(g.Drives(140, 250), g.Drives(140, 28.5));
  ASSERT_FALSE(a.clear);
  EXPECT_TRUE(Names(a, "probe_ruby", "workpiece")) << a.part_a << " / " << a.part_b;
  EXPECT_NEAR(a.position[g.model.DriveIndex("X")], 30, 1e-3);
  // Resting on the part (a measurement just latched), it may leave it.
  EXPECT_TRUE(g.guard.CheckMove(g.Drives(140, 29.999), g.Drives(140, 60)).clear);
  // Without the probe: section, the same move is a collision of the ruby with the workpiece.
  Guarded plain(false);
  const control::PathCheck p = plain.guard.CheckMove(g.Drives(140, 250), g.Drives(140, 28.5));
  ASSERT_FALSE(p.clear);
  EXPECT_TRUE(Names(p, "probe_ruby", "workpiece")) << p.part_a << " / " << p.part_b;
  EXPECT_NEAR(p.position[g.model.DriveIndex("X")], 30, 0.01);
}

TEST(ProbeContact, TheRubyIsAnExactSphereAtASharpEdge) {
  // The ruby's centre 3 mm out and 3 mm beyond the stock's end-face rim (r 30, z 220): the
  // clearance is the sphere's, sqrt(18) - 3, not the faceted mesh's (its faces lie inside the
  // sphere by up to tens of um, more than the 5 um the switch trips on).
  Guarded g;
  const control::PathCheck c = g.guard.CheckMove(g.Drives(163, 30), g.Drives(163, 30.0001));
  ASSERT_TRUE(c.clear);
  EXPECT_NEAR(c.min_clearance, std::sqrt(18.0) - 3, 0.002) << c.closest_a << " / " << c.closest_b;
  EXPECT_TRUE(c.closest_a == "probe_ruby" || c.closest_b == "probe_ruby");
}

TEST(ProbeContact, TheShankInTheWorkpieceIsACollision) {
  // Even on the measuring path: further in, the shank's end (at the ruby's centre, r 2) meets
  // the stock at X 27.
  Guarded g;
  const control::PathCheck c = g.guard.CheckMeasuringPath(g.Drives(140, 250), g.Drives(140, 20));
  ASSERT_FALSE(c.clear);
  EXPECT_TRUE(Names(c, "probe_stylus", "workpiece")) << c.part_a << " / " << c.part_b;
  EXPECT_NEAR(c.position[g.model.DriveIndex("X")], 27, 0.01);
}

TEST(ProbeContact, OnlyTheRubyMayTouchOnlyTheAddedParts) {
  Guarded g;
  CollisionWorld& w = g.guard.world();
  const int ruby = g.Part("probe_ruby"), workpiece = g.Part("workpiece");
  EXPECT_TRUE(w.part(ruby).measures);
  EXPECT_TRUE(w.Measures(ruby, workpiece));
  EXPECT_FALSE(w.MayTouch(ruby, workpiece));  // only on a measuring path
  w.SetMeasuring(true);
  EXPECT_TRUE(w.MayTouch(ruby, workpiece));
  EXPECT_TRUE(w.MayTouch(workpiece, ruby));
  for (const char* part : {"probe_stylus", "probe_band", "probe_body"}) {
    EXPECT_FALSE(w.part(g.Part(part)).measures) << part;
    EXPECT_FALSE(w.MayTouch(g.Part(part), workpiece)) << part;
  }
  // The machine's own parts are no workpiece: the ruby on a jaw or the tailstock collides.
  for (const char* part : {"spindle_jaw1", "spindle_chuck_body", "tailstock_centre"})
    EXPECT_FALSE(w.MayTouch(ruby, g.Part(part))) << part;
  // The part as turned replaces the stock: the rule holds for the new parts.
  TurnedStock stock = TurnedStock::FromCylinder(kStock, 0.0005);
  for (size_t i = 0; i < stock.slices.size() / 2; ++i) stock.slices[i] = {{0, 0.025}};
  g.guard.world().SetAdded(stock.Cylinders(1e-6));
  ASSERT_GE(w.size(), g.Part("probe_ruby") + 2);
  w.SetMeasuring(true);
  for (int i = 0; i < w.size(); ++i)
    if (w.part(i).name == "workpiece") {
      EXPECT_TRUE(w.MayTouch(ruby, i));
      EXPECT_FALSE(w.MayTouch(g.Part("probe_stylus"), i));
    }
}

}  // namespace
}  // namespace vmt::sim
