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

FictivePoint FaceArc::At(double u) const {
  const double angle = start_angle + sweep * u;
  return {centre.x1 + radius * std::cos(angle), centre.y1 + radius * std::sin(angle)};
}

FictivePoint FaceArc::Tangent(double u) const {
  const double angle = start_angle + sweep * u;
  return {-radius * sweep * std::sin(angle), radius * sweep * std::cos(angle)};
}

FaceArc FaceArcOf(FictivePoint from, FictivePoint to, bool clockwise, bool has_centre, double i,
                  double j, double r, std::string& error) {
  FaceArc arc;
  error.clear();
  const double dx = to.x1 - from.x1, dy = to.y1 - from.y1, chord = std::hypot(dx, dy);
  double cx = 0, cy = 0;
  if (has_centre) {
    cx = from.x1 + i;
    cy = from.y1 + j;
  } else if (r != 0) {
    // On the chord's bisector, as G17..G19 place it; R < 0 picks the arc over 180 degrees.
    const double rr = std::abs(r);
    if (chord < 1e-12) {
      error = "a full circle of G31 needs its centre (I/J), not R";
      return arc;
    }
    if (chord > 2 * rr + kFaceArcTolerance) {
      error = "radius R too small for the end point";
      return arc;
    }
    const double h = std::sqrt(std::max(0.0, rr * rr - chord * chord / 4));
    const double side = ((r > 0) == clockwise) ? -1 : 1;
    cx = (from.x1 + to.x1) / 2 - side * h * dy / chord;
    cy = (from.y1 + to.y1) / 2 + side * h * dx / chord;
  } else {
    error = "G02/G03 of G31 needs a centre (I for X1, J for Y1) or a radius R";
    return arc;
  }
  const double r_start = std::hypot(from.x1 - cx, from.y1 - cy);
  const double r_end = std::hypot(to.x1 - cx, to.y1 - cy);
  if (std::abs(r_start - r_end) > kFaceArcTolerance || r_start < 1e-9) {
    error = "end point not on the arc (radius " + std::to_string(r_start) + " at the start, " +
            std::to_string(r_end) + " at the end)";
    return arc;
  }
  arc.centre = {cx, cy};
  arc.radius = r_start;
  arc.start_angle = std::atan2(from.y1 - cy, from.x1 - cx);
  // The end's angle, swept the programmed way; end = start is a full circle (as in G17..G19).
  double sweep = std::atan2(to.y1 - cy, to.x1 - cx) - arc.start_angle;
  if (clockwise) {
    while (sweep >= -1e-12) sweep -= 2 * std::numbers::pi;
  } else {
    while (sweep <= 1e-12) sweep += 2 * std::numbers::pi;
  }
  if (std::abs(std::abs(sweep) - 2 * std::numbers::pi) < 1e-9 && chord > 1e-9)
    sweep = std::fmod(sweep, 2 * std::numbers::pi);
  arc.sweep = sweep;
  return arc;
}

namespace {

// C's change along the piece u0..u1 of the arc (at most 90 deg of arc): the chord's sweep, plus
// a turn where the centre lies between the piece and its chord (header comment).
double PieceSweepDeg(const FaceArc& arc, double u0, double u1, int depth) {
  const FictivePoint s = arc.At(u0), e = arc.At(u1);
  const double dx = e.x1 - s.x1, dy = e.y1 - s.y1, l2 = dx * dx + dy * dy;
  if (l2 < 1e-30) return 0;
  // A chord through the centre has no defined sweep: halves of the piece have chords that
  // miss it (three points of a circle are never on one line).
  const double t = std::clamp(-(s.x1 * dx + s.y1 * dy) / l2, 0.0, 1.0);
  if (std::hypot(s.x1 + t * dx, s.y1 + t * dy) < 1e-9 && depth < 8) {
    const double um = (u0 + u1) / 2;
    return PieceSweepDeg(arc, u0, um, depth + 1) + PieceSweepDeg(arc, um, u1, depth + 1);
  }
  double sweep = SweepDeg(s, e);
  const double ox = -arc.centre.x1, oy = -arc.centre.y1;  // the spindle axis from the arc's centre
  if (ox * ox + oy * oy < arc.radius * arc.radius) {
    const FictivePoint m = arc.At((u0 + u1) / 2);
    const double side_centre = dx * (0 - s.y1) - dy * (0 - s.x1);
    const double side_arc = dx * (m.y1 - s.y1) - dy * (m.x1 - s.x1);
    if (side_centre * side_arc > 0) sweep += arc.sweep > 0 ? 360 : -360;
  }
  return sweep;
}

// Whether the arc passes the angle `phi` (rad, about its centre).
bool ArcPasses(const FaceArc& arc, double phi) {
  const double turn = 2 * std::numbers::pi;
  const double rel = arc.sweep >= 0 ? phi - arc.start_angle : arc.start_angle - phi;
  const double wrapped = rel - turn * std::floor(rel / turn);
  return wrapped <= std::abs(arc.sweep);
}

}  // namespace

double FaceArcSweepDeg(const FaceArc& arc, double u) {
  const int pieces = std::max(
      1, static_cast<int>(std::ceil(std::abs(arc.sweep * u) / (std::numbers::pi / 2) - 1e-12)));
  double sum = 0;
  for (int k = 0; k < pieces; ++k)
    sum += PieceSweepDeg(arc, u * k / pieces, u * (k + 1) / pieces, 0);
  return sum;
}

FaceLine FaceArcBoundsOf(const FaceArc& arc) {
  FaceLine b;
  b.length = arc.radius * std::abs(arc.sweep);
  const FictivePoint s = arc.At(0), e = arc.At(1);
  const double rs = std::hypot(s.x1, s.y1), re = std::hypot(e.x1, e.y1);
  b.r_min = std::min(rs, re);
  b.r_max = std::max(rs, re);
  // The circle's nearest and furthest points from the spindle axis, where the arc passes them.
  const double d = std::hypot(arc.centre.x1, arc.centre.y1);
  if (d > 0) {
    const double far = std::atan2(arc.centre.y1, arc.centre.x1);
    if (ArcPasses(arc, far + std::numbers::pi)) b.r_min = std::abs(d - arc.radius);
    if (ArcPasses(arc, far)) b.r_max = d + arc.radius;
  }
  b.through_centre = b.r_min < kFaceCentreClearance;
  if (b.through_centre || !(arc.radius > 0)) return b;
  b.theta_s_max = 1 / b.r_min;
  b.r_ss_max = (1 + d / arc.radius) / b.r_min;
  b.theta_ss_max = 1 / (arc.radius * b.r_min) + 1 / (b.r_min * b.r_min);
  return b;
}

double FaceChordStep(const FaceLine& line, double tolerance_mm) {
  const double curvature = line.r_ss_max + line.r_max * line.theta_ss_max;
  if (!(curvature > 0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(8 * tolerance_mm / curvature);
}

}  // namespace vmt::control::nc
