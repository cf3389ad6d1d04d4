// The exact signed distance to a solid of revolution given as annular sections: values worked
// out by hand in the meridian plane (r, z), in mm, checked to 1e-12 m.

#include "sim/model/revolved_part.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace vmt::sim {
namespace {

constexpr double kMm = 1e-3;
constexpr double kTol = 1e-12;

Eigen::Vector3d Mm(double x, double y, double z) { return Eigen::Vector3d(x, y, z) * kMm; }

void ExpectNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, double tol) {
  EXPECT_NEAR((actual - expected).norm(), 0, tol)
      << actual.transpose() << " vs " << expected.transpose();
}

// Collar r 30 from z 0 to 50, then the journal r 20 to z 100.
RevolvedPart SteppedShaft() {
  return {"workpiece", "spindle", {{0, 50 * kMm, 0, 30 * kMm}, {50 * kMm, 100 * kMm, 0, 20 * kMm}}};
}

// A full disc r 40 from z 0 to 30, then a ring r 25..40 to z 40: a recess r 25 deep 10 in the
// face (a ring beside a full section).
RevolvedPart FaceRecess() {
  return {"workpiece",
          "spindle",
          {{0, 30 * kMm, 0, 40 * kMm}, {30 * kMm, 40 * kMm, 25 * kMm, 40 * kMm}}};
}

TEST(RevolvedPart, OutsideAStepIsTheRadialGap) {
  const RevolvedDistance d = SignedDistance(SteppedShaft(), Mm(40, 0, 25));
  EXPECT_NEAR(d.distance_m, 10 * kMm, kTol);
  ExpectNear(d.normal, {1, 0, 0}, kTol);
  ExpectNear(d.point_m, Mm(30, 0, 25), kTol);
}

TEST(RevolvedPart, AnyMeridianGivesTheSameDistance) {
  // r = 50 over the journal (r 20), in the meridian (0.6, 0.8).
  const RevolvedDistance d = SignedDistance(SteppedShaft(), Mm(30, 40, 75));
  EXPECT_NEAR(d.distance_m, 30 * kMm, kTol);
  ExpectNear(d.normal, {0.6, 0.8, 0}, kTol);
  ExpectNear(d.point_m, Mm(12, 16, 75), kTol);
}

TEST(RevolvedPart, InsideIsMinusTheDepth) {
  // 5 below the collar's surface, 10 above its end face at z 0.
  const RevolvedDistance d = SignedDistance(SteppedShaft(), Mm(25, 0, 10));
  EXPECT_NEAR(d.distance_m, -5 * kMm, kTol);
  ExpectNear(d.normal, {1, 0, 0}, kTol);
  ExpectNear(d.point_m, Mm(30, 0, 10), kTol);
}

TEST(RevolvedPart, NearAnOuterCornerTheCornerIsNearest) {
  // The collar's corner (30, 50) is 3 across and 4 along from (33, 54).
  const RevolvedDistance d = SignedDistance(SteppedShaft(), Mm(33, 0, 54));
  EXPECT_NEAR(d.distance_m, 5 * kMm, kTol);
  ExpectNear(d.normal, {0.6, 0, 0.8}, kTol);
  ExpectNear(d.point_m, Mm(30, 0, 50), kTol);
}

TEST(RevolvedPart, InTheStepsInnerCornerTheNearerFaceWins) {
  // 2 off the journal, 4 off the collar's shoulder.
  const RevolvedDistance d = SignedDistance(SteppedShaft(), Mm(22, 0, 54));
  EXPECT_NEAR(d.distance_m, 2 * kMm, kTol);
  ExpectNear(d.normal, {1, 0, 0}, kTol);
  // 1 above the shoulder, 3 off the journal.
  const RevolvedDistance s = SignedDistance(SteppedShaft(), Mm(23, 0, 51));
  EXPECT_NEAR(s.distance_m, 1 * kMm, kTol);
  ExpectNear(s.normal, {0, 0, 1}, kTol);
  ExpectNear(s.point_m, Mm(23, 0, 50), kTol);
}

