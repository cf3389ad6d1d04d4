#include "sim/runner/run_path_guard.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "sim/collision/spindle_sweep.hpp"

namespace vmt::sim {
namespace {

/// Turned stock slices whose radii differ by less make one cylinder for PathGuard: well below
/// the cut's allowance, so a merged run never stands above a tool in its cut.
constexpr double kStockTolerance = 2e-6;

}  // namespace

RunPathGuard::RunPathGuard(const MachineModel& m, const Workpiece& workpiece,
                           const MachineBackend& backend)
    : backend_(&backend) {
  std::vector<CylinderPart> parts;
  if (workpiece.present) {
    cutter_ = std::make_unique<StockCutter>(m, workpiece.part);
    parts = cutter_->stock().Cylinders(kStockTolerance);
  }
  const MachineBackend* b = backend_;
  guard_ = std::make_unique<MachinePathGuard>(m, parts, [b] { return b->JointPositions(); });
  guard_->SetSweep(
      SweepOf(guard_->world(), workpiece.present ? workpiece.part.link : std::string("spindle")));
  guard_->before_check = [this](CollisionWorld&) {
    if (!parts_stale_ || !cutter_) return;
    guard_->SetAdded(cutter_->stock().Cylinders(kStockTolerance));
    parts_stale_ = false;
  };
}

void RunPathGuard::FollowSpindle(double t, double cycle_s) {
  const std::vector<double> q = backend_->JointPositions();
  if (cutter_ && cutter_->Cut(q, t)) {
    parts_stale_ = true;
    ++stock_cuts_;
  }
  const int joint = guard_->sweep().joint;
  if (joint < 0) return;
  guard_->SetSpindleTurning(std::abs(q[joint] - spindle_angle_) >= kTurningSpeedRadS * cycle_s);
  spindle_angle_ = q[joint];
}

RunPathGuard::Saved RunPathGuard::Save() const {
  Saved saved{std::nullopt, guard_->Save(), spindle_angle_, parts_stale_, stock_cuts_};
  if (cutter_) saved.cutter = *cutter_;
  return saved;
}

void RunPathGuard::Restore(const Saved& saved) {
  if (cutter_) *cutter_ = *saved.cutter;
  guard_->Restore(saved.guard);
  spindle_angle_ = saved.spindle_angle;
  parts_stale_ = saved.parts_stale;
  stock_cuts_ = saved.stock_cuts;
}

}  // namespace vmt::sim
