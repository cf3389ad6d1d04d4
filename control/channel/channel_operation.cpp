// What the operator and the PLC do to the channel as a whole: the operating mode, start, feed
// hold and Control-Reset, and lending the axes to a JogOfPath channel (jog_of_path.hpp).
#include <cmath>

#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

/// An error the REPOS subroutine may be started again after (see Start).
bool ReposErrorInterrupts(int number) {
  switch (number) {
    case kMsgDriveFault:
    case kMsgFollowingError:
    case kMsgPlcFault:
    case kMsgChangeoverAck:
    case kMsgMeasuringReverseOnly:
      return false;
  }
  return true;
}

}  // namespace

bool Channel::SetMode(ChannelMode mode) {
  // C-axis manual 2.3: a mode change during a changeover is an immediate stop.
  if (state_ == ChannelState::kRunning && headstock_ && headstock_->busy() && mode != mode_) Stop();
  if (state_ == ChannelState::kRunning || backward_.moving()) return false;
  // MDI and an interrupted automatic program do not share the interpreter: MDI needs the
  // program ended or reset first, and an interrupted MDI sequence ("execute in manual mode",
  // REPOS manual 2.1) goes on in MDI, not in automatic.
  const bool interrupted = state_ == ChannelState::kHold && work_.interpreter;
  if (interrupted && mode != ChannelMode::kManual && (mode == ChannelMode::kMdi) != mdi_.running)
    return false;
  if (mode != mode_) {
    // A jog under way is let go as at released keys: it brakes to rest in the new mode (Cycle)
    // rather than stopping dead, an increment runs to its end, and neither goes on when manual
    // mode comes back. X1/Y1 and the tool storage axis alike.
    for (JogAxis& j : jog_.axes) j.key = 0, j.blocked = 0;
    for (FictiveJog& f : jog_.fictive) f.key = 0;
    tool_storage_.ReleaseKey();
    // Where the program was interrupted: the contour the axes must come back to (REPOS 2.1).
    if (mode == ChannelMode::kManual && !repos_.interruption() && state_ == ChannelState::kHold &&
        !repos_.run())
      CaptureInterruption();
    // Travelled back: the program was interrupted at the point the travel started from, and
    // the way back to it is now repositioning's (the axes have left it).
    if (std::optional<std::vector<double>> home = backward_.Leave())
      repos_.MoveInterruptionPoint(*home);
    // Manual mode during the REPOS subroutine's hold: the next start runs it again.
    if (mode == ChannelMode::kManual && repos_.run() && state_ == ChannelState::kHold)
      repos_.Rerun();
    // REPOS manual 2.1: interrupted MDI blocks keep their interpreter through manual mode.
    if ((mode == ChannelMode::kMdi || mode_ == ChannelMode::kMdi) && !interrupted) {
      if (work_.interpreter) last_modal_ = work_.interpreter->modal();
      work_.interpreter.reset();
      if (state_ == ChannelState::kEnded) state_ = ChannelState::kIdle;
    }
  }
  mode_ = mode;
  start_.deferred = false;
  RestartHandwheel();
  return true;
}

CycleStart Channel::StartCase() const {
  if (mode_ == ChannelMode::kManual || !enable_.process) return CycleStart::kRefused;
  if (mode_ == ChannelMode::kMdi && !mdi_.blocks) return CycleStart::kRefused;
  if (JogsMoving()) return CycleStart::kDeferred;
  if (state_ == ChannelState::kHold) {
    if (backward_.moving() || backward_.backward_requested() || backward_.away())
      return CycleStart::kReplay;
    if (bs_.program_distance.holding() ||
        (search_.active() && bs_.state != BlockSearchState::kInactive))
      return CycleStart::kBlockSearchHold;
    if (repos_.run()) return repos_.rerun() ? CycleStart::kReposRerun : CycleStart::kReposContinue;
    if (repos_.interruption() && repos_.called()) return CycleStart::kReposCall;
    return CycleStart::kContinue;
  }
  // REPOS manual 4.2 and 7.1 call the REPOS subroutine's errors (G77 without F or without the
  // function, G77 in the wrong headstock mode) a program interruption: the interrupted program
  // keeps its interruption point and PxxS.REPOS stays set (7.2). vmt reads every error of the
  // subroutine's blocks so (PathGuard's 507 included): the operator may put things right, in
  // manual mode if need be, and Start acknowledges the error and runs the subroutine again from
  // `.REPOS`. Faults of the machine (drives, PLC, a changeover acknowledgement) and the measuring
  // faults only the reverse program leaves still need Control-Reset (or the reverse program).
  if (state_ == ChannelState::kError && repos_.run() && ReposErrorInterrupts(error_number_))
    return CycleStart::kReposAfterError;
  if (state_ == ChannelState::kRunning || state_ == ChannelState::kError)
    return CycleStart::kRefused;
  return CycleStart::kRun;
}

