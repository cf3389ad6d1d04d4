#include "sim/collision/turned_stock.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace vmt::sim {
namespace {

// Far below any tolerance of the part, above the rounding of a point turned with the part.
constexpr double kLowerM = 1e-9;
// Material left thinner than this over a cut is no material: a ring of rounding errors.
constexpr double kThinnestM = 1e-6;

/// A triangle cut by two planes, on the stack: CutSolid clips every triangle in every slice it
/// crosses, each tick the tool cuts. Each plane at most doubles the corners (a corner and a
/// crossing per edge), so twelve hold any triangle's piece, even one rounding bent.
struct Piece {
  std::array<Eigen::Vector3d, 12> corners;
  size_t size = 0;
  const Eigen::Vector3d* begin() const { return corners.data(); }
  const Eigen::Vector3d* end() const { return corners.data() + size; }
};

/// The part of a triangle between the planes z = lo and z = hi.
Piece ClipToSlab(const Eigen::Vector3d* triangle, double lo, double hi) {
  Piece poly;
  std::copy(triangle, triangle + 3, poly.corners.begin());
  poly.size = 3;
  for (const double sign : {1.0, -1.0}) {
    const double bound = sign > 0 ? lo : hi;  // keep sign * (z - bound) >= 0
    Piece out;
    for (size_t i = 0; i < poly.size; ++i) {
      const Eigen::Vector3d& p = poly.corners[i];
      const Eigen::Vector3d& q = poly.corners[(i + 1) % poly.size];
      const double dp = sign * (p.z() - bound), dq = sign * (q.z() - bound);
      if (dp >= 0) out.corners[out.size++] = p;
      if ((dp >= 0) != (dq >= 0)) out.corners[out.size++] = p + (q - p) * (dp / (dp - dq));
    }
    poly = out;
    if (poly.size == 0) break;
  }
  return poly;
}

// A face seen edge-on projects to a segment: rounding must not make it cover the axis.
constexpr double kSquareMicron = 1e-12;

/// The smallest distance from the z axis of a convex planar polygon of `n` corners: of its
/// projection onto the xy plane from the origin, 0 if the projection covers it with more than
/// `edge_on_m2` of area (twice the area, m^2).
double AxisDistance(const Eigen::Vector3d* poly, size_t n, double edge_on_m2 = kSquareMicron) {
  // Squared distances compared, one square root taken: the root is monotonic and correctly
  // rounded, so the result is the same bits as the least of the roots.
  double best_squared = std::numeric_limits<double>::infinity();
  double sign = 0, area2 = 0;
  bool inside = true;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d p = poly[i].head<2>(), q = poly[(i + 1) % n].head<2>();
    const Eigen::Vector2d e = q - p;
    const double len2 = e.squaredNorm();
    const double t = len2 > 0 ? std::clamp(-p.dot(e) / len2, 0.0, 1.0) : 0.0;
    best_squared = std::min(best_squared, (p + e * t).squaredNorm());
    area2 += p.x() * q.y() - q.x() * p.y();
    const double cross = e.x() * -p.y() - e.y() * -p.x();
    if (cross != 0) {
      if (sign == 0) sign = cross;
      if (cross * sign < 0) inside = false;
    }
  }
  const double best = std::isinf(best_squared) ? 1e300 : std::sqrt(best_squared);
  return inside && std::abs(area2) > edge_on_m2 ? 0.0 : best;
}