TEST(RevolvedPart, WhereTwoSectionsMeetThereIsNoSurface) {
  // 2 below the plane z 50 where collar and journal meet: inside both, that plane is no
  // surface; the nearest way out is the step's inner corner (20, 50), sqrt(10^2 + 2^2) away.
  const RevolvedDistance d = SignedDistance(SteppedShaft(), Mm(10, 0, 48));
  EXPECT_NEAR(d.distance_m, -std::sqrt(104.0) * kMm, kTol);
  ExpectNear(d.point_m, Mm(20, 0, 50), kTol);
  ExpectNear(d.normal, Eigen::Vector3d(10, 0, 2) / std::sqrt(104.0), kTol);
}

TEST(RevolvedPart, OnTheAxisTheEndFacesAreNearest) {
  const RevolvedDistance beyond = SignedDistance(SteppedShaft(), Mm(0, 0, 110));
  EXPECT_NEAR(beyond.distance_m, 10 * kMm, kTol);
  ExpectNear(beyond.normal, {0, 0, 1}, kTol);
  ExpectNear(beyond.point_m, Mm(0, 0, 100), kTol);
  const RevolvedDistance inside = SignedDistance(SteppedShaft(), Mm(0, 0, 90));
  EXPECT_NEAR(inside.distance_m, -10 * kMm, kTol);
  ExpectNear(inside.normal, {0, 0, 1}, kTol);
  const RevolvedDistance before = SignedDistance(SteppedShaft(), Mm(0, 0, -5));
  EXPECT_NEAR(before.distance_m, 5 * kMm, kTol);
  ExpectNear(before.normal, {0, 0, -1}, kTol);
  // Deep inside on the axis: the axis is no surface, the journal's radius 20 is.
  const RevolvedDistance core = SignedDistance(SteppedShaft(), Mm(0, 0, 75));
  EXPECT_NEAR(core.distance_m, -20 * kMm, kTol);
  ExpectNear(core.normal, {1, 0, 0}, kTol);  // every meridian is nearest: +x is taken
}

TEST(RevolvedPart, OnTheSurfaceTheDistanceIsZeroWithTheFacesNormal) {
  const RevolvedDistance d = SignedDistance(SteppedShaft(), Mm(0, 20, 70));
  EXPECT_NEAR(d.distance_m, 0, kTol);
  ExpectNear(d.normal, {0, 1, 0}, kTol);
}

TEST(RevolvedPart, InAFaceRecessTheFloorOrTheWallIsNearest) {
  // The recess's floor is the disc's face z 30 from the axis to r 25.
  const RevolvedDistance floor = SignedDistance(FaceRecess(), Mm(10, 0, 35));
  EXPECT_NEAR(floor.distance_m, 5 * kMm, kTol);
  ExpectNear(floor.normal, {0, 0, 1}, kTol);
  ExpectNear(floor.point_m, Mm(10, 0, 30), kTol);
  // Its wall is the ring's bore r 25, facing the axis.
  const RevolvedDistance wall = SignedDistance(FaceRecess(), Mm(22, 0, 38));
  EXPECT_NEAR(wall.distance_m, 3 * kMm, kTol);
  ExpectNear(wall.normal, {-1, 0, 0}, kTol);
  ExpectNear(wall.point_m, Mm(25, 0, 38), kTol);
  // Near the floor's corner: 1.5 above the floor, 2 off the wall.
  const RevolvedDistance corner = SignedDistance(FaceRecess(), Mm(23, 0, 31.5));
  EXPECT_NEAR(corner.distance_m, 1.5 * kMm, kTol);
  ExpectNear(corner.normal, {0, 0, 1}, kTol);
  // On the axis in the recess.
  const RevolvedDistance axis = SignedDistance(FaceRecess(), Mm(0, 0, 35));
  EXPECT_NEAR(axis.distance_m, 5 * kMm, kTol);
  ExpectNear(axis.point_m, Mm(0, 0, 30), kTol);
}

TEST(RevolvedPart, AtTheRecessEdgeTheRingsCornerIsNearest) {
  // Above the ring's inner corner (25, 40), 3 inside and 3 above it.
  const RevolvedDistance d = SignedDistance(FaceRecess(), Mm(22, 0, 43));
  EXPECT_NEAR(d.distance_m, std::sqrt(18.0) * kMm, kTol);
  ExpectNear(d.normal, Eigen::Vector3d(-1, 0, 1) / std::sqrt(2.0), kTol);
  ExpectNear(d.point_m, Mm(25, 0, 40), kTol);
}

