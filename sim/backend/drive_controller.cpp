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

// A servo's position error: with modulo scaling the shorter way round.
double PositionError(const DriveParams& p, double command, double position) {
  const double e = command - position;
  if (p.modulo <= 0) return e;
  // Within one modulo fmod would return e itself (it is exact): spare its libm call, which a
  // rotary axis would pay twice per tick.
  double w = std::abs(e) < p.modulo ? e : std::fmod(e, p.modulo);
  if (w <= -p.modulo / 2) w += p.modulo;
  if (w > p.modulo / 2) w -= p.modulo;
  return w;
}

}  // namespace

control::DriveSetpoint ToSi(const DriveParams& p, const control::DriveSetpoint& sp) {
  control::DriveSetpoint si = sp;
  if (sp.mode != control::DriveMode::kTorque) si.value = sp.value / Unit(p);
  // Without feed-forward (G05, most of the time) 0 / unit is the 0 itself: no division.
  if (sp.velocity_feedforward != 0) si.velocity_feedforward = sp.velocity_feedforward / Unit(p);
  return si;
}

void DriveController::SelectParameterSet(uint8_t number) {
  set_number_ = number;
  set_ = &p_->parameter_sets[number];
  // The integral is torque: it carries over unchanged (bumpless), but never beyond the new limit.
  integral_ = std::clamp(integral_, -set_->torque_limit, set_->torque_limit);
  orient_command_ = std::nan("");  // an orientation in progress re-plans with the new set
}

double DriveController::VelocityReference(const control::DriveSetpoint& sp, double position,
                                          double velocity, double dt_s) {
  using control::DriveMode;
  using namespace control::drive_status;
  // The set first: the overspeed threshold is the active set's velocity limit.
  const bool set_exists = sp.parameter_set < p_->parameter_sets.size();
  if (!set_exists)
    faults_ |= kParameterSetError;
  else if (sp.parameter_set != set_number_)
    SelectParameterSet(sp.parameter_set);
  const bool overspeed = std::abs(velocity) > kOverspeedFactor * set_->velocity_limit;
  if (overspeed) faults_ |= kOverspeed;
  // Fault reset: controller enable off and the cause gone.
  if (faults_ && sp.mode == DriveMode::kOff && set_exists && !overspeed) {
    faults_ = 0;
    overload_s_ = 0;
  }

  const DriveMode previous = mode_;
  mode_ = faults_ ? DriveMode::kOff : sp.mode;  // tripped: power stage off
  command_ = sp.value;
  if (mode_ != previous) {
    // Bumpless change of mode: ramps start from where the axis is.
    ramp_velocity_ = velocity;
    if (previous == DriveMode::kOff) integral_ = 0;
    orient_command_ = std::nan("");
  }
  const DriveParameterSet& g = *set_;
  switch (mode_) {
    case DriveMode::kOff:
    case DriveMode::kTorque:
      ramp_velocity_ = velocity;
      return velocity;
    case DriveMode::kVelocity: {
      const double target = std::clamp(sp.value, -g.velocity_limit, g.velocity_limit);
      const double step = g.acceleration_limit * dt_s;
      ramp_velocity_ += std::clamp(target - ramp_velocity_, -step, step);
      return ramp_velocity_;
    }
    case DriveMode::kPosition:
      break;
  }
  interpolated_ = g.spindle && sp.interpolated;
  if (!g.spindle || interpolated_) {
    // Servo (and a spindle the NC interpolates, G64): proportional position loop; the master
    // interpolates, the drive only follows.
    if (interpolated_) orient_command_ = std::nan("");  // a later M19 plans afresh
    // With feed-forward (G06) the loop only corrects what the feed-forward leaves.
    const double v = g.kv_per_s * PositionError(*p_, sp.value, position) + sp.velocity_feedforward;
    return std::clamp(v, -g.velocity_limit, g.velocity_limit);
  }
  // Spindle orientation (M19): the command is an angle modulo one turn; the drive picks the
  // shortest way once per command and brakes so that it arrives without overshoot.
  if (!(sp.value == orient_command_)) {
    orient_command_ = sp.value;
    orient_target_ = position + Wrap(sp.value - position);
  }
  const double error = orient_target_ - position;
  const double braking = std::sqrt(2 * g.acceleration_limit * std::abs(error));
  const double limit = std::min(g.positioning_speed, braking);
  const double v = std::clamp(g.kv_per_s * error, -limit, limit);
  const double step = g.acceleration_limit * dt_s;
  ramp_velocity_ += std::clamp(v - ramp_velocity_, -step, step);
  return ramp_velocity_;
}

