#include "sim/backend/stylus_contacts.hpp"

#include <algorithm>
#include <stdexcept>

#include "sim/backend/machine_backend.hpp"

namespace vmt::sim {

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
}

void StylusContacts::Step(const std::vector<double>& q_before, const std::vector<double>& q_now,
                          const std::vector<uint8_t>& inputs, double t_s, ProbeWiring& wiring) {
  if (!any_) return;
  // Only the styluses' and the part's links are posed: the rest of the machine does not matter
  // here, and this runs every drive tick.
  if (q_before != q_last_) LinkPoses(*model_, q_before, needed_, X_last_);
  LinkPoses(*model_, q_now, needed_, X_now_);
  const std::vector<Eigen::Isometry3d>& before = X_last_;
  const std::vector<Eigen::Isometry3d>& now = X_now_;
  // Both ends in the part's frame of this tick: a turning part's angle does not matter (it is a
  // solid of revolution), and two different angles would bend a straight move into a chord.
  const Eigen::Isometry3d X_PartW = now[part_link_].inverse();
  for (size_t k = 0; k < model_->probes.size(); ++k) {
    const ProbeStylus& stylus = model_->probes[k];
    const bool ready = stylus.ready_input < 0 || inputs[stylus.ready_input] != 0;
    const StylusTick tick =
        StepStylus(stylus, part_, states_[k], SphereCentres(stylus, X_PartW * before[stylus.link]),
                   SphereCentres(stylus, X_PartW * now[stylus.link]), ready);
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
  X_last_.swap(X_now_);
}

std::vector<StylusOverTravel> StylusContacts::TakeOverTravels() {
  std::vector<StylusOverTravel> taken;
  taken.swap(over_travels_);
  return taken;
}

}  // namespace vmt::sim
