#pragma once
// The blocks after the one in work. Block by block, the channel first takes what the look-ahead
// read early, then reads on from the program. Under G41/G42 the tool nose radius compensation
// turns the programmed contour into the path of the tool tip, reading ahead until each piece of
// that path is final, and the channel runs the pieces as blocks. The look-ahead peeks at the
// blocks (or pieces) after the one in work to choose the speed that block may end at.
//
// A plain value: it is parked with the program in work while the REPOS subroutine runs, and a
// copy of the channel copies it. The feed never reads the program itself: each call that may
// read is handed the channel's reader, and a block's error is handed back for the channel to
// report at the block.

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "control/axes/axis_parameters.hpp"
#include "control/axes/tool_table.hpp"
#include "control/channel/block_motion.hpp"
#include "control/channel/look_ahead.hpp"
#include "control/channel/tool_radius_compensation.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

/// Reads the program's next block into its argument; false at the end of the program, or at the
/// interpreter's error (which the channel looks up).
using ReadBlock = std::function<bool(nc::PreparedBlock&)>;

/// An error of a block the feed took: the channel reports it at that block.
struct BlockError {
  uint32_t program = 0;  ///< the channel's program index of the block
  int32_t block = 0;
  std::string text;
  int number = 0;  ///< the NC message number
};

/// What the feed knows of its channel: the tool list and the axes of the G18 plane.
struct FeedContext {
  const axes::ToolTable& tools;
  int axis_z = -1, axis_x = -1;  ///< the channel's axes Z and X; -1: it has none
};

/// What the look-ahead needs of the channel to plan the blocks after the one in work.
struct LookAheadView {
  const std::vector<axes::AxisParameters>& axes;
  const std::vector<double>& translation;  ///< program -> axis coordinates, per axis
  const std::vector<bool>& homed;
  double spindle_rev_per_s = 0;
  double cycle_s = 0;  ///< the NC cycle: a block takes one at least
  /// A block the path must reach at rest (a spindle / rotary axis changeover comes first).
  std::function<bool(const nc::PreparedBlock&)> at_rest_before;
  /// Axes the NC does not position in a block (bit per axis; PlanBlockMotion's follow_up).
  std::function<uint64_t(const nc::PreparedBlock&)> follow_up;
};

/// A piece of the tip path taken to run.
struct TakenPiece {
  ContourElement element;
  bool further = false;  ///< a further piece of the block taken before: its functions have run
};

class BlockFeed {
 public:
  /// Forgets everything read ahead and ends the compensation (a new program, Reset, a jump).
  void Drop();

  // ---- Block by block.
  enum class Early { kNone, kTaken, kEnded };
  /// The block the look-ahead read and the channel has not run (kTaken, in `b`), or kEnded when
  /// the read-ahead met the program's end (or its error), or kNone: read on from the program.
  Early TakeEarly(nc::PreparedBlock& b);
  /// True while blocks read early wait to be run.
  bool read_early() const { return !peeked_.empty(); }

  // ---- Under G41/G42.
  bool compensating() const { return compensating_; }
  /// The program's end is read ahead (M30, or the text's end): the tip path is closed.
  bool source_done() const { return source_done_; }
  void ForgetSourceDone() { source_done_ = false; }
  /// Starts the compensation with `first`, the first block that moves under it, from `position`
  /// (axis coordinates; `translation` takes program coordinates to them). False: error().
  bool StartCompensation(const FeedContext& ctx, const std::vector<double>& position,
                         const std::vector<double>& translation, const nc::PreparedBlock& first);
  enum class Fill { kPiece, kDrained, kFailed, kSourceEnded };
  /// Reads ahead through `read` until a piece of the tip path is final: kPiece. In a run `read`
  /// gives first what the look-ahead read early (TakeEarly): a block it could not take fails
  /// here, where the channel reaches it. kDrained: the
  /// compensation has given out everything (it ended with G40, or the program's end is read
  /// ahead) and the channel goes back to block by block. kFailed: error(). kSourceEnded: `read`
  /// returned false; unless that is the interpreter's error, the channel calls EndOfSource and
  /// fills again.
  Fill FillPiece(const FeedContext& ctx, const ReadBlock& read);
  /// The program ended where the read-ahead stands: the tip path closes there.
  void EndOfSource();
  /// The next final piece (after FillPiece gave kPiece) and its block in `block`.
  TakenPiece TakePiece(const FeedContext& ctx, nc::PreparedBlock& block);
  /// The error of the last StartCompensation or FillPiece that failed.
  const BlockError& error() const { return error_; }

  // ---- Look-ahead.
  /// Reads ahead through `read` the blocks after `block` (in work, planned as `motion`) while
  /// they continue its path at speed (feed moves with nothing to wait for, in the same frame),
  /// and writes the speed limits at their junctions into `targets`, the last one at rest
  /// (look_ahead.hpp). False when the block must end at rest (`targets` then empty).
  bool PlanAhead(const FeedContext& ctx, const ReadBlock& read, const nc::PreparedBlock& block,
                 const BlockMotion& motion, const LookAheadView& view,
                 std::vector<SpeedTarget>& targets);

 private:
  std::optional<BlockError> Push(const FeedContext& ctx, const nc::PreparedBlock& b);
  bool Peek(size_t k, const ReadBlock& read);
  void FillCompensated(const FeedContext& ctx, const ReadBlock& read, size_t elements);
  bool PeekCompensated(const FeedContext& ctx, const ReadBlock& read, size_t k,
                       nc::PreparedBlock& out);
  static nc::PreparedBlock ElementBlock(const FeedContext& ctx, const ContourElement& e,
                                        nc::PreparedBlock b);

  // Read early by the look-ahead, block by block.
  std::deque<nc::PreparedBlock> peeked_;       ///< read from the program, not run yet
  bool source_returned_false_ = false;         ///< the read-ahead met the end or an error
  std::optional<nc::PreparedBlock> unpushed_;  ///< read ahead under G41/G42, not taken yet
  // The tool nose radius compensation: blocks read ahead and the tip path made of them.
  ToolRadiusCompensation trc_;
  bool compensating_ = false;
  bool source_done_ = false;
  std::deque<nc::PreparedBlock> ahead_;  ///< blocks read ahead; ahead_[0] has tag first_tag_
  std::deque<ContourElement> ready_;     ///< tip path elements ready to run
  int64_t first_tag_ = 0, next_tag_ = 0, last_run_tag_ = -1;
  Vec2 contour_point_;  ///< end of the last programmed element pushed (program coordinates)
  BlockError error_;
  std::vector<LookAheadLeg> legs_;  ///< the look-ahead's scratch: the blocks read ahead
};

}  // namespace vmt::control::channel
