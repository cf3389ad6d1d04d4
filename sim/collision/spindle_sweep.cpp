#include "sim/collision/spindle_sweep.hpp"

#include <algorithm>
#include <cmath>

namespace vmt::sim {

SpindleSweep SweepOf(const CollisionWorld& world, const std::string& link) {
  SpindleSweep s;
  const MachineModel& model = world.model();
  const int l = model.LinkIndex(link);
  if (l < 0 || model.links[l].parent_joint < 0) return s;
  const JointType type = model.joints[model.links[l].parent_joint].type;
  if (type != JointType::kRevolute && type != JointType::kContinuous) return s;
  s.joint = model.links[l].parent_joint;
  for (const Visual& v : model.links[l].collisions) {
    if (!v.mesh || v.mesh->indices.empty()) continue;
    int part = -1;
    for (int i = 0; i < world.size() && part < 0; ++i)
      if (world.part(i).link == l && world.part(i).name == v.name) part = i;
    if (part < 0) continue;
    double r = 0, z_lo = 1e300, z_hi = -1e300;
    const auto& pos = v.mesh->positions;
    for (size_t i = 0; i + 2 < pos.size(); i += 3) {
      const Eigen::Vector3d p = v.X_LinkVisual * Eigen::Vector3d(pos[i], pos[i + 1], pos[i + 2]);
      r = std::max(r, std::hypot(p.x(), p.y()));
      z_lo = std::min(z_lo, p.z()), z_hi = std::max(z_hi, p.z());
    }
    if (!(r > 0) || !(z_hi > z_lo)) continue;
    s.parts.push_back(part);
    s.swept.push_back({v.name, link, r, z_hi - z_lo, z_lo});
  }
  return s;
}

StraightMoveCheck CheckSpindleStart(CollisionWorld& world, const std::vector<double>& q,
                                    int joint, int first_swept) {
  const MachineModel& m = world.model();
  auto turns = [&](int link) {
    for (int l = link; m.links[l].parent_joint >= 0;
         l = m.joints[m.links[l].parent_joint].parent_link)
      if (m.links[l].parent_joint == joint) return true;
    return false;
  };
  std::vector<char> turning(world.size());
  for (int i = 0; i < world.size(); ++i) turning[i] = turns(world.part(i).link);
  world.Pose(q);
  StraightMoveCheck out;
  out.u = 0;
  out.q = q;
  for (int a = std::max(first_swept, 0); a < world.size(); ++a)
    for (int b = 0; b < world.size(); ++b) {
      if (turning[b] || world.MayTouch(a, b)) continue;
      // The boxes first: the exact distance only where it could be the smallest.
      if (world.BoxDistance(a, b) > out.min_clearance_m) continue;
      ++out.pairs_checked;
      const double d = world.Distance(a, b);
      if (d < out.min_clearance_m) out.min_clearance_m = d, out.closest_a = a, out.closest_b = b;
      if (d <= 0 && world.Collide(a, b, &out.point)) {
        out.clear = false;
        out.part_a = a, out.part_b = b;
        out.min_clearance_m = 0;
        return out;
      }
    }
  return out;
}

}  // namespace vmt::sim
