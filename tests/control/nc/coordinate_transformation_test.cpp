// The geometry of G31/G32 (coordinate_transformation.hpp): round trips, the sweep along a line,
// the derivative bounds of a face line against finite differences, and the chord bound against
// brute force.

#include "control/nc/coordinate_transformation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

namespace vmt::control::nc {
namespace {

constexpr double kDeg = 180 / std::numbers::pi;

TEST(CoordinateTransformation, FaceRoundTrip) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-100, 100);
  for (int k = 0; k < 1000; ++k) {
    const FictivePoint p{coordinate(rng), coordinate(rng)};
    double x = 0, c = 0;
    FaceToMachine(p, x, c);
    EXPECT_GE(x, 0);
    EXPECT_GT(c, -180 - 1e-12);
    EXPECT_LE(c, 180 + 1e-12);
    const FictivePoint q = MachineToFace(x, c);
    EXPECT_NEAR(q.x1, p.x1, 1e-12);
    EXPECT_NEAR(q.y1, p.y1, 1e-12);
  }
  // The axes of the face: X1 is C0, Y1 is C90, -X1 is C180.
  double x = 0, c = 0;
  FaceToMachine({0, 25}, x, c);
  EXPECT_DOUBLE_EQ(x, 25);
  EXPECT_DOUBLE_EQ(c, 90);
  FaceToMachine({-10, 0}, x, c);
  EXPECT_DOUBLE_EQ(c, 180);
  FaceToMachine({0, 0}, x, c);
  EXPECT_EQ(x, 0);
  EXPECT_EQ(c, 0);
}

TEST(CoordinateTransformation, SweepAndNearestC) {
  EXPECT_NEAR(SweepDeg({10, 0}, {0, 10}), 90, 1e-12);
  EXPECT_NEAR(SweepDeg({0, 10}, {10, 0}), -90, 1e-12);
  EXPECT_EQ(SweepDeg({0, 0}, {10, 0}), 0);
  // Along a line that misses the centre the start's C plus the sweep is continuous: from
  // C 350 (X1 ~ +, Y1 ~ -) past C 360 without a jump.
  const FictivePoint a = MachineToFace(20, 350), b = MachineToFace(20, 20);
  EXPECT_NEAR(350 + SweepDeg(a, b), 380, 1e-9);
  EXPECT_NEAR(FaceC({10, 10}, 700), 765, 1e-9);  // 45 deg, two turns on
  EXPECT_NEAR(FaceC({0, 0}, 33), 33, 0);
}

TEST(CoordinateTransformation, CylinderRoundTrip) {
  EXPECT_NEAR(CylinderC(std::numbers::pi * 20, 20), 180, 1e-12);
  EXPECT_NEAR(CylinderY1(CylinderC(12.5, 35), 35), 12.5, 1e-12);
}

// r(s), theta(s) along the line by finite differences: the bounds of FaceLineOf hold.
TEST(CoordinateTransformation, FaceLineBoundsHoldAlongTheLine) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-60, 60);
  for (int k = 0; k < 200; ++k) {
    const FictivePoint a{coordinate(rng), coordinate(rng)}, b{coordinate(rng), coordinate(rng)};
    const FaceLine l = FaceLineOf(a, b);
    if (l.through_centre || l.length < 1) continue;
    const double h = 1e-3;
    const auto at = [&](double s) {
      const double u = s / l.length;
      return FictivePoint{a.x1 + (b.x1 - a.x1) * u, a.y1 + (b.y1 - a.y1) * u};
    };
    const auto theta = [&](double s) { return SweepDeg(a, at(s)) / kDeg; };
    const auto radius = [&](double s) { const FictivePoint p = at(s); return std::hypot(p.x1, p.y1); };
    for (int i = 1; i < 200; ++i) {
      const double s = l.length * i / 200;
      if (s < h || s > l.length - h) continue;
      const double th1 = (theta(s + h) - theta(s - h)) / (2 * h);
      const double th2 = (theta(s + h) - 2 * theta(s) + theta(s - h)) / (h * h);
      const double r2 = (radius(s + h) - 2 * radius(s) + radius(s - h)) / (h * h);
      EXPECT_LE(std::abs(th1), l.theta_s_max * (1 + 1e-6) + 1e-9);
      EXPECT_LE(std::abs(th2), l.theta_ss_max * (1 + 1e-3) + 1e-6);
      EXPECT_LE(std::abs(r2), l.r_ss_max * (1 + 1e-3) + 1e-6);
      EXPECT_GE(radius(s), l.r_min - 1e-9);
    }
  }
}

