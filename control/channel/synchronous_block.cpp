// Spindle-synchronous blocks: G33 thread cutting, G63 and G64 tapping. A block of these runs to
// its end once started: a thread cannot stop in its groove, so feed hold (and the feed
// override) take effect after it.
#include "control/channel/synchronous_block.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "control/channel/channel_messages.hpp"

namespace vmt::control::channel {
namespace {

MotionError Faster(const char* g, double speed, double max_speed) {
  char text[160];
  std::snprintf(text, sizeof text, "%s at %.3f mm/s is faster than the axes' %.3f mm/s", g, speed,
                max_speed);
  return {text, kMsgLeadTooFast};
}

}  // namespace

SynchronousBlock::SynchronousBlock(std::vector<axes::AxisParameters> axes, int spindle_drive,
                                   axes::AxisParameters spindle)
    : axes_(std::move(axes)), spindle_drive_(spindle_drive), spindle_(std::move(spindle)) {}

std::optional<MotionError> SynchronousBlock::Start(const SynchronousContext& c,
                                                   const std::vector<double>& translation,
                                                   uint64_t follow_up, const AmplifierTelegram& at,
                                                   bool& moves) {
  s_ = Synchronous{};
  moves = false;
  const nc::PreparedBlock& b = c.block;
  const char* g = b.motion == nc::Motion::kThread    ? "G33"
                  : b.motion == nc::Motion::kTapping ? "G63"
                                                     : "G64";
  if (b.modal.compensation != nc::Compensation::kOff)
    return MotionError{std::string(g) + " with tool nose radius compensation: program G40 first",
                       kMsgNotAvailable};
  if (spindle_drive_ < 0)
    return MotionError{std::string(g) + " needs a main spindle", kMsgSpindleStill};
  // G33 and G63 need the spindle turning (M3/M4 with S); G64 takes the spindle into position
  // control and needs the direction and speed M3/M4 and S give it.
  DriveSetpoint& command = c.spindle.command;
  const bool rigid = b.motion == nc::Motion::kRigidTapping;
  const bool turning =
      rigid ? (b.modal.spindle == 3 || b.modal.spindle == 4) && b.modal.spindle_speed > 0
            : command.mode == DriveMode::kVelocity && command.value != 0;
  if (!turning)
    return MotionError{
        std::string("spindle not turning for ") + g + ": program M3 or M4 with S first",
        kMsgSpindleStill};
  if (auto error = PlanSynchronousPath(b, c.commanded, translation, axes_, follow_up, s_.path))
    return error;
  c.profile = PathProfile{};
  if (!s_.path.line.moves) return std::nullopt;
  moves = true;
  c.motion = s_.path.line;
  const double k = s_.path.mm_per_deg;
  if (b.motion == nc::Motion::kThread) {
    s_.phase = SyncPhase::kWaitForSpeed;
    s_.spindle_deg = s_.spindle_last_deg = at.feedback[spindle_drive_].position;
  } else if (b.motion == nc::Motion::kTapping) {
    // lead x S along the dominant axis, whatever the spindle actually does.
    const double speed = k * std::abs(b.modal.spindle_speed) * 6;
    if (speed > s_.path.max_speed * (1 + 1e-9)) return Faster("G63", speed, s_.path.max_speed);
    c.profile.max_rate = speed / c.motion.length;
    c.profile.max_accel = s_.path.max_accel / c.motion.length;
    c.profile.max_jerk = s_.path.max_jerk / c.motion.length;
    s_.phase = SyncPhase::kRunning;
  } else {
    s_.direction = b.modal.spindle == 4 ? -1 : 1;
    RigidTappingLimits(s_.path, b.modal.spindle_speed, spindle_.rapid_per_s, spindle_.acceleration,
                       c.profile);
    // lead x S, within the axes' and the spindle's limits; the spindle override may raise the
    // speed only as far as they allow.
    const double limit = c.profile.max_rate;
    const double programmed = k * std::abs(b.modal.spindle_speed) * 6 / c.motion.length;
    c.profile.max_rate = std::min(limit, programmed);
    s_.max_override = limit / c.profile.max_rate;
    s_.phase = SyncPhase::kStopSpindle;
    command.velocity_feedforward = 0;
    if (!(command.mode == DriveMode::kPosition && command.interpolated)) {
      command.mode = DriveMode::kVelocity;  // brake first; Cycle takes it over
      command.value = 0;
    }
  }
  return std::nullopt;
}

std::optional<MotionError> SynchronousBlock::WaitForSpeed(const SynchronousContext& c, double w,
                                                          double dt, double spindle_setpoint) {
  // The thread starts once the spindle runs at its commanded speed (override included).
  const DriveSetpoint& command = c.spindle.command;
  if (command.mode != DriveMode::kVelocity || command.value == 0)
    return MotionError{"spindle not turning for G33", kMsgSpindleStill};
  const double target = spindle_setpoint;
  if (target == 0 || std::abs(w - target) > std::max(0.01 * std::abs(target), 1.0))
    return std::nullopt;
  const double k = s_.path.mm_per_deg;
  const double length = c.motion.length;
  if (k * std::abs(w) > s_.path.max_speed) return Faster("G33", k * std::abs(w), s_.path.max_speed);
  s_.direction = w < 0 ? -1 : 1;
  s_.law.mm_per_deg = k;
  s_.law.length = length;
  s_.law.ramp_in_deg = ThreadLaw::RampDeg(k, w, s_.path.max_accel);
  if (2 * k * s_.law.ramp_in_deg > length) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "G33 thread %.3f mm is shorter than its ramp-in and run-out (%.3f mm) at "
                  "this spindle speed",
                  length, 2 * k * s_.law.ramp_in_deg);
    return MotionError{text, kMsgLeadTooFast};
  }
  // Dead time: the axes reach this cycle's command one NC cycle later (fine interpolation),
  // where the spindle will be w dt further on.
  s_.zero_mark_deg = ThreadZeroMark(s_.spindle_deg + w * dt, s_.direction, s_.law.ramp_in_deg);
  s_.phase = SyncPhase::kRunning;
  return std::nullopt;
}

