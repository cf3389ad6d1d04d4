#include "control/channel/channel.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "control/nc/parser.hpp"

namespace vmt::control::channel {
namespace {

constexpr double kArcTolerance = 0.01;  // mm: start and end radius may differ this much
// Look-ahead: how far (mm) the path may be thought to round a corner when choosing its speed.
constexpr double kCornerDeviation = 0.01;

// Plane axes (first, second) by address: G17 X-Y, G18 Z-X, G19 Y-Z; the arc turns
// counter-clockwise from first to second.
void PlaneAxes(int plane, const char*& first, const char*& second, char& i_first, char& i_second) {
  if (plane == 17)
    first = "X", second = "Y", i_first = 'I', i_second = 'J';
  else if (plane == 19)
    first = "Y", second = "Z", i_first = 'J', i_second = 'K';
  else
    first = "Z", second = "X", i_first = 'K', i_second = 'I';
}

}  // namespace

const char* ToString(ChannelState s) {
  switch (s) {
    case ChannelState::kIdle:
      return "idle";
    case ChannelState::kRunning:
      return "running";
    case ChannelState::kHold:
      return "hold";
    case ChannelState::kEnded:
      return "ended";
    case ChannelState::kError:
      return "error";
  }
  return "?";
}

const char* ToString(ChannelMode m) {
  switch (m) {
    case ChannelMode::kAutomatic:
      return "automatic";
    case ChannelMode::kManual:
      return "manual";
    case ChannelMode::kMdi:
      return "mdi";
  }
  return "?";
}

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
  last_modal_ = config_.initial;
  for (size_t a = 0; a < n; ++a) {
    if (config_.axes[a].name == "Z") axis_z_ = static_cast<int>(a);
    if (config_.axes[a].name == "X") axis_x_ = static_cast<int>(a);
  }
}

void Channel::DropLookahead() {
  peeked_ = false;
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
  return interpreter;
}

void Channel::SetJogMode(int code) {
  jog_mode_ = static_cast<JogMode>(std::clamp(code, 0, 7));
  switch (jog_mode_) {
    case JogMode::kIncrement1:
      jog_increment_ = 0.001;
      break;
    case JogMode::kIncrement10:
      jog_increment_ = 0.01;
      break;
    case JogMode::kIncrement100:
      jog_increment_ = 0.1;
      break;
    case JogMode::kIncrement1000:
      jog_increment_ = 1;
      break;
    default:
      jog_increment_ = 0;
  }
  for (size_t a = 0; a < jog_.size(); ++a) {
    jog_[a].handwheel = jog_mode_ == JogMode::kHandwheel;
    jog_[a].handwheel_target = commanded_[a];
  }
}

