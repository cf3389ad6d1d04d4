#include "control/channel/channel.hpp"

#include <cmath>
#include <cstdio>

#include "control/nc/parser.hpp"

namespace vmt::control::channel {

Channel::Channel(ChannelConfig config, std::vector<const nc::Program*> programs)
    : ChannelData(config), config_(std::move(config)), programs_(std::move(programs)) {
  for (size_t a = 0; a < config_.axes.size(); ++a) {
    if (config_.axes[a].name == "Z") axis_z_ = static_cast<int>(a);
    if (config_.axes[a].name == "X") axis_x_ = static_cast<int>(a);
  }
}

void Channel::DropLookahead() {
  work_.feed.Drop();
  work_.continuation_ready = false;
  look_.carry_speed = look_.carry_accel = look_.carry_leftover = 0;
}

const nc::Program* Channel::ProgramOf(uint32_t index) const {
  // MDI runs its blocks as program 0 in front of the channel's programs.
  if (mdi_.running) return index == 0 ? &mdi_.blocks->program : programs_[index - 1];
  return programs_[index];
}

const nc::ModalState& Channel::modal() const {
  return work_.interpreter ? work_.interpreter->modal() : last_modal_;
}

nc::Interpreter Channel::MakeInterpreter() {
  nc::InterpreterConfig ic;
  ic.axes.clear();
  for (const ChannelAxis& a : config_.axes) ic.axes.push_back(a.name);
  std::vector<const nc::Program*> programs = programs_;
  if (mode_ == ChannelMode::kMdi && mdi_.blocks) {
    // MDI blocks run in the modal state the last program left; subprograms stay callable.
    programs.insert(programs.begin(), &mdi_.blocks->program);
    ic.initial = last_modal_;
    mdi_.running = true;
  } else {
    ic.initial = config_.initial;
    mdi_.running = false;
  }
  DropLookahead();
  nc::Interpreter interpreter(std::move(programs), ic);
  // Incremental moves start from where the axes stand, in program coordinates.
  std::vector<double> position(out_.commanded.size());
  for (size_t a = 0; a < position.size(); ++a)
    position[a] = out_.commanded[a] - frames_.translation[a];
  interpreter.SetPosition(position);
  return interpreter;
}

void Channel::ForgetEndedProgram() {
  if (work_.interpreter) last_modal_ = work_.interpreter->modal();
  work_.interpreter.reset();
  parked_ = ProgramInWork{};
  repos_.Clear();
  measuring_.ForgetProgram();  // SETTING holds for one run of the program
}

bool Channel::SelectProgram(size_t index) {
  // Ended or reset only: an interrupted program (hold, or an error the reverse program may
  // leave) would lose its interruption point.
  if (index >= programs_.size()) return false;
  if (state_ == ChannelState::kEnded)
    ForgetEndedProgram();
  else if (state_ != ChannelState::kIdle || work_.interpreter)
    return false;
  std::rotate(programs_.begin(), programs_.begin() + static_cast<std::ptrdiff_t>(index),
              programs_.begin() + static_cast<std::ptrdiff_t>(index) + 1);
  return true;
}

bool Channel::Mdi(const std::string& text) {
  const nc::Dialect dialect = programs_.empty() ? nc::Dialect::kMtc200 : programs_[0]->dialect;
  auto parsed = std::make_shared<const nc::ParseResult>(nc::ParseProgram(text, "MDI", dialect));
  if (!parsed->ok()) {
    Fail(nc::Format(parsed->errors[0], parsed->program.files), kMsgMdiSyntax);
    return false;
  }
  mdi_.blocks = std::move(parsed);
  return true;
}

bool Channel::Reverse() {
  if (mode_ != ChannelMode::kAutomatic || programs_.empty()) return false;
  if (state_ != ChannelState::kHold && state_ != ChannelState::kError) return false;
  // The reverse vector valid at the interrupted block (REV .LABEL): the reverse program runs
  // from its label before `.HOME`. During the REPOS subroutine that is the subroutine's own
  // (4.1): it starts where the operator left the axes, away from the contour the interrupted
  // program's reverse vector was written for, so without a REV of its own it has none.
  const nc::ReverseLabel label =
      work_.interpreter && work_.block.block >= 0 ? work_.block.reverse : nc::ReverseLabel{};
  if (repos_.run()) {  // the REPOS subroutine is given up (4.1); its variables are the program's
    HandBackVariables();
    SwapProgramInWork();
  }
  parked_ = ProgramInWork{};
  repos_.Clear();
  if (!work_.interpreter) work_.interpreter = MakeInterpreter();
  if (!work_.interpreter->Reverse(label)) {
    Fail(programs_[0]->files[0] + ": error: the program has no reverse program .HOME",
         kMsgNoHomeLabel);
    return false;
  }
  // A block search that has not handed over to the run (waiting for the return to the contour
  // or at it) is given up, as Control-Reset gives it up: the block search manual knows no
  // reverse program, and vmt's reading is that the search has rebuilt an interrupted program
  // whose reverse program runs from where the axes stand.
  if (bs_.state != BlockSearchState::kInactive) {
    search_.Reset();
    bs_.state = BlockSearchState::kInactive;
    bs_.command = false;
    cax_.aligning = false;
    bs_.program_distance.Drop();
  }
  // The interrupted block is abandoned where the axes stand; the reverse program starts there.
  // A changeover in progress is given up and the original mode restored (C-axis manual 2.3).
  headstock_.Abandon();
  DropLookahead();
  work_.active = false;
  work_.homing = false;
  work_.dwell_left_s = 0;
  sp_.orienting = false;
  further_.StopRestoring();
  // Fast measurement 6.1 / 7.2 network 9: the PLC acknowledges Q9999 once the reverse program
  // is active; the reverse program waits for that before its first block.
  std::erase_if(aux_.functions, [](const nc::AuxFunction& f) {
    return !(f.letter == 'Q' && f.value == measure::kQ9999);
  });
  error_.clear();
  error_number_ = 0;
  std::vector<double> position(out_.commanded.size());
  for (size_t a = 0; a < position.size(); ++a)
    position[a] = out_.commanded[a] - frames_.translation[a];
  work_.interpreter->SetPosition(position);
  reversing_ = true;
  programmed_stop_.Leave();
  state_ = ChannelState::kRunning;
  // Fast measurement 4.4: the stylus first travels its reverse vectors back.
  measuring_.StartReversal(work_.block);
  return true;
}

uint32_t Channel::line() const {
  if (!work_.active && state_ != ChannelState::kError) return 0;
  if (work_.block.block < 0) return 0;
  return ProgramOf(work_.block.program)->blocks[work_.block.block].pos.line;
}

void Channel::Fail(const std::string& message, int number) {
  state_ = ChannelState::kError;
  error_ = message;
  error_number_ = number;
  work_.active = false;
  work_.homing = false;
}

std::vector<OperatorMessage> Channel::messages() const {
  std::vector<OperatorMessage> list;
  if (state_ == ChannelState::kError)
    list.push_back({OperatorMessage::Source::kNc, error_number_, 0, error_});
  if (plc_message_.number != 0)
    list.push_back(
        {OperatorMessage::Source::kPlc, plc_message_.number, plc_message_.parameter, {}});
  if (headstock_)
    if (std::string stalled = headstock_->Stalled(); !stalled.empty())
      list.push_back({OperatorMessage::Source::kNc, kMsgChangeoverStalled, 0, std::move(stalled)});
  return list;
}

void Channel::Fail(const nc::Program& program, int32_t block, const std::string& text, int number) {
  Fail(nc::Format({program.blocks[block].pos, text}, program.files), number);
}

void Channel::Tick(const AmplifierTelegram& at, MasterTelegram& mdt) {
  // Block search 4.2.1: the axes change hands at standstill only.
  if (const bool suspend = out_.suspend_requested || out_.axes_elsewhere;
      suspend != out_.suspended && AxesAtRest()) {
    out_.suspended = suspend;
    // A held program whose axes go to the other channel is left as in manual mode (REPOS 2.1):
    // where it was interrupted is the contour to come back to. Block search has no contour yet.
    if (suspend && state_ == ChannelState::kHold && work_.interpreter && !repos_.interruption() &&
        !repos_.run() && bs_.state == BlockSearchState::kInactive)
      CaptureInterruption();
  }
  headstock_.PowerOn();
  if (drives_.trip_reset_pending) CollectTrips(at);
  if (out_.take_over_pending && !out_.holding) {
    for (size_t a = 0; a < config_.axes.size(); ++a)
      out_.commanded[a] = at.feedback[config_.axes[a].drive].position;
    out_.previous = out_.commanded;
    out_.holding = true;
  }
  out_.take_over_pending = false;
  if (start_.program) {
    start_.program = false;
    if (!out_.holding) {
      for (size_t a = 0; a < config_.axes.size(); ++a)
        out_.commanded[a] = at.feedback[config_.axes[a].drive].position;
      out_.previous = out_.commanded;
      out_.holding = true;
    }
    if (!work_.interpreter) {
      backward_.Forget();
      work_.interpreter = MakeInterpreter();
      BeginBlockSearch();
    }
  }
  if (!out_.holding) {
    AcknowledgeDriveTrips(mdt);
    return;
  }
  CheckDrives(at);

  if (++out_.tick_in_cycle >= config_.ticks_per_cycle) {
    out_.tick_in_cycle = 0;
    out_.previous = out_.commanded;
    sp_.previous_deg = sp_.command.value;
    const double dt = config_.tick_s * config_.ticks_per_cycle;
    TrackReferences(at, dt);
    if (headstock_) HeadstockCycle(at, dt);
    drive_positions_.resize(at.feedback.size());
    for (size_t d = 0; d < at.feedback.size(); ++d) drive_positions_[d] = at.feedback[d].position;
    ToolStorageCycle(dt);
    if (ToolStorageArrived()) tool_storage_wait_ = false;
    NcCycleOwner owner = CycleOwner();
    if (owner >= NcCycleOwner::kBlockSearch) {
      // Fast measurement 6.1: a probe's collision fails the channel here, ending the move and
      // the dwell.
      measuring_.WatchCollision(MeasuringLinkNow(), at, reversing_);
      owner = ProgramCycleOwner();
    }
    switch (owner) {
      case NcCycleOwner::kNone:
        break;
      case NcCycleOwner::kAxesLent:
        SearchCycle(at);  // 4.2.1: the search decodes on while the axes are lent; the rest waits
        break;
      case NcCycleOwner::kJog:
        Jogging(dt);
        break;
      case NcCycleOwner::kJogBraking:
        Jogging(dt);
        if (!JogsMoving() && std::exchange(start_.deferred, false)) Start();
        break;
      case NcCycleOwner::kBackward:
        ReplayCycle(dt);
        break;
      default:
        ProgramCycle(owner, at, dt);
        break;
    }
    ReposCycle(at);
    if (state_ == ChannelState::kEnded && !bs_.offset.empty()) RemoveSearchOffset();
    UpdateBlockSearchStatus();
  }
  // Fine interpolation: the drives get a straight line between the last two NC cycle points.
  const double f = static_cast<double>(out_.tick_in_cycle + 1) / config_.ticks_per_cycle;
  // G06 (low-lag): the drives get the path velocity as feed-forward; G33/G63/G64 too, so that
  // the axes do not lag the spindle by their following error.
  const double cycle_s = config_.tick_s * config_.ticks_per_cycle;
  const bool low_lag = mode_ != ChannelMode::kManual &&
                       (work_.block.modal.low_lag || InSynchronousBlock()) &&
                       (state_ == ChannelState::kRunning || state_ == ChannelState::kHold);
  const auto axis_setpoint = [&](size_t a) {
    DriveSetpoint sp{DriveMode::kPosition,
                     out_.previous[a] + (out_.commanded[a] - out_.previous[a]) * f, 0};
    if (low_lag) sp.velocity_feedforward = (out_.commanded[a] - out_.previous[a]) / cycle_s;
    return sp;
  };
  // Each drive of the channel gets its setpoint once: the feed axes', then the main spindle's
  // - through a headstock, whose changeover decides what its drives get, the rotary axis' too
  // (one drive for both in section 2) -, the further spindles' and the tool storage axis'.
  // Control-Reset's acknowledgement of a drive's trip then holds that drive off.
  for (size_t a = 0; a < config_.axes.size(); ++a)
    if (!headstock_ || static_cast<int>(a) != config_.rotary_axis)
      mdt.setpoints[config_.axes[a].drive] = axis_setpoint(a);
  const DriveSetpoint spindle = SpindleSetpoint();
  if (headstock_)
    headstock_.WriteSetpoints(spindle, axis_setpoint(config_.rotary_axis), mdt);
  else if (config_.spindle_drive >= 0)
    mdt.setpoints[config_.spindle_drive] = spindle;
  further_.WriteSetpoints(mdt);
  if (ToolStorageNc()) tool_storage_.WriteSetpoint(f, mdt);
  AcknowledgeDriveTrips(mdt);
}

DriveSetpoint Channel::SpindleSetpoint() const {
  // C-axis manual 2.3: under M3/M4 (and M19) only the spindle override acts on the spindle,
  // never the feed override. M19's positioning speed is the drive's own.
  // G63 holds the spindle override at 100 % (the compensating chuck takes up the rest).
  DriveSetpoint sp = sp_.command;
  const bool tapping = InSynchronousBlock() && work_.block.motion == nc::Motion::kTapping;
  if (sp.mode == DriveMode::kVelocity && !tapping) sp.value *= sp_.override;
  // G64 interpolates the spindle: fine interpolation to the drive tick as for the axes.
  if (sp.mode == DriveMode::kPosition && sp.interpolated) {
    const double f = static_cast<double>(out_.tick_in_cycle + 1) / config_.ticks_per_cycle;
    sp.value = sp_.previous_deg + (sp.value - sp_.previous_deg) * f;
  }
  return sp;
}

uint64_t Channel::FollowUpAxes(const nc::PreparedBlock& b) const {
  return headstock_.FollowUpAxes(b, config_.rotary_axis);
}

bool Channel::UpdateTranslation(const nc::ModalState& modal, const nc::Program& program,
                                int32_t block) {
  const axes::ToolEdge* edge = ActiveEdge(tools_, modal);
  if (!edge && modal.tool_length != nc::ToolLength::kOff && modal.correction != 0) {
    Fail(program, block,
         "T" + std::to_string(modal.tool) + " D" + std::to_string(modal.correction) +
             " is not in the tool list (G" + std::to_string(nc::GCode(modal.tool_length)) + ")",
         kMsgToolNotInList);
    return false;
  }
  channel::TranslationOf(config_, zero_offsets_, frames_.shift, modal, edge, frames_.translation);
  if (headstock_) {
    // The rotary axis' offsets act in rotary axis mode only (C-axis manual 2.3 Zero Point
    // Shifts); they stay selected meanwhile and come back with it (see RotaryOffsetsActive).
    const size_t r = static_cast<size_t>(config_.rotary_axis);
    headstock_.set_rotary_translation(frames_.translation[r]);
    if (!headstock_.RotaryOffsetsActive()) frames_.translation[r] = 0;
  }
  return true;
}

bool Channel::NextHomingStage() {
  // G74: the programmed axes travel to their reference points, in the order of the values
  // (ISG: G74 X1 Z2 homes X first); equal values home together.
  if (work_.homing_stages.empty()) {
    work_.homing = false;
    // The program continues from the reference points, in its own coordinates.
    std::vector<double> position(out_.commanded.size());
    for (size_t a = 0; a < position.size(); ++a)
      position[a] = out_.commanded[a] - frames_.translation[a];
    work_.interpreter->SetPosition(position);
    return false;
  }
  const uint64_t bits = work_.homing_stages.front().second;
  work_.homing_stages.erase(work_.homing_stages.begin());
  work_.motion = BlockMotion{};
  work_.motion.start = out_.commanded;
  work_.motion.end = out_.commanded;
  double rate = std::numeric_limits<double>::infinity();
  double accel = rate;
  for (size_t a = 0; a < out_.commanded.size(); ++a) {
    if (!(bits >> a & 1)) continue;
    const ChannelAxis& axis = config_.axes[a];
    work_.motion.end[a] = axis.reference_position;
    frames_.homed[a] = true;
    const double distance = std::abs(work_.motion.end[a] - work_.motion.start[a]);
    if (distance < 1e-12) continue;
    const double speed = axis.homing_per_s > 0 ? axis.homing_per_s
                         : axis.jog_per_s > 0  ? axis.jog_per_s
                                               : axis.rapid_per_s / 10;
    rate = std::min(rate, speed / distance);
    accel = std::min(accel, axis.acceleration / distance);
  }
  work_.profile = PathProfile{};
  work_.continuation_ready = false;
  if (!std::isfinite(rate)) return NextHomingStage();
  work_.motion.moves = true;
  work_.profile.max_rate = rate;
  work_.profile.max_accel = accel;
  work_.active = true;
  return true;
}

bool Channel::StartMotion(const AmplifierTelegram& at) {
  const nc::Program& program = *ProgramOf(work_.block.program);
  if (work_.block.repos) return StartReposMotion(at);
  if (work_.block.homing) {
    work_.homing_stages.clear();
    for (size_t a = 0; a < out_.commanded.size(); ++a) {
      if (!(work_.block.programmed >> a & 1)) continue;
      // The value orders the axes in ISG; in MTC200 it is a placeholder (G74 X0, like G77).
      const int order = program.dialect == nc::Dialect::kIsg
                            ? static_cast<int>(std::lround(work_.block.target[a]))
                            : 0;
      auto it = std::find_if(work_.homing_stages.begin(), work_.homing_stages.end(),
                             [&](const auto& s) { return s.first == order; });
      if (it == work_.homing_stages.end())
        work_.homing_stages.emplace_back(order, uint64_t{1} << a);
      else
        it->second |= uint64_t{1} << a;
    }
    std::sort(work_.homing_stages.begin(), work_.homing_stages.end());
    work_.homing = true;
    if (!repos_.run()) PathBarrier();
    return NextHomingStage();
  }
  for (size_t a = 0; a < out_.commanded.size(); ++a)
    if (!frames_.homed[a] && (work_.block.programmed >> a & 1)) {
      Fail(program, work_.block.block,
           "axis " + config_.axes[a].name + " has no reference: home it first (G74)", kMsgNotHomed);
      return false;
    }

  // #CAX TRACK: C's target from the path's tangent; a turn beyond ANGLIMIT runs first on its
  // own, and the block starts when it ends (Tick).
  nc::PreparedBlock tracked;
  const nc::PreparedBlock* planned = &work_.block;
  if (cax_.command) {
    tracked = work_.block;
    std::optional<double> align;
    if (!TrackC(tracked, out_.commanded, SpindleRevPerS(at), align)) return false;
    if (align) {
      cax_.aligning = true;
      return StartCaxAlignment(*align);
    }
    planned = &tracked;
  }
  if (nc::SpindleSynchronous(work_.block.motion)) {
    if (!repos_.run()) PathBarrier();  // the spindle cannot be turned back in step
    return StartSynchronous(at);
  }
  sync_.Clear();
  if (const auto error =
          PlanBlockMotion(*planned, out_.commanded, frames_.translation, config_.axes,
                          SpindleRevPerS(at), work_.motion, FollowUpAxes(work_.block))) {
    Fail(program, work_.block.block, error->text, error->number);
    return false;
  }
  bs_.program_distance.BlockStarts(work_.motion, config_.axes);
  work_.profile = PathProfile{};
  if (!work_.motion.moves) {
    if (bs_.program_distance.pending()) HoldAtBreakpoint();  // at the very start of the block
    return true;
  }
  // The REPOS subroutine's moves are approach moves, checked whole before they start
  // as G77's are (its blocks are reached at rest for that: LookAhead), and so are a JogOfPath
  // channel's. The program's own cuts are not: the stock is theirs to cut.
  if ((repos_.run() || config_.approach_program) &&
      !GuardBlockMove(repos_.run() ? "REPOS subroutine" : "JogOfPath"))
    return false;
  work_.profile.max_rate = work_.motion.max_rate;
  work_.profile.max_accel = work_.motion.max_accel;
  work_.profile.max_jerk = work_.motion.max_jerk;
  work_.active = true;
  if (!repos_.run()) RecordPath(work_.motion, work_.block.motion == nc::Motion::kRapid);
  if (look_.carry_speed > 0) {
    // Continuing at speed from the block before (look-ahead): same path speed and
    // acceleration, from where the last cycle's remainder takes it.
    work_.profile.rate = look_.carry_speed / work_.motion.length;
    work_.profile.accel = look_.carry_accel / work_.motion.length;
    work_.profile.u = std::min(0.5, look_.carry_leftover / work_.motion.length);
    look_.carry_speed = look_.carry_accel = look_.carry_leftover = 0;
    work_.motion.PointAt(work_.profile.u, out_.commanded);
  }
  LookAhead(at);
  if (bs_.program_distance.pending()) work_.continuation_ready = false;  // stop at the breakpoint
  return true;
}

double Channel::SpindleRevPerS(const AmplifierTelegram& at) const {
  if (at.feedback.empty() || config_.spindle_drive < 0) return 0;
  return at.feedback[config_.spindle_drive].velocity / 360.0;
}

void Channel::Interpolate(double dt) {
  const double u_before = work_.profile.u;
  const double override = state_ == ChannelState::kHold ? 0.0 : override_;
  work_.profile.ahead = {};
  if (work_.continuation_ready) {
    ProfileTargets(work_.targets, work_.motion.length, override, look_.profile_targets);
    work_.profile.ahead = look_.profile_targets;
  }
  work_.profile.Advance(dt, override);
  work_.motion.PointAt(work_.profile.u, out_.commanded);
  if (work_.profile.done()) {
    out_.commanded = work_.motion.end;  // exactly the programmed point
    work_.active = false;
    // Ended at speed (look-ahead): the next block takes the speed over at once, with what
    // this cycle had left of its distance.
    if (work_.profile.rate > 0 && work_.continuation_ready) {
      look_.carry_speed = work_.profile.rate * work_.motion.length;
      look_.carry_accel = work_.profile.accel * work_.motion.length;
      // Passed the end at speed: the cycle went on by u - 1; arrived at it: the rest of the
      // cycle at the end speed.
      look_.carry_leftover =
          work_.profile.u > 1
              ? (work_.profile.u - 1) * work_.motion.length
              : std::max(0.0, look_.carry_speed * dt - (1 - u_before) * work_.motion.length);
    }
  }
}

}  // namespace vmt::control::channel
