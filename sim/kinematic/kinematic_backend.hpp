#pragma once
// The ideal machine: every enabled drive moves exactly at its own velocity reference (position
// loop Kv, ramps, M19 profile of DriveController), so a position command is followed with the
// first-order lag 1/Kv of a perfect velocity loop; gears and an engaged clutch tie joints
// exactly. No masses, no torque (so no drive ever overloads; overspeed and parameter-set faults
// trip as on the physics backend). For fast studies, block search, and as the reference the
// physics backend is checked against.

#include "sim/backend/coupling_graph.hpp"
#include "sim/backend/machine_backend.hpp"

namespace vmt::sim {

class KinematicBackend final : public MachineBackend {
 public:
  KinematicBackend(const MachineModel& model, const InitialState& init);

  void Step() override;
  std::vector<double> JointPositions() const override { return q_; }
  std::unique_ptr<MachineBackend> Copy() const override {
    return std::make_unique<KinematicBackend>(*this);
  }
  void Restore(const MachineBackend& saved) override;

 private:
  void UpdateFeedback();

  std::vector<double> clutch_offsets_;
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
};

}  // namespace vmt::sim
