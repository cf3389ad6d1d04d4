#include "sim/collision/machine_path_guard.hpp"

#include <cmath>

namespace vmt::sim {

MachinePathGuard::MachinePathGuard(const MachineModel& model,
                                   const std::vector<CylinderPart>& added,
                                   std::function<std::vector<double>()> current)
    : model_(&model), world_(model, added), current_(std::move(current)), added_(added) {}

void MachinePathGuard::SetAdded(std::vector<CylinderPart> added) {
  added_ = std::move(added);
  stale_ = true;
}

void MachinePathGuard::SetSweep(SpindleSweep sweep) {
  if (world_swept_)
    for (const int part : sweep_.parts) world_.SetAside(part, false);
  sweep_ = std::move(sweep);
  stale_ = true;
}

void MachinePathGuard::Refresh(bool swept) {
  if (!stale_ && swept == world_swept_) return;
  std::vector<CylinderPart> parts = added_;
  if (swept) parts.insert(parts.end(), sweep_.swept.begin(), sweep_.swept.end());
  world_.SetAdded(parts);
  for (const int part : sweep_.parts) world_.SetAside(part, swept);
  world_swept_ = swept;
  stale_ = false;
}

std::vector<double> MachinePathGuard::JointPositions(const std::vector<double>& base,
                                                     const std::vector<double>& drives,
                                                     const std::vector<char>& moving) const {
  std::vector<double> q = base;
  std::vector<char> set(q.size(), 0);
  // Two drives may read one joint (C's load encoder is on the spindle S1 turns): the one that
  // moves has it, so the standing ones go first.
  for (int pass = 0; pass < 2; ++pass)
    for (size_t d = 0; d < model_->drives.size() && d < drives.size(); ++d) {
      if (static_cast<bool>(moving[d]) != (pass == 1)) continue;
      const DriveParams& p = model_->drives[d];
      const double si =
          drives[d] / (p.info.kind == control::AxisKind::kRotary ? kDegPerRad : kMmPerM);
      // The position is load-side: the motor turns ratio times as far; a load encoder reads
      // the load's own joint.
      q[p.motor_joint] = si * p.ratio, set[p.motor_joint] = 1;
      if (p.load_joint >= 0) q[p.load_joint] = si, set[p.load_joint] = 1;
    }
  // Belts and gears carry the motor's motion to the load.
  for (const GearCoupling& g : model_->gears) {
    if (set[g.motor_joint] && !set[g.load_joint]) q[g.load_joint] = q[g.motor_joint] / g.ratio;
    if (set[g.load_joint] && !set[g.motor_joint]) q[g.motor_joint] = q[g.load_joint] * g.ratio;
  }
  return q;
}

control::PathCheck MachinePathGuard::CheckMeasuringPath(const std::vector<double>& from,
                                                        const std::vector<double>& to) {
  world_.SetMeasuring(true);
  const control::PathCheck c = CheckMove(from, to);
  world_.SetMeasuring(false);
  return c;
}

control::PathCheck MachinePathGuard::CheckSpindleStart(const std::vector<double>& at,
                                                       int spindle) {
  if (sweep_.joint < 0 || spindle < 0) return {};
  if (before_check) before_check(world_);
  Refresh(true);
  const std::vector<char> standing(at.size(), 0);
  const StraightMoveCheck c =
      sim::CheckSpindleStart(world_, JointPositions(current_(), at, standing), sweep_.joint,
                             world_.size() - static_cast<int>(sweep_.swept.size()));
  control::PathCheck out;
  out.clear = c.clear;
  out.min_clearance = c.closest_a >= 0 ? c.min_clearance_m * kMmPerM : 0;
  if (c.closest_a >= 0) out.closest_a = world_.part(c.closest_a).name;
  if (c.closest_b >= 0) out.closest_b = world_.part(c.closest_b).name;
  out.position = at;
  if (c.clear) return out;
  out.part_a = world_.part(c.part_a).name;
  out.part_b = world_.part(c.part_b).name;
  for (int i = 0; i < 3; ++i) out.point[i] = c.point[i] * kMmPerM;
  return out;
}

control::PathCheck MachinePathGuard::CheckMove(const std::vector<double>& from,
                                               const std::vector<double>& to) {
  if (before_check) before_check(world_);
  Refresh(turning_);
  std::vector<char> moving(from.size(), 0);
  double path = 0;
  for (size_t d = 0; d < from.size() && d < to.size(); ++d) {
    moving[d] = from[d] != to[d];
    if (moving[d] && d < model_->drives.size() &&
        model_->drives[d].info.kind == control::AxisKind::kLinear)
      path += (to[d] - from[d]) * (to[d] - from[d]);
  }
  const std::vector<double> base = current_();
  const StraightMoveCheck c = CheckStraightMove(world_, JointPositions(base, from, moving),
                                                JointPositions(base, to, moving), options);
  control::PathCheck out;
  out.clear = c.clear;
  out.min_clearance = c.min_clearance_m * kMmPerM;
  if (c.closest_a >= 0) out.closest_a = world_.part(c.closest_a).name;
  if (c.closest_b >= 0) out.closest_b = world_.part(c.closest_b).name;
  if (c.clear) return out;
  out.part_a = world_.part(c.part_a).name;
  out.part_b = world_.part(c.part_b).name;
  for (int i = 0; i < 3; ++i) out.point[i] = c.point[i] * kMmPerM;
  out.distance = std::sqrt(path) * c.u;
  out.position.resize(from.size());
  for (size_t d = 0; d < from.size(); ++d)
    out.position[d] = moving[d] ? from[d] + (to[d] - from[d]) * c.u : from[d];
  return out;
}

}  // namespace vmt::sim
