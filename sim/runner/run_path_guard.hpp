#pragma once
// PathGuard in a run: the machine's collision geometry with the scene's workpiece as the tools
// have turned it so far, posed where the backend stands, and the chuck swept while the spindle
// turns. Each NC cycle, before the channel may ask, the stock is cut where the tools stand and
// the spindle's turning noted (FollowSpindle); PathGuard's solids of the stock are rebuilt only
// before a check that follows a cut.

#include <cstdint>
#include <memory>
#include <optional>

#include "sim/backend/machine_backend.hpp"
#include "sim/collision/machine_path_guard.hpp"
#include "sim/collision/stock_cutter.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {

class RunPathGuard {
 public:
  /// `backend` is read at each check and each NC cycle; it must outlive this.
  RunPathGuard(const MachineModel& m, const Workpiece& workpiece, const MachineBackend& backend);
  RunPathGuard(const RunPathGuard&) = delete;  // PathGuard's hook points here
  RunPathGuard& operator=(const RunPathGuard&) = delete;

  MachinePathGuard& guard() { return *guard_; }
  /// The stock as turned (null without a workpiece) and the ticks in which a cut changed it.
  const StockCutter* cutter() const { return cutter_.get(); }
  int64_t stock_cuts() const { return stock_cuts_; }
  /// At the start of an NC cycle of `cycle_s` seconds, at `t`.
  void FollowSpindle(double t, double cycle_s);

  /// The stock as turned and PathGuard's state, kept to go back to (a run's in-memory
  /// snapshot).
  struct Saved {
    std::optional<StockCutter> cutter;
    MachinePathGuard::Saved guard;
    double spindle_angle;
    bool parts_stale;
    int64_t stock_cuts;
  };
  Saved Save() const;
  void Restore(const Saved& saved);

 private:
  const MachineBackend* backend_;
  std::unique_ptr<StockCutter> cutter_;
  std::unique_ptr<MachinePathGuard> guard_;
  double spindle_angle_ = 0;
  bool parts_stale_ = false;  ///< a cut since PathGuard's stock was built
  int64_t stock_cuts_ = 0;
};

}  // namespace vmt::sim
