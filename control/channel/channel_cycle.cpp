// Who owns the NC cycle, and the program's part of it: the block in work waits for what it
// waits for, the next block is read, the block's motion is interpolated.

#include "control/channel/channel.hpp"

namespace vmt::control::channel {

NcCycleOwner Channel::CycleOwner() const {
  if (out_.suspended) return NcCycleOwner::kAxesLent;
  if (mode_ == ChannelMode::kManual) return NcCycleOwner::kJog;
  if (JogsMoving()) return NcCycleOwner::kJogBraking;
  if (backward_.away()) return NcCycleOwner::kBackward;
  if (state_ == ChannelState::kRunning || state_ == ChannelState::kHold) return ProgramCycleOwner();
  return NcCycleOwner::kNone;
}

NcCycleOwner Channel::ProgramCycleOwner() const {
  // Block search owns the cycle while it is under way, its return to the contour included.
  if (search_.active() && bs_.state != BlockSearchState::kInactive)
    return NcCycleOwner::kBlockSearch;
  if (!aux_.functions.empty()) return NcCycleOwner::kAuxAcknowledge;
  if (headstock_.waiting()) return NcCycleOwner::kChangeover;
  if (tool_storage_wait_) return NcCycleOwner::kToolStorage;
  if (work_.pending_motion) return NcCycleOwner::kMotionStart;
  if (work_.dwell_left_s > 0) return NcCycleOwner::kDwell;
  if (sp_.orienting) return NcCycleOwner::kSpindle;
  if (measuring_.in_work() && !work_.active) return NcCycleOwner::kMeasuring;
  if (!work_.active && state_ == ChannelState::kRunning) return NcCycleOwner::kNextBlock;
  return NcCycleOwner::kBlockInWork;
}

void Channel::ProgramCycle(NcCycleOwner owner, const AmplifierTelegram& at, double dt) {
  bool finished = false;
  switch (owner) {
    case NcCycleOwner::kBlockSearch:
      // Decoding without motion, its handshakes and holds (a return move interpolates below).
      SearchCycle(at);
      break;
    case NcCycleOwner::kChangeover:
      // Block preparation and execution wait until the changeover ends (C-axis manual 1.2).
      if (headstock_->mode() == headstock_.waiting_for())
        finished = RunBlock(at) && !work_.active && work_.dwell_left_s <= 0 && !sp_.orienting &&
                   !headstock_.waiting();
      else if (state_ == ChannelState::kRunning)
        headstock_.RequestAgain();  // again, if a jog key turned the changeover round
      break;
    case NcCycleOwner::kMotionStart:
      work_.pending_motion = false;
      if (StartMotion(at))
        finished = !work_.active && work_.dwell_left_s <= 0 && !work_.homing && !sp_.orienting;
      break;
    case NcCycleOwner::kDwell:
      if (state_ == ChannelState::kRunning) work_.dwell_left_s -= dt;
      finished = work_.dwell_left_s <= 0;
      break;
    case NcCycleOwner::kSpindle:
      // M19 ends when the spindle reports itself in position, G77 Sj=0 when its spindles
      // are at speed.
      sp_.orienting = false;
      if (config_.spindle_drive >= 0) {
        const uint32_t status = at.feedback[config_.spindle_drive].status;
        sp_.orienting = sp_.command.mode == DriveMode::kPosition
                            ? !(status & drive_status::kInPosition)
                            : sp_.command.value != 0 && !(status & drive_status::kAtSpeed);
      }
      sp_.orienting |= further_.UpdateRestoring(at);
      finished = !sp_.orienting;
      break;
    case NcCycleOwner::kMeasuring:
      finished = measuring_.Cycle(MeasuringLinkNow());
      break;
    case NcCycleOwner::kNextBlock:
      if (programmed_stop_.Finish()) {
        // M00 / M01: the block before is done, its motion and the acknowledgement of its
        // functions included; the channel holds before the next one.
        state_ = ChannelState::kHold;
        break;
      }
      finished = NextBlock(at) && !work_.active && work_.dwell_left_s <= 0 && !sp_.orienting &&
                 !headstock_.waiting();
      if (finished && measuring_.in_work()) finished = measuring_.Cycle(MeasuringLinkNow());
      break;
    default:
      // The PLC's acknowledgement, MRY's tool storage axis (REPOS manual 4.2): the block
      // waits. The block in work: its motion runs below.
      break;
  }
  // A block interrupted and jogged away from stays where the program left it until the
  // axes are repositioned (REPOS manual 2.1): interpolating it would take them back.
  const bool frozen = state_ == ChannelState::kHold && repos_.interruption() &&
                      repos_.interruption()->left_contour && !repos_.run();
  if (work_.active && !frozen) {
    if (sync_.active())
      SynchronousCycle(at, dt);
    else
      Interpolate(dt);
    if (measuring_.in_work()) measuring_.WatchMove(MeasuringLinkNow(), at);
    finished = !work_.active;
    if (finished && bs_.program_distance.pending()) {
      HoldAtBreakpoint();
      finished = false;
    }
    // A measuring instruction's move has ended: its next step follows at once.
    if (finished && measuring_.in_work()) finished = measuring_.Cycle(MeasuringLinkNow());
    if (finished && work_.homing) finished = !NextHomingStage();
    // C is aligned (#CAX TRACK): the block's own motion follows as one unit with it.
    if (finished && std::exchange(cax_.aligning, false))
      finished = StartMotion(at) && !work_.active && !sp_.orienting;
    if (finished && look_.carry_speed > 0) {
      // Blended: the next block runs on from here in the same cycle.
      finished = NextBlock(at) && !work_.active && !sp_.orienting;
      look_.carry_speed = look_.carry_accel = look_.carry_leftover = 0;
    }
  }
  if (finished && single_block_ && state_ == ChannelState::kRunning) state_ = ChannelState::kHold;
}

}  // namespace vmt::control::channel