TEST(RevolvedPart, InsideUnderTheRingTheRecessCornerIsTheWayOut) {
  // In the disc, 1 below the plane z 30, 5 outside r 25: the ring covers the face there, so
  // the way out is the recess's corner (25, 30).
  const RevolvedDistance d = SignedDistance(FaceRecess(), Mm(30, 0, 29));
  EXPECT_NEAR(d.distance_m, -std::sqrt(26.0) * kMm, kTol);
  ExpectNear(d.point_m, Mm(25, 0, 30), kTol);
  ExpectNear(d.normal, Eigen::Vector3d(-5, 0, 1) / std::sqrt(26.0), kTol);
  // Inside the ring, 1 under its face.
  const RevolvedDistance ring = SignedDistance(FaceRecess(), Mm(30, 0, 39));
  EXPECT_NEAR(ring.distance_m, -1 * kMm, kTol);
  ExpectNear(ring.normal, {0, 0, 1}, kTol);
}

// A face groove r 15..25, 10 deep, in the face z 30 of a disc r 40: over the groove's depth
// the core r 15 and the ring r 25..40 share the stretch of z.
RevolvedPart FaceGroove() {
  return {"workpiece",
          "spindle",
          {{0, 30 * kMm, 0, 40 * kMm},
           {30 * kMm, 40 * kMm, 0, 15 * kMm},
           {30 * kMm, 40 * kMm, 25 * kMm, 40 * kMm}}};
}

TEST(RevolvedPart, InAFaceGrooveTheCoreTheRingOrTheFloorIsNearest) {
  // 3 off the core, 7 off the floor and the ring.
  const RevolvedDistance core = SignedDistance(FaceGroove(), Mm(18, 0, 37));
  EXPECT_NEAR(core.distance_m, 3 * kMm, kTol);
  ExpectNear(core.normal, {1, 0, 0}, kTol);
  ExpectNear(core.point_m, Mm(15, 0, 37), kTol);
  // 1 above the floor (the disc's face between core and ring).
  const RevolvedDistance floor = SignedDistance(FaceGroove(), Mm(22, 0, 31));
  EXPECT_NEAR(floor.distance_m, 1 * kMm, kTol);
  ExpectNear(floor.normal, {0, 0, 1}, kTol);
  // 2 off the ring's bore, facing the axis.
  const RevolvedDistance ring = SignedDistance(FaceGroove(), Mm(23, 0, 36));
  EXPECT_NEAR(ring.distance_m, 2 * kMm, kTol);
  ExpectNear(ring.normal, {-1, 0, 0}, kTol);
  // Above the core's face.
  const RevolvedDistance top = SignedDistance(FaceGroove(), Mm(5, 0, 41));
  EXPECT_NEAR(top.distance_m, 1 * kMm, kTol);
  ExpectNear(top.normal, {0, 0, 1}, kTol);
}

TEST(RevolvedPart, UnderAFaceGrooveOnlyItsFloorIsSurface) {
  // 1 under the floor.
  const RevolvedDistance floor = SignedDistance(FaceGroove(), Mm(20, 0, 29));
  EXPECT_NEAR(floor.distance_m, -1 * kMm, kTol);
  ExpectNear(floor.normal, {0, 0, 1}, kTol);
  // Under the core the disc goes on into it: the way out is the groove's corner (15, 30).
  const RevolvedDistance core = SignedDistance(FaceGroove(), Mm(10, 0, 29));
  EXPECT_NEAR(core.distance_m, -std::sqrt(26.0) * kMm, kTol);
  ExpectNear(core.point_m, Mm(15, 0, 30), kTol);
  ExpectNear(core.normal, Eigen::Vector3d(5, 0, 1) / std::sqrt(26.0), kTol);
  // Under the ring likewise: the corner (25, 30).
  const RevolvedDistance ring = SignedDistance(FaceGroove(), Mm(30, 0, 29));
  EXPECT_NEAR(ring.distance_m, -std::sqrt(26.0) * kMm, kTol);
  ExpectNear(ring.point_m, Mm(25, 0, 30), kTol);
}

