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
namespace {

int SpindleM(const DriveSetpoint& sp) {
  if (sp.mode == DriveMode::kPosition) return 19;
  return sp.value > 0 ? 3 : sp.value < 0 ? 4 : 5;
}

/// 7.3: a rotary axis positioned in rotary axis mode before the interruption has its state back
/// only in that mode: in spindle mode (a spindle key selected it, C-axis manual 4.2) it is no
/// positioned axis, whatever angle the spindle stands at.
bool OutOfItsMode(const axes::HeadstockChangeover* headstock, int rotary_axis, size_t a) {
  return headstock && static_cast<int>(a) == rotary_axis &&
         headstock->mode() != axes::HeadstockMode::kRotary;
}

}  // namespace

std::vector<double> Channel::TranslationOf(const nc::ModalState& modal) const {
  std::optional<axes::ToolEdge> edge;
  if (modal.tool_length != nc::ToolLength::kOff && modal.correction != 0)
    edge = config_.tools.Find(modal.tool, modal.correction);
  const double sign = modal.tool_length == nc::ToolLength::kSubtract ? -1 : 1;
  std::vector<double> t(config_.axes.size());
  for (size_t a = 0; a < t.size(); ++a) {
    const double length = edge ? edge->Length(a, config_.axes[a].name) : 0;
    t[a] = config_.zero_offsets.Offset(modal.zero_offset, a) + frames_.shift[a] - sign * length;
  }
  return t;
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
  i.spindle_m = SpindleM(sp_.command);
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
  repos_.interruption = std::move(i);
  repos_.start = out_.commanded;
}

bool Channel::FictiveRepos(int& x, int& c) const {
  x = c = -1;
  if (!repos_.interruption ||
      repos_.interruption->modal.transformation != nc::Transformation::kFace)
    return false;
  for (size_t a = 0; a < config_.axes.size(); ++a) {
    if (config_.axes[a].name == "X") x = static_cast<int>(a);
    if (config_.axes[a].name == "C") c = static_cast<int>(a);
  }
  return x >= 0 && c >= 0 && !std::isnan(repos_.interruption->point[x]) &&
         !std::isnan(repos_.interruption->point[c]);
}

nc::FictivePoint Channel::FictiveOf(const std::vector<double>& position, int x, int c) const {
  // Program coordinates of the interrupted block's frame, as its X1/Y1 were programmed.
  const std::vector<double> t = TranslationOf(repos_.interruption->modal);
  return nc::MachineToFace(position[x] - t[x], position[c] - t[c]);
}

std::vector<double> Channel::ReposTarget() const {
  std::vector<double> target(config_.axes.size(), std::nan(""));
  if (!repos_.interruption) return target;
  const Interruption& i = *repos_.interruption;
  const std::vector<double>& base =
      repos_.function == ReposFunction::kRestart ? i.block_start : i.point;
  // 2.5: zero offset and tool edits during the interruption move the interruption point and
  // the block start with the contour.
  const std::vector<double> now = TranslationOf(i.modal);
  for (size_t a = 0; a < target.size(); ++a) target[a] = base[a] + (now[a] - i.translation[a]);
  return target;
}

bool Channel::ToolStorageKnown() const {
  return config_.tool_storage_drive >= 0 &&
         static_cast<size_t>(config_.tool_storage_drive) < drive_positions_.size();
}

bool Channel::ToolStorageRestored() const {
  // 6.2 / 7.3: only with Bxx.045 'Reposition Tool Storage Axis' = yes.
  if (!config_.process.reposition_tool_storage || !ToolStorageKnown() || !repos_.interruption)
    return true;
  // 3.4: an endless one compares the short way round, however often it has turned.
  return std::abs(ReposDistanceToGo(config_.tool_storage, repos_.interruption->tool_storage,
                                    drive_positions_[config_.tool_storage_drive])) <=
         kToolStorageWindow;
}

bool Channel::SpindleRelevant() const {
  // 7.3: all spindles; a spindle with rotary axis capability if it was in spindle mode.
  if (config_.spindle_drive < 0 || !repos_.interruption) return false;
  return !headstock_ || repos_.interruption->headstock_mode != axes::HeadstockMode::kRotary;
}

