#include "sim/collision/machine_path_guard.hpp"

#include <algorithm>
#include <cmath>

namespace vmt::sim {
namespace {

/// A move's two ends as joint positions, and which drives move between them.
struct MoveJoints {
  std::vector<char> moving;
  std::vector<double> q_from, q_to;
};

MoveJoints JointsOfMove(const MachinePathGuard& guard, const std::vector<double>& base,
                        const std::vector<double>& from, const std::vector<double>& to) {
  MoveJoints m;
  m.moving.assign(from.size(), 0);
  for (size_t d = 0; d < from.size() && d < to.size(); ++d) m.moving[d] = from[d] != to[d];
  m.q_from = guard.JointPositions(base, from, m.moving);
  m.q_to = guard.JointPositions(base, to, m.moving);
  return m;
}

}  // namespace

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

MachinePathGuard::Saved MachinePathGuard::Save() const {
  return {world_.Save(), added_, sweep_, turning_, world_swept_, stale_, world_version_, proof_};
}

void MachinePathGuard::Restore(const Saved& saved) {
  world_.Restore(saved.world);
  added_ = saved.added;
  sweep_ = saved.sweep;
  turning_ = saved.turning;
  world_swept_ = saved.world_swept;
  stale_ = saved.stale;
  world_version_ = saved.world_version;
  proof_ = saved.proof;
}

void MachinePathGuard::Refresh(bool swept) {
  if (!stale_ && swept == world_swept_) return;
  std::vector<CylinderPart> parts = added_;
  if (swept) parts.insert(parts.end(), sweep_.swept.begin(), sweep_.swept.end());
  world_.SetAdded(parts);
  for (const int part : sweep_.parts) world_.SetAside(part, swept);
  world_swept_ = swept;
  stale_ = false;
  ++world_version_;
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
  // What a measuring path proves leaves its spheres' touching of the workpiece out.
  std::optional<Proof> proof = std::move(proof_);
  const control::PathCheck c = CheckMove(from, to);
  world_.SetMeasuring(false);
  proof_ = std::move(proof);
  return c;
}

control::PathCheck MachinePathGuard::CheckSpindleStart(const std::vector<double>& at, int spindle) {
  if (sweep_.joint < 0 || spindle < 0) return {};
  if (before_check) before_check(world_);
  proof_.reset();
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
  MoveJoints m = JointsOfMove(*this, current_(), from, to);
  const StraightMoveCheck c = CheckStraightMove(world_, m.q_from, m.q_to, options);
  control::PathCheck out;
  out.clear = c.clear;
  out.min_clearance = c.min_clearance_m * kMmPerM;
  if (c.closest_a >= 0) out.closest_a = world_.part(c.closest_a).name;
  if (c.closest_b >= 0) out.closest_b = world_.part(c.closest_b).name;
  proof_.reset();
  if (c.clear && c.closest_a >= 0 && c.pairs_resting == 0)
    proof_ = Proof{{std::move(m.q_from), std::move(m.q_to), c.min_clearance_m},
                   world_version_,
                   out.closest_a,
                   out.closest_b};
  if (c.clear) return out;
  out.part_a = world_.part(c.part_a).name;
  out.part_b = world_.part(c.part_b).name;
  for (int i = 0; i < 3; ++i) out.point[i] = c.point[i] * kMmPerM;
  double path = 0;  // the linear axes' path length
  for (size_t d = 0; d < from.size() && d < model_->drives.size(); ++d)
    if (m.moving[d] && model_->drives[d].info.kind == control::AxisKind::kLinear)
      path += (to[d] - from[d]) * (to[d] - from[d]);
  out.distance = std::sqrt(path) * c.u;
  out.position.resize(from.size());
  for (size_t d = 0; d < from.size(); ++d)
    out.position[d] = m.moving[d] ? from[d] + (to[d] - from[d]) * c.u : from[d];
  return out;
}

bool MachinePathGuard::Proves(const std::vector<double>& from, const std::vector<double>& to,
                              control::PathCheck& check) {
  if (!proof_) return false;
  if (before_check) before_check(world_);
  Refresh(turning_);
  if (world_version_ != proof_->world_version) return false;
  const MoveJoints m = JointsOfMove(*this, current_(), from, to);
  const std::optional<Stray> stray =
      StrayFrom(world_, proof_->move, m.q_from, m.q_to, world_swept_ ? sweep_.joint : -1);
  // The proven move's clearance may be that much less than reported. A move that strays by at
  // most as much again is proven, and its clearance reported as the query's with that margin.
  const double reported = proof_->move.clearance_m;
  const double tolerance =
      std::max(options.clearance_absolute_m, options.clearance_relative * reported);
  if (!stray || !(stray->slides_m <= options.clearance_relative * (reported - tolerance)))
    return false;
  double clearance_m = reported - stray->slides_m;
  std::string closest_a = proof_->closest_a, closest_b = proof_->closest_b;
  if (stray->any_turned) {
    // The pairs of the parts a rotation moved are queried, the rest stand proven.
    const PairScope scope{&stray->turned, clearance_m};
    const StraightMoveCheck c = CheckStraightMove(world_, m.q_from, m.q_to, options, &scope);
    if (!c.clear || c.pairs_resting > 0) return false;  // the whole move's query tells
    if (c.closest_a >= 0) {
      clearance_m = c.min_clearance_m;
      closest_a = world_.part(c.closest_a).name;
      closest_b = world_.part(c.closest_b).name;
    }
  }
  check = {};
  check.min_clearance = clearance_m * kMmPerM;
  check.closest_a = std::move(closest_a);
  check.closest_b = std::move(closest_b);
  return true;
}

}  // namespace vmt::sim
