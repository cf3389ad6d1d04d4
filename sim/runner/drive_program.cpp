#include "sim/runner/drive_program.hpp"

#include <algorithm>
#include <cmath>

#include "control/channel/channel.hpp"

namespace vmt::sim {

using control::DriveMode;

double TrapezoidProfile::Duration() const {
  const double d = std::abs(end - start);
  if (d == 0) return 0;
  if (d < speed * speed / accel) return 2 * std::sqrt(d / accel);
  return d / speed + speed / accel;
}

double TrapezoidProfile::At(double t_s) const {
  const double d = std::abs(end - start);
  const double sign = end >= start ? 1 : -1;
  const double t = t_s - t0_s;
  const double total = Duration();
  if (t <= 0) return start;
  if (t >= total) return end;
  const double peak = std::min(speed, std::sqrt(d * accel));
  const double t_acc = peak / accel;
  double s;
  if (t < t_acc)
    s = 0.5 * accel * t * t;
  else if (t < total - t_acc)
    s = 0.5 * peak * t_acc + peak * (t - t_acc);
  else
    s = d - 0.5 * accel * (total - t) * (total - t);
  return start + sign * s;
}

double SignalNumber(const control::gateway::SignalImage& image, int id) {
  using control::gateway::SignalType;
  switch (image.table()[id].type) {
    case SignalType::kBool:
      return image.Bool(id) ? 1 : 0;
    case SignalType::kReal:
    case SignalType::kLreal:
      return image.Real(id);
    case SignalType::kString:
      return 0;
    default:
      return static_cast<double>(image.Int(id));
  }
}

void SetSignalNumber(control::gateway::SignalImage& image, int id, double value) {
  using control::gateway::SignalType;
  switch (image.table()[id].type) {
    case SignalType::kBool:
      image.SetBool(id, value != 0);
      return;
    case SignalType::kReal:
    case SignalType::kLreal:
      image.SetReal(id, value);
      return;
    case SignalType::kString:
      return;
    default:
      image.SetInt(id, std::llround(value));
  }
}

bool Holds(const Condition& c, const control::AmplifierTelegram& at,
           const std::vector<ClutchState>& clutches, const control::channel::Channel* channel,
           const control::gateway::SignalImage* image) {
  using namespace control::drive_status;
  switch (c.kind) {
    case Condition::Kind::kSignal:
      return image && SignalNumber(*image, c.index) == c.signal_value;
    case Condition::Kind::kInput:
      return (at.inputs[c.index] != 0) == c.value;
    case Condition::Kind::kInPosition:
      return ((at.feedback[c.index].status & kInPosition) != 0) == c.value;
    case Condition::Kind::kAtSpeed:
      return ((at.feedback[c.index].status & kAtSpeed) != 0) == c.value;
    case Condition::Kind::kStandstill:
      return ((at.feedback[c.index].status & kStandstill) != 0) == c.value;
    case Condition::Kind::kClutch:
      return clutches[c.index] == c.clutch;
    case Condition::Kind::kNc:
      return channel && channel->state() == c.nc;
  }
  return false;
}

DriveProgram::DriveProgram(const Scene& scene, const control::AmplifierTelegram& feedback,
                           control::channel::Channel* channel, control::gateway::SignalImage* image)
    : scene_(&scene), channel_(channel), image_(image) {
  const MachineModel& m = *scene.model;
  setpoints_.resize(m.drives.size());
  profiles_.resize(m.drives.size());
  profiling_.assign(m.drives.size(), false);
  outputs_.assign(m.io.size(), 0);
  faults_.sensor.assign(m.io.size(), -1);
  faults_.valve.assign(m.io.size(), -1);
  faults_.drive.assign(m.drives.size(), false);
  for (size_t d = 0; d < m.drives.size(); ++d) {
    if (m.drives[d].spindle)
      setpoints_[d] = {DriveMode::kVelocity, 0, 0};
    else
      setpoints_[d] = {DriveMode::kPosition, feedback.feedback[d].position, 0};
  }
}

namespace {
uint8_t ParameterSet(const TimelineStep& step) { return static_cast<uint8_t>(step.parameter_set); }
}  // namespace

bool DriveProgram::Execute(const TimelineStep& step, double t_s,
                           const control::AmplifierTelegram& at,
                           const std::vector<ClutchState>& clutches,
                           std::vector<ProgramEvent>& events) {
  const MachineModel& m = *scene_->model;
  using Kind = TimelineStep::Kind;
  switch (step.kind) {
    case Kind::kMove: {
      const DriveParams& p = m.drives[step.drive];
      const double unit = p.info.kind == control::AxisKind::kLinear ? kMmPerM : kDegPerRad;
      // The profile keeps to the limits of the set the move names (set 0's if the drive lacks
      // it: the drive reports that itself).
      const size_t set = static_cast<size_t>(step.parameter_set);
      const DriveParameterSet& g = set < p.parameter_sets.size() ? p.parameter_sets[set] : p;
      // Start where the command is, or where the axis is if it was not position controlled.
      const double from = setpoints_[step.drive].mode == DriveMode::kPosition
                              ? setpoints_[step.drive].value
                              : at.feedback[step.drive].position;
      profiles_[step.drive] = {from, step.target, std::min(step.feed, g.velocity_limit * unit),
                               g.acceleration_limit * unit, t_s};
      profiling_[step.drive] = true;
      setpoints_[step.drive] = {DriveMode::kPosition, from, ParameterSet(step)};
      return true;
    }
    case Kind::kSpeed:
      profiling_[step.drive] = false;
      setpoints_[step.drive] = {DriveMode::kVelocity, step.target, ParameterSet(step)};
      return true;
    case Kind::kOrient:
      profiling_[step.drive] = false;
      setpoints_[step.drive] = {DriveMode::kPosition, step.target, ParameterSet(step)};
      return true;
    case Kind::kOff:
      profiling_[step.drive] = false;
      setpoints_[step.drive] = {DriveMode::kOff, 0, 0};
      return true;
    case Kind::kOutput:
      outputs_[step.io] = step.level;
      return true;
    case Kind::kNcStart:
      if (channel_) channel_->Start();
      return true;
    case Kind::kNcStop:
      if (channel_) channel_->Stop();
      return true;
    case Kind::kNcReset:
      if (channel_) channel_->Reset();
      return true;
    case Kind::kNcOverride:
      if (channel_) channel_->SetFeedOverride(step.target);
      return true;
    case Kind::kNcSingleBlock:
      if (channel_) channel_->SetSingleBlock(step.level);
      return true;
    case Kind::kNcOptionalStop:
      if (channel_) channel_->SetOptionalStop(step.level);
      return true;
    case Kind::kNcMode:
      if (channel_ && !channel_->SetMode(static_cast<control::channel::ChannelMode>(step.code))) {
        failures_.push_back(step.text + ": refused while the program runs");
        events.push_back({t_s, "refused", step.text});
      }
      return true;
    case Kind::kNcJogIncrement:
      if (channel_) channel_->SetJogIncrement(step.target);
      return true;
    case Kind::kNcJogMode:
      if (channel_) channel_->SetJogMode(step.code);
      return true;
    case Kind::kNcMdi:
      if (channel_ && !channel_->Mdi(step.mdi)) events.push_back({t_s, "refused", step.text});
      return true;
    case Kind::kNcSelect:
      if (channel_ && !channel_->SelectProgram(static_cast<size_t>(step.code))) {
        failures_.push_back(step.text + ": refused while a program is active");
        events.push_back({t_s, "refused", step.text});
      }
      return true;
    case Kind::kNcReverse:
      if (channel_ && !channel_->Reverse()) {
        failures_.push_back(step.text + ": refused (" +
                            (channel_->error().empty() ? "not interrupted" : channel_->error()) +
                            ")");
        events.push_back({t_s, "refused", step.text});
      }
      return true;
    case Kind::kNcZeroOffset:
    case Kind::kNcToolLength: {
      const bool done =
          !channel_ ||
          (step.kind == Kind::kNcZeroOffset
               ? channel_->SetZeroOffset(step.code, step.axis, step.target)
               : channel_->SetToolLength(step.code, step.edge, step.axis, step.target));
      if (!done) {
        failures_.push_back(step.text + ": the tool list has no such edge");
        events.push_back({t_s, "refused", step.text});
      }
      return true;
    }
    case Kind::kHandwheel:
      if (channel_ && step.fictive >= 0)
        channel_->HandwheelFictive(step.fictive, step.code);
      else if (channel_)
        channel_->Handwheel(step.axis, step.code);
      return true;
    case Kind::kSignal:
      if (image_) SetSignalNumber(*image_, step.signal, step.target);
      return true;
    case Kind::kFault: {
      using F = TimelineStep::Fault;
      faults_.any = true;
      if (step.fault == F::kSensorStuck) faults_.sensor[step.io] = step.level;
      if (step.fault == F::kValveStuck) faults_.valve[step.io] = step.level;
      if (step.fault == F::kDrive) faults_.drive[step.drive] = true;
      if (step.fault == F::kPlcOverrun) faults_.plc_missed_scans = step.code;
      if (step.fault == F::kPlcClientGone) ++faults_.plc_client_gone;
      if (step.fault == F::kClear && step.io >= 0)
        faults_.sensor[step.io] = faults_.valve[step.io] = -1;
      if (step.fault == F::kClear && step.drive >= 0) faults_.drive[step.drive] = false;
      return true;
    }
    case Kind::kJog:
      // The key goes down when the step begins and comes up after `hold`.
      if (!channel_) return true;
      if (step.fictive >= 0) {
        if (t_s == step_since_s_) channel_->JogFictive(step.fictive, step.direction);
        if (t_s - step_since_s_ < step.wait_s - 1e-9) return false;
        channel_->JogFictive(step.fictive, 0);
        return true;
      }
      if (step.jog_to && t_s == step_since_s_) {
        // The distance from the NC's position of the axis (the drive's actual one lags it by
        // the following error; before the NC has taken its axes over, the actual one is all
        // there is); none (already there) presses no key, and an increment of 0 would be
        // continuous jogging.
        const double from = channel_->holds_positions()
                                ? channel_->position(static_cast<size_t>(step.axis))
                                : at.feedback[step.drive].position;
        const double to_go = step.target - from;
        if (std::abs(to_go) < 5e-4) return true;
        channel_->SetJogIncrement(std::abs(to_go));
        channel_->Jog(step.axis, to_go > 0 ? 1 : -1);
      } else if (t_s == step_since_s_) {
        channel_->Jog(step.axis, step.direction);
      }
      if (t_s - step_since_s_ < step.wait_s - 1e-9) return false;
      channel_->Jog(step.axis, 0);
      return true;
    case Kind::kWait:
      return t_s - step_since_s_ >= step.wait_s - 1e-9;
    case Kind::kWaitUntil: {
      // The feedback in hand is one tick old: it cannot yet show the effect of commands given in
      // this tick (an "at speed" of the old setpoint), so a wait never ends in its first tick.
      if (t_s == step_since_s_) return false;
      // "In position" means the move is done, not that the axis has yet to start.
      const bool moving =
          step.until.kind == Condition::Kind::kInPosition && profiling_[step.until.index] &&
          t_s < profiles_[step.until.index].t0_s + profiles_[step.until.index].Duration();
      if (!moving && Holds(step.until, at, clutches, channel_, image_)) return true;
      if (t_s - step_since_s_ >= step.timeout_s) {
        failures_.push_back(step.text + " timed out after " + std::to_string(step.timeout_s) +
                            " s");
        events.push_back({t_s, "timeout", step.text});
        return true;  // go on: the rest of the run is still worth its trace
      }
      return false;
    }
  }
  return true;
}

void DriveProgram::Tick(double t_s, const control::AmplifierTelegram& at,
                        const std::vector<ClutchState>& clutches, control::MasterTelegram& mdt,
                        std::vector<ProgramEvent>& events) {
  while (next_ < scene_->timeline.size()) {
    const TimelineStep& step = scene_->timeline[next_];
    if (t_s < step.not_before_s - 1e-9) break;
    if (step_since_s_ < 0) {
      step_since_s_ = t_s;
      events.push_back({t_s, "step", step.text});
    }
    if (!Execute(step, t_s, at, clutches, events)) break;
    ++next_;
    step_since_s_ = -1;
  }
  for (size_t d = 0; d < setpoints_.size(); ++d)
    if (profiling_[d]) setpoints_[d].value = profiles_[d].At(t_s);
  mdt.setpoints = setpoints_;
  mdt.outputs = outputs_;
}

}  // namespace vmt::sim