double DriveController::Torque(double velocity_reference, double velocity, double dt_s) {
  using control::DriveMode;
  const DriveParameterSet& g = *set_;
  double torque = 0;
  if (mode_ == DriveMode::kOff) {
    saturated_ = false;
  } else if (mode_ == DriveMode::kTorque) {
    torque = std::clamp(command_, -g.torque_limit, g.torque_limit);
    saturated_ = torque != command_;
  } else {
    const double error = velocity_reference - velocity;
    const double proportional = g.velocity_kp * error;
    const double candidate = integral_ + proportional * dt_s / g.velocity_ti_s;
    const double unclamped = proportional + candidate;
    torque = std::clamp(unclamped, -g.torque_limit, g.torque_limit);
    saturated_ = torque != unclamped;
    // Anti-windup: integrate only while the output is not pushing further into the limit.
    if (!saturated_ || (unclamped > 0) != (error > 0)) integral_ = candidate;
  }
  // Overload (the amplifier's i2t, simplified): net time at the torque limit; the trip takes
  // the power stage off from the next tick.
  overload_s_ = saturated_ ? overload_s_ + dt_s : std::max(0.0, overload_s_ - dt_s);
  if (overload_s_ >= p_->overload_time_s) faults_ |= control::drive_status::kOverload;
  return torque;
}

void DriveController::Feedback(double position, double velocity, double torque,
                               control::DriveFeedback& fb) const {
  using namespace control::drive_status;
  const DriveParameterSet& g = *set_;
  const double unit = Unit(*p_);
  const double res = p_->encoder_resolution;
  // floor(x + 0.5), not round(): the same for an encoder, and no libm call on the hot path.
  const double quantised = std::floor(position * counts_per_unit_ + 0.5) * res;
  // Modulo scaling: the drive reports the position within [0, modulo).
  const double reported =
      p_->modulo > 0 ? quantised - p_->modulo * std::floor(quantised / p_->modulo) : quantised;
  fb.position = reported * unit;
  fb.velocity = velocity * unit;
  fb.torque = torque;
  fb.parameter_set = set_number_;
  // A trip of this tick shows at once, though the power stage goes off with the next tick.
  const control::DriveMode mode = faults_ ? control::DriveMode::kOff : mode_;
  fb.status = faults_ ? faults_ : kReady;
  if (mode != control::DriveMode::kOff) fb.status |= kEnabled;
  if (std::abs(velocity) < g.standstill_window) fb.status |= kStandstill;
  if (saturated_) fb.status |= kTorqueLimit;
  // Threshold status (SERCOS S-0-0333, S-0-0337; C-axis manual 4.2 MD_MDX, P_PX, LOAD90):
  // torque and velocity are SI here, so torque x velocity is the mechanical power in W.
  const double abs_torque = std::abs(torque);
  if (p_->torque_threshold > 0 && abs_torque >= p_->torque_threshold) fb.status |= kTorqueThreshold;
  if (p_->power_threshold_w > 0 && abs_torque * std::abs(velocity) >= p_->power_threshold_w)
    fb.status |= kPowerThreshold;
  if (g.torque_limit > 0 && abs_torque >= 0.9 * g.torque_limit) fb.status |= kLoad90;
  fb.following_error = 0;
  if (mode == control::DriveMode::kPosition) {
    const bool orienting = g.spindle && !interpolated_;
    const double target = orienting ? orient_target_ : command_;
    const double error = orienting ? target - quantised : PositionError(*p_, target, quantised);
    fb.following_error = error * unit;
    if (std::abs(error) < g.in_position_window) fb.status |= kInPosition;
    if (std::abs(error) > g.following_error_limit) fb.status |= kFollowingError;
  }
  if (mode == control::DriveMode::kVelocity) {
    const double target = std::clamp(command_, -g.velocity_limit, g.velocity_limit);
    if (ramp_velocity_ == target && std::abs(velocity - target) < g.standstill_window)
      fb.status |= kAtSpeed;
  }
}

}  // namespace vmt::sim