TEST(CoordinateTransformation, LinesThroughTheCentreAreMarked) {
  EXPECT_TRUE(FaceLineOf({-10, 0}, {10, 0}).through_centre);
  EXPECT_TRUE(FaceLineOf({0, 0}, {10, 5}).through_centre);
  EXPECT_FALSE(FaceLineOf({5, 0}, {10, 0}).through_centre);  // radial, one side: C constant
  EXPECT_FALSE(FaceLineOf({-10, 1}, {10, 1}).through_centre);
  EXPECT_NEAR(FaceLineOf({-10, 1}, {10, 1}).d, 1, 1e-12);
}

// Brute force: chords linear in (X, C) between points FaceChordStep apart, sampled densely,
// stay within the tolerance of the line (the distance of each chord point from the line).
TEST(CoordinateTransformation, ChordsStayWithinTheToleranceOfTheLine) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coordinate(-50, 50);
  const double tolerance = 1e-3;
  double worst_ratio = 0;
  for (int k = 0; k < 60; ++k) {
    const FictivePoint a{coordinate(rng), coordinate(rng)}, b{coordinate(rng), coordinate(rng)};
    const FaceLine l = FaceLineOf(a, b);
    if (l.through_centre || l.length < 1 || l.d < 0.5) continue;
    const int chords = static_cast<int>(std::ceil(l.length / FaceChordStep(l, tolerance)));
    const double nx = -(b.y1 - a.y1) / l.length, ny = (b.x1 - a.x1) / l.length;
    double x0 = 0, c0 = 0;
    FaceToMachine(a, x0, c0);
    double prev_x = x0, prev_c = c0;
    for (int i = 1; i <= chords; ++i) {
      const double u = static_cast<double>(i) / chords;
      const FictivePoint p{a.x1 + (b.x1 - a.x1) * u, a.y1 + (b.y1 - a.y1) * u};
      const double x = std::hypot(p.x1, p.y1), c = c0 + SweepDeg(a, p);
      for (int j = 1; j < 16; ++j) {
        const double t = j / 16.0;
        const FictivePoint q = MachineToFace(prev_x + (x - prev_x) * t, prev_c + (c - prev_c) * t);
        const double off = std::abs((q.x1 - a.x1) * nx + (q.y1 - a.y1) * ny);
        worst_ratio = std::max(worst_ratio, off / tolerance);
      }
      prev_x = x, prev_c = c;
    }
  }
  EXPECT_LE(worst_ratio, 1.0);
  EXPECT_GT(worst_ratio, 0.05);  // the bound is not absurdly loose
}

// ---- G02/G03 in the face ----

double OffCircle(FictivePoint p, const FaceArc& arc) {
  return std::abs(std::hypot(p.x1 - arc.centre.x1, p.y1 - arc.centre.y1) - arc.radius);
}

