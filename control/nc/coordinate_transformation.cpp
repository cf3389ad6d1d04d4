#include "control/nc/coordinate_transformation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace vmt::control::nc {
namespace {

constexpr double kDegPerRad = 180 / std::numbers::pi;

}  // namespace

void FaceToMachine(FictivePoint p, double& x, double& c_deg) {
  x = std::hypot(p.x1, p.y1);
  c_deg = x > 0 ? std::atan2(p.y1, p.x1) * kDegPerRad : 0;
}

FictivePoint MachineToFace(double x, double c_deg) {
  const double c = c_deg / kDegPerRad;
  return {x * std::cos(c), x * std::sin(c)};
}

double SweepDeg(FictivePoint a, FictivePoint b) {
  const double cross = a.x1 * b.y1 - a.y1 * b.x1, dot = a.x1 * b.x1 + a.y1 * b.y1;
  if ((a.x1 == 0 && a.y1 == 0) || (b.x1 == 0 && b.y1 == 0)) return 0;
  return std::atan2(cross, dot) * kDegPerRad;
}

double FaceC(FictivePoint p, double near_deg) {
  if (p.x1 == 0 && p.y1 == 0) return near_deg;
  const double c = std::atan2(p.y1, p.x1) * kDegPerRad;
  return near_deg + std::remainder(c - near_deg, 360.0);
}

double CylinderC(double y1, double radius) { return y1 / radius * kDegPerRad; }
double CylinderY1(double c_deg, double radius) { return c_deg / kDegPerRad * radius; }

FaceLine FaceLineOf(FictivePoint a, FictivePoint b) {
  FaceLine l;
  const double dx = b.x1 - a.x1, dy = b.y1 - a.y1;
  l.length = std::hypot(dx, dy);
  const double ra = std::hypot(a.x1, a.y1), rb = std::hypot(b.x1, b.y1);
  l.r_max = std::max(ra, rb);
  if (l.length < 1e-12) {
    l.r_min = std::min(ra, rb);
    return l;
  }
  // Arc length coordinates from the foot of the perpendicular: s_a, s_b along the direction.
  const double ux = dx / l.length, uy = dy / l.length;
  const double sa = a.x1 * ux + a.y1 * uy, sb = sa + l.length;
  l.d = std::abs(a.x1 * uy - a.y1 * ux);
  const double s_near = sa <= 0 && sb >= 0 ? 0 : std::min(std::abs(sa), std::abs(sb));
  l.r_min = std::hypot(l.d, s_near);
  // A radial line (d = 0) that stays on one side keeps C: only one through the centre (or
  // starting or ending in it) has no defined C.
  l.through_centre = l.r_min < kFaceCentreClearance;
  if (l.through_centre) return l;
  l.theta_s_max = l.d / (l.r_min * l.r_min);
  l.r_ss_max = l.d * l.d / (l.r_min * l.r_min * l.r_min);
  // |th''| = 2 d |s| / r^4 rises up to |s| = d / sqrt(3), then falls: its maximum on the
  // segment is at the |s| in [s_lo, s_hi] nearest d / sqrt(3).
  const double s_lo = s_near, s_hi = std::max(std::abs(sa), std::abs(sb));
  const double s_peak = std::clamp(l.d / std::sqrt(3.0), s_lo, s_hi);
  const double r2 = l.d * l.d + s_peak * s_peak;
  l.theta_ss_max = r2 > 0 ? 2 * l.d * s_peak / (r2 * r2) : 0;
  return l;
}

double FaceChordStep(const FaceLine& line, double tolerance_mm) {
  const double curvature = line.r_ss_max + line.r_max * line.theta_ss_max;
  if (!(curvature > 0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(8 * tolerance_mm / curvature);
}

}  // namespace vmt::control::nc
