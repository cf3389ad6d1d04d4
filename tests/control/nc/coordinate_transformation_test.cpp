// The geometry of G31/G32 (coordinate_transformation.hpp): round trips, the sweep along a line,
// the derivative bounds of a face line against finite differences, and the chord bound against
// brute force.

#include "control/nc/coordinate_transformation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

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

}  // namespace
}  // namespace vmt::control::nc