/// The convex hull of the points' projections onto the xy plane, counter-clockwise (Andrew's
/// monotone chain); z is dropped.
std::vector<Eigen::Vector3d> Hull(std::vector<Eigen::Vector3d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const auto turn = [](const Eigen::Vector3d& o, const Eigen::Vector3d& a,
                       const Eigen::Vector3d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector3d> hull(2 * points.size() + 1);
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  for (Eigen::Vector3d& p : hull) p.z() = 0;
  return hull;
}

/// A triangle of a cutting part: whether it stands wholly above the material the part spans,
/// and its extent along the axis.
struct SolidTriangle {
  bool above = false;
  double z_lo = 0, z_hi = 0;
};

/// The ring a cutting part's hull sweeps in a slab of the axis, from its nearest to its
/// farthest point, without the triangles above the material; `above`: one of those reaches
/// into the slab, so the sweep reaches above the material there.
struct Sweep {
  bool any = false, above = false;
  double r_min = 0, r_max = 0;
};

// The rounding of a piece's corners and distances is below 1e-15 m; bounds carry this much.
constexpr double kBoundM = 1e-10;
// Slices swept as one slab first (CutSolid).
constexpr size_t kSlicesPerBlock = 8;

/// The hull's sweep between the planes z = lo and z = hi. As a `bound` (for a block of
/// slices), r_min is at most and r_max at least what any slab inside it sweeps, to the
/// rounding: every polygon covering the axis counts, and the hull of the pieces is taken
/// wherever their box comes near the axis.
Sweep SweepSlab(const std::vector<Eigen::Vector3d>& corners, const std::vector<SolidTriangle>& tri,
                double lo, double hi, bool bound, std::vector<Eigen::Vector3d>& points) {
  const double edge_on = bound ? 0.0 : kSquareMicron, near_axis = bound ? kBoundM : 0.0;
  Sweep sweep;
  sweep.r_min = std::numeric_limits<double>::infinity();
  Eigen::Vector2d box_lo = Eigen::Vector2d::Constant(sweep.r_min), box_hi = -box_lo;
  points.clear();
  double r_max_squared = 0;  // one root at the end, as in AxisDistance
  for (size_t i = 0; i < tri.size(); ++i) {
    if (tri[i].z_hi < lo || tri[i].z_lo > hi) continue;
    if (tri[i].above) {
      sweep.above = true;
      continue;
    }
    const Piece piece = ClipToSlab(&corners[3 * i], lo, hi);
    if (piece.size == 0) continue;
    sweep.any = true;
    sweep.r_min = std::min(sweep.r_min, AxisDistance(piece.begin(), piece.size, edge_on));
    for (const Eigen::Vector3d& p : piece) {
      r_max_squared = std::max(r_max_squared, p.head<2>().squaredNorm());
      box_lo = box_lo.cwiseMin(p.head<2>()), box_hi = box_hi.cwiseMax(p.head<2>());
      points.push_back(p);
    }
  }
  sweep.r_max = std::sqrt(r_max_squared);
  // The slab's cut through the hull may hold the axis with no triangle across it (a drill's
  // flank runs along the axis): the hull of the pieces tells.
  if (sweep.any && sweep.r_min > 0 && (box_lo.array() <= near_axis).all() &&
      (box_hi.array() >= -near_axis).all()) {
    const std::vector<Eigen::Vector3d> hull = Hull(points);
    sweep.r_min = std::min(sweep.r_min, AxisDistance(hull.data(), hull.size(), edge_on));
  }
  return sweep;
}

}  // namespace

TurnedStock TurnedStock::FromCylinder(const CylinderPart& stock, double slice_m) {
  TurnedStock t;
  t.name = stock.name;
  t.link = stock.link;
  t.z0_m = stock.z_m;
  t.slice_m = slice_m;
  const size_t n = static_cast<size_t>(std::max(1.0, std::ceil(stock.length_m / slice_m - 1e-9)));
  t.slices.assign(n, {StockSpan{stock.inner_radius_m, stock.radius_m}});
  return t;
}

TurnedStock TurnedStock::FromPart(const RevolvedPart& part, double slice_m) {
  TurnedStock t;
  t.name = part.name;
  t.link = part.link;
  t.slice_m = slice_m;
  if (part.sections.empty()) return t;
  double z_end = part.sections[0].z1_m;
  t.z0_m = part.sections[0].z0_m;
  for (const RevolvedSection& s : part.sections)
    t.z0_m = std::min(t.z0_m, s.z0_m), z_end = std::max(z_end, s.z1_m);
  const size_t n = static_cast<size_t>(std::max(1.0, std::ceil((z_end - t.z0_m) / slice_m - 1e-9)));
  t.slices.resize(n);
  for (const RevolvedSection& s : part.sections) {
    // Slices the section overlaps by more than a rounding error.
    const double first = std::floor((s.z0_m - t.z0_m) / slice_m + 1e-9);
    const double last = std::ceil((s.z1_m - t.z0_m) / slice_m - 1e-9);
    for (size_t k = static_cast<size_t>(std::max(0.0, first));
         k < std::min(n, static_cast<size_t>(std::max(0.0, last))); ++k)
      t.Add(k, s.r_inner_m, s.r_outer_m);
  }
  return t;
}

