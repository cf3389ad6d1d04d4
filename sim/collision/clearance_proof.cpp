#include "sim/collision/clearance_proof.hpp"

#include <algorithm>
#include <cmath>

namespace vmt::sim {
namespace {

/// Whether the added part `i` (a cylinder along its own z) turns into itself about `joint`.
bool RevolvesAbout(const CollisionWorld& world, int i, int joint) {
  const Joint& j = world.model().joints[joint];
  const Eigen::Isometry3d& X_WC = world.X_WorldLink(j.child_link);
  const Eigen::Vector3d axis = X_WC.linear() * j.axis;
  const Eigen::Isometry3d X_WP = world.X_WorldLink(world.part(i).link) * world.part(i).X_LinkPart;
  const Eigen::Vector3d offset = X_WP.translation() - X_WC.translation();
  constexpr double kTolerance = 1e-9;  // m, and the sine of an angle
  return axis.cross(X_WP.linear().col(2)).norm() < kTolerance &&
         offset.cross(axis).norm() < kTolerance;
}

}  // namespace

std::optional<Stray> StrayFrom(const CollisionWorld& world, const ClearMove& checked,
                               const std::vector<double>& q_from, const std::vector<double>& q_to,
                               int turning_joint) {
  const MachineModel& m = world.model();
  const size_t n = m.joints.size();
  if (q_from.size() < n || q_to.size() < n || checked.q_from.size() < n || checked.q_to.size() < n)
    return std::nullopt;
  // Both moves are straight in joint space: at a fraction u of the way a joint's difference
  // lies between its differences at the two ends, so the larger bounds it all the way.
  std::vector<double> differs(n, 0);
  std::vector<char> moves(n, 0), moved(n, 0);
  for (size_t j = 0; j < n; ++j) {
    if (m.joints[j].type == JointType::kFixed) continue;
    differs[j] =
        std::max(std::abs(q_from[j] - checked.q_from[j]), std::abs(q_to[j] - checked.q_to[j]));
    moves[j] = q_from[j] != q_to[j];
    moved[j] = checked.q_from[j] != checked.q_to[j];
  }
  auto turns = [&](int j) {
    return m.joints[j].type != JointType::kPrismatic && (differs[j] > 0 || moves[j] || moved[j]);
  };
  // The turning joint moves nothing if what hangs from it are bodies of revolution fixed to it.
  bool turning_moves_nothing = turning_joint >= 0;
  Stray out;
  out.turned.assign(world.size(), 0);
  std::vector<char> carries(n, 0);  // some part not turned hangs from the joint
  for (int i = 0; i < world.size(); ++i) {
    if (world.aside(i)) continue;
    bool fixed_below = true;  // only fixed joints between the part and the joint reached
    for (int j = m.links[world.part(i).link].parent_joint; j >= 0;
         j = m.links[m.joints[j].parent_link].parent_joint) {
      if (j == turning_joint && !(fixed_below && world.added(i) && RevolvesAbout(world, i, j)))
        turning_moves_nothing = false;
      if (m.joints[j].type != JointType::kFixed) fixed_below = false;
    }
  }
  for (int i = 0; i < world.size(); ++i) {
    if (world.aside(i)) continue;
    for (int j = m.links[world.part(i).link].parent_joint; j >= 0;
         j = m.links[m.joints[j].parent_link].parent_joint)
      if (turns(j) && !(j == turning_joint && turning_moves_nothing)) out.turned[i] = 1;
    if (out.turned[i]) {
      out.any_turned = true;
      continue;
    }
    for (int j = m.links[world.part(i).link].parent_joint; j >= 0;
         j = m.links[m.joints[j].parent_link].parent_joint)
      carries[j] = 1;
  }
  for (size_t j = 0; j < n; ++j) {
    if (!carries[j] || m.joints[j].type != JointType::kPrismatic) continue;
    // A pair this slide moves against each other was held still by the checked move: the
    // check never measured it.
    if (moves[j] && !moved[j]) return std::nullopt;
    out.slides_m += differs[j];
  }
  return out;
}

}  // namespace vmt::sim
