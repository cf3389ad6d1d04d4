#pragma once
// The channel's function for backward travel (block search manual 4.3, "Rückwärtsfahren"): it
// records the path the program's blocks took (path_memory.hpp) and, while the program is held,
// travels it back block by block and forward again to the interruption point (path_replay.hpp).
// It owns the path and the position on it; the channel decides whether a start may travel back
// (repositioning, block search's offset, where the axes stand) and hands it the commanded
// position to move, the feed override, and PathGuard's check of a leg block search decoded.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "control/channel/block_motion.hpp"
#include "control/channel/path_memory.hpp"
#include "control/channel/path_replay.hpp"

namespace vmt::control::channel {

/// PathGuard's check of a G00 leg along a block block search decoded (the axes never went
/// along it), from where they stand to `leg_end` (channel axes): true if it stopped the leg.
using ReplayGuard =
    std::function<bool(const std::string& move, const std::vector<double>& leg_end)>;

/// What a leg's start or an NC cycle of the travel came to.
enum class ReplayStep : uint8_t {
  kMoving,   ///< a leg is in work, or the travel stands on the path
  kArrived,  ///< forward again at the interruption point: the program may go on from there
};

class BackwardTravel {
 public:
  /// A block's motion starts (`rapid`: G00; `decoded`: block search's, never travelled). A
  /// motion backward travel cannot take forgets the path before it.
  void Record(const BlockMotion& motion, bool rapid, bool decoded);
  /// A block backward travel cannot take (G74, a thread, measuring): the path before it is
  /// forgotten.
  void Forget() { memory_.Clear(); }
  bool empty() const { return memory_.empty(); }

  /// The direction the next start takes while the program is held (Channel::SetBackward).
  void Request(bool backward) { replay_.backward_requested = backward; }
  bool backward_requested() const { return replay_.backward_requested; }
  /// Off the interruption point, on the path behind it.
  bool away() const { return replay_.away; }
  /// A leg is in work (or brakes for feed hold).
  bool moving() const { return replay_.direction != 0; }
  /// Blocks of the path behind the axes (0 at the interruption point, or not away).
  size_t blocks_back() const { return replay_.away ? memory_.size() - replay_.index - 1 : 0; }

  /// The last step recorded is `motion` (copied from it when its block started).
  bool LastStepIs(const BlockMotion& motion) const;
  /// `position` is the end of the last step recorded.
  bool AtLastStepEnd(const std::vector<double>& position) const;
  /// Backward travel can start at `u` on the last step (-1: the axes are not on it): there is
  /// path behind them.
  bool CanGoBackFrom(double u) const;

  /// Feed hold: a leg in work brakes to rest on the path.
  void Hold() {
    if (replay_.direction != 0) replay_.stopping = true;
  }
  /// A start while a leg brakes for feed hold takes it up again.
  void Resume() { replay_.stopping = false; }
  /// The travel begins at the interruption point `position`, at `u` on the last step
  /// (CanGoBackFrom).
  void BeginAt(const std::vector<double>& position, double u);
  /// Backward from where the travel stands: the next leg starts.
  ReplayStep Back(std::vector<double>& commanded, const ReplayGuard& guard);
  /// Forward again towards the interruption point: the next leg starts.
  ReplayStep Forward(std::vector<double>& commanded, const ReplayGuard& guard);
  /// One NC cycle of `dt` s at feed override `override`: moves `commanded` along the leg; at
  /// its end the next leg starts. `held`: the program is still held, else the travel stops.
  ReplayStep Cycle(double dt, double override, bool held, std::vector<double>& commanded,
                   const ReplayGuard& guard);
  /// The operator leaves for manual mode while away: the interruption point, now a point to
  /// reposition to, and the travel is over. Nothing if not away.
  std::optional<std::vector<double>> Leave();
  /// Control-Reset: the path and the travel are forgotten; the direction asked for stays.
  void Reset();

 private:
  ReplayStep StartLeg(std::vector<double>& commanded, const ReplayGuard& guard);

  PathMemory memory_;
  PathReplay replay_;
};

}  // namespace vmt::control::channel