double TurnedStock::OuterRadius(size_t slice) const {
  return slices[slice].empty() ? 0.0 : slices[slice].back().outer_m;
}

void TurnedStock::Add(size_t slice, double inner_m, double outer_m) {
  std::vector<StockSpan>& spans = slices[slice];
  std::vector<StockSpan> merged;
  StockSpan added{inner_m, outer_m};
  bool placed = false;
  for (const StockSpan& s : spans) {
    if (s.outer_m < added.inner_m) {
      merged.push_back(s);
    } else if (s.inner_m > added.outer_m) {
      if (!placed) merged.push_back(added), placed = true;
      merged.push_back(s);
    } else {
      added = {std::min(added.inner_m, s.inner_m), std::max(added.outer_m, s.outer_m)};
    }
  }
  if (!placed) merged.push_back(added);
  spans = std::move(merged);
}

bool TurnedStock::Remove(size_t slice, double inner_m, double outer_m) {
  std::vector<StockSpan>& spans = slices[slice];
  bool changed = false;
  for (size_t i = 0; i < spans.size(); ++i) {
    const StockSpan s = spans[i];
    if (inner_m >= s.outer_m - kLowerM || outer_m <= s.inner_m + kLowerM) continue;
    changed = true;
    std::array<StockSpan, 2> left;
    size_t kept = 0;
    if (inner_m > s.inner_m) left[kept++] = {s.inner_m, inner_m};
    if (s.outer_m - outer_m > kThinnestM) left[kept++] = {outer_m, s.outer_m};
    spans.erase(spans.begin() + static_cast<std::ptrdiff_t>(i));
    spans.insert(spans.begin() + static_cast<std::ptrdiff_t>(i), left.begin(),
                 left.begin() + static_cast<std::ptrdiff_t>(kept));
    i += kept;
    --i;
  }
  return changed;
}

bool TurnedStock::TurnDown(double z_m, double r_m, double allowance_m) {
  // The point cuts as a small ball of the allowance: every slice within it along z too, so the
  // slice ahead of a tool's leading face, which the face touches at their common boundary, is
  // cut as well.
  const double n = static_cast<double>(slices.size());
  const double first = std::max(0.0, std::floor((z_m - allowance_m - z0_m) / slice_m));
  const double last = std::min(n - 1, std::floor((z_m + allowance_m - z0_m) / slice_m));
  if (!(first <= last)) return false;
  const double left = std::max(0.0, r_m - allowance_m);
  bool changed = false;
  for (auto k = static_cast<size_t>(first); k <= static_cast<size_t>(last); ++k)
    changed = Remove(k, left, std::numeric_limits<double>::infinity()) || changed;
  return changed;
}

