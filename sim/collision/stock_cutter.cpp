#include "sim/collision/stock_cutter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/model/model_error.hpp"

namespace vmt::sim {
namespace {

double LargestOuterRadius(const TurnedStock& stock) {
  double r_max = 0;
  for (size_t k = 0; k < stock.slices.size(); ++k) r_max = std::max(r_max, stock.OuterRadius(k));
  return r_max;
}

}  // namespace

StockCutter::StockCutter(const MachineModel& model, const RevolvedPart& part)
    : model_(&model), stock_(TurnedStock::FromPart(part, kStockSliceM)) {
  link_ = model.LinkIndex(part.link);
  if (link_ < 0) throw ModelError(model.yaml_path, part.name, "no link '" + part.link + "'");
  spindle_joint_ = model.links[link_].parent_joint;
  for (const CuttingPart& c : model.cutting_parts) {
    const Visual& v = model.links[c.link].collisions[c.collision];
    if (!v.mesh) continue;
    Cutter cut;
    cut.link = c.link;
    const auto& pos = v.mesh->positions;
    for (const uint32_t i : v.mesh->indices)
      cut.corners.push_back(v.X_LinkVisual *
                            Eigen::Vector3d(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]));
    if (cut.corners.empty()) continue;
    Eigen::Vector3d lo = cut.corners[0], hi = lo;
    for (const Eigen::Vector3d& p : cut.corners) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    cut.centre = (lo + hi) / 2;
    for (const Eigen::Vector3d& p : cut.corners)
      cut.radius = std::max(cut.radius, (p - cut.centre).norm());
    cutters_.push_back(std::move(cut));
  }
  for (const Cutter& c : cutters_) {
    if (std::any_of(holders_.begin(), holders_.end(),
                    [&](const Holder& h) { return h.link == c.link; }))
      continue;
    Holder holder{c.link, {}};
    const std::vector<Visual>& parts = model.links[c.link].collisions;
    for (size_t i = 0; i < parts.size(); ++i) {
      const bool cutting = std::any_of(
          model.cutting_parts.begin(), model.cutting_parts.end(), [&](const CuttingPart& p) {
            return p.link == c.link && p.collision == static_cast<int>(i);
          });
      if (cutting || !parts[i].mesh) continue;
      const auto& pos = parts[i].mesh->positions;
      for (size_t k = 0; k + 2 < pos.size(); k += 3)
        holder.corners.push_back(parts[i].X_LinkVisual *
                                 Eigen::Vector3d(pos[k], pos[k + 1], pos[k + 2]));
    }
    holders_.push_back(std::move(holder));
  }
  r_max_ = LargestOuterRadius(stock_);
  std::vector<int> posed{link_};
  for (const Cutter& c : cutters_) posed.push_back(c.link);
  posed_links_ = LinkChains(model, posed);
}

std::optional<Eigen::Vector3d> StockCutter::CuttingPoint(const std::vector<double>& q) const {
  // Corners this close to the nearest one count as its edge (rounding of the turret's angle).
  constexpr double kEdgeM = 1e-5;
  if (cutters_.empty()) return std::nullopt;
  const std::vector<Eigen::Isometry3d> X_W = LinkPoses(*model_, q);
  const Eigen::Isometry3d X_PartWorld = X_W[link_].inverse();
  double nearest = std::numeric_limits<double>::infinity();
  int link = -1;
  for (const Cutter& c : cutters_) {
    const Eigen::Isometry3d X = X_PartWorld * X_W[c.link];
    for (const Eigen::Vector3d& p : c.corners) {
      const double r = (X * p).head<2>().norm();
      if (r < nearest) nearest = r, link = c.link;
    }
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (const Cutter& c : cutters_) {
    const Eigen::Isometry3d X = X_PartWorld * X_W[c.link];
    for (const Eigen::Vector3d& p : c.corners) {
      const Eigen::Vector3d p_part = X * p;
      if (p_part.head<2>().norm() <= nearest + kEdgeM) sum += p_part, ++count;
    }
  }
  for (const Holder& h : holders_) {
    if (h.link != link) continue;
    const Eigen::Isometry3d X = X_PartWorld * X_W[h.link];
    for (const Eigen::Vector3d& p : h.corners)
      if ((X * p).head<2>().norm() < nearest - kEdgeM) return std::nullopt;
  }
  return X_W[link_] * (sum / count);
}

bool StockCutter::Cut(const std::vector<double>& q, double t_s) {
  if (spindle_joint_ < 0 || cutters_.empty() || stock_.slices.empty()) return false;
  const double angle = q[spindle_joint_];
  const bool turning = last_t_ >= 0 && t_s > last_t_ &&
                       std::abs(angle - last_angle_) / (t_s - last_t_) >= kTurningSpeedRadS;
  last_angle_ = angle, last_t_ = t_s;
  if (!turning) return false;
  LinkPoses(*model_, q, posed_links_, X_W_);
  const std::vector<Eigen::Isometry3d>& X_W = X_W_;
  const Eigen::Isometry3d X_PartWorld = X_W[link_].inverse();
  const double r_max = r_max_;
  const double z_lo = stock_.z0_m,
               z_hi = stock_.z0_m + static_cast<double>(stock_.slices.size()) * stock_.slice_m;
  bool changed = false;
  for (const Cutter& c : cutters_) {
    const Eigen::Isometry3d X = X_PartWorld * X_W[c.link];
    const Eigen::Vector3d centre = X * c.centre;
    if (centre.head<2>().norm() - c.radius > r_max || centre.z() + c.radius < z_lo ||
        centre.z() - c.radius > z_hi)
      continue;
    corners_.clear();
    for (const Eigen::Vector3d& p : c.corners) corners_.push_back(X * p);
    changed = stock_.CutSolid(corners_, kCutAllowanceM) || changed;
  }
  if (changed) r_max_ = LargestOuterRadius(stock_);
  return changed;
}

}  // namespace vmt::sim
