// Repositioning and NC-block restart in the channel (REPOS manual). The program interrupted and
// left by jogging keeps its place (Interruption); the PLC calls a function with PxxC.REPOS or
// PxxC.RESTA; in manual mode the operator jogs the axes back without passing their targets and
// restores the spindle with its keys; in automatic mode Start runs the REPOS subroutine in the
// interrupted program's place, whose G77 blocks return the axes and spindle, and at its RTS the
// program continues at the interruption point or at the start of the interrupted block.
#include <cmath>
#include <map>
#include <string>

#include "control/channel/channel.hpp"
#include "control/nc/modal_g_codes.hpp"

namespace vmt::control::channel {

std::vector<double> Channel::TranslationOf(const nc::ModalState& modal) const {
  std::vector<double> t;
  channel::TranslationOf(config_, zero_offsets_, frames_.shift, modal, ActiveEdge(tools_, modal),
                         t);
  return t;
}

ReposView Channel::ReposViewNow() const {
  const double* tool_storage =
      ToolStorageKnown() ? &drive_positions_[config_.tool_storage_drive] : nullptr;
  return {config_,     zero_offsets_, tools_,   frames_.shift, out_.commanded,
          headstock(), sp_,           further_, tool_storage};
}

void Channel::CaptureInterruption() {
  Interruption i;
  i.point = out_.commanded;
  i.block_start = work_.active ? work_.motion.start : out_.commanded;
  i.modal = work_.block.block >= 0 ? work_.block.modal : modal();
  i.translation = TranslationOf(i.modal);
  i.program = work_.block.program;
  i.line = line();
  i.spindle = sp_.command;
  i.spindle_m = SpindleMOf(sp_.command);
  i.further_spindles = further_.states();
  if (headstock_) {
    i.headstock_mode = headstock_->mode();
    // Outside rotary axis mode (a changeover included) the NC does not position the rotary
    // axis: its command follows the actual position, which the spindle or the PLC's motion
    // functions move (C-axis manual 4.2, 4.3). It has no point on the contour to return to.
    if (i.headstock_mode != axes::HeadstockMode::kRotary) {
      i.point[config_.rotary_axis] = std::nan("");
      i.block_start[config_.rotary_axis] = std::nan("");
    }
  }
  if (ToolStorageKnown()) i.tool_storage = drive_positions_[config_.tool_storage_drive];
  // 4.2: MTP returns to "the location which had been traversed to prior to the interruption":
  // after a T word's (or MTP's) traverse, its station - also while it is still on its way or
  // its drive still settles - not the place the turret has got to. A jog since (manual mode
  // before the program) leaves the turret where the operator put it.
  if (ToolStorageNc() && tool_storage_.axis().programmed)
    i.tool_storage = tool_storage_.axis().target;
  repos_.Interrupt(std::move(i), out_.commanded);
}

bool Channel::ToolStorageKnown() const {
  return config_.tool_storage_drive >= 0 &&
         static_cast<size_t>(config_.tool_storage_drive) < drive_positions_.size();
}

void Channel::ReposCycle(const AmplifierTelegram& at) {
  // The jogs matter only to a function already called (its withdrawal waits for them): looked
  // at then, not on every NC cycle.
  bool motion = false;
  if (repos_.called() && mode_ == ChannelMode::kManual) {
    for (const JogAxis& j : jog_.axes) motion |= j.key != 0;
    for (const FictiveJog& f : jog_.fictive) motion |= f.key != 0;
    motion = motion || JogsMoving();
  }
  repos_.Cycle(ReposViewNow(), at, state_ == ChannelState::kHold || repos_.run(), motion);
}

ReposStatus Channel::repos_status(const AmplifierTelegram* at, bool whole) const {
  ReposStatus s = repos_.Status(ReposViewNow(), at, whole);
  s.allowed = repos_allowed();
  s.feed_override = override_;
  if (const Interruption* i = repos_.interruption(); i && whole)
    s.program =
        i->program < programs_.size() || mdi_.running ? ProgramOf(i->program)->files[0] : "";
  return s;
}

void Channel::SetReposition(bool repositioning, bool restart) {
  repos_.Request(repositioning, restart);
}

bool Channel::SetZeroOffset(int g, size_t axis, double value) {
  if (g < 54 || g > 59 || axis >= config_.axes.size()) return false;
  std::vector<double>& table = zero_offsets_.g54_to_g59[g - 54];
  if (table.size() <= axis) table.resize(config_.axes.size(), 0.0);
  table[axis] = value;
  return true;
}

bool Channel::SetToolLength(int tool, int edge, size_t axis, double value) {
  if (axis >= config_.axes.size()) return false;
  for (axes::ToolEdge& e : tools_.edges)
    if (e.tool == tool && e.edge == edge) {
      if (e.length.size() <= axis) e.length.resize(config_.axes.size(), 0.0);
      e.length[axis] = value;
      return true;
    }
  return false;
}

void Channel::SwapProgramInWork() { std::swap(work_, parked_); }

void Channel::StartReposRun() {
  // 4.1: the REPOS subroutine in the current program, in program 99 or in the cycle memory.
  const int program = work_.interpreter ? work_.interpreter->FindSubroutine("REPOS") : -1;
  if (program < 0 && !repos_.conditions_restored()) {
    Fail(programs_[0]->files[0] +
             ": error: the state before the interruption is not restored and no program has a "
             "REPOS subroutine (.REPOS)",
         kMsgReposNoSubroutine);
    return;
  }
  // The process' @ variables are one set (8.3): the subroutine starts with the program's (or,
  // run again, with its own) and hands them back at its RTS.
  std::map<std::string, double> variables;
  if (const nc::Interpreter* owner = work_.interpreter     ? &*work_.interpreter
                                     : parked_.interpreter ? &*parked_.interpreter
                                                           : nullptr)
    variables = owner->variables();
  // The interrupted program waits, its block in work and what was read ahead, while the
  // subroutine runs in its place with its modal state (G(2), M(5) read the interrupted state).
  // Run again after a stop and manual mode during it, the subroutine's progress is dropped:
  // the interrupted program stays parked and the targets stay the interruption's.
  if (!repos_.run()) SwapProgramInWork();
  sp_.orienting = false;
  further_.StopRestoring();
  work_.active = work_.pending_motion = work_.homing = false;
  work_.dwell_left_s = 0;
  DropLookahead();
  work_.block = nc::PreparedBlock{};
  work_.block.program = parked_.block.program;
  work_.block.modal = repos_.interruption()->modal;
  repos_.StartRun(program >= 0);
  if (program >= 0) {
    nc::InterpreterConfig ic;
    ic.axes.clear();
    for (const ChannelAxis& a : config_.axes) ic.axes.push_back(a.name);
    ic.initial = repos_.interruption()->modal;
    std::vector<const nc::Program*> programs = programs_;
    if (mdi_.running) programs.insert(programs.begin(), &mdi_.blocks->program);
    work_.interpreter.emplace(std::move(programs), ic);
    std::vector<double> position(out_.commanded.size());
    for (size_t a = 0; a < position.size(); ++a)
      position[a] = out_.commanded[a] - frames_.translation[a];
    work_.interpreter->SetPosition(position);
    work_.interpreter->SetVariables(std::move(variables));
    work_.interpreter->RunSubroutine(static_cast<uint32_t>(program), "REPOS");
  }
  state_ = ChannelState::kRunning;
}

bool Channel::CheckReposBlock() {
  const nc::Program& program = *ProgramOf(work_.block.program);
  // 7.1: G77 while the PLC has withdrawn the function interrupts the program.
  if (!repos_.called() || !repos_.interruption()) {
    Fail(program, work_.block.block,
         "G77 without repositioning or NC-block restart (PxxC.REPOS / PxxC.RESTA is 0)",
         kMsgReposNotActive);
    return false;
  }
  const uint64_t feed_axes = work_.block.programmed;
  if (feed_axes && !work_.block.feed_programmed) {
    Fail(program, work_.block.block, "G77 of a feed axis needs an F value in its block",
         kMsgReposNoFeed);
    return false;
  }
  if (const std::string error = further_.CheckRepos(program, work_.block); !error.empty())
    return Fail(error, kMsgNotAvailable), false;
  // 4.2: G77 S1=0 (or S=0) restores the main spindle: a channel without one has none to restore.
  for (const nc::AuxFunction& f : work_.block.aux)
    if (f.letter == 'S' && f.index <= 1 && config_.spindle_drive < 0) {
      const std::string word = f.index == 0 ? "S0" : "S" + std::to_string(f.index) + "=0";
      Fail(program, work_.block.block, "G77 " + word + ": the channel has no spindle S1 to restore",
           kMsgNotAvailable);
      return false;
    }
  // 4.2: the mode before the interruption decides between G77 S1=0 and G77 C0 (the manual's
  // sentence names the modes the other way round; its own example, 8.3, tests rotary axis
  // mode to choose G77 C0).
  if (headstock_) {
    const bool rotary_before =
        repos_.interruption()->headstock_mode == axes::HeadstockMode::kRotary;
    const size_t r = static_cast<size_t>(config_.rotary_axis);
    if ((feed_axes >> r & 1) && !rotary_before) {
      Fail(program, work_.block.block,
           "G77 " + config_.axes[r].name +
               ": the spindle was in spindle mode before the "
               "interruption: restore it with G77 S1=0",
           kMsgReposMode);
      return false;
    }
    for (const nc::AuxFunction& f : work_.block.aux)
      if (f.letter == 'S' && f.index <= 1 && rotary_before) {
        Fail(program, work_.block.block,
             "G77 S1=0: the spindle was in rotary axis mode before the interruption: restore " +
                 config_.axes[r].name + " with G77 " + config_.axes[r].name + "0",
             kMsgReposMode);
        return false;
      }
  }
  return true;
}

bool Channel::StartReposMotion(const AmplifierTelegram& at) {
  const nc::Program& program = *ProgramOf(work_.block.program);
  // 4.2 Spindles: G77 S1=0 restores the main spindle's speed or position; the block waits until
  // it has reached it. Spindles the channel does not command have nothing to restore.
  for (const nc::AuxFunction& f : work_.block.aux)
    if (f.letter == 'S' && f.index <= 1 && config_.spindle_drive >= 0) {
      if (!GuardSpindleStart("spindle start G77 S1", repos_.interruption()->spindle)) return false;
      sp_.command = repos_.interruption()->spindle;
      sp_.referencing = sp_.command.mode == DriveMode::kPosition;
      sp_.orienting = true;
    }
  // The further spindles have no rotary axis mode and no PathGuard sweep (channel_turret_guard).
  further_.Restore(work_.block, repos_.interruption()->further_spindles, at);
  sp_.orienting |= further_.restoring();
  // 4.2 Feed axes: the distance to go between target and actual position, G00-like (all axes
  // reach the target together) at F, without the G functions of interpolation and without tool
  // radius compensation.
  const std::vector<double> target = repos_.Target(ReposViewNow());
  nc::PreparedBlock b = work_.block;
  b.motion = repos_.closing() ? nc::Motion::kRapid : nc::Motion::kLinear;
  b.modal.feed_per_revolution = false;
  b.modal.compensation = nc::Compensation::kOff;
  b.has_centre = false;
  b.radius = 0;
  b.has_effective_distance = 0;
  for (size_t a = 0; a < out_.commanded.size(); ++a) {
    const bool to_target = (work_.block.programmed >> a & 1) && !std::isnan(target[a]);
    b.target[a] = (to_target ? target[a] : out_.commanded[a]) - frames_.translation[a];
  }
  if (const auto error = PlanBlockMotion(b, out_.commanded, frames_.translation, config_.axes, 0,
                                         work_.motion, FollowUpAxes(b))) {
    Fail(program, work_.block.block, error->text, error->number);
    return false;
  }
  // The subroutine's next blocks count from the targets.
  for (size_t a = 0; a < out_.commanded.size(); ++a)
    if ((work_.block.programmed >> a & 1) && work_.interpreter)
      work_.interpreter->SetAxisPosition(a, b.target[a]);
  work_.profile = PathProfile{};
  if (!work_.motion.moves) return true;
  if (!GuardBlockMove(repos_.closing() ? "repositioning" : "G77")) return false;
  work_.profile.max_rate = work_.motion.max_rate;
  work_.profile.max_accel = work_.motion.max_accel;
  work_.profile.max_jerk = work_.motion.max_jerk;
  work_.active = true;
  return true;
}

bool Channel::FinishReposRun(const AmplifierTelegram& at) {
  const ReposView v = ReposViewNow();
  const std::vector<double> target = repos_.Target(v);
  if (!repos_.closing()) {
    // The subroutine (or the operator) has left the axes within their windows, or has not
    // returned some at all (Cxx.086 = 0): a closing move takes every axis to its exact target,
    // so that the program goes on from the point it left, checked like every approach move.
    uint64_t bits = 0;
    for (size_t a = 0; a < target.size(); ++a)
      if (!std::isnan(target[a]) && std::abs(out_.commanded[a] - target[a]) > 1e-9)
        bits |= uint64_t{1} << a;
    if (repos_.SpindleRelevant(v) && !repos_.SpindleRestored(v, at)) {
      Fail(ProgramOf(work_.block.program)->files[0] +
               ": error: the REPOS subroutine has returned with the spindle not in its state "
               "before the interruption (G77 S1=0)",
           kMsgReposNotRestored);
      return false;
    }
    if (repos_.interruption() &&
        !further_.AllRestored(repos_.interruption()->further_spindles, at)) {
      Fail(ProgramOf(work_.block.program)->files[0] +
               ": error: the REPOS subroutine has returned with a further spindle not in its "
               "state before the interruption (G77 Sj=0)",
           kMsgReposNotRestored);
      return false;
    }
    // The closing move and the interrupted block position the rotary axis: not in spindle mode.
    const int r = config_.rotary_axis;
    if (r >= 0 && !std::isnan(target[r]) && OutOfItsMode(headstock(), r, r)) {
      Fail(ProgramOf(work_.block.program)->files[0] +
               ": error: the REPOS subroutine has returned with " + config_.axes[r].name +
               " not in rotary axis mode (G77 " + config_.axes[r].name + "0)",
           kMsgReposNotRestored);
      return false;
    }
    repos_.StartClosing();
    if (bits) {
      nc::PreparedBlock closing = work_.block;
      closing.repos = true;
      closing.returned = false;
      closing.programmed = bits;
      closing.aux.clear();
      closing.instructions.clear();
      closing.events.clear();
      closing.target.assign(out_.commanded.size(), 0);
      closing.fictive = false;  // within the windows: straight in the axes
      work_.block = closing;
      if (!StartReposMotion(at)) return false;
      if (work_.active) return true;
    }
  }
  // Back to the interrupted program: it continues at the interruption point, or its block
  // starts again (restart), shifted with the contour by any offset or tool edit (2.5).
  const ReposFunction function = repos_.function();
  const std::vector<double> shift = [&] {
    std::vector<double> d(target.size(), 0.0);
    const std::vector<double> now = TranslationOf(repos_.interruption()->modal);
    for (size_t a = 0; a < d.size(); ++a) d[a] = now[a] - repos_.interruption()->translation[a];
    return d;
  }();
  HandBackVariables();
  SwapProgramInWork();
  parked_ = ProgramInWork{};
  repos_.Clear();
  if (work_.active) {
    for (size_t a = 0; a < shift.size(); ++a) {
      work_.motion.start[a] += shift[a];
      work_.motion.end[a] += shift[a];
    }
    for (int k = 0; k < 2; ++k)
      if (work_.motion.arc_axes[k] >= 0)
        work_.motion.arc_centre[k] += shift[work_.motion.arc_axes[k]];
    for (int k = 0; k < 2; ++k)
      if (work_.motion.face_axes[k] >= 0)
        work_.motion.face_shift[k] += shift[work_.motion.face_axes[k]];
    if (function == ReposFunction::kRestart) {
      PathProfile fresh;
      fresh.max_rate = work_.profile.max_rate;
      fresh.max_accel = work_.profile.max_accel;
      fresh.max_jerk = work_.profile.max_jerk;
      work_.profile = fresh;
    }
  }
  if (work_.block.block >= 0 &&
      !UpdateTranslation(work_.block.modal, *ProgramOf(work_.block.program), work_.block.block))
    return false;
  state_ = ChannelState::kRunning;
  return true;
}

void Channel::HandBackVariables() {
  // 8.3: what the subroutine wrote the program reads after RTS (one set per process).
  if (repos_.run() && work_.interpreter && parked_.interpreter)
    parked_.interpreter->SetVariables(work_.interpreter->variables());
}

}  // namespace vmt::control::channel