bool TurnedStock::CutSolid(const std::vector<Eigen::Vector3d>& corners, double allowance_m) {
  if (corners.size() < 3 || slices.empty()) return false;
  const double n = static_cast<double>(slices.size());
  double z_lo = corners[0].z(), z_hi = z_lo;
  for (const Eigen::Vector3d& p : corners)
    z_lo = std::min(z_lo, p.z()), z_hi = std::max(z_hi, p.z());
  const double first = std::max(0.0, std::floor((z_lo - allowance_m - z0_m) / slice_m));
  const double last = std::min(n - 1, std::floor((z_hi + allowance_m - z0_m) / slice_m));
  if (!(first <= last)) return false;
  const auto k0 = static_cast<size_t>(first), k1 = static_cast<size_t>(last);
  double highest = 0;
  for (size_t k = k0; k <= k1; ++k) highest = std::max(highest, OuterRadius(k));
  // Most of a tool stands outside the part: each triangle's distance from the axis tells. A
  // triangle wholly above the material says only that the sweep reaches above it, wherever it
  // passes; the closed hull's nearest point lies on one of its triangles.
  const size_t triangles = corners.size() / 3;
  std::vector<SolidTriangle> tri(triangles);
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < triangles; ++i) {
    const Eigen::Vector3d &a = corners[3 * i], &b = corners[3 * i + 1], &c = corners[3 * i + 2];
    const double d = AxisDistance(&corners[3 * i], 3);
    nearest = std::min(nearest, d);
    tri[i] = {d - allowance_m >= highest - kLowerM, std::min({a.z(), b.z(), c.z()}),
              std::max({a.z(), b.z(), c.z()})};
  }
  if (nearest - allowance_m >= highest - kLowerM) return false;
  const auto slab_lo = [&](size_t k) {
    return z0_m + static_cast<double>(k) * slice_m - allowance_m;
  };
  // Most slices a tool spans lie where it stands clear of what is left or in its own cut. A
  // block of slices is swept as one slab first: what the hull sweeps in a slice lies within
  // what it sweeps in the block, so the block's ring bounds the slice's. Only the slices the
  // bounds cannot settle are swept one by one; the result is the same to the last bit.
  std::vector<Sweep> sweeps(k1 - k0 + 1);
  bool from_outside = false;
  std::vector<Eigen::Vector3d> points;
  for (size_t b0 = k0; b0 <= k1; b0 += kSlicesPerBlock) {
    const size_t b1 = std::min(k1, b0 + kSlicesPerBlock - 1);
    const Sweep block =
        SweepSlab(corners, tri, slab_lo(b0), slab_lo(b1) + slice_m + 2 * allowance_m, true, points);
    for (size_t k = b0; k <= b1; ++k) {
      const double lo = slab_lo(k), hi = lo + slice_m + 2 * allowance_m;
      const double outer = OuterRadius(k);
      const bool may_cut = block.any && block.r_min - kBoundM - allowance_m < outer - kLowerM;
      // Whether a slice shows the part coming in from outside counts only while none has.
      bool may_come_in = false;
      if (!from_outside) {
        from_outside = std::any_of(tri.begin(), tri.end(), [&](const SolidTriangle& t) {
          return t.above && t.z_hi >= lo && t.z_lo <= hi;
        });
        may_come_in = !from_outside && block.r_max + kBoundM + allowance_m >= outer;
      }
      if (!may_cut && !may_come_in) continue;
      Sweep& sweep = sweeps[k - k0];
      sweep = SweepSlab(corners, tri, lo, hi, false, points);
      from_outside = from_outside || sweep.above || sweep.r_max + allowance_m >= outer;
    }
  }
  // A part that reaches out of the material came in from outside and took all above it; one
  // wholly inside (in a bore, in the end face) takes only its ring.
  bool changed = false;
  for (size_t k = k0; k <= k1; ++k) {
    const Sweep& sweep = sweeps[k - k0];
    if (!sweep.any || sweep.r_min - allowance_m >= OuterRadius(k) - kLowerM) continue;
    const double outer =
        from_outside ? std::numeric_limits<double>::infinity() : sweep.r_max + allowance_m;
    changed = Remove(k, std::max(0.0, sweep.r_min - allowance_m), outer) || changed;
  }
  return changed;
}

std::vector<CylinderPart> TurnedStock::Cylinders(double tolerance_m) const {
  std::vector<CylinderPart> parts;
  size_t start = 0;
  while (start < slices.size()) {
    const std::vector<StockSpan>& first = slices[start];
    // Per span of the run: the smallest and largest inner and outer radius.
    std::vector<StockSpan> low = first, high = first;
    size_t end = start + 1;
    for (; end < slices.size(); ++end) {
      const std::vector<StockSpan>& next = slices[end];
      if (next.size() != first.size()) break;
      bool fits = true;
      for (size_t j = 0; j < next.size() && fits; ++j) {
        const StockSpan& s = next[j];
        fits = std::max(high[j].outer_m, s.outer_m) - std::min(low[j].outer_m, s.outer_m) <=
                   tolerance_m &&
               std::max(high[j].inner_m, s.inner_m) - std::min(low[j].inner_m, s.inner_m) <=
                   tolerance_m;
      }
      if (!fits) break;
      for (size_t j = 0; j < next.size(); ++j) {
        low[j] = {std::min(low[j].inner_m, next[j].inner_m),
                  std::min(low[j].outer_m, next[j].outer_m)};
        high[j] = {std::max(high[j].inner_m, next[j].inner_m),
                   std::max(high[j].outer_m, next[j].outer_m)};
      }
    }
    for (size_t j = 0; j < first.size(); ++j)
      parts.push_back({name, link, high[j].outer_m, static_cast<double>(end - start) * slice_m,
                       z0_m + static_cast<double>(start) * slice_m, low[j].inner_m});
    start = end;
  }
  return parts;
}

}  // namespace vmt::sim
