#include "control/axes/headstock_changeover.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vmt::control::axes {
namespace {

constexpr double kDegPerRad = 180 / 3.14159265358979323846;

// Angle difference wrapped into (-180, 180].
double WrapDeg(double a) {
  a = std::fmod(a, 360.0);
  if (a <= -180) a += 360;
  if (a > 180) a -= 360;
  return a;
}

bool Standstill(const AmplifierTelegram& at, int drive) {
  return drive < 0 || (at.feedback[drive].status & drive_status::kStandstill);
}

}  // namespace

const char* ToString(HeadstockMode mode) {
  switch (mode) {
    case HeadstockMode::kNone:
      return "none";
    case HeadstockMode::kSpindle:
      return "spindle";
    case HeadstockMode::kRotary:
      return "rotary";
  }
  return "?";
}

void HeadstockChangeover::TakeModeFromPlc(const HeadstockPlc& plc) {
  phase_ = ChangeoverPhase::kNone;
  spindle_fn_ = rotary_fn_ = {};
  error_.clear();
  mode_ = plc.rotmod_q == plc.spmod_q ? HeadstockMode::kNone
          : plc.rotmod_q              ? HeadstockMode::kRotary
                                      : HeadstockMode::kSpindle;
  take_over_rotary_ = mode_ == HeadstockMode::kRotary;
  parameter_set_ = SetOf(mode_);  // 2.3: the related drive parameter record is made active
}

void HeadstockChangeover::Request(HeadstockMode target) {
  if (target == HeadstockMode::kNone || this->target() == target) return;
  Enter(target);
}

void HeadstockChangeover::Enter(HeadstockMode target) {
  if (!busy()) before_ = mode_;
  target_ = target;
  mode_ = HeadstockMode::kNone;
  phase_ = ChangeoverPhase::kInternal;
  spindle_fn_ = rotary_fn_ = {};
}

void HeadstockChangeover::Abandon() {
  if (!busy()) return;
  if (before_ == HeadstockMode::kNone) {
    phase_ = ChangeoverPhase::kNone;
    spindle_fn_ = rotary_fn_ = {};
    return;
  }
  Enter(before_);
}

bool HeadstockChangeover::Cycle(const HeadstockPlc& plc, const AmplifierTelegram& at,
                                double dt_s) {
  spindle_ready_ = plc.spindle_ready;
  rotary_ready_ = plc.rotary_ready;
  switch (phase_) {
    case ChangeoverPhase::kNone:
      // 4.1: the acknowledgement is applied for as long as the mode is selected.
      if (mode_ == HeadstockMode::kRotary && !plc.rotmod_q) {
        error_ = "ROTMOD_Q removed in rotary axis mode";
        return false;
      }
      if (mode_ == HeadstockMode::kSpindle && !plc.spmod_q) {
        error_ = "SPMOD_Q removed in spindle mode";
        return false;
      }
      return true;
    case ChangeoverPhase::kInternal:
      // (2): decelerate in speed control with the set in use, then at standstill activate the
      // parameter set of the new mode.
      spindle_fn_.setpoint = rotary_fn_.setpoint = {DriveMode::kVelocity, 0, 0};
      // 2.3 Immediate Stop: the internal sequence stops and its commands stay pending, so no
      // ROTMOD / SPMOD goes out to the PLC while the stop is in force.
      if (!plc.stop && Standstill(at, config_.spindle_drive) &&
          Standstill(at, config_.rotary_drive)) {
        phase_ = ChangeoverPhase::kExternal;
        external_s_ = 0;
        parameter_set_ = SetOf(target_);
      }
      return true;
    case ChangeoverPhase::kExternal: {
      external_s_ += dt_s;
      spindle_axd_ = plc.spindle_axd;
      rotary_axd_ = plc.rotary_axd;
      RunFunction(spindle_fn_, plc.spindle_axd, at.feedback[config_.spindle_drive], plc.stop,
                  dt_s);
      if (config_.separate_servo())
        RunFunction(rotary_fn_, plc.rotary_axd, at.feedback[config_.rotary_drive], plc.stop,
                    dt_s);
      // (4): the PLC reports the new mode, and only that one.
      const bool done = target_ == HeadstockMode::kRotary ? plc.rotmod_q && !plc.spmod_q
                                                          : plc.spmod_q && !plc.rotmod_q;
      if (done) {
        // (5): position / speed control changeover.
        mode_ = target_;
        phase_ = ChangeoverPhase::kNone;
        spindle_fn_ = rotary_fn_ = {};
        take_over_rotary_ = mode_ == HeadstockMode::kRotary;
      }
      return true;
    }
  }
  return true;
}

