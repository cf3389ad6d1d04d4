#include "sim/backend/drive_controller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vmt::sim {
namespace {

double Unit(const DriveParams& p) {
  return p.info.kind == control::AxisKind::kLinear ? kMmPerM : kDegPerRad;
}

// Angle difference wrapped into (-pi, pi].
double Wrap(double a) {
  const double two_pi = 2 * std::numbers::pi;
  a = std::fmod(a, two_pi);
  if (a <= -std::numbers::pi) a += two_pi;
  if (a > std::numbers::pi) a -= two_pi;
  return a;
}

}  // namespace

control::DriveSetpoint ToSi(const DriveParams& p, const control::DriveSetpoint& sp) {
  control::DriveSetpoint si = sp;
  if (sp.mode != control::DriveMode::kTorque) si.value = sp.value / Unit(p);
  si.velocity_feedforward = sp.velocity_feedforward / Unit(p);
  return si;
}

double DriveController::VelocityReference(const control::DriveSetpoint& sp, double position,
                                          double velocity, double dt_s) {
  using control::DriveMode;
  const DriveMode previous = mode_;
  mode_ = sp.mode;
  command_ = sp.value;
  if (mode_ != previous) {
    // Bumpless change of mode: ramps start from where the axis is.
    ramp_velocity_ = velocity;
    if (previous == DriveMode::kOff) integral_ = 0;
    orient_command_ = std::nan("");
  }
  switch (mode_) {
    case DriveMode::kOff:
    case DriveMode::kTorque:
      ramp_velocity_ = velocity;
      return velocity;
    case DriveMode::kVelocity: {
      const double target = std::clamp(sp.value, -p_->velocity_limit, p_->velocity_limit);
      const double step = p_->acceleration_limit * dt_s;
      ramp_velocity_ += std::clamp(target - ramp_velocity_, -step, step);
      return ramp_velocity_;
    }
    case DriveMode::kPosition:
      break;
  }
  if (!p_->spindle) {
    // Servo: proportional position loop; the master interpolates, the drive only follows.
    // With feed-forward (G06) the loop only corrects what the feed-forward leaves.
    const double v = p_->kv_per_s * (sp.value - position) + sp.velocity_feedforward;
    return std::clamp(v, -p_->velocity_limit, p_->velocity_limit);
  }
  // Spindle orientation (M19): the command is an angle modulo one turn; the drive picks the
  // shortest way once per command and brakes so that it arrives without overshoot.
  if (!(sp.value == orient_command_)) {
    orient_command_ = sp.value;
    orient_target_ = position + Wrap(sp.value - position);
  }
  const double error = orient_target_ - position;
  const double braking = std::sqrt(2 * p_->acceleration_limit * std::abs(error));
  const double limit = std::min(p_->positioning_speed, braking);
  const double v = std::clamp(p_->kv_per_s * error, -limit, limit);
  const double step = p_->acceleration_limit * dt_s;
  ramp_velocity_ += std::clamp(v - ramp_velocity_, -step, step);
  return ramp_velocity_;
}

double DriveController::Torque(double velocity_reference, double velocity, double dt_s) {
  using control::DriveMode;
  if (mode_ == DriveMode::kOff) {
    saturated_ = false;
    return 0;
  }
  if (mode_ == DriveMode::kTorque) {
    const double t = std::clamp(command_, -p_->torque_limit, p_->torque_limit);
    saturated_ = t != command_;
    return t;
  }
  const double error = velocity_reference - velocity;
  const double proportional = p_->velocity_kp * error;
  const double candidate = integral_ + proportional * dt_s / p_->velocity_ti_s;
  const double unclamped = proportional + candidate;
  const double torque = std::clamp(unclamped, -p_->torque_limit, p_->torque_limit);
  saturated_ = torque != unclamped;
  // Anti-windup: integrate only while the output is not pushing further into the limit.
  if (!saturated_ || (unclamped > 0) != (error > 0)) integral_ = candidate;
  return torque;
}

control::DriveFeedback DriveController::Feedback(double position, double velocity,
                                                 double torque) const {
  using namespace control::drive_status;
  const double unit = Unit(*p_);
  const double res = p_->encoder_resolution;
  // floor(x + 0.5), not round(): the same for an encoder, and no libm call on the hot path.
  const double quantised = std::floor(position * counts_per_unit_ + 0.5) * res;
  control::DriveFeedback fb;
  fb.position = quantised * unit;
  fb.velocity = velocity * unit;
  fb.torque = torque;
  fb.status = kReady;
  if (mode_ != control::DriveMode::kOff) fb.status |= kEnabled;
  if (std::abs(velocity) < p_->standstill_window) fb.status |= kStandstill;
  if (saturated_) fb.status |= kTorqueLimit;
  if (mode_ == control::DriveMode::kPosition) {
    const double target = p_->spindle ? orient_target_ : command_;
    fb.following_error = (target - quantised) * unit;
    if (std::abs(target - quantised) < p_->in_position_window) fb.status |= kInPosition;
    if (std::abs(target - quantised) > p_->following_error_limit) fb.status |= kFollowingError;
  }
  if (mode_ == control::DriveMode::kVelocity) {
    const double target = std::clamp(command_, -p_->velocity_limit, p_->velocity_limit);
    if (ramp_velocity_ == target && std::abs(velocity - target) < p_->standstill_window)
      fb.status |= kAtSpeed;
  }
  return fb;
}

}  // namespace vmt::sim
