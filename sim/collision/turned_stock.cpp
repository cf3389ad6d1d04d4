#include "sim/collision/turned_stock.hpp"

#include <algorithm>
#include <cmath>

namespace vmt::sim {
namespace {

// Far below any tolerance of the part, above the rounding of a point turned with the part.
constexpr double kLowerM = 1e-9;

/// The part of a convex polygon between the planes z = lo and z = hi.
std::vector<Eigen::Vector3d> ClipToSlab(std::vector<Eigen::Vector3d> poly, double lo, double hi) {
  for (const double sign : {1.0, -1.0}) {
    const double bound = sign > 0 ? lo : hi;  // keep sign * (z - bound) >= 0
    std::vector<Eigen::Vector3d> out;
    for (size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector3d& p = poly[i];
      const Eigen::Vector3d& q = poly[(i + 1) % poly.size()];
      const double dp = sign * (p.z() - bound), dq = sign * (q.z() - bound);
      if (dp >= 0) out.push_back(p);
      if ((dp >= 0) != (dq >= 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
    }
    poly = std::move(out);
    if (poly.empty()) break;
  }
  return poly;
}

/// The smallest distance from the z axis of a convex planar polygon: of its projection onto the
/// xy plane from the origin, 0 if the projection covers it.
double AxisDistance(const std::vector<Eigen::Vector3d>& poly) {
  double best = 1e300;
  double sign = 0, area2 = 0;
  bool inside = true;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d p = poly[i].head<2>(), q = poly[(i + 1) % poly.size()].head<2>();
    const Eigen::Vector2d e = q - p;
    const double len2 = e.squaredNorm();
    const double t = len2 > 0 ? std::clamp(-p.dot(e) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (p + e * t).norm());
    area2 += p.x() * q.y() - q.x() * p.y();
    const double cross = e.x() * -p.y() - e.y() * -p.x();
    if (cross != 0) {
      if (sign == 0) sign = cross;
      if (cross * sign < 0) inside = false;
    }
  }
  // A face seen edge-on projects to a segment: rounding must not make it cover the axis.
  constexpr double kSquareMicron = 1e-12;
  return inside && std::abs(area2) > kSquareMicron ? 0.0 : best;
}

}  // namespace

TurnedStock TurnedStock::FromCylinder(const CylinderPart& stock, double slice_m) {
  TurnedStock t;
  t.name = stock.name;
  t.link = stock.link;
  t.z0_m = stock.z_m;
  t.slice_m = slice_m;
  const size_t n = static_cast<size_t>(std::max(1.0, std::ceil(stock.length_m / slice_m - 1e-9)));
  t.radius_m.assign(n, stock.radius_m);
  return t;
}

TurnedStock TurnedStock::FromPart(const RevolvedPart& part, double slice_m) {
  TurnedStock t;
  t.name = part.name;
  t.link = part.link;
  t.slice_m = slice_m;
  double z_end = 0;
  bool any = false;
  for (const RevolvedSection& s : part.sections) {
    if (s.r_inner_m > 0) {
      t.rings.push_back({part.name, part.link, s.r_outer_m, s.z1_m - s.z0_m, s.z0_m, s.r_inner_m});
      continue;
    }
    t.z0_m = any ? std::min(t.z0_m, s.z0_m) : s.z0_m;
    z_end = any ? std::max(z_end, s.z1_m) : s.z1_m;
    any = true;
  }
  if (!any) return t;
  const size_t n = static_cast<size_t>(std::max(1.0, std::ceil((z_end - t.z0_m) / slice_m - 1e-9)));
  t.radius_m.assign(n, 0.0);
  for (const RevolvedSection& s : part.sections) {
    if (s.r_inner_m > 0) continue;
    // Slices the section overlaps by more than a rounding error.
    const double first = std::floor((s.z0_m - t.z0_m) / slice_m + 1e-9);
    const double last = std::ceil((s.z1_m - t.z0_m) / slice_m - 1e-9);
    for (size_t k = static_cast<size_t>(std::max(0.0, first));
         k < std::min(n, static_cast<size_t>(std::max(0.0, last))); ++k)
      t.radius_m[k] = std::max(t.radius_m[k], s.r_outer_m);
  }
  return t;
}

bool TurnedStock::Cut(double z_m, double r_m, double allowance_m) {
  // The point cuts as a small ball of the allowance: every slice within it along z too, so the
  // slice ahead of a tool's leading face, which the face touches at their common boundary, is
  // cut as well.
  const double n = static_cast<double>(radius_m.size());
  const double first = std::max(0.0, std::floor((z_m - allowance_m - z0_m) / slice_m));
  const double last = std::min(n - 1, std::floor((z_m + allowance_m - z0_m) / slice_m));
  if (!(first <= last)) return false;
  const double left = std::max(0.0, r_m - allowance_m);
  bool changed = false;
  for (auto k = static_cast<size_t>(first); k <= static_cast<size_t>(last); ++k) {
    if (left >= radius_m[k] - kLowerM) continue;
    radius_m[k] = left;
    changed = true;
  }
  return changed;
}

bool TurnedStock::CutTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c, double allowance_m) {
  const double n = static_cast<double>(radius_m.size());
  const double z_lo = std::min({a.z(), b.z(), c.z()}), z_hi = std::max({a.z(), b.z(), c.z()});
  const double first = std::max(0.0, std::floor((z_lo - allowance_m - z0_m) / slice_m));
  const double last = std::min(n - 1, std::floor((z_hi + allowance_m - z0_m) / slice_m));
  if (!(first <= last)) return false;
  const auto k0 = static_cast<size_t>(first), k1 = static_cast<size_t>(last);
  // Most of a tool stands outside the part: one distance for the whole triangle tells.
  const std::vector<Eigen::Vector3d> triangle{a, b, c};
  const double highest = *std::max_element(radius_m.begin() + static_cast<std::ptrdiff_t>(k0),
                                           radius_m.begin() + static_cast<std::ptrdiff_t>(k1) + 1);
  if (AxisDistance(triangle) - allowance_m >= highest - kLowerM) return false;
  bool changed = false;
  for (size_t k = k0; k <= k1; ++k) {
    const double lo = z0_m + static_cast<double>(k) * slice_m - allowance_m;
    const std::vector<Eigen::Vector3d> piece =
        ClipToSlab(triangle, lo, lo + slice_m + 2 * allowance_m);
    if (piece.empty()) continue;
    const double left = std::max(0.0, AxisDistance(piece) - allowance_m);
    if (left >= radius_m[k] - kLowerM) continue;
    radius_m[k] = left;
    changed = true;
  }
  return changed;
}

std::vector<CylinderPart> TurnedStock::Cylinders(double tolerance_m) const {
  std::vector<CylinderPart> parts;
  size_t start = 0;
  while (start < radius_m.size()) {
    double lo = radius_m[start], hi = lo;
    size_t end = start + 1;
    for (; end < radius_m.size(); ++end) {
      const double r = radius_m[end];
      if (std::max(hi, r) - std::min(lo, r) > tolerance_m) break;
      lo = std::min(lo, r), hi = std::max(hi, r);
    }
    if (hi > 0)
      parts.push_back({name, link, hi, static_cast<double>(end - start) * slice_m,
                       z0_m + static_cast<double>(start) * slice_m});
    start = end;
  }
  parts.insert(parts.end(), rings.begin(), rings.end());
  return parts;
}

}  // namespace vmt::sim