void Channel::Handwheel(size_t axis, int counts) {
  if (mode_ != ChannelMode::kManual || jog_mode_ != JogMode::kHandwheel || axis >= jog_.size())
    return;
  take_over_pending_ = true;
  JogAxis& j = jog_[axis];
  if (!j.handwheel) j.handwheel = true, j.handwheel_target = commanded_[axis];
  j.handwheel_target += counts * config_.handwheel_per_count;
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
  if (!interpreter_) interpreter_ = MakeInterpreter();
  if (!interpreter_->JumpTo("HOME")) {
    Fail(programs_[0]->files[0] + ": error: the program has no reverse program .HOME",
         kMsgNoHomeLabel);
    return false;
  }
  // The interrupted block is abandoned where the axes stand; the reverse program starts there.
  DropLookahead();
  active_ = false;
  homing_ = false;
  dwell_left_s_ = 0;
  aux_output_.clear();
  error_.clear();
  error_number_ = 0;
  interruption_point_.clear();
  std::vector<double> position(commanded_.size());
  for (size_t a = 0; a < position.size(); ++a) position[a] = commanded_[a] - translation_[a];
  interpreter_->SetPosition(position);
  reversing_ = true;
  state_ = ChannelState::kRunning;
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

void Channel::Fail(const nc::Program& program, int32_t block, const std::string& text, int number) {
  if (planning_only_) {
    plan_failed_ = true;  // the look-ahead's plan of a later block: its error comes in its turn
    return;
  }
  Fail(nc::Format({program.blocks[block].pos, text}, program.files), number);
}

bool Channel::SetMode(ChannelMode mode) {
  if (state_ == ChannelState::kRunning) return false;
  // MDI and an interrupted automatic program do not share the interpreter: MDI needs the
  // program ended or reset first.
  if (mode == ChannelMode::kMdi && state_ == ChannelState::kHold) return false;
  if (mode != mode_) {
    for (JogAxis& j : jog_) j = JogAxis{};
    // Where the program was interrupted: the contour the axes must come back to.
    if (mode == ChannelMode::kManual && interruption_point_.empty() &&
        state_ == ChannelState::kHold)
      interruption_point_ = commanded_;
    if (mode == ChannelMode::kMdi || mode_ == ChannelMode::kMdi) {
      if (interpreter_) last_modal_ = interpreter_->modal();
      interpreter_.reset();
      if (state_ == ChannelState::kEnded) state_ = ChannelState::kIdle;
    }
  }
  mode_ = mode;
  if (mode == ChannelMode::kManual && jog_mode_ == JogMode::kHandwheel)
    for (size_t a = 0; a < jog_.size(); ++a)
      jog_[a].handwheel = true, jog_[a].handwheel_target = commanded_[a];
  return true;
}

void Channel::Jog(size_t axis, int direction) {
  if (mode_ != ChannelMode::kManual || axis >= jog_.size()) return;
  jog_[axis].key = direction > 0 ? 1 : direction < 0 ? -1 : 0;
  take_over_pending_ = true;
}

int Channel::AxisMotion(size_t axis) const {
  const double d = commanded_[axis] - previous_[axis];
  return d > 0 ? 1 : d < 0 ? -1 : 0;
}

void Channel::Jogging(double dt) {
  for (size_t a = 0; a < jog_.size(); ++a) {
    JogAxis& j = jog_[a];
    const ChannelAxis& axis = config_.axes[a];
    const double normal = axis.jog_per_s > 0 ? axis.jog_per_s : axis.rapid_per_s / 10;
    const double rapid = axis.jog_rapid_per_s > 0 ? axis.jog_rapid_per_s : axis.rapid_per_s / 2;
    const double speed = (jog_mode_ == JogMode::kRapid ? rapid : normal) * override_;
    // Jogging stops at the software limits, braking in time.
    const bool limited = axis.travel_max > axis.travel_min;
    auto within = [&](double x) {
      return limited ? std::clamp(x, axis.travel_min, axis.travel_max) : x;
    };
    if (jog_mode_ == JogMode::kHandwheel) {
      // Follow the counts at most at the jogging rapid, braking so as not to pass the target.
      if (!j.handwheel) j.handwheel = true, j.handwheel_target = commanded_[a];
      j.handwheel_target = within(j.handwheel_target);
      const double to_go = j.handwheel_target - commanded_[a];
      const double braking = std::sqrt(2 * axis.acceleration * std::abs(to_go));
      const double target = std::copysign(std::min(rapid * override_, braking), to_go);
      const double step = axis.acceleration * dt;
      j.velocity = std::clamp(target, j.velocity - step, j.velocity + step);
      if (std::abs(to_go) <= std::abs(j.velocity * dt) || std::abs(to_go) < 1e-9) {
        commanded_[a] = j.handwheel_target;
        j.velocity = 0;
      } else {
        commanded_[a] += j.velocity * dt;
      }
      continue;
    }
    const double increment = jog_mode_ == JogMode::kParametric ? axis.jog_distance : jog_increment_;
    if (increment > 0 || j.stepping) {
      // Incremental: a key press starts one increment, which then runs to its end.
      if (!j.stepping && j.key != 0) {
        j.stepping = true;
        j.from = commanded_[a];
        j.to = within(commanded_[a] + j.key * increment);
        j.increment = PathProfile{};
        const double distance = std::max(std::abs(j.to - j.from), 1e-12);
        j.increment.max_rate = speed / distance;
        j.increment.max_accel = axis.acceleration / distance;
        j.key = 0;  // one increment per press
      }
      if (j.stepping) {
        j.increment.Advance(dt, 1.0);
        commanded_[a] = j.from + (j.to - j.from) * j.increment.u;
        if (j.increment.done()) commanded_[a] = j.to, j.stepping = false;
      }
      continue;
    }
    // Continuous: towards the jog speed while the key is held, braking when it is released.
    double target = j.key * speed;
    const double step = axis.acceleration * dt;
    if (limited) {
      const double room =
          j.key > 0 ? axis.travel_max - commanded_[a] : commanded_[a] - axis.travel_min;
      target = j.key * std::min(speed, std::sqrt(2 * axis.acceleration * std::max(0.0, room)));
    }
    j.velocity = std::clamp(target, j.velocity - step, j.velocity + step);
    const double next = commanded_[a] + j.velocity * dt;
    commanded_[a] = within(next);
    if (commanded_[a] != next) j.velocity = 0;
  }
}

void Channel::Start() {
  if (mode_ == ChannelMode::kManual) return;
  if (mode_ == ChannelMode::kMdi && !mdi_) return;
  if (state_ == ChannelState::kHold) {
    // Continuing from off the contour would jump back to the path: the axes must first be
    // repositioned to the interruption point (REPOS manual; the REPOS function is issue 6's).
    for (size_t a = 0; a < commanded_.size() && !interruption_point_.empty(); ++a)
      if (std::abs(commanded_[a] - interruption_point_[a]) > 1e-6) {
        Fail("axis " + config_.axes[a].name +
                 " has left the contour at the interruption point: reposition it first",
             kMsgLeftContour);
        return;
      }
    interruption_point_.clear();
    state_ = ChannelState::kRunning;
    return;
  }
  if (state_ == ChannelState::kRunning || state_ == ChannelState::kError) return;
  if (state_ == ChannelState::kEnded) {
    // Start after the end runs the program again from its first block.
    if (interpreter_) last_modal_ = interpreter_->modal();
    interpreter_.reset();
  }
  state_ = ChannelState::kRunning;
  start_pending_ = true;  // positions are taken from the feedback at the next tick
}

void Channel::Stop() {
  if (state_ == ChannelState::kRunning) state_ = ChannelState::kHold;
}

void Channel::Reset() {
  state_ = ChannelState::kIdle;
  error_.clear();
  error_number_ = 0;
  active_ = false;
  homing_ = false;
  reversing_ = false;
  dwell_left_s_ = 0;
  aux_output_.clear();
  interruption_point_.clear();
  if (interpreter_) last_modal_ = interpreter_->modal();
  interpreter_.reset();
  DropLookahead();
  previous_ = commanded_;
  spindle_ = {DriveMode::kVelocity, 0, 0};
  // Control-Reset drops the G92 shift and returns to the initial modal state (offsets too).
  std::fill(shift_.begin(), shift_.end(), 0.0);
  last_modal_ = config_.initial;
  for (size_t a = 0; a < translation_.size(); ++a)
    translation_[a] = config_.zero_offsets.Offset(config_.initial.zero_offset, a);
}

void Channel::Tick(const AmplifierTelegram& at, MasterTelegram& mdt) {
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
    if (!interpreter_) interpreter_ = MakeInterpreter();
  }
  if (!holding_positions_) return;

  if (++tick_in_cycle_ >= config_.ticks_per_cycle) {
    tick_in_cycle_ = 0;
    previous_ = commanded_;
    const double dt = config_.tick_s * config_.ticks_per_cycle;
    if (mode_ == ChannelMode::kManual) {
      Jogging(dt);
    } else if (state_ == ChannelState::kRunning || state_ == ChannelState::kHold) {
      bool finished = false;
      if (!aux_output_.empty()) {
        // The block waits for the PLC's acknowledgement of its auxiliary functions.
      } else if (pending_motion_) {
        pending_motion_ = false;
        if (StartMotion(at)) finished = !active_ && dwell_left_s_ <= 0 && !homing_;
      } else if (dwell_left_s_ > 0) {
        if (state_ == ChannelState::kRunning) dwell_left_s_ -= dt;
        finished = dwell_left_s_ <= 0;
      } else if (!active_ && state_ == ChannelState::kRunning) {
        finished = NextBlock(at) && !active_ && dwell_left_s_ <= 0;
      }
      if (active_) {
        Interpolate(dt);
        finished = !active_;
        if (finished && homing_) finished = !NextHomingStage();
        if (finished && carry_speed_ > 0) {
          // Blended: the next block runs on from here in the same cycle.
          finished = NextBlock(at) && !active_;
          carry_speed_ = carry_accel_ = carry_leftover_ = 0;
        }
      }
      if (finished && single_block_ && state_ == ChannelState::kRunning)
        state_ = ChannelState::kHold;
    }
  }
  // Fine interpolation: the drives get a straight line between the last two NC cycle points.
  const double f = static_cast<double>(tick_in_cycle_ + 1) / config_.ticks_per_cycle;
  // G06 (low-lag): the drives get the path velocity as feed-forward.
  const double cycle_s = config_.tick_s * config_.ticks_per_cycle;
  const bool low_lag = mode_ != ChannelMode::kManual && block_.modal.low_lag &&
                       (state_ == ChannelState::kRunning || state_ == ChannelState::kHold);
  for (size_t a = 0; a < config_.axes.size(); ++a) {
    DriveSetpoint& sp = mdt.setpoints[config_.axes[a].drive];
    sp = {DriveMode::kPosition, previous_[a] + (commanded_[a] - previous_[a]) * f, 0};
    if (low_lag) sp.velocity_feedforward = (commanded_[a] - previous_[a]) / cycle_s;
  }
  if (config_.spindle_drive >= 0) mdt.setpoints[config_.spindle_drive] = spindle_;
}

