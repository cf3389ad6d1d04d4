#pragma once
// The owner of the channel's NC cycle: one function of the channel moves the axes in a cycle,
// and Channel::CycleOwner decides which from its state, in a fixed order of priority.

#include <cstdint>

namespace vmt::control::channel {

/// Who owns an NC cycle, in the order the channel asks (Channel::CycleOwner): the first that
/// applies. From kBlockSearch on the cycle is the program's: its block in work waits for
/// something, or the next block is read, and the block's motion is interpolated after.
enum class NcCycleOwner : uint8_t {
  kNone,            ///< idle, ended or in error: nothing runs
  kAxesLent,        ///< output suspended: block search decodes on, the rest waits (4.2.1)
  kJog,             ///< manual mode: the jog keys and the handwheel
  kJogBraking,      ///< a jog left for another mode brakes to rest; a start waits for it
  kBackward,        ///< backward travel, until back at the interruption point (4.3)
  kBlockSearch,     ///< block search: decoding, its handshakes and holds, return to contour
  kAuxAcknowledge,  ///< the block waits for the PLC to acknowledge its M, H, Q and T
  kChangeover,      ///< the block waits for the headstock changeover (C-axis manual 1.2)
  kToolStorage,     ///< MRY: the block waits for the tool storage axis (REPOS manual 4.2)
  kMotionStart,     ///< the block's motion starts, its functions acknowledged
  kDwell,           ///< G04 dwell time
  kSpindle,         ///< M19 orients the spindle, G77 Sj=0 waits for the spindles' speed
  kMeasuring,       ///< the next step of a measuring instruction
  kNextBlock,       ///< M00 / M01 hold, or the next block is read
  kBlockInWork,     ///< the block in work's motion, or nothing while held
};

}  // namespace vmt::control::channel