std::string HeadstockChangeover::Stalled() const {
  if (phase_ != ChangeoverPhase::kExternal || external_s_ < config_.stall_message_s) return "";
  const bool rotary = target_ == HeadstockMode::kRotary;
  char head[160];
  std::snprintf(head, sizeof head, "changeover to %s mode: no %s from the PLC within %.1f s",
                rotary ? "rotary axis" : "spindle", rotary ? "ROTMOD_Q" : "SPMOD_Q",
                config_.stall_message_s);
  std::string why;
  auto check = [&why](const char* drive, const std::array<int64_t, 4>& axd) {
    const int64_t request = axd[kAxdFunction] & 0xff;
    if (request & axd::kSpeedSpec) {
      if (axd[kAxdSpeed] == 0)
        why +=
            std::string("; the ") + drive + " drive's speed specification has speed 0 (AXD 65013)";
      else if (axd[kAxdAccel] == 0)
        why += std::string("; the ") + drive +
               " drive's speed specification has acceleration 0 (AXD 65014)";
    }
    return request != 0;
  };
  bool any = check("spindle", spindle_axd_);
  if (config_.separate_servo()) any = check("rotary", rotary_axd_) || any;
  if (!any && config_.separate_servo())
    why +=
        "; no AXD motion function is requested (65012 = 0): a clutch whose dogs meet tooth "
        "on tooth does not mesh unless a drive turns";
  return head + why;
}

// The AXD motion functions (2.2): hunting, positioning, speed specification, each acknowledged
// in the upper byte of 65012 while it runs (positioning and speed: once reached). An immediate
// stop halts them (2.3: "It also stops the motion functions").
void HeadstockChangeover::RunFunction(Function& f, const std::array<int64_t, 4>& axd,
                                      const DriveFeedback& fb, bool stop, double dt_s) const {
  const int64_t request = axd[kAxdFunction] & 0xff;
  f.word = request;
  f.setpoint = {DriveMode::kVelocity, 0, 0};
  if (stop) {
    f.speed = 0;
    return;
  }
  if (request & axd::kHunting) {
    const double half = config_.hunting_half_period_s;
    const auto k = static_cast<int64_t>(std::floor((f.hunting_s + half / 2) / half));
    f.setpoint.value = (k % 2 == 0 ? 1 : -1) * config_.hunting_speed;
    f.hunting_s += dt_s;
    f.word |= axd::kHuntingAck;
  } else if (request & axd::kPositioning) {
    const double angle = static_cast<double>(axd[kAxdAngle]) * 1e-4;
    const double error = WrapDeg(angle - fb.position);
    const double v = std::clamp(error * 10, -config_.positioning_speed, config_.positioning_speed);
    f.setpoint.value = v;
    if (std::abs(error) < config_.positioning_window) f.word |= axd::kPositioningAck;
  } else if (request & axd::kSpeedSpec) {
    const double rpm = std::clamp(static_cast<double>(axd[kAxdSpeed]) * 1e-4,
                                  -axd::kMaxSpeedRpm, axd::kMaxSpeedRpm);
    const double target = rpm * 6;
    const double accel = static_cast<double>(axd[kAxdAccel]) * kDegPerRad;
    // The last step lands exactly on the target: speed + (target - speed) need not equal
    // target in floating point, and the acknowledgement below compares for equality.
    const double step = accel > 0 ? accel * dt_s : HUGE_VAL;
    if (std::abs(target - f.speed) <= step)
      f.speed = target;
    else
      f.speed += std::copysign(step, target - f.speed);
    f.setpoint.value = f.speed;
    if (f.speed == target) f.word |= axd::kSpeedSpecAck;
  } else {
    f.speed = 0;
  }
}

void HeadstockChangeover::WriteSetpoints(const DriveSetpoint& spindle,
                                         const DriveSetpoint& rotary, MasterTelegram& mdt) const {
  const DriveSetpoint off{DriveMode::kOff, 0, 0};
  const DriveSetpoint still{DriveMode::kVelocity, 0, 0};
  if (!config_.separate_servo()) {
    // Section 2: one drive, speed control with set 0 or position control with the rotary set.
    DriveSetpoint sp = still;
    if (busy())
      sp = spindle_fn_.setpoint;
    else if (mode_ == HeadstockMode::kSpindle)
      sp = spindle;
    else if (mode_ == HeadstockMode::kRotary)
      sp = rotary;
    sp.parameter_set = parameter_set_;
    mdt.setpoints[config_.spindle_drive] = spindle_ready_ ? sp : off;
    return;
  }
  // Section 3: two drives; the PLC switches their enables (4.3).
  DriveSetpoint s = still, r = rotary;
  if (busy()) {
    s = spindle_fn_.setpoint;
    r = rotary_fn_.setpoint;
  } else if (mode_ == HeadstockMode::kSpindle) {
    s = spindle;
  }
  mdt.setpoints[config_.spindle_drive] = spindle_ready_ ? s : off;
  mdt.setpoints[config_.rotary_drive] = rotary_ready_ ? r : off;
}

}  // namespace vmt::control::axes