bool Channel::NextBlock(const AmplifierTelegram& at) {
  if (compensating_) return NextCompensated(at);
  bool read = false;
  if (peeked_) {
    // The block the look-ahead has read already.
    peeked_ = false;
    read = peek_ok_;
    if (read) block_ = peek_;
  } else {
    read = ReadNext(block_);
  }
  if (!read) {
    if (interpreter_->error())
      Fail(nc::Format(*interpreter_->error(), {interpreter_->ErrorFile()}), kMsgProgramError);
    else
      state_ = ChannelState::kEnded, reversing_ = false;
    return false;
  }
  if (block_.modal.compensation != 40 && block_.motion != nc::Motion::kNone) {
    // G41/G42: from here the channel reads ahead, so that each block's path can be offset
    // with its successor in view.
    if (axis_z_ < 0 || axis_x_ < 0) {
      Fail(*ProgramOf(block_.program), block_.block,
           "tool nose radius compensation G41/G42 needs the axes Z and X", kMsgNotAvailable);
      return false;
    }
    compensating_ = true;
    source_done_ = false;
    trc_.Reset();
    ahead_.clear();
    ready_.clear();
    first_tag_ = next_tag_ = 0;
    last_run_tag_ = -1;
    contour_point_ = {commanded_[axis_z_] - translation_[axis_z_],
                      commanded_[axis_x_] - translation_[axis_x_]};
    if (!PushAhead(block_)) return false;
    return NextCompensated(at);
  }
  return RunBlock(at);
}