void Channel::Start() {
  const CycleStart start = StartCase();
  if (start == CycleStart::kRefused) return;
  if (start == CycleStart::kDeferred) {
    start_.deferred = true;
    return;
  }
  if (state_ == ChannelState::kHold) {
    programmed_stop_.Leave();
    // A start acknowledges backward travel's refusal, unless it takes up a leg that braked.
    if (!backward_.moving() && error_number_ == kMsgBackward) error_.clear(), error_number_ = 0;
    // Fast measurement 6.1, Q9998: the new start acknowledges OVERSIZE / UNDERSIZE.
    if (start != CycleStart::kReplay && start != CycleStart::kBlockSearchHold &&
        error_number_ == kMsgMeasuringContinuable)
      error_.clear(), error_number_ = 0;
  }
  switch (start) {
    case CycleStart::kRefused:
    case CycleStart::kDeferred:
      return;
    case CycleStart::kReplay:
      StartReplay();
      return;
    case CycleStart::kBlockSearchHold:
      StartBlockSearchHold();
      return;
    case CycleStart::kReposRerun:
      // Stopped during the REPOS subroutine and left for manual mode (jogged, perhaps): its
      // G77 in work no longer starts where the axes stand. It runs again from `.REPOS`, to
      // the same interruption point; the subroutine's progress is no new interruption.
    case CycleStart::kReposCall:  // the REPOS subroutine returns the axes (4.1)
      StartReposRun();
      return;
    case CycleStart::kReposContinue:
      state_ = ChannelState::kRunning;
      return;
    case CycleStart::kContinue:
      ContinueHeldProgram();
      return;
    case CycleStart::kReposAfterError:
      error_.clear();
      error_number_ = 0;
      StartReposRun();
      return;
    case CycleStart::kRun:
      // Start after the end runs the program again from its first block.
      if (state_ == ChannelState::kEnded) ForgetEndedProgram();
      programmed_stop_.Leave();
      state_ = ChannelState::kRunning;
      start_.program = true;  // positions are taken from the feedback at the next tick
      return;
  }
}

void Channel::ContinueHeldProgram() {
  // Continuing from off the contour would jump back to the path: the axes must first be
  // repositioned to the interruption point.
  for (size_t a = 0; a < out_.commanded.size() && repos_.interruption(); ++a) {
    // The rotary axis outside rotary axis mode follows the spindle: no contour to leave.
    if (headstock_.RotaryAxisOff() && static_cast<int>(a) == config_.rotary_axis) continue;
    const double point = repos_.interruption()->point[a];
    if (std::isnan(point)) continue;  // not on the contour (CaptureInterruption)
    if (std::abs(out_.commanded[a] - point) > 1e-6) {
      Fail("axis " + config_.axes[a].name +
               " has left the contour at the interruption point: reposition it first",
           kMsgLeftContour);
      return;
    }
  }
  repos_.Clear();
  state_ = ChannelState::kRunning;
}

void Channel::Stop() {
  start_.deferred = false;
  if (state_ == ChannelState::kRunning) state_ = ChannelState::kHold;
  backward_.Hold();
}

void Channel::Reset() {
  // Control-Reset aborts a changeover; the mode is again what the PLC acknowledges (2.3).
  headstock_.TakeModeFromPlc();
  state_ = ChannelState::kIdle;
  error_.clear();
  error_number_ = 0;
  start_.deferred = false;
  work_.active = false;
  work_.homing = false;
  reversing_ = false;
  work_.dwell_left_s = 0;
  sp_.orienting = false;
  further_.StopRestoring();
  aux_.functions.clear();
  programmed_stop_.Leave();
  tool_storage_.ForgetProgramTraverse();
  tool_storage_wait_ = false;
  if (repos_.run()) SwapProgramInWork();
  parked_ = ProgramInWork{};
  repos_.Clear();
  measuring_.Reset();
  // Block search 7: a reset leaves block search without the handshake.
  search_.Reset();
  bs_.state = BlockSearchState::kInactive;
  bs_.command = false;
  // 7: a CNC reset clears the CNC's and the PLC's signal of the handshake alike, so the next
  // search waits for the PLC's TRUE again.
  bs_.plc_state = false;
  cax_.command.reset();
  cax_.aligning = false;
  bs_.program_distance.Drop();
  bs_.offset.clear();  // the G92 shift goes below
  backward_.Reset();
  if (work_.interpreter) last_modal_ = work_.interpreter->modal();
  work_.interpreter.reset();
  DropLookahead();
  out_.previous = out_.commanded;
  sp_.command = {DriveMode::kVelocity, 0, 0};
  further_.Reset();
  sp_.referencing = false;
  headstock_.ForgetManual();
  // A real control acknowledges its drives' errors with Control-Reset: the drives that tripped
  // get their controller enable removed for a cycle (the drive's fault reset), see Tick.
  drives_.trip_reset_pending = true;
  // Control-Reset drops the G92 shift and returns to the initial modal state (offsets too).
  std::fill(frames_.shift.begin(), frames_.shift.end(), 0.0);
  last_modal_ = config_.initial;
  for (size_t a = 0; a < frames_.translation.size(); ++a)
    frames_.translation[a] = zero_offsets_.Offset(config_.initial.zero_offset, a);
  if (headstock_) {
    const size_t r = static_cast<size_t>(config_.rotary_axis);
    headstock_.set_rotary_translation(frames_.translation[r]);
    if (!headstock_.RotaryOffsetsActive()) frames_.translation[r] = 0;
  }
}

void Channel::FollowAxesOf(const Channel& holder) {
  if (!out_.suspended || !out_.holding || !holder.out_.holding) return;
  for (size_t a = 0; a < config_.axes.size(); ++a) {
    if (!Lent(a)) continue;
    for (size_t h = 0; h < holder.config_.axes.size(); ++h)
      if (holder.config_.axes[h].drive == config_.axes[a].drive)
        out_.commanded[a] = out_.previous[a] = holder.out_.commanded[h];
  }
}

bool Channel::AxesAtRest() const {
  // A block held by a feed hold stands as well as one that has ended: no axis moved in the
  // last NC cycle (a jog may stand for a cycle as it turns round).
  if (JogsMoving()) return false;
  for (size_t a = 0; a < out_.commanded.size(); ++a)
    if (out_.commanded[a] != out_.previous[a]) return false;
  return true;
}

}  // namespace vmt::control::channel
