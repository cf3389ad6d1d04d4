#pragma once
// control::PathGuard on the machine model: drive positions to joint positions (through the
// drive's gear or load encoder and the model's gear couplings), the straight-move check on the
// CollisionWorld, and the answer back in machine units. Joints no drive sets (a spindle whose
// clutch is open, the turret's driven tool) stay where `current` says the machine stands now
// (the backend's poses). While the spindle turns, or before it starts, the chuck is checked as
// the solid it sweeps (spindle_sweep.hpp).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "control/path_guard.hpp"
#include "sim/collision/clearance_proof.hpp"
#include "sim/collision/spindle_sweep.hpp"
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
  /// The main spindle's `sweep` (the workpiece's link) against the rest: `spindle` is the
  /// channel's main spindle drive, the one whose chuck `sweep` is.
  control::PathCheck CheckSpindleStart(const std::vector<double>& at, int spindle) override;
  /// The last clear CheckMove as proof (clearance_proof.hpp): with the world unchanged since,
  /// it answers for a move whose slides stray from it by no more than its clearance may be off
  /// (options.clearance_relative), querying only the pairs of the parts a rotation moved.
  bool Proves(const std::vector<double>& from, const std::vector<double>& to,
              control::PathCheck& check) override;
  /// The joint positions (SI) for the drives' positions on top of `base`; where two drives
  /// read one joint, the one `moving` marks wins.
  std::vector<double> JointPositions(const std::vector<double>& base,
                                     const std::vector<double>& drives,
                                     const std::vector<char>& moving) const;
  CollisionWorld& world() { return world_; }
  StraightMoveOptions options;
  /// Called before every check: the runner brings the workpiece up to date here (SetAdded).
  std::function<void(CollisionWorld&)> before_check;
  /// The parts the scene adds (the workpiece as turned), in the world from the next check on.
  void SetAdded(std::vector<CylinderPart> added);
  /// What the chuck sweeps while its spindle turns (SweepOf the workpiece's link).
  void SetSweep(SpindleSweep sweep);
  const SpindleSweep& sweep() const { return sweep_; }
  /// While the spindle turns, the chuck's parts are checked as the solid they sweep.
  void SetSpindleTurning(bool turning) { turning_ = turning; }

 private:
  struct Proof {
    ClearMove move;
    int64_t world_version = -1;
    std::string closest_a, closest_b;
  };

 public:
  /// What the checks change, kept to go back to (a run's in-memory snapshot).
  struct Saved {
    CollisionWorld::Saved world;
    std::vector<CylinderPart> added;
    SpindleSweep sweep;
    bool turning, world_swept, stale;
    int64_t world_version;
    std::optional<Proof> proof;
  };
  Saved Save() const;
  void Restore(const Saved& saved);

 private:
  const MachineModel* model_;
  CollisionWorld world_;
  std::function<std::vector<double>()> current_;
  /// Brings the world's added parts and the chuck up to date: `swept`, the chuck as it sweeps.
  void Refresh(bool swept);
  std::vector<CylinderPart> added_;
  SpindleSweep sweep_;
  bool turning_ = false;
  bool world_swept_ = false;    ///< the world holds the sweep in the chuck's place
  bool stale_ = false;          ///< added_ or the sweep changed since the world was built
  int64_t world_version_ = 0;   ///< counts the world's rebuilds (Refresh)
  std::optional<Proof> proof_;  ///< the last CheckMove, when it was clear
};

}  // namespace vmt::sim
