#pragma once
// A program in work: its interpreter, the block in work with its motion and profile, dwell,
// homing, and the blocks after it (block_feed.hpp). The channel runs one; while the REPOS
// subroutine runs in the interrupted program's place, that one is parked, and the two swap as
// one value when the subroutine starts and ends. It is a plain value: copying a channel copies it.

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "control/channel/block_feed.hpp"
#include "control/channel/block_motion.hpp"
#include "control/channel/look_ahead.hpp"
#include "control/channel/path_profile.hpp"
#include "control/nc/interpreter.hpp"
#include "control/nc/program.hpp"

namespace vmt::control::channel {

struct ProgramInWork {
  std::optional<nc::Interpreter> interpreter;
  nc::PreparedBlock block;  ///< the block in work
  BlockMotion motion;
  PathProfile profile;
  bool active = false;          ///< a block is in work
  bool pending_motion = false;  ///< the block's motion waits for the aux acknowledgement
  bool homing = false;
  double dwell_left_s = 0;
  std::vector<std::pair<int, uint64_t>> homing_stages;  ///< G74: order, axes bits
  BlockFeed feed;  ///< the blocks after the one in work: read early, or the G41/G42 tip path
  std::vector<SpeedTarget> targets;  ///< speed limits ahead of the block in work
  bool continuation_ready = false;   ///< this block ends at speed into the next
  /// The interpreter's rotary axis position before the block last read (ReadNext), and after it.
  double rotary_start = 0, rotary_next_start = 0;
};

/// MDI: the blocks the next start runs in MDI mode, and whether the program in work is theirs.
struct MdiState {
  std::shared_ptr<const nc::ParseResult> blocks;  ///< shared by copies of the channel
  bool running = false;
};

}  // namespace vmt::control::channel
