#include "sim/kinematic/kinematic_backend.hpp"

namespace vmt::sim {

KinematicBackend::KinematicBackend(const MachineModel& model, const InitialState& init)
    : MachineBackend(model, init) {
  clutch_offsets_.assign(model.clutches.size(), 0.0);
  q_ = InitialJointPositions(model, init);
  qd_.assign(q_.size(), 0.0);
  RebuildPlan();
  UpdateFeedback();
  StartProbes([this](int j) { return q_[j]; });
}

void KinematicBackend::RebuildPlan() {
  std::vector<CouplingEdge> edges;
  for (const GearCoupling& g : model_->gears)
    edges.push_back({g.motor_joint, g.load_joint, g.ratio, 0});
  for (size_t k = 0; k < clutches_.size(); ++k)
    if (clutches_[k].state == ClutchState::kEngaged) {
      const DogClutch& c = model_->clutches[k];
      edges.push_back({c.motor_joint, c.load_joint, c.ratio, clutch_offsets_[k]});
    }
  const size_t n = q_.size();
  group_.assign(n, -1);
  followers_.assign(n, {});
  int groups = 0;
  for (size_t leader = 0; leader < n; ++leader) {
    // Breadth-first from the leader: each coupled joint follows one already placed.
    std::vector<bool> placed(n, false);
    placed[leader] = true;
    for (bool grew = true; grew;) {
      grew = false;
      for (const CouplingEdge& e : edges) {
        if (placed[e.motor_joint] && !placed[e.load_joint]) {
          followers_[leader].push_back({e.load_joint, e.motor_joint, 1 / e.ratio, e.offset});
          placed[e.load_joint] = grew = true;
        } else if (placed[e.load_joint] && !placed[e.motor_joint]) {
          followers_[leader].push_back({e.motor_joint, e.load_joint, e.ratio, -e.ratio * e.offset});
          placed[e.motor_joint] = grew = true;
        }
      }
    }
    if (group_[leader] < 0) {
      for (size_t j = 0; j < n; ++j)
        if (placed[j]) group_[j] = groups;
      ++groups;
    }
  }
  group_led_.assign(groups, -1);
  group_held_.assign(groups, 0);
}

void KinematicBackend::Restore(const MachineBackend& saved) {
  // Every member is a value (the model is shared and constant), so the copy is the state.
  *this = static_cast<const KinematicBackend&>(saved);
}

void KinematicBackend::Step() {
  const double dt = kDriveTickS;
  // Member buffers only: this runs thousands of times per simulated second.
  q_before_ = q_;
  const std::vector<double>& q_before = q_before_;

  // A clamp holds its joint and what is coupled to it: the ideal machine's clamp never slips.
  std::fill(group_held_.begin(), group_held_.end(), 0);
  for (size_t k = 0; k < actuators_.size(); ++k) {
    const Actuator& a = model_->actuators[k];
    actuators_[k].Step(a, mdt_.outputs[a.valve], dt);
    if (actuators_[k].Holds(a)) group_held_[group_[model_->drives[a.holds_drive].motor_joint]] = 1;
  }

  // Enabled drives lead their coupled group, first in YAML order; a second enabled drive on the
  // same group follows (on the real machine it would fight: the PLC must switch enables).
  // Groups without an enabled drive stand still: an ideal machine has no inertia to coast on.
  for (size_t d = 0; d < controllers_.size(); ++d) {
    DriveController& ctrl = controllers_[d];
    const DriveParams& p = model_->drives[d];
    const control::DriveSetpoint sp = ToSi(p, mdt_.setpoints[d]);
    // Position loop on its encoder (possibly load side), velocity loop on the motor.
    const double pos = EncoderPosition(p, [&q_before](int j) { return q_before[j]; });
    const double vel = LoadSide(p, qd_[p.motor_joint]);
    const double v_ref = ctrl.VelocityReference(sp, pos, vel, dt);
    // The controller's mode, not the setpoint's: a tripped drive's power stage is off.
    const bool leads = ctrl.mode() == control::DriveMode::kPosition ||
                       ctrl.mode() == control::DriveMode::kVelocity;
    const int group = group_[p.motor_joint];
    int64_t& led = group_led_[group];
    if (!leads || led == ticks_ || group_held_[group]) continue;
    led = ticks_;
    q_[p.motor_joint] = q_before[p.motor_joint] + p.ratio * v_ref * dt;
    for (const Follower& f : followers_[p.motor_joint])
      q_[f.joint] = q_[f.from] * f.scale + f.offset;
  }

  for (size_t j = 0; j < q_.size(); ++j) qd_[j] = (q_[j] - q_before[j]) / dt;

  for (size_t k = 0; k < clutches_.size(); ++k) {
    const DogClutch& c = model_->clutches[k];
    const double phase = DogClutchLogic::PhaseError(c, q_[c.motor_joint], q_[c.load_joint]);
    const double slip = qd_[c.load_joint] - qd_[c.motor_joint] / c.ratio;
    const bool was_engaged = clutches_[k].state == ClutchState::kEngaged;
    clutches_[k].Step(c, mdt_.outputs[c.valve_engage], mdt_.outputs[c.valve_release], phase, slip,
                      dt);
    const bool engaged = clutches_[k].state == ClutchState::kEngaged;
    // The dogs mesh where they stand, within the phase tolerance (their play): snapping to the
    // exact tooth would move the follower up to the tolerance in one tick, through the motor
    // ratio a speed far beyond the drives' limits (an overspeed trip of the C servo).
    if (!was_engaged && engaged)
      clutch_offsets_[k] = q_[c.load_joint] - q_[c.motor_joint] / c.ratio;
    if (engaged != was_engaged) RebuildPlan();
  }
  // The styluses before the drives sample: a contact within this tick latches where it was.
  if (styluses_.any()) styluses_.Step(q_before, q_, at_.inputs, time_s(), probes_);
  ++ticks_;
  UpdateFeedback();
  SampleProbes([this](int j) { return q_[j]; });
}

// Flattened: left to itself, GCC's link-time inliner keeps DriveController::Feedback out of line
// here, which costs the kinematic step 2-3 % (docs/performance-log.md).
[[gnu::flatten]] void KinematicBackend::UpdateFeedback() {
  for (size_t d = 0; d < controllers_.size(); ++d) {
    const DriveParams& p = model_->drives[d];
    controllers_[d].Feedback(EncoderPosition(p, [this](int j) { return q_[j]; }),
                             LoadSide(p, qd_[p.motor_joint]), 0, at_.feedback[d]);
  }
  ReadInputs();
}

}  // namespace vmt::sim
