#pragma once
// The distance from program start (block search 4.1.2) and the breakpoint (3.5). The distance
// counts the path of every block whose motion starts, or that block search passes, while
// #DISTANCE PROG START is ON; CLEAR sets it back to 0. The breakpoint, a distance from program
// start, cuts the block that reaches it: the path stops there like at an M0, and the next start
// runs the rest of the block.

#include <optional>
#include <vector>

#include "control/channel/block_motion.hpp"
#include "control/channel/block_search.hpp"
#include "control/nc/program.hpp"

namespace vmt::control::channel {

class ProgramDistance {
 public:
  /// A program start: ON and cleared (4.1.2), no breakpoint, nothing held.
  void Restart();
  /// The breakpoint of this run, mm from program start; 0: none.
  void SetBreakpoint(double mm) { breakpoint_ = mm; }
  /// #DISTANCE PROG START ON / OFF / CLEAR in a block (inline: every block of a search asks).
  void Command(nc::DistanceCommand command) {
    if (command == nc::DistanceCommand::kOn) on_ = true;
    if (command == nc::DistanceCommand::kOff) on_ = false;
    if (command == nc::DistanceCommand::kClear) distance_ = block_start_ = block_length_ = 0;
  }

  /// The length `motion` adds to the distance: its path (DistanceOf), 0 while OFF.
  double LengthOf(const BlockMotion& motion, const std::vector<axes::AxisParameters>& axes) const {
    return on_ ? DistanceOf(motion, axes) : 0;
  }
  /// Block search passes a block of `length` without running it.
  void Pass(double length) { distance_ += length; }
  /// A block's motion starts: its length counts, and `motion` ends at the breakpoint if that
  /// lies in it (pending()).
  void BlockStarts(BlockMotion& motion, const std::vector<axes::AxisParameters>& axes);
  /// After block search machining goes on inside the continue block, whose motion is `motion`
  /// from its start, of `length`, starting at `start` mm: from `u` on. A breakpoint in the rest
  /// cuts it as it would cut the block whole. Returns where on the (perhaps cut) motion the
  /// continue position lies.
  double ContinueInBlock(double start, double length, double u, BlockMotion& motion);

  /// 3.5: the breakpoint lies before `continue_mm`, where it must lie after it.
  bool BreakpointBefore(double continue_mm) const {
    return breakpoint_ > 0 && breakpoint_ < continue_mm - 1e-9;
  }
  double breakpoint() const { return breakpoint_; }
  /// The block in work ends at the breakpoint: the path holds when it has run.
  bool pending() const { return pending_; }
  /// The path has reached the breakpoint and holds.
  void Hold();
  bool holding() const { return holding_; }
  /// The start after the hold: the rest of the cut block, if the breakpoint cut one, and in
  /// `u` where on the block it starts. The hold is over.
  std::optional<BlockMotion> Resume(double& u);
  /// Given up (a reverse program, Control-Reset): no hold, no rest of a block.
  void Drop();

  double distance() const { return distance_; }  ///< mm up to the end of the block in work
  /// mm from program start at `u` of the block in work (0 at its start), on the block as it
  /// was before the breakpoint cut it.
  double DistanceAt(double u) const { return block_start_ + u * block_length_; }
  /// Where the breakpoint cut the block in work (its u); 1 when it did not.
  double CutFraction() const { return rest_ ? cut_u_ : 1; }

 private:
  /// The breakpoint's cut of `motion` if it lies in the block in work from `from_u` on.
  void Cut(BlockMotion& motion, double from_u);

  bool on_ = true;
  double distance_ = 0, block_start_ = 0, block_length_ = 0;
  double breakpoint_ = 0;  ///< 0: none or passed
  std::optional<BlockMotion> rest_;
  double cut_u_ = 0;
  bool holding_ = false, pending_ = false;
};

}  // namespace vmt::control::channel