TEST(RevolvedPart, InABoreOnTheAxisTheBoreIsNearest) {
  const RevolvedPart tube{"tube", "spindle", {{0, 10 * kMm, 10 * kMm, 20 * kMm}}};
  const RevolvedDistance d = SignedDistance(tube, Mm(0, 0, 5));
  EXPECT_NEAR(d.distance_m, 10 * kMm, kTol);
  ExpectNear(d.point_m, Mm(10, 0, 5), kTol);
  ExpectNear(d.normal, {-1, 0, 0}, kTol);
}

TEST(RevolvedPart, APartWithoutSectionsIsInfinitelyFar) {
  EXPECT_TRUE(std::isinf(SignedDistance(RevolvedPart{}, Mm(0, 0, 0)).distance_m));
}

// The cheap bound from the bounding cylinder never exceeds the exact distance (the two round
// differently at a corner: an ulp or two), on a grid of
// points round each part (on the axis, in recesses, beyond the ends, far out) and on every
// meridian; within the cylinder it gives no bound.
TEST(RevolvedPart, TheBoundingCylindersBoundNeverExceedsTheDistance) {
  for (const RevolvedPart& part : {SteppedShaft(), FaceRecess(), FaceGroove()}) {
    int bounded = 0;
    for (double r = 0; r <= 60; r += 2.5)
      for (double z = -30; z <= 130; z += 2.5)
        for (const double angle : {0.0, 1.0, 4.0}) {
          const Eigen::Vector3d p = Mm(r * std::cos(angle), r * std::sin(angle), z);
          const double bound = DistanceLowerBound(part, p);
          const double exact = SignedDistance(part, p).distance_m;
          EXPECT_LE(bound, exact + 1e-15) << "at r " << r << " z " << z;
          if (bound > -1) {
            ++bounded;
            EXPECT_GT(bound, 0);
            EXPECT_GT(exact, 0);
          }
        }
    EXPECT_GT(bounded, 300);  // beyond r 40 or the ends there is a bound
  }
  // Far off the end of the shaft on its axis the bound is the distance itself.
  EXPECT_NEAR(DistanceLowerBound(SteppedShaft(), Mm(0, 0, 130)), 30 * kMm, kTol);
  EXPECT_TRUE(std::isinf(DistanceLowerBound(SteppedShaft(), Mm(25, 0, 75))));  // in the step
  EXPECT_GT(DistanceLowerBound(RevolvedPart{}, Mm(0, 0, 0)), 1e300);
}

TEST(RevolvedPart, BadSectionsAreNamed) {
  EXPECT_EQ(RevolvedPartError(SteppedShaft()), "");
  EXPECT_EQ(RevolvedPartError(FaceRecess()), "");
  RevolvedPart p = SteppedShaft();
  p.sections[1].z0_m = 40 * kMm;
  EXPECT_EQ(RevolvedPartError(p), "sections[1]: shares material with sections[0]");
  EXPECT_EQ(RevolvedPartError(FaceGroove()), "");
  p = FaceGroove();
  p.sections[2].r_inner_m = 10 * kMm;  // the ring into the core
  EXPECT_EQ(RevolvedPartError(p), "sections[2]: shares material with sections[1]");
  p = SteppedShaft();
  p.sections[0].r_outer_m = 0;
  EXPECT_EQ(RevolvedPartError(p), "sections[0]: r_outer must be greater than r_inner");
  p = SteppedShaft();
  p.sections[1].z1_m = p.sections[1].z0_m;
  EXPECT_EQ(RevolvedPartError(p), "sections[1]: z1 must be greater than z0");
  p = SteppedShaft();
  p.sections[0].r_inner_m = -1;
  EXPECT_EQ(RevolvedPartError(p), "sections[0]: r_inner must be >= 0");
  p = SteppedShaft();
  p.sections[0].z0_m = std::nan("");
  EXPECT_EQ(RevolvedPartError(p), "sections[0]: a number that is not finite");
}

}  // namespace
}  // namespace vmt::sim
