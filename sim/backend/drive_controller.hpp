#pragma once
// The control law inside one drive amplifier, on the load side and in SI units: position loop
// (Kv), spindle ramp and M19 orientation, velocity PI with torque limit and anti-windup, encoder
// quantisation and the status bits. The physics backend closes the loop through Bullet; the
// kinematic backend takes the velocity reference as the actual velocity (an ideal velocity loop),
// so that both share the same position-loop behaviour and following error.

#include "control/drive_bus.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

class DriveController {
 public:
  explicit DriveController(const DriveParams& params)
      : p_(&params), counts_per_unit_(1 / params.encoder_resolution) {}

  /// Velocity the drive asks for this tick (m/s | rad/s), given the setpoint in SI and the true
  /// load position and velocity. Keeps the ramp and orientation state.
  double VelocityReference(const control::DriveSetpoint& sp_si, double position, double velocity,
                           double dt_s);
  /// Torque (N | N m, load side) for the velocity reference; PI with anti-windup.
  double Torque(double velocity_reference, double velocity, double dt_s);

  /// Feedback in machine units for the control (encoder-quantised position).
  control::DriveFeedback Feedback(double position, double velocity, double torque) const;

  bool enabled() const { return mode_ != control::DriveMode::kOff; }
  bool saturated() const { return saturated_; }
  const DriveParams& params() const { return *p_; }

 private:
  const DriveParams* p_;
  double counts_per_unit_;  ///< 1 / encoder resolution: a multiply on the hot path
  control::DriveMode mode_ = control::DriveMode::kOff;
  double command_ = 0;        ///< SI: last position or velocity command
  double ramp_velocity_ = 0;  ///< velocity mode: reference after the acceleration ramp
  double orient_target_ = 0;  ///< M19: absolute target chosen when the command arrives
  double orient_command_ = 0;
  double integral_ = 0;  ///< velocity PI state (torque units)
  bool saturated_ = false;
};

/// Setpoint value from machine units to SI (mm -> m, deg -> rad).
control::DriveSetpoint ToSi(const DriveParams& p, const control::DriveSetpoint& sp);

}  // namespace vmt::sim