std::optional<MotionError> SynchronousBlock::Cycle(const SynchronousContext& c,
                                                   const AmplifierTelegram& at, double dt,
                                                   double spindle_setpoint) {
  const DriveFeedback& spindle = at.feedback[spindle_drive_];
  const double k = s_.path.mm_per_deg;
  const double length = c.motion.length;
  auto finish = [&] {
    c.commanded = c.motion.end;  // exactly the programmed point
    s_.phase = SyncPhase::kNone;
  };
  if (c.block.motion == nc::Motion::kThread) {
    // The spindle's actual position, unwrapped (a modulo encoder reports 0..360).
    double step = spindle.position - s_.spindle_last_deg;
    step -= 360 * std::round(step / 360);
    s_.spindle_deg += step;
    s_.spindle_last_deg = spindle.position;
    const double w = spindle.velocity;
    if (s_.phase == SyncPhase::kWaitForSpeed) {
      if (auto error = WaitForSpeed(c, w, dt, spindle_setpoint)) return error;
      if (s_.phase == SyncPhase::kWaitForSpeed) return std::nullopt;
    }
    const double psi = s_.direction * (s_.spindle_deg + w * dt - s_.zero_mark_deg);
    if (!s_.law.running_out() &&
        psi >= s_.law.LawEndDeg() - ThreadLaw::RampDeg(k, w, s_.path.max_accel))
      s_.law.BeginRunOut(std::max(psi, s_.law.ramp_in_deg));
    const double s = s_.law.PathAt(psi);
    c.profile.u = s / length;
    c.motion.PointAt(c.profile.u, c.commanded);
    if (s_.law.running_out() && psi >= s_.law.run_out_end_deg) finish();
    return std::nullopt;
  }
  if (c.block.motion == nc::Motion::kTapping) {
    // Feed override held at 100 %, feed hold after the block.
    c.profile.Advance(dt, 1.0);
    c.motion.PointAt(c.profile.u, c.commanded);
    if (c.profile.done()) finish();
    return std::nullopt;
  }
  // G64: brake a turning spindle, then position control where it stands.
  DriveSetpoint& command = c.spindle.command;
  if (s_.phase == SyncPhase::kStopSpindle) {
    if (command.mode == DriveMode::kVelocity) {
      const bool still =
          (spindle.status & drive_status::kStandstill) || std::abs(spindle.velocity) < 0.1;
      if (!still) return std::nullopt;
      command = {DriveMode::kPosition, spindle.position, 0};
      command.interpolated = true;
    }
    s_.spindle_start_deg = c.spindle.previous_deg = command.value;
    s_.phase = SyncPhase::kRunning;
  }
  c.profile.Advance(dt, std::min(c.spindle.override, s_.max_override));
  c.motion.PointAt(c.profile.u, c.commanded);
  const double u = std::min(c.profile.u, 1.0);
  command.value = s_.spindle_start_deg + s_.direction * u * length / k;
  command.velocity_feedforward = s_.direction * c.profile.rate * length / k;
  if (c.profile.done()) {
    command.velocity_feedforward = 0;
    finish();  // the spindle stands in position control at its end position
  }
  return std::nullopt;
}

}  // namespace vmt::control::channel
