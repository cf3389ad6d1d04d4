#pragma once
// One block search from program start to the continue position (block search 3, 4): the
// position the program has the axes at, the continue block and where in it machining goes on,
// and the search's phases.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "control/channel/block_motion.hpp"
#include "control/channel/block_search.hpp"
#include "control/channel/program_distance.hpp"
#include "control/drive_bus.hpp"

namespace vmt::control::channel {

struct BlockSearchRun {
  explicit BlockSearchRun(const BlockSearchParameters& p) : matcher(p) {}
  ContinueMatcher matcher;
  std::vector<double> position;  ///< where the program has the axes, machine coordinates
  DriveSetpoint spindle{DriveMode::kVelocity, 0, 0};  ///< the spindle as the program left it
  bool found = false;            ///< the block boundary of the continue position (phase 1)
  bool by_distance = false;      ///< phase 2: searching on for the distance from program start
  bool ends_program = false;     ///< the search ends the program (type 5, position not found)
  bool start_requested = false;  ///< a start while the search holds
  std::vector<double> restart;   ///< the continue position, machine coordinates
  /// The continue block's motion from its start, and where in it machining goes on; no
  /// motion: the program goes on with the next block.
  BlockMotion restart_motion;
  double restart_u = 0;
  double restart_distance = 0;  ///< distance from program start at the block's start
  double restart_length = 0;    ///< the block's length for that distance
  int64_t blocks = 0;           ///< blocks decoded in search mode
  /// Under G41/G42 the search runs the tip path, as a run does: block_ is a piece of it, a
  /// further piece of a block already simulated, or a corner the compensation inserted
  /// before its block. The per mille lies in the block's own piece: found at an inserted
  /// corner, the search runs it and takes the own piece that follows.
  bool further_piece = false, inserted_piece = false, await_own_piece = false;
  /// After the continue block's boundary, the continue position is still to be placed
  /// (DecideContinue): on the block's own piece, or by the distance from program start.
  bool Deciding() const { return await_own_piece || by_distance; }
  /// Type 1's end position was read (3.1): the program ends before its block.
  bool end_reached = false;
  bool return_rest = false;  ///< C is being aligned; the other axes' return follows (4.2.2)
  /// G31 at the continue position: the return runs on the face's line, as G77 X1/Y1 does.
  bool face_return = false;
  /// The block in work waited for a spindle / rotary axis changeover, which has ended: it
  /// is simulated again from there (BlockSearchSimulation).
  bool changed_over = false;
  /// Where the interpreter had the rotary axis before the block in work (RebaseRotaryAxis).
  double rotary_start = 0;
};

/// What block search keeps across program starts and while the program runs (block search 3.5,
/// 4.1.2, 4.2, 5, 7): the CNC objects, the PLC's handshake, the distance from program start, the
/// breakpoint and the manual return's offset.
struct BlockSearchData {
  BlockSearchParameters next;     ///< the objects as they stand (the next start takes them)
  BlockSearchParameters started;  ///< the running program's (the _r read-backs)
  BlockSearchState state = BlockSearchState::kInactive;
  bool plc_enable = false, plc_state = false, command = false;  ///< the on/off handshake (7)
  BlockSearchStatus status;                                     ///< as of the last NC cycle
  std::vector<std::string> warnings;
  /// The distance from program start (4.1.2) and the breakpoint (3.5).
  ProgramDistance program_distance;
  /// Manual return (4.2): actual minus continue position, kept until the program ends.
  std::vector<double> offset;
};

}  // namespace vmt::control::channel