bool Channel::SpindleRestored(const AmplifierTelegram& at) const {
  const DriveSetpoint& before = repos_.interruption->spindle;
  if (headstock_ && headstock_->mode() != axes::HeadstockMode::kSpindle) return false;
  if (sp_.command.mode != before.mode || std::abs(sp_.command.value - before.value) > 1e-9)
    return false;
  const uint32_t status = static_cast<size_t>(config_.spindle_drive) < at.feedback.size()
                              ? at.feedback[config_.spindle_drive].status
                              : 0;
  if (before.mode == DriveMode::kPosition) return status & drive_status::kInPosition;
  // The status bit of the last tick may still answer the command before this cycle's.
  const double actual = at.feedback[config_.spindle_drive].velocity;
  const double command = before.value * sp_.override;
  if (std::abs(actual - command) > std::max(6.0, 0.02 * std::abs(command))) return false;
  return before.value == 0 || (status & drive_status::kAtSpeed);
}

void Channel::ReposCycle(const AmplifierTelegram& at) {
  if (!repos_.interruption) {
    repos_.function = ReposFunction::kNone;
    repos_.crest = false;
    return;
  }
  Interruption& i = *repos_.interruption;
  for (size_t a = 0; a < out_.commanded.size() && !i.left_contour; ++a)
    if (!std::isnan(i.point[a]) && std::abs(out_.commanded[a] - i.point[a]) > 1e-6)
      i.left_contour = true;
  // 7.1: the signals count only in the situation of 2.1 (interrupted, left by jogging, no
  // Control-Reset), and only if the program may be continued other than by the reverse
  // program (Bxx.032, 6.1).
  const bool evaluated = (state_ == ChannelState::kHold || repos_.run) && i.left_contour &&
                         !config_.process.reverse_program_required;
  const ReposFunction function = evaluated ? repos_.request : ReposFunction::kNone;
  // 7.3: updated only while a function is called; the relevant axes within their windows, the
  // spindle in its former state. Withdrawing the function drops it at once.
  repos_.crest = false;
  // 7.1 instruction: withdrawn in manual mode, repositioning ends once the motion under way has
  // ended: a jog still moving, or its key still held, keeps its zone and stops at the target;
  // the next press is a plain jog.
  bool key_held = false;
  for (const JogAxis& j : jog_.axes) key_held |= j.key != 0;
  for (const FictiveJog& f : jog_.fictive) key_held |= f.key != 0;
  if (evaluated && function == ReposFunction::kNone && repos_.function != ReposFunction::kNone &&
      mode_ == ChannelMode::kManual && (key_held || JogsMoving()))
    return;
  if (function != repos_.function && function != ReposFunction::kNone)
    repos_.start = out_.commanded;
  repos_.function = function;
  if (repos_.function == ReposFunction::kNone) return;
  const std::vector<double> target = ReposTarget();
  bool restored = true;
  // 6.1 instruction: under G31 X and C count as the fictive point, with X's window.
  int fx = -1, fc = -1;
  const bool fictive = FictiveRepos(fx, fc);
  for (size_t a = 0; a < target.size() && restored; ++a) {
    const ChannelAxis& axis = config_.axes[a];
    if (fictive && (static_cast<int>(a) == fx || static_cast<int>(a) == fc)) continue;
    if (std::isnan(target[a]) || axis.repos_window <= 0) continue;
    restored = WithinReposWindow(axis, target[a], out_.commanded[a]) &&
               !OutOfItsMode(headstock(), config_.rotary_axis, a);
  }
  if (fictive && restored && config_.axes[fx].repos_window > 0)
    restored = WithinFictiveWindow(config_.axes[fx], FictiveOf(target, fx, fc),
                                   FictiveOf(out_.commanded, fx, fc)) &&
               !OutOfItsMode(headstock(), config_.rotary_axis, fc);
  if (restored && SpindleRelevant()) restored = SpindleRestored(at);
  if (restored && repos_.interruption)
    restored = further_.AllRestored(repos_.interruption->further_spindles, at);
  repos_.crest = restored && ToolStorageRestored();
}

