#pragma once
// control::PathGuard on the machine model: drive positions to joint positions (through the
// drive's gear or load encoder and the model's gear couplings), the straight-move check on the
// CollisionWorld, and the answer back in machine units. Joints no drive sets (a spindle whose
// clutch is open, the turret's driven tool) stay where `current` says the machine stands now
// (the backend's poses).

#include <functional>
#include <vector>

#include "control/path_guard.hpp"
#include "sim/collision/straight_move_check.hpp"

namespace vmt::sim {

class MachinePathGuard : public control::PathGuard {
 public:
  /// `current`: the joint positions (SI) the machine stands at now.
  MachinePathGuard(const MachineModel& model, const std::vector<CylinderPart>& added,
                   std::function<std::vector<double>()> current);
  control::PathCheck CheckMove(const std::vector<double>& from,
                               const std::vector<double>& to) override;
  control::PathCheck CheckMeasuringPath(const std::vector<double>& from,
                                        const std::vector<double>& to) override;
  /// The joint positions (SI) for the drives' positions on top of `base`; where two drives
  /// read one joint, the one `moving` marks wins.
  std::vector<double> JointPositions(const std::vector<double>& base,
                                     const std::vector<double>& drives,
                                     const std::vector<char>& moving) const;
  CollisionWorld& world() { return world_; }
  StraightMoveOptions options;
  /// Called before every check: the runner brings the workpiece up to date here (as turned).
  std::function<void(CollisionWorld&)> before_check;

 private:
  const MachineModel* model_;
  CollisionWorld world_;
  std::function<std::vector<double>()> current_;
};

}  // namespace vmt::sim
