#pragma once
// The ideal machine: every enabled drive moves exactly at its own velocity reference (position
// loop Kv, ramps, M19 profile of DriveController), so a position command is followed with the
// first-order lag 1/Kv of a perfect velocity loop; gears and an engaged clutch tie joints
// exactly. No masses, no torque (so no drive ever overloads; overspeed and parameter-set faults
// trip as on the physics backend). For fast studies, block search, and as the reference the
// physics backend is checked against.

#include "sim/backend/coupling_graph.hpp"
#include "sim/backend/drive_controller.hpp"
#include "sim/backend/machine_backend.hpp"
#include "sim/backend/probe_wiring.hpp"

namespace vmt::sim {

class KinematicBackend : public MachineBackend {
 public:
  KinematicBackend(const MachineModel& model, const InitialState& init);

  const std::vector<control::DriveInfo>& Drives() const override { return drive_infos_; }
  const std::vector<control::IoInfo>& Io() const override { return model_->io; }
  void Write(const control::MasterTelegram& mdt) override;
  const control::AmplifierTelegram& Read() const override { return at_; }

  void Step() override;
  double time_s() const override { return ticks_ * kDriveTickS; }
  std::vector<double> JointPositions() const override { return q_; }
  ClutchState Clutch(int index) const override { return clutches_[index].state; }
  const DogClutchLogic& ClutchLogic(int index) const override { return clutches_[index]; }
  double ActuatorStroke(int index) const override { return actuators_[index].stroke; }
  const MachineModel& model() const override { return *model_; }
  void SetProbeSwitch(int io_input, bool level, double tick_fraction) override {
    probes_.SetSwitch(io_input, level, tick_fraction);
  }
  void SetProbeSamplingPhase(const ProbeSamplingPhase& phase) override {
    probes_.SetSamplingPhase(phase);
  }
  void SetWorkpiece(const RevolvedPart& part) override { styluses_.SetPart(part); }
  std::vector<StylusOverTravel> TakeStylusOverTravels() override {
    return styluses_.TakeOverTravels();
  }

 private:
  void UpdateFeedback();

  const MachineModel* model_;
  std::vector<control::DriveInfo> drive_infos_;
  std::vector<DriveController> controllers_;
  std::vector<DogClutchLogic> clutches_;
  std::vector<double> clutch_offsets_;
  std::vector<ActuatorLogic> actuators_;
  std::vector<double> q_, qd_;
  std::vector<double> q_before_;

  // Who follows whom, rebuilt when a clutch opens or closes: q[joint] = q[from] * scale + offset.
  struct Follower {
    int joint, from;
    double scale, offset;
  };
  void RebuildPlan();
  std::vector<std::vector<Follower>> followers_;  ///< per leading joint, in propagation order
  std::vector<int> group_;                        ///< coupled group of each joint
  std::vector<int64_t> group_led_;   ///< per group: the tick in which an enabled drive led it
  std::vector<uint8_t> group_held_;  ///< per group: a clamp holds one of its joints this tick
  control::MasterTelegram mdt_;
  control::AmplifierTelegram at_;
  MachineInputs inputs_;
  ProbeWiring probes_;
  StylusContacts styluses_;
  std::vector<double> probe_positions_;  ///< per drive, unquantised (ActualPositions)
  int64_t ticks_ = 0;
};

}  // namespace vmt::sim