ReposStatus Channel::repos_status(const AmplifierTelegram* at, bool whole) const {
  ReposStatus s;
  s.allowed = repos_allowed();
  s.function = repos_.function;
  s.conditions_restored = repos_.crest;
  s.subroutine_running = repos_.run;
  s.feed_override = override_;
  if (!repos_.interruption) return s;
  const Interruption& i = *repos_.interruption;
  s.left_contour = i.left_contour;
  const std::vector<double> target = ReposTarget();
  for (size_t a = 0; a < config_.axes.size(); ++a) {
    const ChannelAxis& axis = config_.axes[a];
    ReposAxisStatus x;
    x.name = axis.name;
    x.command_value = out_.commanded[a];
    x.relevant = !std::isnan(target[a]) && axis.repos_window > 0;
    if (!std::isnan(target[a])) {
      x.final_value = target[a];
      x.distance_to_go = ReposDistanceToGo(axis, target[a], out_.commanded[a]);
      x.adjust = x.relevant && (!WithinReposWindow(axis, target[a], out_.commanded[a]) ||
                                OutOfItsMode(headstock(), config_.rotary_axis, a));
    }
    s.axes.push_back(x);
  }
  // 5.2: under G31 the screen shows the fictive axes X1, Y1 as well, and X and C are adjusted
  // as the fictive point is, with X's window (6.1).
  int fx = -1, fc = -1;
  if (FictiveRepos(fx, fc)) {
    const nc::FictivePoint to = FictiveOf(target, fx, fc), now = FictiveOf(out_.commanded, fx, fc);
    const bool relevant = config_.axes[fx].repos_window > 0;
    const bool adjust = relevant && (!WithinFictiveWindow(config_.axes[fx], to, now) ||
                                     OutOfItsMode(headstock(), config_.rotary_axis, fc));
    s.axes[fx].relevant = s.axes[fc].relevant = relevant;
    s.axes[fx].adjust = s.axes[fc].adjust = adjust;
    static const std::string kNames[2] = {"X1", "Y1"};
    for (int k = 0; k < 2; ++k) {
      ReposAxisStatus f;
      f.name = kNames[k];
      f.final_value = k == 0 ? to.x1 : to.y1;
      f.command_value = k == 0 ? now.x1 : now.y1;
      f.distance_to_go = f.final_value - f.command_value;
      f.relevant = relevant;
      f.adjust = adjust;
      s.axes.push_back(f);
    }
  }
  ReposSpindleStatus& sp = s.spindle;
  sp.relevant = SpindleRelevant();
  sp.override = sp_.override;
  sp.actual_m = SpindleM(sp_.command);
  sp.command_m = i.spindle_m;
  sp.command_rpm = i.spindle.mode == DriveMode::kVelocity ? i.spindle.value / 6 : 0;
  if (at && static_cast<size_t>(config_.spindle_drive) < at->feedback.size())
    sp.actual_rpm = at->feedback[config_.spindle_drive].velocity / 6;
  else
    sp.actual_rpm = sp_.rpm;
  // Without the drives' feedback: the command restored, in spindle mode.
  sp.adjust =
      sp.relevant && !(at ? SpindleRestored(*at)
                          : (!headstock_ || headstock_->mode() == axes::HeadstockMode::kSpindle) &&
                                sp_.command.mode == i.spindle.mode &&
                                std::abs(sp_.command.value - i.spindle.value) < 1e-9);
  s.further_spindles = further_.ReposStatus(i.further_spindles, at);
  s.tool_storage_relevant = config_.process.reposition_tool_storage && ToolStorageKnown();
  s.tool_storage_adjust = !ToolStorageRestored();
  if (!whole) return s;
  s.programmed_feed = i.modal.feed;
  s.program = i.program < programs_.size() || mdi_.running ? ProgramOf(i.program)->files[0] : "";
  s.line = i.line;
  s.tool = i.modal.tool;
  s.correction = i.modal.correction;
  s.spindle_m = i.modal.spindle;
  s.coolant = i.modal.coolant;
  s.g_codes = nc::ActiveGCodes(i.modal);  // G31 / G32 too (5.2)
  return s;
}

void Channel::SetReposition(bool repositioning, bool restart) {
  repos_.request = repositioning && !restart   ? ReposFunction::kRepositioning
                   : restart && !repositioning ? ReposFunction::kRestart
                                               : ReposFunction::kNone;
}

bool Channel::SetZeroOffset(int g, size_t axis, double value) {
  if (g < 54 || g > 59 || axis >= config_.axes.size()) return false;
  std::vector<double>& table = config_.zero_offsets.g54_to_g59[g - 54];
  if (table.size() <= axis) table.resize(config_.axes.size(), 0.0);
  table[axis] = value;
  return true;
}

