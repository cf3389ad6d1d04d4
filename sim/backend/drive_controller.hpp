#pragma once
// The control law inside one drive amplifier, on the load side and in SI units: position loop
// (Kv), spindle ramp and M19 orientation, velocity PI with torque limit and anti-windup, encoder
// quantisation, the parameter set the master selects, the amplifier's protections and the
// status bits. The physics backend closes the loop through Bullet; the kinematic backend takes
// the velocity reference as the actual velocity (an ideal velocity loop), so that both share the
// same position-loop behaviour and following error.
//
// Parameter sets (DriveSetpoint::parameter_set, SERCOS S-0-0217): a switch takes effect in the
// tick the setpoint names the new set. At standstill it is bumpless. While moving, the position
// loop's output jumps by (kv_new / kv_old - 1) times the speed (the velocity loop then catches
// up within the new torque limit), a speed ramp carries on from the velocity it has reached
// towards the new limits, the velocity loop keeps its integral torque (clamped into the new
// torque limit, so it never holds more than the new set allows), and an M19 orientation re-plans
// its path with the new set. A switch to a set whose velocity limit the axis exceeds by the
// overspeed factor trips the drive.
//
// Protections (status bits of control/drive_bus.hpp): the drive trips -- power stage off, the
// axis coasts, kReady and kEnabled clear -- on
// - kOverload: net time at the torque limit reaches DriveParams::overload_time_s (the amplifier's
//   i2t: time at the limit counts up, time below counts down to 0);
// - kOverspeed: |velocity| (motor side, in load units) above kOverspeedFactor x the active set's
//   velocity limit, in any mode (a servo dragged through an engaged clutch);
// - kParameterSetError: the setpoint names a set the drive does not have.
// Modulo scaling (DriveParams::modulo): the feedback position is reported within one modulo
// (a rotary axis' 0..360 degrees) and a servo's position loop and following error take the
// shorter way between command and position, so an NC command need not be wrapped.
//
// A trip latches. A setpoint with mode kOff (controller enable removed, as a SERCOS drive's
// fault reset needs) resets it once the cause is gone: the named set exists and the speed is
// below the overspeed threshold. The overload count starts again from 0.

#include "control/drive_bus.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

/// Overspeed trips above this multiple of the velocity limit (a margin over the limit that the
/// velocity loop itself may briefly overshoot).
inline constexpr double kOverspeedFactor = 1.2;

class DriveController {
 public:
  explicit DriveController(const DriveParams& params)
      : p_(&params),
        set_(&params.parameter_sets.at(0)),
        counts_per_unit_(1 / params.encoder_resolution) {}

  /// Velocity the drive asks for this tick (m/s | rad/s), given the setpoint in SI, the encoder
  /// position of the position loop (EncoderPosition) and the motor velocity in load units.
  /// Keeps the ramp and orientation state, selects the parameter set, checks overspeed.
  double VelocityReference(const control::DriveSetpoint& sp_si, double position, double velocity,
                           double dt_s);
  /// Torque (N | N m, load side) for the velocity reference; PI with anti-windup. Counts the
  /// time at the torque limit (overload).
  double Torque(double velocity_reference, double velocity, double dt_s);

  /// Feedback in machine units for the control (encoder-quantised position), written into the
  /// drive's entry of the telegram in place. fb.probe is left alone: the probe latch writes it
  /// (ProbeWiring), and building a whole DriveFeedback per drive and tick -- clearing and
  /// copying its probe registers -- was a large part of a kinematic step.
  void Feedback(double position, double velocity, double torque, control::DriveFeedback& fb) const;

  /// The mode the drive is in: the setpoint's, or kOff while tripped.
  control::DriveMode mode() const { return mode_; }
  bool enabled() const { return mode_ != control::DriveMode::kOff; }
  bool saturated() const { return saturated_; }
  /// Fault bits latched (kOverload | kOverspeed | kParameterSetError), 0 when ready.
  uint32_t faults() const { return faults_; }
  const DriveParams& params() const { return *p_; }

 private:
  void SelectParameterSet(uint8_t number);

  const DriveParams* p_;
  const DriveParameterSet* set_;
  double counts_per_unit_;  ///< 1 / encoder resolution: a multiply on the hot path
  control::DriveMode mode_ = control::DriveMode::kOff;
  uint8_t set_number_ = 0;
  double command_ = 0;        ///< SI: last position or velocity command
  double ramp_velocity_ = 0;  ///< velocity mode: reference after the acceleration ramp
  double orient_target_ = 0;  ///< M19: absolute target chosen when the command arrives
  double orient_command_ = 0;
  bool interpolated_ = false;  ///< spindle set in position mode following the NC (G64)
  double integral_ = 0;        ///< velocity PI state (torque units)
  bool saturated_ = false;
  double overload_s_ = 0;  ///< net time at the torque limit
  uint32_t faults_ = 0;
};

/// Setpoint value from machine units to SI (mm -> m, deg -> rad).
control::DriveSetpoint ToSi(const DriveParams& p, const control::DriveSetpoint& sp);

/// A motor joint's position or velocity on the load side (divided by the drive's ratio). A
/// direct drive (ratio 1, most of them) skips the division: x / 1 is x exactly, and the
/// divisions were the dearest instructions of a kinematic tick.
inline double LoadSide(const DriveParams& p, double motor) {
  return p.ratio == 1 ? motor : motor / p.ratio;
}

/// The position the drive's position loop closes on (m | rad, load side), from a function that
/// gives a joint's position: the load-side encoder's joint (`encoder: load`), else the motor
/// joint through the ratio.
template <typename JointPosition>
double EncoderPosition(const DriveParams& p, const JointPosition& joint_position) {
  return p.load_joint >= 0 ? joint_position(p.load_joint)
                           : LoadSide(p, joint_position(p.motor_joint));
}

}  // namespace vmt::sim
