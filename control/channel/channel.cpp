#include "control/channel/channel.hpp"

#include <cmath>
#include <cstdio>

#include "control/nc/parser.hpp"

namespace vmt::control::channel {

Channel::Channel(ChannelConfig config, std::vector<const nc::Program*> programs)
    : config_(std::move(config)), programs_(std::move(programs)) {
  const size_t n = config_.axes.size();
  jog_.resize(n);
  commanded_.assign(n, 0.0);
  previous_ = commanded_;
  translation_.assign(n, 0.0);
  shift_.assign(n, 0.0);
  homed_.resize(n);
  for (size_t a = 0; a < n; ++a) homed_[a] = config_.axes[a].homed_at_start;
  spindle_ = {DriveMode::kVelocity, 0, 0};
  further_spindles_.assign(config_.spindles.size(), FurtherSpindleState{});
  if (config_.headstock) headstock_.emplace(*config_.headstock);
  spindle_homed_ = config_.spindle.homed_at_start;
  last_modal_ = config_.initial;
  for (size_t a = 0; a < n; ++a) {
    if (config_.axes[a].name == "Z") axis_z_ = static_cast<int>(a);
    if (config_.axes[a].name == "X") axis_x_ = static_cast<int>(a);
  }
}

void Channel::DropLookahead() {
  peeked_.clear();
  unpushed_.reset();
  source_returned_false_ = false;
  continuation_ready_ = false;
  carry_speed_ = carry_accel_ = carry_leftover_ = 0;
  compensating_ = false;
  source_done_ = false;
  trc_.Reset();
  ahead_.clear();
  ready_.clear();
}

const nc::Program* Channel::ProgramOf(uint32_t index) const {
  // MDI runs its blocks as program 0 in front of the channel's programs.
  if (running_mdi_) return index == 0 ? &mdi_->program : programs_[index - 1];
  return programs_[index];
}

const nc::ModalState& Channel::modal() const {
  return interpreter_ ? interpreter_->modal() : last_modal_;
}

std::unique_ptr<nc::Interpreter> Channel::MakeInterpreter() {
  nc::InterpreterConfig ic;
  ic.axes.clear();
  for (const ChannelAxis& a : config_.axes) ic.axes.push_back(a.name);
  std::vector<const nc::Program*> programs = programs_;
  if (mode_ == ChannelMode::kMdi && mdi_) {
    // MDI blocks run in the modal state the last program left; subprograms stay callable.
    programs.insert(programs.begin(), &mdi_->program);
    ic.initial = last_modal_;
    running_mdi_ = true;
  } else {
    ic.initial = config_.initial;
    running_mdi_ = false;
  }
  DropLookahead();
  auto interpreter = std::make_unique<nc::Interpreter>(std::move(programs), ic);
  // Incremental moves start from where the axes stand, in program coordinates.
  std::vector<double> position(commanded_.size());
  for (size_t a = 0; a < position.size(); ++a) position[a] = commanded_[a] - translation_[a];
  interpreter->SetPosition(position);
  interpreter->SetEventSource([this](int n) {
    if (events_) return events_(n);
    auto it = own_events_.find(n);
    return it != own_events_.end() && it->second;
  });
  interpreter->SetDataAccess(MakeDataAccess());
  return interpreter;
}

void Channel::ForgetEndedProgram() {
  if (interpreter_) last_modal_ = interpreter_->modal();
  interpreter_.reset();
  parked_ = ProgramInWork{};
  ClearRepos();
  measuring_setting_.reset();  // SETTING holds for one run of the program
  reverse_vectors_ = {};
}

bool Channel::SelectProgram(size_t index) {
  // Ended or reset only: an interrupted program (hold, or an error the reverse program may
  // leave) would lose its interruption point.
  if (index >= programs_.size()) return false;
  if (state_ == ChannelState::kEnded)
    ForgetEndedProgram();
  else if (state_ != ChannelState::kIdle || interpreter_)
    return false;
  std::rotate(programs_.begin(), programs_.begin() + static_cast<std::ptrdiff_t>(index),
              programs_.begin() + static_cast<std::ptrdiff_t>(index) + 1);
  return true;
}

bool Channel::Mdi(const std::string& text) {
  const nc::Dialect dialect = programs_.empty() ? nc::Dialect::kMtc200 : programs_[0]->dialect;
  auto parsed = std::make_shared<nc::ParseResult>(nc::ParseProgram(text, "MDI", dialect));
  if (!parsed->ok()) {
    Fail(nc::Format(parsed->errors[0], parsed->program.files), kMsgMdiSyntax);
    return false;
  }
  mdi_ = std::move(parsed);
  return true;
}

bool Channel::Reverse() {
  if (mode_ != ChannelMode::kAutomatic || programs_.empty()) return false;
  if (state_ != ChannelState::kHold && state_ != ChannelState::kError) return false;
  // The reverse vector valid at the interrupted block (REV .LABEL): the reverse program runs
  // from its label before `.HOME`. During the REPOS subroutine that is the subroutine's own
  // (4.1): it starts where the operator left the axes, away from the contour the interrupted
  // program's reverse vector was written for, so without a REV of its own it has none.
  const nc::ReverseLabel label = interpreter_ && block_.block >= 0 ? block_.reverse
                                                                   : nc::ReverseLabel{};
  if (repos_run_) {  // the REPOS subroutine is given up (4.1); its variables are the program's
    HandBackVariables();
    SwapProgramInWork();
  }
  parked_ = ProgramInWork{};
  ClearRepos();
  if (!interpreter_) interpreter_ = MakeInterpreter();
  if (!interpreter_->Reverse(label)) {
    Fail(programs_[0]->files[0] + ": error: the program has no reverse program .HOME",
         kMsgNoHomeLabel);
    return false;
  }
  // A block search that has not handed over to the run (waiting for the return to the contour
  // or at it) is given up, as Control-Reset gives it up: the block search manual knows no
  // reverse program, and vmt's reading is that the search has rebuilt an interrupted program
  // whose reverse program runs from where the axes stand.
  if (bs_state_ != BlockSearchState::kInactive) {
    search_.reset();
    bs_state_ = BlockSearchState::kInactive;
    bs_command_ = false;
    cax_aligning_ = false;
    breakpoint_rest_.reset();
    breakpoint_hold_ = breakpoint_pending_ = false;
  }
  // The interrupted block is abandoned where the axes stand; the reverse program starts there.
  // A changeover in progress is given up and the original mode restored (C-axis manual 2.3).
  if (headstock_) headstock_->Abandon();
  waiting_for_ = axes::HeadstockMode::kNone;
  DropLookahead();
  active_ = false;
  homing_ = false;
  dwell_left_s_ = 0;
  orienting_ = further_restoring_ = false;
  // Fast measurement 6.1 / 7.2 network 9: the PLC acknowledges Q9999 once the reverse program
  // is active; the reverse program waits for that before its first block.
  std::erase_if(aux_output_, [](const nc::AuxFunction& f) {
    return !(f.letter == 'Q' && f.value == measure::kQ9999);
  });
  error_.clear();
  error_number_ = 0;
  std::vector<double> position(commanded_.size());
  for (size_t a = 0; a < position.size(); ++a) position[a] = commanded_[a] - translation_[a];
  interpreter_->SetPosition(position);
  reversing_ = true;
  programmed_stop_.Leave();
  state_ = ChannelState::kRunning;
  // Fast measurement 4.4: the stylus first travels its reverse vectors back.
  StartReversal();
  return true;
}

uint32_t Channel::line() const {
  if (!active_ && state_ != ChannelState::kError) return 0;
  if (block_.block < 0) return 0;
  return ProgramOf(block_.program)->blocks[block_.block].pos.line;
}

void Channel::Fail(const std::string& message, int number) {
  state_ = ChannelState::kError;
  error_ = message;
  error_number_ = number;
  active_ = false;
  homing_ = false;
}

std::vector<OperatorMessage> Channel::messages() const {
  std::vector<OperatorMessage> list;
  if (state_ == ChannelState::kError)
    list.push_back({OperatorMessage::Source::kNc, error_number_, 0, error_});
  if (plc_message_.number != 0)
    list.push_back(
        {OperatorMessage::Source::kPlc, plc_message_.number, plc_message_.parameter, {}});
  return list;
}

void Channel::Fail(const nc::Program& program, int32_t block, const std::string& text, int number) {
  if (planning_only_) {
    plan_failed_ = true;  // read ahead under G41/G42: the block's error comes in its turn
    return;
  }
  Fail(nc::Format({program.blocks[block].pos, text}, program.files), number);
}

void Channel::Tick(const AmplifierTelegram& at, MasterTelegram& mdt) {
  // Block search 4.2.1: the axes change hands at standstill only.
  if (const bool suspend = suspend_requested_ || axes_elsewhere_;
      suspend != output_suspended_ && AxesAtRest()) {
    output_suspended_ = suspend;
    // A held program whose axes go to the other channel is left as in manual mode (REPOS 2.1):
    // where it was interrupted is the contour to come back to. Block search has no contour yet.
    if (suspend && state_ == ChannelState::kHold && interpreter_ && !interruption_ &&
        !repos_run_ && bs_state_ == BlockSearchState::kInactive)
      CaptureInterruption();
  }
  if (headstock_ && !headstock_known_) HeadstockPowerOn();
  if (trip_reset_pending_) CollectTrips(at);
  if (take_over_pending_ && !holding_positions_) {
    for (size_t a = 0; a < config_.axes.size(); ++a)
      commanded_[a] = at.feedback[config_.axes[a].drive].position;
    previous_ = commanded_;
    holding_positions_ = true;
  }
  take_over_pending_ = false;
  if (start_pending_) {
    start_pending_ = false;
    if (!holding_positions_) {
      for (size_t a = 0; a < config_.axes.size(); ++a)
        commanded_[a] = at.feedback[config_.axes[a].drive].position;
      previous_ = commanded_;
      holding_positions_ = true;
    }
    if (!interpreter_) {
      path_memory_.Clear();
      interpreter_ = MakeInterpreter();
      BeginBlockSearch();
    }
  }
  if (!holding_positions_) {
    AcknowledgeDriveTrips(mdt);
    return;
  }
  CheckDrives(at);

  if (++tick_in_cycle_ >= config_.ticks_per_cycle) {
    tick_in_cycle_ = 0;
    previous_ = commanded_;
    spindle_previous_deg_ = spindle_.value;
    const double dt = config_.tick_s * config_.ticks_per_cycle;
    TrackReferences(at, dt);
    if (headstock_) HeadstockCycle(at, dt);
    drive_positions_.resize(at.feedback.size());
    for (size_t d = 0; d < at.feedback.size(); ++d) drive_positions_[d] = at.feedback[d].position;
    ToolStorageCycle(dt);
    if (ToolStorageArrived()) tool_storage_wait_ = false;
    NcCycleOwner owner = CycleOwner();
    if (owner >= NcCycleOwner::kBlockSearch) {
      WatchProbeCollision(at);  // fast measurement 6.1: a collision fails the channel here
      owner = ProgramCycleOwner();  // ... and has ended the move and the dwell
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
        if (!JogsMoving() && std::exchange(start_deferred_, false)) Start();
        break;
      case NcCycleOwner::kBackward:
        ReplayCycle(dt);
        break;
      default:
        ProgramCycle(owner, at, dt);
        break;
    }
    ReposCycle(at);
    if (state_ == ChannelState::kEnded && !search_offset_.empty()) RemoveSearchOffset();
    UpdateBlockSearchStatus();
  }
  // Fine interpolation: the drives get a straight line between the last two NC cycle points.
  const double f = static_cast<double>(tick_in_cycle_ + 1) / config_.ticks_per_cycle;
  // G06 (low-lag): the drives get the path velocity as feed-forward; G33/G63/G64 too, so that
  // the axes do not lag the spindle by their following error.
  const double cycle_s = config_.tick_s * config_.ticks_per_cycle;
  const bool low_lag = mode_ != ChannelMode::kManual &&
                       (block_.modal.low_lag || InSynchronousBlock()) &&
                       (state_ == ChannelState::kRunning || state_ == ChannelState::kHold);
  for (size_t a = 0; a < config_.axes.size(); ++a) {
    DriveSetpoint& sp = mdt.setpoints[config_.axes[a].drive];
    sp = {DriveMode::kPosition, previous_[a] + (commanded_[a] - previous_[a]) * f, 0};
    if (low_lag) sp.velocity_feedforward = (commanded_[a] - previous_[a]) / cycle_s;
  }
  // The rotary axis' setpoint before the spindle's: one drive for both in section 2.
  const DriveSetpoint rotary =
      headstock_ ? mdt.setpoints[config_.axes[config_.rotary_axis].drive] : DriveSetpoint{};
  const DriveSetpoint spindle = SpindleSetpoint();
  if (config_.spindle_drive >= 0) mdt.setpoints[config_.spindle_drive] = spindle;
  if (headstock_) headstock_->WriteSetpoints(spindle, rotary, at, mdt);
  WriteFurtherSpindles(mdt);
  WriteToolStorage(mdt);
  AcknowledgeDriveTrips(mdt);
}

DriveSetpoint Channel::SpindleSetpoint() const {
  // C-axis manual 2.3: under M3/M4 (and M19) only the spindle override acts on the spindle,
  // never the feed override. M19's positioning speed is the drive's own.
  // G63 holds the spindle override at 100 % (the compensating chuck takes up the rest).
  DriveSetpoint sp = spindle_;
  const bool tapping = InSynchronousBlock() && block_.motion == nc::Motion::kTapping;
  if (sp.mode == DriveMode::kVelocity && !tapping) sp.value *= spindle_override_;
  // G64 interpolates the spindle: fine interpolation to the drive tick as for the axes.
  if (sp.mode == DriveMode::kPosition && sp.interpolated) {
    const double f = static_cast<double>(tick_in_cycle_ + 1) / config_.ticks_per_cycle;
    sp.value = spindle_previous_deg_ + (sp.value - spindle_previous_deg_) * f;
  }
  return sp;
}

uint64_t Channel::FollowUpAxes(const nc::PreparedBlock& b) const {
  // Outside rotary axis mode the rotary axis tracks its actual position (HeadstockCycle); a
  // block that does not program it leaves it there rather than moving it back to where the
  // program last put it (with a load-side encoder it reads the turning spindle).
  if (!headstock_ || config_.rotary_axis < 0 || headstock_->mode() == axes::HeadstockMode::kRotary)
    return 0;
  const uint64_t bit = uint64_t{1} << config_.rotary_axis;
  // X1/Y1 program C but position it only in rotary axis mode (coordinate_transformation.hpp).
  return b.programmed & bit && !b.fictive ? 0 : bit;
}

bool Channel::RunBlock(const AmplifierTelegram& at) {
  const nc::Program& program = *ProgramOf(block_.program);
  // G77 (REPOS manual 4.2) is refused at the start of its block, before any changeover.
  if (block_.repos && waiting_for_ == axes::HeadstockMode::kNone && !CheckReposBlock())
    return false;
  if (headstock_) {
    const axes::HeadstockMode need = ModeNeeded(block_);
    if (need != axes::HeadstockMode::kNone && headstock_->mode() != need) {
      headstock_->Request(need);
      manual_changeover_ = false;
      waiting_for_ = need;
      return true;
    }
    if (waiting_for_ == axes::HeadstockMode::kRotary) RebaseRotaryAxis();
    waiting_for_ = axes::HeadstockMode::kNone;
    // X1/Y1 of G31/G32 position C, which the NC does only in rotary axis mode; unlike C they
    // do not select it (coordinate_transformation.hpp).
    if (block_.fictive && headstock_->mode() != axes::HeadstockMode::kRotary) {
      Fail(program, block_.block,
           "X1/Y1 of G" + std::to_string(nc::GCode(block_.modal.transformation)) +
               " need the headstock in rotary axis mode: select it (G00 " +
               config_.axes[config_.rotary_axis].name + "..) first",
           kMsgTransformation);
      return false;
    }
    // C-axis manual 2.3: offsets of the rotary axis are programmed only in rotary axis mode.
    // The manual is silent on G92 C in spindle mode; a control refuses it rather than shift an
    // axis it does not position.
    const size_t r = static_cast<size_t>(config_.rotary_axis);
    if (block_.set_position && (block_.programmed >> r & 1) &&
        headstock_->mode() != axes::HeadstockMode::kRotary) {
      Fail(program, block_.block,
           "G92 of " + config_.axes[r].name + " outside rotary axis mode: program " +
               config_.axes[r].name + " in a G00/G01 block first",
           kMsgOffsetInSpindleMode);
      return false;
    }
  }
  auto unsupported = [&](const std::string& what) {
    Fail(program, block_.block, what + " is not supported by vmt (docs/conformance.md)",
         kMsgNotAvailable);
    return false;
  };
  if (block_.measuring) return unsupported("G100 measuring");
  if (block_.has_centre && block_.motion != nc::Motion::kArcCw &&
      block_.motion != nc::Motion::kArcCcw)
    return unsupported("I/J/K outside G02/G03");

  // The T word indexes an NC-controlled turret before MTP / MRY of its block act on it.
  if (!IndexToolStorage(block_, program)) return false;
  bool mry = false;
  // Instructions of later issues stop the program rather than pass unnoticed. The
  // #-commands that only steer block search (and its return to the contour) have no effect on
  // a normal run.
  for (uint32_t index : block_.instructions) {
    const nc::Statement& st = program.statements[index];
    if (st.kind == nc::Statement::Kind::kHashCommand) {
      const std::string& text = program.texts[st.text];
      if (const std::string refused = RefusedHashCommand(text); !refused.empty()) {
        Fail(nc::Format({st.pos, refused}, program.files), kMsgNotAvailable);
        return false;
      }
      const int c = TrackedAxis();
      if (const auto done = CaxTrackInstruction(program, st, block_,
                                                c < 0 ? 0 : commanded_[static_cast<size_t>(c)])) {
        if (!*done) return false;
        continue;
      }
      if (SteersBlockSearch(text)) continue;
      Fail(nc::Format({st.pos, "instruction #" + text.substr(0, text.find(' ')) +
                                   " is not supported by vmt (docs/conformance.md)"},
                      program.files),
           kMsgNotAvailable);
      return false;
    }
    const bool mtp = st.instruction == nc::Instruction::kMtp;
    const bool waits = st.instruction == nc::Instruction::kMry;
    // REPOS manual 4.2 Tool Storage Axis: in the REPOS subroutine MTP returns the tool storage
    // axis to where it was; the PLC controls the turret, so the NC outputs the T word of the
    // interruption again. MRY waits for the tool storage axis, which the acknowledgement of
    // that T word already does.
    // An NC-controlled tool storage axis the NC traverses back itself, and MRY waits for it.
    if (repos_run_ && interruption_ && (mtp || waits)) {
      if (mtp && ToolStorageNc()) {
        if (!ReturnToolStorage()) return false;
      } else if (mtp) {
        block_.aux.push_back({'T', 0, static_cast<double>(interruption_->modal.tool)});
      } else {
        mry = true;
      }
      continue;
    }
    if (ToolStorageNc() && (waits || (mtp && StationOf(1)))) {
      // In the program an NC-controlled one traverses asynchronously (4.2, "As in NC-program
      // controlled mode"): MRY waits for its traverse as in the REPOS subroutine, and MTP
      // ("Adjust tool turret", 8.3) brings the active tool's station back to the work, after
      // a jog in manual mode, say. A PLC-controlled one: the PLC's business, as before.
      if (mtp && !IndexToolStorage(block_.modal.tool, program, block_.block)) return false;
      if (waits) mry = true;
      continue;
    }
    if (nc::IsMeasuringCall(st.instruction)) continue;  // StartMeasuring below
    Fail(nc::Format({st.pos, "instruction " + program.symbols.Name(st.name) +
                                 " is not supported by vmt (docs/conformance.md)"},
                    program.files),
         kMsgNotAvailable);
    return false;
  }
  // MRY: until the drive stands at the place, not only its command (a following error lags).
  if (mry) tool_storage_wait_ = !ToolStorageArrived();
  DistanceCommand(block_);
  if (!block_.calls.empty()) {
    PathBarrier();  // a probing move is no path to travel back along
    return StartMeasuring(at);
  }
  for (const auto& [n, set] : block_.events) {
    own_events_[n] = set;
    if (event_sink_) event_sink_(n, set);
  }

  const std::vector<double> before = translation_;
  if (!UpdateTranslation(block_.modal, program, block_.block)) return false;
  if (block_.set_position) {
    // G92: the programmed values become the current position of those axes (a shift that
    // stays until Control-Reset).
    for (size_t a = 0; a < commanded_.size(); ++a)
      if (block_.programmed >> a & 1) {
        shift_[a] += commanded_[a] - (block_.target[a] + translation_[a]);
        translation_[a] = commanded_[a] - block_.target[a];
        if (headstock_ && static_cast<int>(a) == config_.rotary_axis)
          rotary_translation_ = translation_[a];
      }
  }
  const bool arc = block_.motion == nc::Motion::kArcCw || block_.motion == nc::Motion::kArcCcw;
  if (arc && translation_ != before) {
    Fail(program, block_.block,
         "zero offset or tool correction changes in an arc block: program it in a straight block",
         kMsgTranslationInArc);
    return false;
  }

  // Spindle: M3/M4 with S (rpm), M5, M19 (orient to 0 deg); a start is checked by PathGuard.
  DriveSetpoint spindle = spindle_;
  const bool orient = SpindleFunctions(block_, spindle);
  if (!GuardSpindleStart("spindle start", spindle)) return false;
  // Sj= / Mj= of the further spindles (G77 Sj=0 restores them instead, StartReposMotion).
  if (!block_.repos && !FurtherSpindleWords(program, block_, further_spindles_)) return false;
  spindle_ = spindle;
  if (orient) spindle_referencing_ = orienting_ = true;

  // M, H, Q and T go to the PLC; the block goes on when it has acknowledged them.
  if (config_.aux_handshake) {
    for (const nc::AuxFunction& f : block_.aux)
      if (f.letter == 'M' || f.letter == 'H' || f.letter == 'Q' || f.letter == 'T')
        aux_output_.push_back(f);
    if (!aux_output_.empty()) ++aux_strobe_;
  }

  programmed_stop_.Prepare(block_);
  dwell_left_s_ = block_.dwell_s;
  if (block_.end) state_ = ChannelState::kEnded, reversing_ = false;
  if (block_.motion == nc::Motion::kNone && !block_.homing && !block_.repos) return true;
  if (!aux_output_.empty() || tool_storage_wait_) {
    pending_motion_ = true;
    return true;
  }
  return StartMotion(at);
}

bool Channel::UpdateTranslation(const nc::ModalState& modal, const nc::Program& program,
                                int32_t block) {
  // Tool length: G48 adds the edge's lengths, G49 subtracts them, G47 ignores the tool list.
  const axes::ToolEdge* edge = nullptr;
  std::optional<axes::ToolEdge> found;
  if (modal.tool_length != nc::ToolLength::kOff && modal.correction != 0) {
    found = config_.tools.Find(modal.tool, modal.correction);
    if (!found) {
      Fail(program, block,
           "T" + std::to_string(modal.tool) + " D" + std::to_string(modal.correction) +
               " is not in the tool list (G" + std::to_string(nc::GCode(modal.tool_length)) + ")",
           kMsgToolNotInList);
      return false;
    }
    edge = &*found;
  }
  const double sign = modal.tool_length == nc::ToolLength::kSubtract ? -1 : 1;
  for (size_t a = 0; a < translation_.size(); ++a) {
    const double length = edge ? edge->Length(a, config_.axes[a].name) : 0;
    translation_[a] = config_.zero_offsets.Offset(modal.zero_offset, a) + shift_[a] - sign * length;
  }
  if (headstock_) {
    // The rotary axis' offsets act in rotary axis mode only (C-axis manual 2.3 Zero Point
    // Shifts); they stay selected meanwhile and come back with it (see RotaryOffsetsActive).
    const size_t r = static_cast<size_t>(config_.rotary_axis);
    rotary_translation_ = translation_[r];
    if (!RotaryOffsetsActive()) translation_[r] = 0;
  }
  return true;
}

bool Channel::NextHomingStage() {
  // G74: the programmed axes travel to their reference points, in the order of the values
  // (ISG: G74 X1 Z2 homes X first); equal values home together.
  if (homing_stages_.empty()) {
    homing_ = false;
    // The program continues from the reference points, in its own coordinates.
    std::vector<double> position(commanded_.size());
    for (size_t a = 0; a < position.size(); ++a) position[a] = commanded_[a] - translation_[a];
    interpreter_->SetPosition(position);
    return false;
  }
  const uint64_t bits = homing_stages_.front().second;
  homing_stages_.erase(homing_stages_.begin());
  motion_ = BlockMotion{};
  motion_.start = commanded_;
  motion_.end = commanded_;
  double rate = std::numeric_limits<double>::infinity();
  double accel = rate;
  for (size_t a = 0; a < commanded_.size(); ++a) {
    if (!(bits >> a & 1)) continue;
    const ChannelAxis& axis = config_.axes[a];
    motion_.end[a] = axis.reference_position;
    homed_[a] = true;
    const double distance = std::abs(motion_.end[a] - motion_.start[a]);
    if (distance < 1e-12) continue;
    const double speed = axis.homing_per_s > 0 ? axis.homing_per_s
                         : axis.jog_per_s > 0  ? axis.jog_per_s
                                               : axis.rapid_per_s / 10;
    rate = std::min(rate, speed / distance);
    accel = std::min(accel, axis.acceleration / distance);
  }
  profile_ = PathProfile{};
  continuation_ready_ = false;
  if (!std::isfinite(rate)) return NextHomingStage();
  motion_.moves = true;
  profile_.max_rate = rate;
  profile_.max_accel = accel;
  active_ = true;
  return true;
}

bool Channel::StartMotion(const AmplifierTelegram& at) {
  const nc::Program& program = *ProgramOf(block_.program);
  if (block_.repos) return StartReposMotion(at);
  if (block_.homing) {
    homing_stages_.clear();
    for (size_t a = 0; a < commanded_.size(); ++a) {
      if (!(block_.programmed >> a & 1)) continue;
      // The value orders the axes in ISG; in MTC200 it is a placeholder (G74 X0, like G77).
      const int order = program.dialect == nc::Dialect::kIsg
                            ? static_cast<int>(std::lround(block_.target[a]))
                            : 0;
      auto it = std::find_if(homing_stages_.begin(), homing_stages_.end(),
                             [&](const auto& s) { return s.first == order; });
      if (it == homing_stages_.end())
        homing_stages_.emplace_back(order, uint64_t{1} << a);
      else
        it->second |= uint64_t{1} << a;
    }
    std::sort(homing_stages_.begin(), homing_stages_.end());
    homing_ = true;
    if (!repos_run_) PathBarrier();
    return NextHomingStage();
  }
  for (size_t a = 0; a < commanded_.size(); ++a)
    if (!homed_[a] && (block_.programmed >> a & 1)) {
      Fail(program, block_.block,
           "axis " + config_.axes[a].name + " has no reference: home it first (G74)", kMsgNotHomed);
      return false;
    }

  // #CAX TRACK: C's target from the path's tangent; a turn beyond ANGLIMIT runs first on its
  // own, and the block starts when it ends (Tick).
  nc::PreparedBlock tracked;
  const nc::PreparedBlock* planned = &block_;
  if (cax_track_) {
    tracked = block_;
    std::optional<double> align;
    if (!TrackC(tracked, commanded_, SpindleRevPerS(at), align)) return false;
    if (align) {
      cax_aligning_ = true;
      return StartCaxAlignment(*align);
    }
    planned = &tracked;
  }
  if (nc::SpindleSynchronous(block_.motion)) {
    if (!repos_run_) PathBarrier();  // the spindle cannot be turned back in step
    return StartSynchronous(at);
  }
  sync_.phase = SyncPhase::kNone;
  if (const auto error = PlanBlockMotion(*planned, commanded_, translation_, config_.axes,
                                         SpindleRevPerS(at), motion_, FollowUpAxes(block_))) {
    Fail(program, block_.block, error->text, error->number);
    return false;
  }
  CountDistance();
  profile_ = PathProfile{};
  if (!motion_.moves) {
    if (breakpoint_pending_) HoldAtBreakpoint();  // at the very start of the block
    return true;
  }
  // Issue 6: the REPOS subroutine's moves are approach moves, checked whole before they start
  // as G77's are (its blocks are reached at rest for that: LookAhead), and so are a JogOfPath
  // channel's. The program's own cuts are not: the stock is theirs to cut.
  if ((repos_run_ || config_.approach_program) &&
      !GuardBlockMove(repos_run_ ? "REPOS subroutine" : "JogOfPath"))
    return false;
  profile_.max_rate = motion_.max_rate;
  profile_.max_accel = motion_.max_accel;
  profile_.max_jerk = motion_.max_jerk;
  active_ = true;
  if (!repos_run_) RecordPath(motion_, block_.motion == nc::Motion::kRapid);
  if (carry_speed_ > 0) {
    // Continuing at speed from the block before (look-ahead): same path speed and
    // acceleration, from where the last cycle's remainder takes it.
    profile_.rate = carry_speed_ / motion_.length;
    profile_.accel = carry_accel_ / motion_.length;
    profile_.u = std::min(0.5, carry_leftover_ / motion_.length);
    carry_speed_ = carry_accel_ = carry_leftover_ = 0;
    motion_.PointAt(profile_.u, commanded_);
  }
  LookAhead(at);
  if (breakpoint_pending_) continuation_ready_ = false;  // stop at the breakpoint
  return true;
}

double Channel::SpindleRevPerS(const AmplifierTelegram& at) const {
  if (at.feedback.empty() || config_.spindle_drive < 0) return 0;
  return at.feedback[config_.spindle_drive].velocity / 360.0;
}

void Channel::Interpolate(double dt) {
  const double u_before = profile_.u;
  const double override = state_ == ChannelState::kHold ? 0.0 : override_;
  profile_.ahead = {};
  if (continuation_ready_) {
    ProfileTargets(targets_, motion_.length, override, profile_targets_);
    profile_.ahead = profile_targets_;
  }
  profile_.Advance(dt, override);
  motion_.PointAt(profile_.u, commanded_);
  if (profile_.done()) {
    commanded_ = motion_.end;  // exactly the programmed point
    active_ = false;
    // Ended at speed (look-ahead): the next block takes the speed over at once, with what
    // this cycle had left of its distance.
    if (profile_.rate > 0 && continuation_ready_) {
      carry_speed_ = profile_.rate * motion_.length;
      carry_accel_ = profile_.accel * motion_.length;
      // Passed the end at speed: the cycle went on by u - 1; arrived at it: the rest of the
      // cycle at the end speed.
      carry_leftover_ = profile_.u > 1
                            ? (profile_.u - 1) * motion_.length
                            : std::max(0.0, carry_speed_ * dt - (1 - u_before) * motion_.length);
    }
  }
}

}  // namespace vmt::control::channel
