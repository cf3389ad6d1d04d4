#include "sim/model/revolved_part.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace vmt::sim {
namespace {

// Two sections meet when one ends where the other begins; their z values come from the same
// numbers in a scene, so anything closer than this is the same plane.
constexpr double kSamePlaneM = 1e-12;

// A piece of the meridian outline, (r, z), with the outward normal of the material beside it.
struct Edge {
  Eigen::Vector2d a, b, normal;
};

// Calls visit(edge) for each piece of the part's outline in the meridian half-plane r >= 0:
// every side of every section's rectangle, less what a section on its other side covers (two
// sections share no material, so only a neighbour whose own side lies on the same line can).
// No container: the stylus asks this every drive tick.
template <class Visit>
void ForEachOutlineEdge(const RevolvedPart& part, Visit&& visit) {
  const std::vector<RevolvedSection>& all = part.sections;
  // The side on line `at` along [lo, hi] (of the other coordinate), less the sides of sections
  // from index `from` on that lie on the same line from the other side; `radial` sides run
  // along z at r = at.
  auto side = [&](auto&& self, bool radial, double at, double lo, double hi, double normal,
                  size_t from) -> void {
    for (size_t j = from; j < all.size(); ++j) {
      const RevolvedSection& n = all[j];
      // The neighbour's side facing this one: its inner (outer) radius beside an outer (inner)
      // side, its start (end) beside an end (start) face.
      const double its =
          radial ? (normal > 0 ? n.r_inner_m : n.r_outer_m) : (normal > 0 ? n.z0_m : n.z1_m);
      if (std::abs(its - at) > kSamePlaneM) continue;
      const double n_lo = radial ? n.z0_m : n.r_inner_m, n_hi = radial ? n.z1_m : n.r_outer_m;
      if (n_hi <= lo || n_lo >= hi) continue;
      if (n_lo > lo) self(self, radial, at, lo, n_lo, normal, j + 1);
      if (n_hi < hi) self(self, radial, at, n_hi, hi, normal, j + 1);
      return;
    }
    if (hi <= lo) return;
    if (radial)
      visit(Edge{{at, lo}, {at, hi}, {normal, 0}});
    else
      visit(Edge{{lo, at}, {hi, at}, {0, normal}});
  };
  for (const RevolvedSection& s : all) {
    side(side, true, s.r_outer_m, s.z0_m, s.z1_m, 1, 0);
    if (s.r_inner_m > 0) side(side, true, s.r_inner_m, s.z0_m, s.z1_m, -1, 0);
    side(side, false, s.z1_m, s.r_inner_m, s.r_outer_m, 1, 0);
    side(side, false, s.z0_m, s.r_inner_m, s.r_outer_m, -1, 0);
  }
}

bool Inside(const RevolvedPart& part, const Eigen::Vector2d& p) {
  for (const RevolvedSection& s : part.sections)
    if (p.x() >= s.r_inner_m && p.x() <= s.r_outer_m && p.y() >= s.z0_m && p.y() <= s.z1_m)
      return true;
  return false;
}

}  // namespace

RevolvedDistance SignedDistance(const RevolvedPart& part, const Eigen::Vector3d& p_Link_m) {
  RevolvedDistance out;
  out.distance_m = std::numeric_limits<double>::infinity();
  const double r = std::hypot(p_Link_m.x(), p_Link_m.y());
  const Eigen::Vector3d e_r =
      r > 0 ? Eigen::Vector3d(p_Link_m.x() / r, p_Link_m.y() / r, 0) : Eigen::Vector3d::UnitX();
  const Eigen::Vector2d p(r, p_Link_m.z());

  double nearest = std::numeric_limits<double>::infinity();
  Eigen::Vector2d q = p, edge_normal = Eigen::Vector2d::Zero();
  ForEachOutlineEdge(part, [&](const Edge& e) {
    const Eigen::Vector2d ab = e.b - e.a;
    const double u = std::clamp((p - e.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const Eigen::Vector2d on = e.a + u * ab;
    const double d = (p - on).norm();
    if (d < nearest) nearest = d, q = on, edge_normal = e.normal;
  });
  if (!std::isfinite(nearest)) return out;

  const bool inside = Inside(part, p);
  out.distance_m = inside ? -nearest : nearest;
  // Off the surface the direction to (or from) the nearest point is the gradient, also round a
  // corner; on it, the edge's own normal.
  Eigen::Vector2d n = edge_normal;
  if (nearest > 0)
    n = inside ? Eigen::Vector2d((q - p) / nearest) : Eigen::Vector2d((p - q) / nearest);
  out.normal = n.x() * e_r + n.y() * Eigen::Vector3d::UnitZ();
  out.point_m = q.x() * e_r + q.y() * Eigen::Vector3d::UnitZ();
  return out;
}

double DistanceLowerBound(const RevolvedPart& part, const Eigen::Vector3d& p_Link_m) {
  if (part.sections.empty()) return std::numeric_limits<double>::infinity();
  double r_max = 0, z_min = std::numeric_limits<double>::infinity(), z_max = -z_min;
  for (const RevolvedSection& s : part.sections) {
    r_max = std::max(r_max, s.r_outer_m);
    z_min = std::min(z_min, s.z0_m);
    z_max = std::max(z_max, s.z1_m);
  }
  const double r = std::hypot(p_Link_m.x(), p_Link_m.y());
  const double dr = r - r_max, dz = std::max(z_min - p_Link_m.z(), p_Link_m.z() - z_max);
  if (dr <= 0 && dz <= 0) return -std::numeric_limits<double>::infinity();
  return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0));
}

std::string RevolvedPartError(const RevolvedPart& part) {
  for (size_t i = 0; i < part.sections.size(); ++i) {
    const RevolvedSection& s = part.sections[i];
    const std::string name = "sections[" + std::to_string(i) + "]";
    if (!std::isfinite(s.z0_m) || !std::isfinite(s.z1_m) || !std::isfinite(s.r_inner_m) ||
        !std::isfinite(s.r_outer_m))
      return name + ": a number that is not finite";
    if (!(s.z1_m > s.z0_m)) return name + ": z1 must be greater than z0";
    if (s.r_inner_m < 0) return name + ": r_inner must be >= 0";
    if (!(s.r_outer_m > s.r_inner_m)) return name + ": r_outer must be greater than r_inner";
    for (size_t j = 0; j < i; ++j) {
      const RevolvedSection& o = part.sections[j];
      if (std::min(s.z1_m, o.z1_m) - std::max(s.z0_m, o.z0_m) > kSamePlaneM &&
          std::min(s.r_outer_m, o.r_outer_m) - std::max(s.r_inner_m, o.r_inner_m) > kSamePlaneM)
        return name + ": shares material with sections[" + std::to_string(j) + "]";
    }
  }
  return "";
}

}  // namespace vmt::sim