bool Channel::PushAhead(const nc::PreparedBlock& b) {
  const nc::Program& program = *ProgramOf(b.program);
  if (b.homing || b.set_position || b.repos || b.measuring) {
    Fail(program, b.block,
         "G74, G77, G92 and G100 are not allowed while tool nose radius compensation "
         "(G41/G42) is active: cancel it with G40 first",
         kMsgNotAvailable);
    return false;
  }
  ContourElement e;
  e.tag = next_tag_;
  e.start = contour_point_;
  e.end = e.start;
  e.rapid = b.motion == nc::Motion::kRapid;
  e.side = b.modal.compensation == 41   ? CompensationSide::kLeft
           : b.modal.compensation == 42 ? CompensationSide::kRight
                                        : CompensationSide::kOff;
  if (e.side != CompensationSide::kOff) {
    const auto edge = config_.tools.Find(b.modal.tool, b.modal.correction);
    if (!edge && b.modal.correction != 0) {
      Fail(program, b.block,
           "T" + std::to_string(b.modal.tool) + " D" + std::to_string(b.modal.correction) +
               " is not in the tool list (G" + std::to_string(b.modal.compensation) + ")",
           kMsgToolNotInList);
      return false;
    }
    e.nose_radius_mm = edge ? edge->nose_radius : 0;
    e.edge_position = edge ? edge->edge_position : 0;
  }
  if (b.motion != nc::Motion::kNone) {
    if (b.modal.plane != 18) {
      Fail(program, b.block, "tool nose radius compensation G41/G42 works in the plane G18",
           kMsgNotAvailable);
      return false;
    }
    e.end = {b.target[axis_z_], b.target[axis_x_]};
    if (b.motion == nc::Motion::kArcCw || b.motion == nc::Motion::kArcCcw) {
      e.kind = b.motion == nc::Motion::kArcCw ? ElementKind::kArcCw : ElementKind::kArcCcw;
      if (b.has_centre) {
        e.centre = {e.start.z + b.centre[2], e.start.x + b.centre[0]};
      } else if (b.radius != 0) {
        // Centre from R, as the interpolation computes it (R < 0: the arc over 180 degrees).
        const double dz = e.end.z - e.start.z, dx = e.end.x - e.start.x;
        const double chord = std::hypot(dz, dx), r = std::abs(b.radius);
        if (chord < 1e-12 || chord > 2 * r + kArcTolerance) {
          Fail(program, b.block, "radius R too small for the end point", kMsgArcGeometry);
          return false;
        }
        const double h = std::sqrt(std::max(0.0, r * r - chord * chord / 4));
        const double side = ((b.radius > 0) == (b.motion == nc::Motion::kArcCw)) ? -1 : 1;
        e.centre = {(e.start.z + e.end.z) / 2 - side * h * dx / chord,
                    (e.start.x + e.end.x) / 2 + side * h * dz / chord};
      } else {
        Fail(program, b.block, "G02/G03 needs a centre (I/J/K) or a radius R", kMsgArcGeometry);
        return false;
      }
    }
  }
  ++next_tag_;
  contour_point_ = e.end;
  ahead_.push_back(b);
  trc_.Push(e);
  return true;
}

bool Channel::NextCompensated(const AmplifierTelegram& at) {
  ContourElement e;
  while (ready_.empty()) {
    while (trc_.Pop(e)) ready_.push_back(e);
    if (!ready_.empty()) break;
    if (const auto& err = trc_.error()) {
      const nc::PreparedBlock& b = ahead_[static_cast<size_t>(err->tag - first_tag_)];
      Fail(*ProgramOf(b.program), b.block, err->message, kMsgGouge);
      return false;
    }
    if (source_done_ || (!trc_.active() && !trc_.pending())) {
      // Everything read ahead has run: back to block-by-block.
      compensating_ = false;
      ahead_.clear();
      if (source_done_) {
        state_ = ChannelState::kEnded, reversing_ = false;
        return false;
      }
      return NextBlock(at);
    }
    nc::PreparedBlock b;
    if (!ReadNext(b)) {
      if (interpreter_->error()) {
        Fail(nc::Format(*interpreter_->error(), {interpreter_->ErrorFile()}), kMsgProgramError);
        return false;
      }
      source_done_ = true;
      trc_.Flush();
      continue;
    }
    if (!PushAhead(b)) return false;
    if (b.end) source_done_ = true, trc_.Flush();
  }
  e = ready_.front();
  ready_.pop_front();
  while (first_tag_ < e.tag) ahead_.pop_front(), ++first_tag_;
  block_ = ElementBlock(e, ahead_.front());
  if (e.tag != last_run_tag_) {
    last_run_tag_ = e.tag;
    return RunBlock(at);
  }
  return StartMotion(at);
}

bool Channel::ReadNext(nc::PreparedBlock& b) {
  // A block the look-ahead read but could not take (its error comes now), or the end it met.
  if (unpushed_) {
    b = *unpushed_;
    unpushed_.reset();
    return true;
  }
  if (source_returned_false_) return false;
  return interpreter_->Next(b);
}

void Channel::FillCompensated() {
  // Reads ahead under G41/G42 until the compensation has a final element; errors are left for
  // NextCompensated to report when the channel gets there.
  ContourElement e;
  for (int k = 0; k < 4 && ready_.empty(); ++k) {
    if (source_done_ || trc_.error() || (!trc_.active() && !trc_.pending()) || unpushed_ ||
        source_returned_false_)
      return;
    nc::PreparedBlock b;
    if (!interpreter_->Next(b)) {
      source_returned_false_ = true;
      return;
    }
    planning_only_ = true;
    plan_failed_ = false;
    const bool pushed = PushAhead(b) && !plan_failed_;
    planning_only_ = false;
    if (!pushed) {
      unpushed_ = b;
      return;
    }
    if (b.end) source_done_ = true, trc_.Flush();
    while (trc_.Pop(e)) ready_.push_back(e);
  }
}

