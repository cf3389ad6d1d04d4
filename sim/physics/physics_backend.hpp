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

#include "sim/backend/machine_backend.hpp"

class btMultiBody;
class btMultiBodyDynamicsWorld;
class btMultiBodyGearConstraint;

namespace vmt::sim {

class PhysicsBackend : public MachineBackend {
 public:
  PhysicsBackend(const MachineModel& model, const InitialState& init);
  ~PhysicsBackend() override;

  void Step() override;
  std::vector<double> JointPositions() const override;

  /// Joint velocities (m/s | rad/s).
  std::vector<double> JointVelocities() const;

 private:
  struct World;
  void Couple(int clutch_index);
  void Uncouple(int clutch_index);
  void Clamp(int actuator_index, bool hold);
  void UpdateFeedback(const std::vector<double>& torques);

  std::unique_ptr<World> world_;
  std::vector<double> q_before_;         ///< joint positions before the tick's motion (styluses)
  std::vector<double> torques_;          ///< load side, per drive, of the last tick
};

}  // namespace vmt::sim
