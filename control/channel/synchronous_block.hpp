#pragma once
// A spindle-synchronous block in work (G33 thread cutting, G63/G64 tapping): its phase, path
// and thread law, and the spindle positions it follows.

#include <cstdint>

#include "control/channel/spindle_synchronous_motion.hpp"

namespace vmt::control::channel {

enum class SyncPhase : uint8_t { kNone, kWaitForSpeed, kStopSpindle, kRunning };
struct Synchronous {
  SyncPhase phase = SyncPhase::kNone;
  SynchronousPath path;
  ThreadLaw law;             ///< G33
  double zero_mark_deg = 0;  ///< G33: phi_sync, unwrapped spindle degrees
  double spindle_deg = 0;    ///< G33: the spindle's actual position, unwrapped
  double spindle_last_deg = 0;
  int direction = 1;             ///< spindle rotation: +1 M3, -1 M4
  double spindle_start_deg = 0;  ///< G64: phi0, where the spindle's interpolation starts
  double max_override = 1;       ///< G64: spindle override within the axes' and spindle's limits
};

}  // namespace vmt::control::channel
