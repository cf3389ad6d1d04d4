#pragma once
// Block search ("Satzvorlauf", twincat-cnc-block-search-de.md): the program runs without axis
// motion up to a continue position, rebuilding its whole context (modal state, variables,
// offsets, tool, spindle, technology sent to the PLC), then the axes return to the contour and
// machining goes on from there. This file holds the plain data of it: the CNC objects the PLC
// or the operator sets before the program start (5.1-5.4), the states and status data the PLC
// reads (5.6), and the matching of the continue position, which the skipped blocks
// (block_search_simulation.hpp) run.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "control/axes/axis_parameters.hpp"
#include "control/channel/block_motion.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

/// mc_cmd_bs_type_w (5.1). Type 2 no longer exists; 5 searches to the program end (decode
/// only, 3.4); 6 sets only the breakpoint, without a search (3.5.1).
enum class BlockSearchType : uint8_t {
  kNone = 0,
  kFileOffset = 1,
  kBlockCounter = 3,
  kBlockNumber = 4,
  kProgramEnd = 5,
  kBreakpointOnly = 6,
};

/// A position in a file (type 1, 5.2): the offset of a line start, the file as it was
/// started, main (0) or subprogram path (1), and the pass at which it counts.
struct FilePosition {
  int64_t offset = -1;  ///< -1: not given
  std::string name;
  int path = 0;   ///< mc_cmd_bs_pos_*_type_w: 0 HP, 1 UP
  int count = 1;  ///< mc_cmd_bs_pos_*_count_w, 1..MAX_SGN16

  bool operator==(const FilePosition&) const = default;
};

/// The block search parameters (5.1-5.4), in the manual's units as the CNC objects carry them
/// (0.1 um for distances, per mille for the covered distance). The channel takes them at the
/// program start (5: later changes do not affect the running program).
struct BlockSearchParameters {
  BlockSearchType type = BlockSearchType::kNone;
  bool auto_return = false;         ///< mc_cmd_bs_auto_return_w
  bool no_hold_at_restart = false;  ///< mc_cmd_bs_no_hold_at_restart_w
  int64_t deviation_max = 0;        ///< mc_cmd_bs_deviation_max_w, 0.1 um
  int64_t file_offset = 0;          ///< mc_command_file_offset_w: the entry point (3.6)
  double breakpoint_position = 0;   ///< mc_cmd_bs_breakpoint_position_w, 0.1 um; 0 = none
  double distance_prog_start = 0;   ///< mc_cmd_bs_distance_prog_start_w, 0.1 um; 0 = none
  double covered_distance = 0;      ///< mc_cmd_bs_covered_distance_w, per mille 0..1000
  FilePosition start, end;          ///< type 1: continue position, optional end position
  uint32_t intern_block_count = 0;  ///< type 3: mc_cmd_bs_intern_block_count_w
  uint32_t block_number = 0;        ///< type 4: mc_cmd_bs_block_number_w
  uint32_t block_number_pass = 1;   ///< type 4: mc_cmd_bs_block_number_pass_w
  std::string block_nbr_prog_name;  ///< type 4: mc_cmd_bs_block_nbr_prog_name_w, "" = any

  bool searches() const {
    return type != BlockSearchType::kNone && type != BlockSearchType::kBreakpointOnly;
  }
  bool operator==(const BlockSearchParameters&) const = default;
};

/// What is wrong with the parameters, "" if nothing (the ranges of 5.1-5.4).
std::string CheckBlockSearch(const BlockSearchParameters& p);

/// block_search_state_r, HLI_BS_* (5.6, figure 26).
enum class BlockSearchState : uint8_t {
  kInactive = 0,
  kWaitForPlcOn = 1,
  kActive = 2,
  kWaitForPlcOff = 3,
  kWaitReturnToContour = 4,
  kReturningToContour = 5,
  kWaitForContinueContour = 6,
};
const char* ToString(BlockSearchState s);  ///< "HLI_BS_ACTIVE", ...

