#include "sim/backend/stylus_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/backend/machine_backend.hpp"

namespace vmt::sim {
namespace {

// What the reach and the room leave beyond the rounding of poses and distances (a few ulps of a
// machine's size).
constexpr double kReachRoundingM = 1e-9;

bool Below(const MachineModel& model, int link, int ancestor) {
  for (; link >= 0; link = model.links[link].parent_joint < 0
                               ? -1
                               : model.joints[model.links[link].parent_joint].parent_link)
    if (link == ancestor) return true;
  return false;
}

/// Per joint, how far a unit of its motion moves any stylus sphere relative to the part at
/// `part_link` (see StylusContacts::reach_). A joint that carries the part and every stylus
/// alike moves nothing relative; a slide moves by its travel; the spindle's turn about the
/// part's own axis leaves every distance from the part as it was; a joint that turns only
/// styluses through fixed joints moves a sphere by its distance from the axis per radian. Any
/// other turn has no bound here: while it moves, every tick is posed.
std::vector<double> JointReach(const MachineModel& model, int part_link) {
  std::vector<double> reach(model.joints.size(), 0.0);
  for (size_t j = 0; j < model.joints.size(); ++j) {
    const Joint& joint = model.joints[j];
    if (joint.type == JointType::kFixed) continue;
    const bool moves_part = Below(model, part_link, joint.child_link);
    bool moves_all = moves_part, moves_any = false;
    for (const ProbeStylus& stylus : model.probes) {
      const bool below = Below(model, stylus.link, joint.child_link);
      moves_all = moves_all && below;
      moves_any = moves_any || below;
    }
    if (moves_all || (!moves_part && !moves_any)) continue;
    if (joint.type == JointType::kPrismatic) {
      reach[j] = 1;
      continue;
    }
    if (joint.child_link == part_link && !moves_any && joint.axis.x() == 0 && joint.axis.y() == 0)
      continue;
    reach[j] = std::numeric_limits<double>::infinity();
    if (moves_part) continue;
    double radius = 0;
    bool rigid = true;
    for (const ProbeStylus& stylus : model.probes) {
      if (!Below(model, stylus.link, joint.child_link)) continue;
      // The stylus' link in the joint's child frame, through fixed joints only.
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      for (int link = stylus.link; link != joint.child_link && rigid;) {
        const Joint& up = model.joints[model.links[link].parent_joint];
        rigid = up.type == JointType::kFixed;
        X = up.X_ParentJoint * X;
        link = up.parent_link;
      }
      for (const MeasuringSphere& s : stylus.spheres) {
        const Eigen::Vector3d p = X * s.centre_m;
        radius = std::max(radius, (p - p.dot(joint.axis) * joint.axis).norm());
      }
    }
    if (rigid) reach[j] = radius * (1 + 1e-9);
  }
  return reach;
}

}  // namespace

StylusContacts::StylusContacts(const MachineModel& model)
    : model_(&model), states_(model.probes.size()) {}

void StylusContacts::SetPart(const RevolvedPart& part) {
  const int link = model_->LinkIndex(part.link);
  if (link < 0)
    throw std::invalid_argument("workpiece '" + part.name + "': no link '" + part.link + "'");
  part_ = part;
  part_link_ = link;
  any_ = !model_->probes.empty() && !part_.sections.empty();
  std::vector<int> links{link};
  for (const ProbeStylus& stylus : model_->probes) links.push_back(stylus.link);
  needed_ = LinkChains(*model_, links);
  q_last_.clear();
  reach_ = JointReach(*model_, link);
  far_room_ = 0;
}

bool StylusContacts::StaysFar(const std::vector<double>& q_before,
                              const std::vector<double>& q_now) const {
  if (far_room_ <= 0 || q_far_.size() != q_now.size() || q_before.size() != q_now.size())
    return false;
  // A centre moves no farther from where it was at q_far_ than its joints' reach allows, and the
  // part's bounding cylinder is no nearer than that much closer: the spheres' distance bound
  // falls by at most the first sum, the tick's travel is at most the second.
  double moved = 0;
  for (size_t j = 0; j < q_now.size(); ++j) {
    const double from_far =
        std::max(std::abs(q_before[j] - q_far_[j]), std::abs(q_now[j] - q_far_[j]));
    const double in_tick = std::abs(q_now[j] - q_before[j]);
    if (from_far + in_tick != 0) moved += reach_[j] * (from_far + in_tick);
  }
  return moved + kReachRoundingM < far_room_;
}

void StylusContacts::Step(const std::vector<double>& q_before, const std::vector<double>& q_now,
                          const std::vector<uint8_t>& inputs, double t_s, ProbeWiring& wiring) {
  if (!any_) return;
  if (StaysFar(q_before, q_now)) {
    // Far from the part every tick is a quiet one; the joints' motion since the last posed
    // tick shows it without posing a link.
    for (size_t k = 0; k < model_->probes.size(); ++k) {
      const ProbeStylus& stylus = model_->probes[k];
      const bool ready = stylus.ready_input < 0 || inputs[stylus.ready_input] != 0;
      const StylusTick tick = QuietTick(stylus, states_[k], ready);
      if (tick.changed) wiring.SetSwitch(tick.io_input, tick.level, tick.tick_fraction);
    }
    return;
  }
  // Only the styluses' and the part's links are posed: the rest of the machine does not matter
  // here, and this runs every drive tick.
  if (q_before != q_last_) LinkPoses(*model_, q_before, needed_, X_last_);
  LinkPoses(*model_, q_now, needed_, X_now_);
  const std::vector<Eigen::Isometry3d>& before = X_last_;
  const std::vector<Eigen::Isometry3d>& now = X_now_;
  // Both ends in the part's frame of this tick: a turning part's angle does not matter (it is a
  // solid of revolution), and two different angles would bend a straight move into a chord.
  const Eigen::Isometry3d X_PartW = now[part_link_].inverse();
  far_room_ = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < model_->probes.size(); ++k) {
    const ProbeStylus& stylus = model_->probes[k];
    const bool ready = stylus.ready_input < 0 || inputs[stylus.ready_input] != 0;
    const std::vector<Eigen::Vector3d> after = SphereCentres(stylus, X_PartW * now[stylus.link]);
    const StylusTick tick =
        StepStylus(stylus, part_, states_[k], SphereCentres(stylus, X_PartW * before[stylus.link]),
                   after, ready);
    far_room_ = std::min(far_room_, FarRoom(stylus, part_, states_[k], after));
    if (tick.changed) wiring.SetSwitch(tick.io_input, tick.level, tick.tick_fraction);
    if (!tick.over_travel) continue;
    StylusOverTravel o;
    o.t_s = t_s + tick.over_travel_fraction * kDriveTickS;
    o.t_number = stylus.t_number;
    o.sphere = tick.over_travel_sphere;
    // One part per sphere where the model names as many; a single part covers them all.
    if (!stylus.sphere_parts.empty())
      o.sphere_part =
          stylus.sphere_parts[std::min<size_t>(o.sphere, stylus.sphere_parts.size() - 1)];
    o.part = part_.name;
    o.point_m = now[part_link_] * tick.over_travel_point_m;
    over_travels_.push_back(o);
  }
  q_last_ = q_now;
  q_far_ = q_now;
  X_last_.swap(X_now_);
}

std::vector<StylusOverTravel> StylusContacts::TakeOverTravels() {
  std::vector<StylusOverTravel> taken;
  taken.swap(over_travels_);
  return taken;
}

}  // namespace vmt::sim
