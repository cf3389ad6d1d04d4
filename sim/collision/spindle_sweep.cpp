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

}  // namespace vmt::sim
