#include "sim/collision/turned_stock.hpp"

#include <algorithm>
#include <cmath>

namespace vmt::sim {

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

bool TurnedStock::Cut(double z_m, double r_m, double allowance_m) {
  const double k = std::floor((z_m - z0_m) / slice_m);
  if (!(k >= 0) || k >= static_cast<double>(radius_m.size())) return false;
  double& r = radius_m[static_cast<size_t>(k)];
  const double left = std::max(0.0, r_m - allowance_m);
  if (left >= r) return false;
  r = left;
  return true;
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
  return parts;
}

}  // namespace vmt::sim