bool Channel::SetToolLength(int tool, int edge, size_t axis, double value) {
  if (axis >= config_.axes.size()) return false;
  for (axes::ToolEdge& e : config_.tools.edges)
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
  if (program < 0 && !repos_.crest) {
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
  if (!repos_.run) SwapProgramInWork();
  repos_.rerun = false;
  sp_.orienting = false;
  further_.StopRestoring();
  work_.active = work_.pending_motion = work_.homing = false;
  work_.dwell_left_s = 0;
  DropLookahead();
  work_.block = nc::PreparedBlock{};
  work_.block.program = parked_.block.program;
  work_.block.modal = repos_.interruption->modal;
  repos_.run = true;
  repos_.closing = false;
  repos_.finish = program < 0;
  if (program >= 0) {
    nc::InterpreterConfig ic;
    ic.axes.clear();
    for (const ChannelAxis& a : config_.axes) ic.axes.push_back(a.name);
    ic.initial = repos_.interruption->modal;
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
  if (repos_.function == ReposFunction::kNone || !repos_.interruption) {
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
    const bool rotary_before = repos_.interruption->headstock_mode == axes::HeadstockMode::kRotary;
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
      if (!GuardSpindleStart("spindle start G77 S1", repos_.interruption->spindle)) return false;
      sp_.command = repos_.interruption->spindle;
      sp_.referencing = sp_.command.mode == DriveMode::kPosition;
      sp_.orienting = true;
    }
  // The further spindles have no rotary axis mode and no PathGuard sweep (channel_turret_guard).
  further_.Restore(work_.block, repos_.interruption->further_spindles, at);
  sp_.orienting |= further_.restoring();
  // 4.2 Feed axes: the distance to go between target and actual position, G00-like (all axes
  // reach the target together) at F, without the G functions of interpolation and without tool
  // radius compensation.
  const std::vector<double> target = ReposTarget();
  nc::PreparedBlock b = work_.block;
  b.motion = repos_.closing ? nc::Motion::kRapid : nc::Motion::kLinear;
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
  if (!GuardBlockMove(repos_.closing ? "repositioning" : "G77")) return false;
  work_.profile.max_rate = work_.motion.max_rate;
  work_.profile.max_accel = work_.motion.max_accel;
  work_.profile.max_jerk = work_.motion.max_jerk;
  work_.active = true;
  return true;
}

bool Channel::FinishReposRun(const AmplifierTelegram& at) {
  const std::vector<double> target = ReposTarget();
  if (!repos_.closing) {
    // The subroutine (or the operator) has left the axes within their windows, or has not
    // returned some at all (Cxx.086 = 0): a closing move takes every axis to its exact target,
    // so that the program goes on from the point it left, checked like every approach move.
    uint64_t bits = 0;
    for (size_t a = 0; a < target.size(); ++a)
      if (!std::isnan(target[a]) && std::abs(out_.commanded[a] - target[a]) > 1e-9)
        bits |= uint64_t{1} << a;
    if (SpindleRelevant() && !SpindleRestored(at)) {
      Fail(ProgramOf(work_.block.program)->files[0] +
               ": error: the REPOS subroutine has returned with the spindle not in its state "
               "before the interruption (G77 S1=0)",
           kMsgReposNotRestored);
      return false;
    }
    if (repos_.interruption && !further_.AllRestored(repos_.interruption->further_spindles, at)) {
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
    repos_.closing = true;
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
  const ReposFunction function = repos_.function;
  const std::vector<double> shift = [&] {
    std::vector<double> d(target.size(), 0.0);
    const std::vector<double> now = TranslationOf(repos_.interruption->modal);
    for (size_t a = 0; a < d.size(); ++a) d[a] = now[a] - repos_.interruption->translation[a];
    return d;
  }();
  HandBackVariables();
  SwapProgramInWork();
  parked_ = ProgramInWork{};
  ClearRepos();
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
  if (repos_.run && work_.interpreter && parked_.interpreter)
    parked_.interpreter->SetVariables(work_.interpreter->variables());
}

void Channel::ClearRepos() {
  repos_.interruption.reset();
  repos_.function = ReposFunction::kNone;
  repos_.crest = false;
  repos_.run = repos_.closing = repos_.finish = repos_.rerun = false;
}

}  // namespace vmt::control::channel