/// stop_conditions_r, HLI_SC_* (5.6): why the path stands. The bits vmt sets; the catalog's
/// table (signal_catalog_block_search.cpp) says for each of the others why vmt never sets it.
namespace stop_condition {
inline constexpr uint32_t kFeedhold = 0x0001;
inline constexpr uint32_t kSingleBlock = 0x0004;
inline constexpr uint32_t kM00OrM01 = 0x0010;
inline constexpr uint32_t kPlcAcknowledge = 0x0020;
inline constexpr uint32_t kOverrideZero = 0x0040;
inline constexpr uint32_t kOverrideRapidZero = 0x0080;
inline constexpr uint32_t kDelayTime = 0x0200;
inline constexpr uint32_t kIpoInputEmpty = 0x1000;
inline constexpr uint32_t kIpoInputDisabled = 0x2000;
inline constexpr uint32_t kWaitForAxes = 0x8000;
inline constexpr uint32_t kChannelError = 0x00010000;
inline constexpr uint32_t kWaitTechnoAck = 0x00020000;
inline constexpr uint32_t kWaitContinueAfterCollision = 0x00040000;
inline constexpr uint32_t kStopReversible = 0x00200000;
inline constexpr uint32_t kBreakpointStop = 0x00400000;
inline constexpr uint32_t kM0Stop = 0x02000000;
inline constexpr uint32_t kM1Stop = 0x04000000;
}  // namespace stop_condition

/// The status data of block search and path the PLC reads (5.5, 5.6), as of the last NC cycle.
struct BlockSearchStatus {
  BlockSearchState state = BlockSearchState::kInactive;
  /// block_search_active_r: the interpolator works without axis motion (states 2 and 3).
  bool active() const {
    return state == BlockSearchState::kActive || state == BlockSearchState::kWaitForPlcOff;
  }
  /// bahn_lc_control.block_search.command_r: the NC asks the PLC to switch block search on.
  bool command = false;
  double covered_distance = 0;  ///< covered_distance_r: per mille of the block in work
  double dist_prog_start = 0;   ///< dist_prog_start: mm since program start or the last CLEAR
  uint32_t block_count = 0;     ///< block_count_r: the decoder's line count of the block in work
  double path_deviation = 0;    ///< block_search_path_deviation_r: mm from the continue position
  uint32_t stop_conditions = 0;  ///< stop_conditions_r
  /// The continue position (machine coordinates per channel axis) once it is found.
  std::vector<double> continue_position;
  /// Warnings of the search (the continue position was not found, a distance before the found
  /// block): they do not stop the channel. Oldest first, never cleared during a run.
  std::vector<std::string> warnings;
};

/// Recognises the continue position (types 1, 3, 4) among the blocks the interpreter hands out
/// in search mode (SetEveryBlock): by file offset and pass, by the decoder's line count, or by
/// block number, program name and pass.
class ContinueMatcher {
 public:
  explicit ContinueMatcher(const BlockSearchParameters& p) : p_(p) {}
  /// True when `block` of `program` (index `program_index` in the channel's list, 0 = main) is
  /// the continue position. Counts passes: call it once per executed block, in order.
  bool Matches(const nc::PreparedBlock& block, const nc::Program& program,
               uint32_t program_index);
  /// Type 1's end position (5.2.2): true when `block` is it (its pass counted too).
  bool EndMatches(const nc::PreparedBlock& block, const nc::Program& program,
                  uint32_t program_index);

 private:
  static bool AtFilePosition(const FilePosition& f, const nc::PreparedBlock& block,
                             const nc::Program& program, uint32_t program_index);
  BlockSearchParameters p_;
  int passes_ = 0, end_passes_ = 0;
};

/// True for the #-commands that steer block search and the return to the contour (typed when the
/// program is parsed, nc::HashCommandOf): #DISTANCE PROG START (4.1.2), #BLOCKSEARCH (6) and
/// #CAX TRACK (4.2.2; the manual's program spells it #CAXTRACK). A normal run passes them.
/// #VECTOR OFFSET (4.2.3) is not one: vmt refuses it.
bool SteersBlockSearch(nc::HashCommand command);

/// The refusal of a #-command that vmt does not run, naming it and why; empty for any other.
std::string RefusedHashCommand(nc::HashCommand command);

/// Path length of a block's motion for the distance from program start (4.1.2): the travel of
/// the main axes (X, Y, Z); a block that moves none of them counts the travel of the following
/// axis that takes longest at its rapid limit. mm (degrees for a rotary axis alone).
double DistanceOf(const BlockMotion& motion, const std::vector<axes::AxisParameters>& axes);

}  // namespace vmt::control::channel