nc::PreparedBlock Channel::ElementBlock(const ContourElement& e, nc::PreparedBlock b) const {
  // The block runs the tip path the compensation made of it: lines and arcs in Z/X.
  b.target[axis_z_] = e.end.z;
  b.target[axis_x_] = e.end.x;
  b.radius = 0;
  b.has_centre = false;
  if (e.kind != ElementKind::kLine) {
    b.motion = e.kind == ElementKind::kArcCw ? nc::Motion::kArcCw : nc::Motion::kArcCcw;
    b.centre[2] = e.centre.z - e.start.z;
    b.centre[0] = e.centre.x - e.start.x;
    b.has_centre = true;
  } else if (b.motion == nc::Motion::kArcCw || b.motion == nc::Motion::kArcCcw) {
    b.motion = nc::Motion::kLinear;  // an arc the compensation shrank to a point
  } else if (e.inserted && b.motion == nc::Motion::kNone) {
    b.motion = e.rapid ? nc::Motion::kRapid : nc::Motion::kLinear;
  }
  return b;
}

bool Channel::RunBlock(const AmplifierTelegram& at) {
  const nc::Program& program = *ProgramOf(block_.program);
  auto unsupported = [&](const std::string& what) {
    Fail(program, block_.block, what + " is not available in the channel yet", kMsgNotAvailable);
    return false;
  };
  if (block_.repos) return unsupported("G77 (REPOS)");
  if (block_.measuring) return unsupported("G100 measuring");
  if (block_.has_centre && block_.motion != nc::Motion::kArcCw &&
      block_.motion != nc::Motion::kArcCcw)
    return unsupported("I/J/K outside G02/G03");

  // Instructions of later issues stop the program rather than pass unnoticed. The
  // #-commands that only steer block search (and its return to the contour) have no effect on
  // a normal run.
  for (uint32_t index : block_.instructions) {
    const nc::Statement& st = program.statements[index];
    std::string name = st.kind == nc::Statement::Kind::kHashCommand ? "#" + program.texts[st.text]
                                                                    : program.symbols.Name(st.name);
    for (const char* steering :
         {"#DISTANCE PROG START", "#BLOCKSEARCH", "#CAX TRACK", "#VECTOR OFFSET"})
      if (name.rfind(steering, 0) == 0) name.clear();
    if (!name.empty()) {
      Fail(nc::Format({st.pos, "instruction " + name.substr(0, name.find(' ')) +
                                   " is not available in the channel yet"},
                      program.files),
           kMsgNotAvailable);
      return false;
    }
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
      }
  }
  const bool arc = block_.motion == nc::Motion::kArcCw || block_.motion == nc::Motion::kArcCcw;
  if (arc && translation_ != before) {
    Fail(program, block_.block,
         "zero offset or tool correction changes in an arc block: program it in a straight block",
         kMsgTranslationInArc);
    return false;
  }

  // Spindle: M3/M4 with S (rpm), M5, M19 (orient to 0 deg).
  for (const nc::AuxFunction& f : block_.aux) {
    if (f.letter != 'M' || config_.spindle_drive < 0) continue;
    const int m = static_cast<int>(f.value);
    const double rpm = block_.modal.spindle_speed;
    if (m == 3) spindle_ = {DriveMode::kVelocity, rpm * 6, 0};
    if (m == 4) spindle_ = {DriveMode::kVelocity, -rpm * 6, 0};
    if (m == 5) spindle_ = {DriveMode::kVelocity, 0, 0};
    if (m == 19) spindle_ = {DriveMode::kPosition, 0, 0};
  }
  // An S word alone changes the speed of a running spindle.
  if (spindle_.mode == DriveMode::kVelocity && spindle_.value != 0)
    spindle_.value = std::copysign(block_.modal.spindle_speed * 6, spindle_.value);

  // M, H, Q and T go to the PLC; the block goes on when it has acknowledged them.
  if (config_.aux_handshake) {
    for (const nc::AuxFunction& f : block_.aux)
      if (f.letter == 'M' || f.letter == 'H' || f.letter == 'Q' || f.letter == 'T')
        aux_output_.push_back(f);
    if (!aux_output_.empty()) ++aux_strobe_;
  }

  dwell_left_s_ = block_.dwell_s;
  if (block_.end) state_ = ChannelState::kEnded, reversing_ = false;
  if (block_.motion == nc::Motion::kNone && !block_.homing) return true;
  if (!aux_output_.empty()) {
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
  if (modal.tool_length != 47 && modal.correction != 0) {
    found = config_.tools.Find(modal.tool, modal.correction);
    if (!found) {
      Fail(program, block,
           "T" + std::to_string(modal.tool) + " D" + std::to_string(modal.correction) +
               " is not in the tool list (G" + std::to_string(modal.tool_length) + ")",
           kMsgToolNotInList);
      return false;
    }
    edge = &*found;
  }
  const double sign = modal.tool_length == 49 ? -1 : 1;
  for (size_t a = 0; a < translation_.size(); ++a) {
    const double length = edge && a < edge->length.size() ? edge->length[a] : 0;
    translation_[a] = config_.zero_offsets.Offset(modal.zero_offset, a) + shift_[a] - sign * length;
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
  start_ = commanded_;
  end_ = commanded_;
  double rate = std::numeric_limits<double>::infinity();
  double accel = rate;
  for (size_t a = 0; a < commanded_.size(); ++a) {
    if (!(bits >> a & 1)) continue;
    const ChannelAxis& axis = config_.axes[a];
    end_[a] = axis.reference_position;
    homed_[a] = true;
    const double distance = std::abs(end_[a] - start_[a]);
    if (distance < 1e-12) continue;
    const double speed = axis.homing_per_s > 0 ? axis.homing_per_s
                         : axis.jog_per_s > 0  ? axis.jog_per_s
                                               : axis.rapid_per_s / 10;
    rate = std::min(rate, speed / distance);
    accel = std::min(accel, axis.acceleration / distance);
  }
  profile_ = PathProfile{};
  arc_axes_[0] = arc_axes_[1] = -1;
  if (!std::isfinite(rate)) return NextHomingStage();
  profile_.max_rate = rate;
  profile_.max_accel = accel;
  active_ = true;
  return true;
}

bool Channel::StartMotion(const AmplifierTelegram& at) {
  const nc::Program& program = *ProgramOf(block_.program);
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
    return NextHomingStage();
  }
  for (size_t a = 0; a < commanded_.size(); ++a)
    if (!homed_[a] && (block_.programmed >> a & 1)) {
      Fail(program, block_.block,
           "axis " + config_.axes[a].name + " has no reference: home it first (G74)", kMsgNotHomed);
      return false;
    }

  start_ = commanded_;
  end_ = block_.target;
  for (size_t a = 0; a < end_.size(); ++a) end_[a] += translation_[a];
  const size_t n = config_.axes.size();
  for (size_t a = 0; a < n; ++a) {
    const ChannelAxis& axis = config_.axes[a];
    // Checked before the move starts, so the axis never runs into its limit switch.
    if (axis.travel_max > axis.travel_min &&
        (end_[a] < axis.travel_min - 1e-9 || end_[a] > axis.travel_max + 1e-9)) {
      char text[160];
      std::snprintf(text, sizeof text, "axis %s target %.4f is beyond its travel %.4f .. %.4f",
                    axis.name.c_str(), end_[a], axis.travel_min, axis.travel_max);
      Fail(program, block_.block, text, kMsgSoftwareLimit);
      return false;
    }
  }
  std::vector<double> delta(n);
  double max_delta = 0;
  for (size_t a = 0; a < n; ++a)
    max_delta = std::max(max_delta, std::abs(delta[a] = end_[a] - start_[a]));
  const bool arc = block_.motion == nc::Motion::kArcCw || block_.motion == nc::Motion::kArcCcw;
  if (max_delta < 1e-12 && !arc) return true;

  // Per-axis limits on du/dt and d2u/dt2 for a straight move in axis space.
  double axis_rate = std::numeric_limits<double>::infinity();
  double axis_accel = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < n; ++a) {
    if (std::abs(delta[a]) < 1e-12) continue;
    axis_rate = std::min(axis_rate, config_.axes[a].rapid_per_s / std::abs(delta[a]));
    axis_accel = std::min(axis_accel, config_.axes[a].acceleration / std::abs(delta[a]));
  }
  profile_ = PathProfile{};
  arc_axes_[0] = arc_axes_[1] = -1;

  // Path feed, mm/s: F mm/min, or mm/rev times the spindle speed (G95).
  double feed = block_.modal.feed / 60.0;
  if (block_.modal.feed_per_revolution)
    feed = block_.modal.feed * std::abs(at.feedback.empty() || config_.spindle_drive < 0
                                            ? 0
                                            : at.feedback[config_.spindle_drive].velocity / 360.0);
  if (block_.motion != nc::Motion::kRapid && feed <= 0) {
    Fail(program, block_.block, "no feed programmed (F)", kMsgNoFeed);
    return false;
  }

  // Jerk: the axes' limit, as for the acceleration (0: not limited).
  double axis_jerk = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < n; ++a)
    if (std::abs(delta[a]) >= 1e-12 && config_.axes[a].jerk > 0)
      axis_jerk = std::min(axis_jerk, config_.axes[a].jerk / std::abs(delta[a]));
  if (std::isfinite(axis_jerk)) profile_.max_jerk = axis_jerk;
  if (block_.motion == nc::Motion::kRapid) {
    profile_.max_rate = axis_rate;
    profile_.max_accel = axis_accel;
  } else if (!arc) {
    // Path length over the linear axes; rotary axes count with their effective distance
    // (RX: radius at which the C axis' motion counts, C-axis manual 1.2), or alone in deg.
    double length2 = 0, rotary2 = 0;
    for (size_t a = 0; a < n; ++a) {
      if (!config_.axes[a].rotary)
        length2 += delta[a] * delta[a];
      else if (block_.has_effective_distance & 1)
        length2 += std::pow(block_.effective_distance[0] * delta[a] * std::numbers::pi / 180, 2);
      else
        rotary2 += delta[a] * delta[a];
    }
    const double length = std::sqrt(length2 > 0 ? length2 : rotary2);
    profile_.max_rate = std::min(feed / length, axis_rate);
    profile_.max_accel = axis_accel;
  } else {
    const char *first, *second;
    char i_first, i_second;
    PlaneAxes(block_.modal.plane, first, second, i_first, i_second);
    for (size_t a = 0; a < n; ++a) {
      if (config_.axes[a].name == first) arc_axes_[0] = static_cast<int>(a);
      if (config_.axes[a].name == second) arc_axes_[1] = static_cast<int>(a);
    }
    if (arc_axes_[0] < 0 || arc_axes_[1] < 0) {
      Fail(program, block_.block,
           std::string("the arc plane G") + std::to_string(block_.modal.plane) + " needs axes " +
               first + " and " + second,
           kMsgArcPlane);
      return false;
    }
    const int a0 = arc_axes_[0], a1 = arc_axes_[1];
    const double s0 = start_[a0], s1 = start_[a1], e0 = end_[a0], e1 = end_[a1];
    const bool cw = block_.motion == nc::Motion::kArcCw;
    double c0, c1;
    if (block_.has_centre) {
      c0 = s0 + block_.centre[i_first - 'I'];
      c1 = s1 + block_.centre[i_second - 'I'];
    } else if (block_.radius != 0) {
      // Centre from R: on the chord's bisector; R < 0 picks the arc over 180 degrees.
      const double dx = e0 - s0, dy = e1 - s1, chord = std::hypot(dx, dy);
      const double r = std::abs(block_.radius);
      if (chord < 1e-12 || chord > 2 * r + kArcTolerance) {
        Fail(program, block_.block, "radius R too small for the end point", kMsgArcGeometry);
        return false;
      }
      const double h = std::sqrt(std::max(0.0, r * r - chord * chord / 4));
      const double side = ((block_.radius > 0) == cw) ? -1 : 1;
      c0 = (s0 + e0) / 2 - side * h * dy / chord;
      c1 = (s1 + e1) / 2 + side * h * dx / chord;
    } else {
      Fail(program, block_.block, "G02/G03 needs a centre (I/J/K) or a radius R", kMsgArcGeometry);
      return false;
    }
    const double r_start = std::hypot(s0 - c0, s1 - c1), r_end = std::hypot(e0 - c0, e1 - c1);
    if (std::abs(r_start - r_end) > kArcTolerance || r_start < 1e-9) {
      Fail(program, block_.block,
           "end point not on the arc (radius " + std::to_string(r_start) + " at the start, " +
               std::to_string(r_end) + " at the end)",
           kMsgArcGeometry);
      return false;
    }
    arc_centre_[0] = c0;
    arc_centre_[1] = c1;
    arc_radius_ = r_start;
    arc_start_angle_ = std::atan2(s1 - c1, s0 - c0);
    double sweep = std::atan2(e1 - c1, e0 - c0) - arc_start_angle_;
    if (cw) {
      while (sweep >= -1e-12) sweep -= 2 * std::numbers::pi;
    } else {
      while (sweep <= 1e-12) sweep += 2 * std::numbers::pi;
    }
    if (std::abs(std::abs(sweep) - 2 * std::numbers::pi) < 1e-9 &&
        std::hypot(e0 - s0, e1 - s1) > 1e-9)
      sweep = std::fmod(sweep, 2 * std::numbers::pi);
    arc_sweep_ = sweep;
    const double length = arc_radius_ * std::abs(sweep);
    const double accel = std::min(config_.axes[a0].acceleration, config_.axes[a1].acceleration);
    // Centripetal acceleration v^2/r must stay within the axes' limit too.
    const double v = std::min(feed, std::sqrt(accel * arc_radius_));
    profile_.max_rate = v / length;
    profile_.max_accel = accel / length;
    const double jerk = std::min(config_.axes[a0].jerk > 0 ? config_.axes[a0].jerk : HUGE_VAL,
                                 config_.axes[a1].jerk > 0 ? config_.axes[a1].jerk : HUGE_VAL);
    profile_.max_jerk = std::isfinite(jerk) ? jerk / length : 0;
  }
  active_ = true;
  segment_length_ = SegmentLength();
  if (carry_speed_ > 0 && !planning_only_) {
    // Continuing at speed from the block before (look-ahead): same path speed and
    // acceleration, from where the last cycle's remainder takes it.
    profile_.rate = carry_speed_ / segment_length_;
    profile_.accel = carry_accel_ / segment_length_;
    profile_.u = std::min(0.5, carry_leftover_ / segment_length_);
    carry_speed_ = carry_accel_ = carry_leftover_ = 0;
    ApplyU();
  }
  if (!planning_only_) LookAhead(at);
  return true;
}

