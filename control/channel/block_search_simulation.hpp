#pragma once
// Block search's decoding of the skipped blocks (twincat-cnc-block-search-de.md 2, 3, 4, 8):
// each block up to the continue position runs without axis motion. Its modal state, offsets,
// tool, spindle and events take effect, its technology goes to the PLC and waits for the
// acknowledgement, a spindle / rotary axis changeover runs as in a run, and its path is followed
// on paper from where the program has the axes, so that the continue position, the distance from
// program start and the path for backward travel are those of an uninterrupted run.
//
// The object owns the search's run (BlockSearchRun). It never reads the program itself and
// never touches the channel: each call is handed a `SearchLink` with the channel's reader, the
// state the blocks change (frames, events, PLC functions, headstock, the path memory), and the
// few channel functions a block needs (offsets, the turret, #CAX TRACK, the measuring
// instructions, a way to fail). The search's phases around it (the PLC's handshake, the return to
// the contour) stay the channel's: they move axes.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "control/channel/aux_output.hpp"
#include "control/channel/backward_travel.hpp"
#include "control/channel/block_motion.hpp"
#include "control/channel/block_search_run.hpp"
#include "control/channel/cax_track.hpp"
#include "control/channel/channel_config.hpp"
#include "control/channel/channel_types.hpp"
#include "control/channel/headstock_control.hpp"
#include "control/channel/program_events.hpp"
#include "control/channel/program_frames.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

/// What the skipped blocks read and change, for one call.
struct SearchLink {
  const ChannelConfig& config;
  BlockSearchData& data;  ///< the started parameters, the search's state, warnings, distance
  nc::Interpreter& interpreter;
  const ChannelState& state;
  ProgramFrames& frames;  ///< offsets and G92 the blocks set
  ProgramEvents& events;  ///< the program's own events
  AuxOutput& aux;         ///< technology to the PLC
  HeadstockControl& headstock;
  const CaxTrackState& cax;  ///< #CAX TRACK: C follows the contour while a command is on
  /// The path memory: the decoded path, for backward travel from the continue position.
  BackwardTravel& backward;
  /// Where the axes are commanded (machine coordinates): C's after a changeover.
  const std::vector<double>& commanded;
  /// G41/G42 is on: the blocks ahead are prepared already (a changeover does not rebase C).
  bool compensating = false;
  /// The rotary axis #CAX TRACK turns, -1: none.
  int tracked_axis = -1;

  std::function<const nc::Program&(uint32_t index)> program_of;
  /// Fails the channel with `text` (message number `number`) at `block` of `program`.
  std::function<void(const nc::Program& program, int32_t block, const std::string& text,
                     int number)>
      fail;
  /// Fails the channel with a message that carries its own position.
  std::function<void(const std::string& message, int number)> fail_message;
  /// `modal`'s offsets and tool take effect for the block: false if that failed the channel.
  std::function<bool(const nc::ModalState& modal, const nc::Program& program, int32_t block)>
      take_offsets;
  /// The block's T words index an NC-controlled turret: false if that failed the channel.
  /// Empty without such a turret.
  std::function<bool(const nc::PreparedBlock& b, const nc::Program& program)> index_tool_storage;
  /// A measuring instruction of the skipped part, simulated from `position` (FastMeasurement).
  std::function<bool(const nc::PreparedBlock& b, std::vector<double>& position)> simulate_measuring;
  /// #CAX TRACK in `st`: nothing if `st` is another command, false if it failed the channel.
  std::function<std::optional<bool>(const nc::Program& program, const nc::Statement& st,
                                    nc::PreparedBlock& b, double c_machine)>
      cax_instruction;
  /// While tracking (cax.command): C's target of `b` from its tangent; `align_to` set when C
  /// turns first.
  std::function<bool(nc::PreparedBlock& b, const std::vector<double>& from, double rev_per_s,
                     std::optional<double>& align_to)>
      track_c;
};

class BlockSearchSimulation {
 public:
  /// Blocks decoded per NC cycle: fast, yet a program looping for ever with motion still leaves
  /// the cycle (and the scene's end) in charge.
  static constexpr int kBlocksPerCycle = 20000;

  /// A search starts with the axes at `position` and the spindle at `spindle`.
  void Begin(const BlockSearchParameters& p, const std::vector<double>& position,
             const DriveSetpoint& spindle);
  void Reset() { run_.reset(); }
  bool active() const { return run_.has_value(); }
  BlockSearchRun& run() { return *run_; }
  const BlockSearchRun& run() const { return *run_; }

  /// Decodes blocks until technology waits for the PLC, a changeover runs, the continue
  /// position is found, the program ends or kBlocksPerCycle have passed. `next_block()` reads
  /// the next one into `block` (the channel's block in work; false on an error, the channel
  /// failed); under G41/G42 it also marks in the run whether the block is a further piece of a
  /// block's tip path or a corner inserted before its block. The block that waited for a
  /// changeover is simulated again first, from where C stands now. False after an error. A
  /// template so that the reader, called for every block, is called directly.
  template <typename NextBlock>
  bool SimulateBlocks(const SearchLink& link, nc::PreparedBlock& block, NextBlock&& next_block) {
    if (!ChangeoverEnded(link, block)) return false;
    for (int n = 0; n < kBlocksPerCycle && GoesOn(link); ++n) {
      if (!next_block()) return false;
      ++run_->blocks;
      if (!SimulateBlock(link, block)) return false;
    }
    return true;
  }

 private:
  /// False while technology waits (PLC acknowledgement, a changeover) or the search ended.
  static bool GoesOn(const SearchLink& link);
  bool SimulateBlock(const SearchLink& link, nc::PreparedBlock& b);
  /// The block's instructions, events, offsets, spindle, turret and PLC functions.
  bool SimulateTechnology(const SearchLink& link, nc::PreparedBlock& b, const nc::Program& program);
  /// The motion part of SimulateBlock; `boundary`: `b` is the block of the continue position.
  bool SimulateMotion(const SearchLink& link, nc::PreparedBlock& b, bool boundary);
  /// The continue position is found at `b`, at u in its motion (planned from its start).
  /// False (an error) when the breakpoint lies before it.
  bool FoundContinuePosition(const SearchLink& link, const nc::PreparedBlock& b,
                             const BlockMotion& motion, double u);
  /// Block search 3.5: false, with the error, if the breakpoint lies before `continue_mm`
  /// from program start (`b`: the block where the search has got to).
  bool BreakpointAfter(const SearchLink& link, double continue_mm, const nc::PreparedBlock& b);
  /// The changeover `b` needs, requested as in a run: false while it runs (the block waits).
  bool Changeover(const SearchLink& link, const nc::PreparedBlock& b);
  /// The changeover `b` waited for has ended: `b` goes on from there, rotary axis rebased.
  void EndChangeover(const SearchLink& link, nc::PreparedBlock& b);
  /// The block in work waited for a changeover that has ended now: it is simulated from there.
  /// False after an error.
  bool ChangeoverEnded(const SearchLink& link, nc::PreparedBlock& b);
  /// The search reached the end of the program (its text or M30).
  void EndsProgram(const SearchLink& link, const char* warning);
  /// The decoded path into the path memory (`keep`: not for a search to the program's end);
  /// G74, G100 and threads end what backward travel can take.
  static void RecordPath(const SearchLink& link, const nc::PreparedBlock& b,
                         const BlockMotion& motion, bool keep);

  std::optional<BlockSearchRun> run_;
};

}  // namespace vmt::control::channel
