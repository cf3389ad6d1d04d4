#pragma once
// The channel's function for a spindle-synchronous block (G33 thread cutting, G63 and G64
// tapping; the law in spindle_synchronous_motion.hpp). It owns the block's phase, path and
// thread law and the spindle positions it follows. The channel hands it the block in work (its
// motion and profile, the axes' commanded positions), the main spindle's command and the drives'
// feedback, and turns an error it reports into the channel's error state at the block.

#include <cstdint>
#include <optional>
#include <vector>

#include "control/axes/axis_parameters.hpp"
#include "control/channel/block_motion.hpp"
#include "control/channel/main_spindle_state.hpp"
#include "control/channel/path_profile.hpp"
#include "control/channel/spindle_synchronous_motion.hpp"
#include "control/drive_bus.hpp"
#include "control/nc/interpreter.hpp"

namespace vmt::control::channel {

enum class SyncPhase : uint8_t { kNone, kWaitForSpeed, kStopSpindle, kRunning };

/// A spindle-synchronous block in work between NC cycles.
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

/// What the block in work shares with it: the block, its motion and profile, where the axes
/// are commanded, and the main spindle (its command, override and last NC cycle's command).
struct SynchronousContext {
  const nc::PreparedBlock& block;
  BlockMotion& motion;
  PathProfile& profile;
  std::vector<double>& commanded;
  MainSpindleState& spindle;
};

class SynchronousBlock {
 public:
  /// `axes`: the channel's; `spindle_drive` and `spindle` the main spindle's drive and
  /// parameters (rapid and acceleration limit G64's spindle).
  SynchronousBlock(std::vector<axes::AxisParameters> axes, int spindle_drive,
                   axes::AxisParameters spindle);

  /// Plans the block from the axes' commanded positions (`translation`: program -> axis;
  /// `follow_up`: axes that stay where they are) and starts it. False with nothing to move.
  /// An error ("G63 at ... is faster than the axes' ...") if it cannot run.
  std::optional<MotionError> Start(const SynchronousContext& c,
                                   const std::vector<double>& translation, uint64_t follow_up,
                                   const AmplifierTelegram& at, bool& moves);
  /// One NC cycle of `dt` s: the axes follow the spindle (G33), their profile at 100 % (G63),
  /// or lead the spindle (G64). `spindle_setpoint`: the spindle's speed command with override.
  /// At the end the axes stand exactly at the programmed point and done() holds.
  std::optional<MotionError> Cycle(const SynchronousContext& c, const AmplifierTelegram& at,
                                   double dt, double spindle_setpoint);
  /// No synchronous block is in work (another block starts, or the channel stops).
  void Clear() { s_.phase = SyncPhase::kNone; }
  /// A synchronous block is in work (until its end).
  bool active() const { return s_.phase != SyncPhase::kNone; }

 private:
  std::optional<MotionError> WaitForSpeed(const SynchronousContext& c, double spindle_deg_per_s,
                                          double dt, double spindle_setpoint);

  std::vector<axes::AxisParameters> axes_;
  int spindle_drive_;
  axes::AxisParameters spindle_;
  Synchronous s_;
};

}  // namespace vmt::control::channel