double Channel::SegmentLength() const {
  // |dP/du| in axis space (mm and degrees): a line's and a helix's are constant.
  double sum = 0;
  for (size_t a = 0; a < end_.size(); ++a) {
    if (static_cast<int>(a) == arc_axes_[0] || static_cast<int>(a) == arc_axes_[1]) continue;
    sum += (end_[a] - start_[a]) * (end_[a] - start_[a]);
  }
  if (arc_axes_[0] >= 0) sum += std::pow(arc_radius_ * arc_sweep_, 2);
  return std::max(std::sqrt(sum), 1e-12);
}

void Channel::ApplyU() {
  const double u = profile_.u;
  for (size_t a = 0; a < commanded_.size(); ++a)
    commanded_[a] = start_[a] + (end_[a] - start_[a]) * u;
  if (arc_axes_[0] >= 0) {
    const double angle = arc_start_angle_ + arc_sweep_ * u;
    commanded_[arc_axes_[0]] = arc_centre_[0] + arc_radius_ * std::cos(angle);
    commanded_[arc_axes_[1]] = arc_centre_[1] + arc_radius_ * std::sin(angle);
  }
}

void Channel::LookAhead(const AmplifierTelegram& at) {
  // Blending between feed moves: read the next block, and if it continues the path (a feed
  // move with nothing to wait for, in the same frame), end this block at the speed the corner
  // allows instead of at rest.
  const auto feed_move = [](nc::Motion m) {
    return m == nc::Motion::kLinear || m == nc::Motion::kArcCw || m == nc::Motion::kArcCcw;
  };
  continuation_ready_ = false;
  if (single_block_ || state_ != ChannelState::kRunning || !feed_move(block_.motion) ||
      block_.end || homing_)
    return;
  nc::PreparedBlock next;
  if (compensating_) {
    // Under G41/G42: the next piece of the tip path, reading on until it is final.
    FillCompensated();
    if (ready_.empty()) return;
    const ContourElement& e = ready_.front();
    const auto index = static_cast<size_t>(e.tag - first_tag_);
    if (e.tag < first_tag_ || index >= ahead_.size()) return;
    next = ElementBlock(e, ahead_[index]);
    if (e.tag == last_run_tag_) {
      // A further piece of the block in work: its functions have run already.
      next.aux.clear(), next.events.clear(), next.instructions.clear();
      next.dwell_s = 0;
    }
    next.modal.compensation = 40;  // the tip path itself is not offset again
    peek_ok_ = true;
  } else {
    if (!peeked_) {
      peeked_ = true;
      peek_ok_ = interpreter_->Next(peek_);
    }
    next = peek_;
  }
  const nc::PreparedBlock& n = next;
  const nc::ModalState &m0 = block_.modal, &m1 = n.modal;
  if (!peek_ok_ || !feed_move(n.motion) || !n.aux.empty() || !n.events.empty() ||
      !n.instructions.empty() || n.dwell_s != 0 || n.homing || n.set_position || n.repos ||
      n.measuring || n.end || m1.compensation != 40 || m1.zero_offset != m0.zero_offset ||
      m1.tool_length != m0.tool_length || m1.tool != m0.tool || m1.correction != m0.correction)
    return;
  // Plan the next block from this one's end without touching the channel's state.
  const nc::PreparedBlock current = block_;
  const std::vector<double> start = start_, end = end_, commanded = commanded_;
  const double centre[2] = {arc_centre_[0], arc_centre_[1]};
  const double radius = arc_radius_, angle0 = arc_start_angle_, sweep = arc_sweep_;
  const int axes[2] = {arc_axes_[0], arc_axes_[1]};
  const PathProfile profile = profile_;
  const double length1 = segment_length_;
  // Directions: the last millionth of this block, the first of the next.
  std::vector<double> t1(end.size()), t2(end.size());
  profile_.u = 1 - 1e-6;
  ApplyU();
  for (size_t a = 0; a < t1.size(); ++a) t1[a] = end[a] - commanded_[a];
  block_ = n;
  commanded_ = end;
  planning_only_ = true;
  plan_failed_ = false;
  active_ = false;  // a next block that moves nothing is no continuation
  const bool planned = StartMotion(at) && active_ && !plan_failed_;
  planning_only_ = false;
  double v2 = 0, length2 = 0, accel2 = 0;
  if (planned) {
    length2 = segment_length_;
    v2 = profile_.max_rate * length2;
    accel2 = profile_.max_accel * length2;
    profile_.u = 1e-6;
    ApplyU();
    for (size_t a = 0; a < t2.size(); ++a) t2[a] = commanded_[a] - start_[a];
  }
  // Back to this block.
  block_ = current;
  start_ = start, end_ = end, commanded_ = commanded;
  arc_centre_[0] = centre[0], arc_centre_[1] = centre[1];
  arc_radius_ = radius, arc_start_angle_ = angle0, arc_sweep_ = sweep;
  arc_axes_[0] = axes[0], arc_axes_[1] = axes[1];
  profile_ = profile;
  segment_length_ = length1;
  active_ = true;
  if (!planned) return;
  double n1 = 0, n2 = 0, dot = 0;
  for (size_t a = 0; a < t1.size(); ++a)
    n1 += t1[a] * t1[a], n2 += t2[a] * t2[a], dot += t1[a] * t2[a];
  if (n1 <= 0 || n2 <= 0) return;
  const double cos_turn = std::clamp(dot / std::sqrt(n1 * n2), -1.0, 1.0);
  const double v1 = profile_.max_rate * length1;
  const double accel = std::min(profile_.max_accel * length1, accel2);
  // Corner speed: the centripetal acceleration of an arc kCornerDeviation from the corner
  // stays within the axes' acceleration (junction deviation); tangent joins keep the feed.
  double v = std::min(v1, v2);
  if (cos_turn < 0.99999) {
    const double sin_half = std::sqrt((1 - cos_turn) / 2);
    v = std::min(v, std::sqrt(accel * kCornerDeviation * sin_half / std::max(1e-9, 1 - sin_half)));
  }
  // The next block must be able to stop within its length (nothing beyond it is known).
  v = std::min(v, std::sqrt(accel2 * length2));
  if (v > 1e-9) profile_.end_rate = v / length1, continuation_ready_ = true;
}

void Channel::Interpolate(double dt) {
  const double u_before = profile_.u;
  profile_.Advance(dt, state_ == ChannelState::kHold ? 0.0 : override_);
  ApplyU();
  if (profile_.done()) {
    commanded_ = end_;  // exactly the programmed point
    active_ = false;
    // Ended at speed (look-ahead): the next block takes the speed over at once, with what
    // this cycle had left of its distance.
    if (profile_.rate > 0 && continuation_ready_) {
      carry_speed_ = profile_.rate * segment_length_;
      carry_accel_ = profile_.accel * segment_length_;
      carry_leftover_ = std::max(0.0, carry_speed_ * dt - (1 - u_before) * segment_length_);
    }
  }
}

}  // namespace vmt::control::channel
