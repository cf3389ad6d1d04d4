#include "sim/backend/machine_backend.hpp"

#include <stdexcept>

#include "common/demand.hpp"
#include "sim/backend/coupling_graph.hpp"

namespace vmt::sim {

MachineBackend::MachineBackend(const MachineModel& model, const InitialState& init)
    : model_(&model),
      drive_infos_(model.DriveInfos()),
      inputs_(model),
      probes_(model),
      styluses_(model) {
  for (const DriveParams& p : model.drives) controllers_.emplace_back(p);
  clutches_.resize(model.clutches.size());
  for (size_t k = 0; k < model.clutches.size(); ++k) {
    auto it = init.clutch_engaged.find(model.clutches[k].name);
    if (it != init.clutch_engaged.end() && it->second) clutches_[k].state = ClutchState::kEngaged;
  }
  actuators_.resize(model.actuators.size());
  mdt_.setpoints.resize(model.drives.size());
  mdt_.outputs.assign(model.io.size(), 0);
  at_.feedback.resize(model.drives.size());
  at_.inputs.assign(model.io.size(), 0);
}

void MachineBackend::Restore(const MachineBackend&) {
  VMT_DEMAND(false, "a backend without Copy has nothing to restore");
}

void MachineBackend::Write(const control::MasterTelegram& mdt) {
  mdt_.setpoints = mdt.setpoints;
  mdt_.setpoints.resize(model_->drives.size());
  mdt_.outputs = mdt.outputs;
  mdt_.outputs.resize(model_->io.size(), 0);
}

std::vector<double> InitialJointPositions(const MachineModel& model, const InitialState& init) {
  std::vector<double> q(model.joints.size(), 0.0);
  std::vector<bool> known(model.joints.size(), false);
  for (const auto& [name, value] : init.drive_positions) {
    const int d = model.DriveIndex(name);
    if (d < 0) throw std::invalid_argument("no drive named '" + name + "'");
    const DriveParams& p = model.drives[d];
    const double unit = p.info.kind == control::AxisKind::kLinear ? kMmPerM : kDegPerRad;
    q[p.motor_joint] = p.ratio * value / unit;
    known[p.motor_joint] = true;
    // A load-side encoder reads its own joint: place that one too, so that the drive reads the
    // initial value (unless another drive placed it already).
    if (p.load_joint >= 0 && !known[p.load_joint]) {
      q[p.load_joint] = value / unit;
      known[p.load_joint] = true;
    }
  }
  std::vector<CouplingEdge> edges;
  for (const GearCoupling& g : model.gears)
    edges.push_back({g.motor_joint, g.load_joint, g.ratio, 0});
  for (const DogClutch& k : model.clutches) {
    auto it = init.clutch_engaged.find(k.name);
    if (it != init.clutch_engaged.end() && it->second)
      edges.push_back({k.motor_joint, k.load_joint, k.ratio, 0});
  }
  for (const auto& [name, engaged] : init.clutch_engaged) {
    bool found = false;
    for (const DogClutch& k : model.clutches) found = found || k.name == name;
    if (!found) throw std::invalid_argument("no clutch named '" + name + "'");
  }
  PropagateCouplings(edges, q, known);
  return q;
}

}  // namespace vmt::sim
