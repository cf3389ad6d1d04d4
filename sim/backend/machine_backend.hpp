#pragma once
// A simulated machine behind the DriveBus: the physics (Bullet) and the kinematic (ideal) backend
// are the two kinds. The runner steps it at the drive tick and reads link poses for rendering and
// collision checking.

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "control/drive_bus.hpp"
#include "sim/backend/actuator.hpp"
#include "sim/backend/dog_clutch.hpp"
#include "sim/backend/drive_controller.hpp"
#include "sim/backend/probe_wiring.hpp"
#include "sim/backend/stylus_contacts.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

inline constexpr double kDriveTickS = 250e-6;  ///< SERCOS position loop and probe sampling

/// The machine's state at t = 0.
struct InitialState {
  std::map<std::string, double> drive_positions;  ///< load side, machine units (mm | deg)
  std::map<std::string, bool> clutch_engaged;     ///< by coupling name; default released
};

/// What both backends share lives here once: the telegrams, the drive controllers, the clutches'
/// and actuators' logic, the machine's inputs, the probe wiring and the styluses. A backend adds
/// only how its joints move (Step, JointPositions).
class MachineBackend : public control::DriveBus {
 public:
  const std::vector<control::DriveInfo>& Drives() const final { return drive_infos_; }
  const std::vector<control::IoInfo>& Io() const final { return model_->io; }
  void Write(const control::MasterTelegram& mdt) final;
  const control::AmplifierTelegram& Read() const final { return at_; }

  /// Advance one drive tick (kDriveTickS).
  virtual void Step() = 0;
  double time_s() const { return ticks_ * kDriveTickS; }
  /// Joint positions (m | rad), one per model joint: what the renderer and PathGuard pose.
  virtual std::vector<double> JointPositions() const = 0;
  /// A copy of the machine as it stands, to go back to with Restore (a run's in-memory
  /// snapshot); null where the backend has none: Bullet's world does not copy.
  virtual std::unique_ptr<MachineBackend> Copy() const { return nullptr; }
  /// Back to `saved`, a Copy of this backend.
  virtual void Restore(const MachineBackend& saved);
  ClutchState Clutch(int index) const { return clutches_[index].state; }
  /// The clutch's logic: state, stroke and clashes (dogs ratcheting at speed).
  const DogClutchLogic& ClutchLogic(int index) const { return clutches_[index]; }
  /// Stroke of an actuator (machine.yaml order): 0 off end .. 1 on end.
  double ActuatorStroke(int index) const { return actuators_[index].stroke; }
  const MachineModel& model() const { return *model_; }
  /// A probe switch (the stylus' contact) on I/O input `io_input` changes to `level` at
  /// `tick_fraction` (0..1) of the tick being stepped: the PLC reads the input from that tick on,
  /// and each drive whose probe input (machine.yaml `probe_inputs:`) is wired to it knows where
  /// its axis was at that instant (DriveFeedback::probe, ProbeEdgeLatch::exact_position). Call
  /// it between Step()s for the next tick, or from within Step before the drives sample. Throws
  /// std::invalid_argument for an input a device drives, an output or a key (ProbeWiring).
  void SetProbeSwitch(int io_input, bool level, double tick_fraction) {
    probes_.SetSwitch(io_input, level, tick_fraction);
  }
  /// Where the drives' probe sampling stands to a contact (ProbeSamplingPhase); off until set.
  void SetProbeSamplingPhase(const ProbeSamplingPhase& phase) { probes_.SetSamplingPhase(phase); }
  /// The scene's workpiece, which the model's styluses (machine.yaml `probe:`) touch from the
  /// next Step on: each tick the stylus' contact trips its input at the exact instant
  /// (StylusContacts). Throws std::invalid_argument for a part on a link the model lacks.
  void SetWorkpiece(const RevolvedPart& part) { styluses_.SetPart(part); }
  /// Styluses deflected beyond their over-travel (crashed) since the last call.
  std::vector<StylusOverTravel> TakeStylusOverTravels() { return styluses_.TakeOverTravels(); }

 protected:
  /// The devices at t = 0; clutches named engaged in `init` start engaged (the backend couples
  /// their joints).
  MachineBackend(const MachineModel& model, const InitialState& init);

  /// The machine's inputs and the probe inputs, from the devices' state after a tick.
  void ReadInputs() {
    inputs_.Read(mdt_.outputs, clutches_, actuators_, at_.feedback, at_.inputs);
    probes_.ShowInputs(at_.inputs);
  }
  /// Each wired drive's probe sampling, from the joints' positions at the end of the tick.
  template <typename JointPosition>
  void SampleProbes(const JointPosition& joint) {
    if (!probes_.any()) return;
    ActualPositions(*model_, joint, probes_.wired(), probe_positions_);
    probes_.Step(mdt_.setpoints, at_.inputs, probe_positions_, at_.feedback);
  }
  /// Where the probes stand at t = 0.
  template <typename JointPosition>
  void StartProbes(const JointPosition& joint) {
    ActualPositions(*model_, joint, probe_positions_);
    probes_.Start(probe_positions_);
  }

  const MachineModel* model_;
  std::vector<control::DriveInfo> drive_infos_;
  std::vector<DriveController> controllers_;
  std::vector<DogClutchLogic> clutches_;
  std::vector<ActuatorLogic> actuators_;
  control::MasterTelegram mdt_;
  control::AmplifierTelegram at_;
  MachineInputs inputs_;
  ProbeWiring probes_;
  StylusContacts styluses_;
  std::vector<double> probe_positions_;  ///< per drive, unquantised (ActualPositions)
  int64_t ticks_ = 0;
};

/// Joint positions for an initial state: drive positions on their motor joints through their
/// ratios (and on a load-side encoder's joint), then gear and engaged-clutch partners. Throws
/// std::invalid_argument on unknown names.
std::vector<double> InitialJointPositions(const MachineModel& model, const InitialState& init);

}  // namespace vmt::sim
