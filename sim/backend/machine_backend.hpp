#pragma once
// A simulated machine behind the DriveBus: the physics (Bullet) and the kinematic (ideal) backend
// implement this. The runner steps it at the drive tick and reads link poses for rendering and
// collision checking.

#include <map>
#include <string>
#include <vector>

#include "control/drive_bus.hpp"
#include "sim/backend/actuator.hpp"
#include "sim/backend/dog_clutch.hpp"
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

class MachineBackend : public control::DriveBus {
 public:
  /// Advance one drive tick (kDriveTickS).
  virtual void Step() = 0;
  virtual double time_s() const = 0;
  /// Joint positions (m | rad), one per model joint: what the renderer and PathGuard pose.
  virtual std::vector<double> JointPositions() const = 0;
  virtual ClutchState Clutch(int index) const = 0;
  /// The clutch's logic: state, stroke and clashes (dogs ratcheting at speed).
  virtual const DogClutchLogic& ClutchLogic(int index) const = 0;
  /// Stroke of an actuator (machine.yaml order): 0 off end .. 1 on end.
  virtual double ActuatorStroke(int index) const = 0;
  virtual const MachineModel& model() const = 0;
  /// A probe switch (the stylus' contact) on I/O input `io_input` changes to `level` at
  /// `tick_fraction` (0..1) of the tick being stepped: the PLC reads the input from that tick on,
  /// and each drive whose probe input (machine.yaml `probe_inputs:`) is wired to it knows where
  /// its axis was at that instant (DriveFeedback::probe, ProbeEdgeLatch::exact_position). Call
  /// it between Step()s for the next tick, or from within Step before the drives sample. Throws
  /// std::invalid_argument for an input a device drives, an output or a key (ProbeWiring).
  virtual void SetProbeSwitch(int io_input, bool level, double tick_fraction) = 0;
  /// Where the drives' probe sampling stands to a contact (ProbeSamplingPhase); off until set.
  virtual void SetProbeSamplingPhase(const ProbeSamplingPhase& phase) = 0;
  /// The scene's workpiece, which the model's styluses (machine.yaml `probe:`) touch from the
  /// next Step on: each tick the stylus' contact trips its input at the exact instant
  /// (StylusContacts). Throws std::invalid_argument for a part on a link the model lacks.
  virtual void SetWorkpiece(const RevolvedPart& part) = 0;
  /// Styluses deflected beyond their over-travel (crashed) since the last call.
  virtual std::vector<StylusOverTravel> TakeStylusOverTravels() = 0;
};

/// Joint positions for an initial state: drive positions on their motor joints through their
/// ratios (and on a load-side encoder's joint), then gear and engaged-clutch partners. Throws
/// std::invalid_argument on unknown names.
std::vector<double> InitialJointPositions(const MachineModel& model, const InitialState& init);

}  // namespace vmt::sim