TEST(CoordinateTransformation, FaceArcsFromCentreOrRadius) {
  std::string error;
  // G02 R30 from X1 20 Y1 0 to X1 20 Y1 20: the centre right of the chord, 39 deg clockwise.
  FaceArc a = FaceArcOf({20, 0}, {20, 20}, true, false, 0, 0, 30, error);
  ASSERT_EQ(error, "");
  EXPECT_NEAR(a.centre.x1, 20 + std::sqrt(800.0), 1e-12);
  EXPECT_NEAR(a.centre.y1, 10, 1e-12);
  EXPECT_NEAR(a.radius, 30, 1e-12);
  EXPECT_NEAR(a.sweep * kDeg, -2 * std::asin(10.0 / 30) * kDeg, 1e-9);
  EXPECT_NEAR(FaceArcSweepDeg(a), 45, 1e-9);  // C from 0 to 45 deg, as the line would
  // R < 0: the arc over 180 deg.
  a = FaceArcOf({20, 0}, {20, 20}, true, false, 0, 0, -30, error);
  ASSERT_EQ(error, "");
  EXPECT_NEAR(a.sweep * kDeg, -(360 - 2 * std::asin(10.0 / 30) * kDeg), 1e-9);
  // I/J relative to the start; end = start: a full circle.
  a = FaceArcOf({10, 0}, {10, 0}, false, true, -10, 0, 0, error);
  ASSERT_EQ(error, "");
  EXPECT_NEAR(a.sweep, 2 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(FaceArcSweepDeg(a), 360, 1e-9);  // about the centre: C one turn on
  EXPECT_NEAR(FaceArcSweepDeg(a, 0.25), 90, 1e-9);
  a = FaceArcOf({10, 0}, {10, 0}, true, true, -10, 0, 0, error);
  EXPECT_NEAR(FaceArcSweepDeg(a), -360, 1e-9);  // G02: the other way
  a = FaceArcOf({10, 0}, {10, 0}, false, true, -6, 0, 0, error);  // centre inside, off-axis
  EXPECT_NEAR(FaceArcSweepDeg(a), 360, 1e-9);
  a = FaceArcOf({10, 0}, {10, 0}, false, true, -4, 0, 0, error);  // the centre outside
  EXPECT_NEAR(FaceArcSweepDeg(a), 0, 1e-9);
  EXPECT_FALSE(FaceArcBoundsOf(a).through_centre);
  EXPECT_NEAR(FaceArcBoundsOf(a).r_min, 2, 1e-12);
  EXPECT_NEAR(FaceArcBoundsOf(a).r_max, 10, 1e-12);
  // Through the centre: marked; half way round (not through it) it is not.
  a = FaceArcOf({10, 0}, {10, 0}, false, true, -5, 0, 0, error);
  EXPECT_TRUE(FaceArcBoundsOf(a).through_centre);
  a = FaceArcOf({10, 0}, {0, 0}, false, true, -5, 0, 0, error);  // ends in it
  EXPECT_TRUE(FaceArcBoundsOf(a).through_centre);
  a = FaceArcOf({10, 0}, {5, 5}, false, true, -5, 0, 0, error);
  EXPECT_FALSE(FaceArcBoundsOf(a).through_centre);
  EXPECT_NEAR(FaceArcBoundsOf(a).r_min, std::hypot(5, 5), 1e-12);
  // Bad words.
  FaceArcOf({10, 0}, {30, 0}, false, false, 0, 0, 5, error);
  EXPECT_EQ(error, "radius R too small for the end point");
  FaceArcOf({10, 0}, {10, 0}, false, false, 0, 0, 5, error);
  EXPECT_NE(error.find("full circle"), std::string::npos);
  FaceArcOf({10, 0}, {20, 0}, false, true, 1, 0, 0, error);
  EXPECT_NE(error.find("end point not on the arc"), std::string::npos);
  FaceArcOf({10, 0}, {20, 0}, false, false, 0, 0, 0, error);
  EXPECT_NE(error.find("needs a centre"), std::string::npos);
}

// Random arcs: X = |P| and C = C0 + FaceArcSweepDeg transformed back lie on the circle, at the
// arc's point (C unwound the way the arc goes), checked against C summed in fine steps; the
// derivative bounds hold by finite differences; chords linear in X and C FaceChordStep apart
// stay within the tolerance of the circle.
TEST(CoordinateTransformation, FaceArcsStayOnTheCircleByBruteForce) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> coordinate(-40, 40), radius(0.5, 30);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> sweep(-2 * std::numbers::pi, 2 * std::numbers::pi);
  const double tolerance = 1e-3;
  int arcs = 0, around = 0;
  double worst_ratio = 0;
  for (int k = 0; k < 300; ++k) {
    FaceArc arc;
    arc.centre = {coordinate(rng), coordinate(rng)};
    arc.radius = radius(rng);
    arc.start_angle = angle(rng);
    arc.sweep = sweep(rng);
    const FaceLine b = FaceArcBoundsOf(arc);
    if (b.through_centre || b.r_min < 0.3) continue;
    ++arcs;
    const FictivePoint a = arc.At(0);
    double x0 = 0, c0 = 0;
    FaceToMachine(a, x0, c0);
    // C summed in steps far below half a turn each.
    const int fine = 20000;
    double c_fine = c0;
    FictivePoint last = a;
    for (int i = 1; i <= fine; ++i) {
      const double u = static_cast<double>(i) / fine;
      const FictivePoint p = arc.At(u);
      c_fine += SweepDeg(last, p);
      last = p;
      if (i % 100 != 0) continue;
      const double c = c0 + FaceArcSweepDeg(arc, u);
      ASSERT_NEAR(c, c_fine, 1e-6) << k << " u " << u;
      const FictivePoint q = MachineToFace(std::hypot(p.x1, p.y1), c);
      EXPECT_LT(std::hypot(q.x1 - p.x1, q.y1 - p.y1), 1e-9);
      EXPECT_LT(OffCircle(q, arc), 1e-6);
      EXPECT_GE(std::hypot(p.x1, p.y1), b.r_min - 1e-9);
      EXPECT_LE(std::hypot(p.x1, p.y1), b.r_max + 1e-9);
    }
    if (std::abs(c_fine - c0) > 300) ++around;
    // Bounds of r'' and th', th'' by finite differences along s.
    const double h = 1e-3, length = b.length;
    const auto at_s = [&](double s) { return arc.At(s / length); };
    const auto theta = [&](double s) { return (c0 + FaceArcSweepDeg(arc, s / length)) / kDeg; };
    const auto r = [&](double s) {
      const FictivePoint p = at_s(s);
      return std::hypot(p.x1, p.y1);
    };
    for (int i = 1; i < 50 && length > 4 * h; ++i) {
      const double s = length * i / 50;
      const double th1 = (theta(s + h) - theta(s - h)) / (2 * h);
      const double th2 = (theta(s + h) - 2 * theta(s) + theta(s - h)) / (h * h);
      const double r2 = (r(s + h) - 2 * r(s) + r(s - h)) / (h * h);
      EXPECT_LE(std::abs(th1), b.theta_s_max * (1 + 1e-6) + 1e-9);
      EXPECT_LE(std::abs(th2), b.theta_ss_max * (1 + 1e-3) + 1e-5);
      EXPECT_LE(std::abs(r2), b.r_ss_max * (1 + 1e-3) + 1e-5);
    }
    // Chords.
    const int chords = static_cast<int>(std::ceil(length / FaceChordStep(b, tolerance)));
    double prev_x = x0, prev_c = c0;
    for (int i = 1; i <= chords; ++i) {
      const double u = static_cast<double>(i) / chords;
      const FictivePoint p = arc.At(u);
      const double x = std::hypot(p.x1, p.y1), c = c0 + FaceArcSweepDeg(arc, u);
      for (int j = 1; j < 16; ++j) {
        const double t = j / 16.0;
        const FictivePoint q = MachineToFace(prev_x + (x - prev_x) * t, prev_c + (c - prev_c) * t);
        worst_ratio = std::max(worst_ratio, OffCircle(q, arc) / tolerance);
      }
      prev_x = x, prev_c = c;
    }
  }
  EXPECT_GT(arcs, 150);
  EXPECT_GE(around, 5);  // arcs that go round the spindle axis: C a turn on
  EXPECT_LE(worst_ratio, 1.0);
  EXPECT_GT(worst_ratio, 0.01);  // the bound is not absurdly loose
}

}  // namespace
}  // namespace vmt::control::nc
