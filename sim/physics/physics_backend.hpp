#pragma once
// The physics machine: one Bullet Featherstone multibody (btMultiBody, double precision) with
// the bed as fixed base and every URDF joint as a link, stepped at the 250 us drive tick. Drives
// close their loops on the joint coordinates and act as joint torques; the belt is a
// btMultiBodyGearConstraint; the dog clutch adds one when its dogs mesh; a clamp (turret) holds
// its joint with a joint motor limited to the clamp's hold torque.
//
// Why Featherstone rather than rigid bodies with hinge/slider constraints: joint coordinates are
// the state itself, so an encoder reads exactly the joint (no constraint drift between carriage
// and slide, no angle unwrapping for a spindle turning thousands of revolutions), there is no
// per-step rotation clamp on a spindle, and a chain of 9 links is one O(n) articulated solve. The
// gear constraint's position correction works only inside one multibody (Bullet reads both
// angles from body A), which the single-multibody layout satisfies.

#include <memory>

#include "sim/backend/drive_controller.hpp"
#include "sim/backend/machine_backend.hpp"
#include "sim/backend/probe_wiring.hpp"

class btMultiBody;
class btMultiBodyDynamicsWorld;
class btMultiBodyGearConstraint;

namespace vmt::sim {

class PhysicsBackend : public MachineBackend {
 public:
  PhysicsBackend(const MachineModel& model, const InitialState& init);
  ~PhysicsBackend() override;

  const std::vector<control::DriveInfo>& Drives() const override { return drive_infos_; }
  const std::vector<control::IoInfo>& Io() const override { return model_->io; }
  void Write(const control::MasterTelegram& mdt) override;
  const control::AmplifierTelegram& Read() const override { return at_; }

  void Step() override;
  double time_s() const override { return ticks_ * kDriveTickS; }
  std::vector<double> JointPositions() const override;
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

  /// Joint velocities (m/s | rad/s).
  std::vector<double> JointVelocities() const;

 private:
  struct World;
  void Couple(int clutch_index);
  void Uncouple(int clutch_index);
  void Clamp(int actuator_index, bool hold);
  void UpdateFeedback(const std::vector<double>& torques);

  const MachineModel* model_;
  std::vector<control::DriveInfo> drive_infos_;
  std::vector<DriveController> controllers_;
  std::vector<DogClutchLogic> clutches_;
  std::vector<ActuatorLogic> actuators_;
  std::unique_ptr<World> world_;
  control::MasterTelegram mdt_;
  control::AmplifierTelegram at_;
  MachineInputs inputs_;
  ProbeWiring probes_;
  StylusContacts styluses_;
  std::vector<double> probe_positions_;  ///< per drive, unquantised (ActualPositions)
  std::vector<double> q_before_;         ///< joint positions before the tick's motion (styluses)
  std::vector<double> torques_;          ///< load side, per drive, of the last tick
  int64_t ticks_ = 0;
};

}  // namespace vmt::sim
