#pragma once
// An ideal machine on the drive bus for the control's tests: the master telegram the kernel
// writes and the amplifier telegram it reads, and per drive a plain description of how the
// drive answers its setpoint each drive tick without dynamics. The rigs of the channel, gateway
// and headstock tests derive from it (their `at` and `mdt` are its telegrams) and keep only
// what is their own: a PLC's acknowledgements, probe latches, drive trips.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "control/drive_bus.hpp"

namespace vmt::test_support {

/// How one ideal drive answers its setpoint.
struct IdealDrive {
  enum class Answer : uint8_t {
    /// The test answers for this drive itself; the bus leaves its feedback alone.
    kNone,
    /// Position mode: the actual position is the setpoint; velocity mode: the position
    /// integrates the command. Velocity and status stay as the test set them.
    kFollow,
    /// Position, velocity and status: position mode stands on its setpoint (the velocity is the
    /// step over the tick), velocity mode and kOff ramp to their command (kOff: 0) at
    /// `acceleration` and integrate the position.
    kServo,
    /// A spindle at its command at once: velocity mode turns at it (at speed; at standstill for
    /// 0), position mode stands in position on its setpoint, kOff stands where it is.
    kInstantSpindle,
  };
  Answer answer = Answer::kNone;
  // kServo only.
  double acceleration = 0;           ///< mm/s^2 | deg/s^2; 0: the command at once
  double standstill_window = 0.01;   ///< |velocity| below this reports kStandstill
  bool in_position = true;           ///< position mode reports kInPosition
  bool at_speed = false;             ///< velocity mode within 1 unit/s of its command: kAtSpeed
  bool enabled = false;              ///< every mode but kOff reports kEnabled
  /// Position mode without DriveSetpoint::interpolated is a spindle's orientation (M19): the
  /// drive reports no velocity while it stands on the setpoint.
  bool orients = false;

  static IdealDrive Follow() { return {Answer::kFollow}; }
  static IdealDrive Servo(double acceleration = 0) {
    IdealDrive d{Answer::kServo};
    d.acceleration = acceleration;
    return d;
  }
  static IdealDrive InstantSpindle() { return {Answer::kInstantSpindle}; }
};

class IdealDriveBus {
 public:
  /// `n` drives, all ready (status `status`) at position 0, answering as kNone until the rig
  /// says otherwise; `tick` is the time between two answers (the drive tick).
  explicit IdealDriveBus(size_t n = 0, uint32_t status = control::drive_status::kReady,
                         double tick = 250e-6)
      : dt(tick) {
    Resize(n, status);
  }

  /// Grows (or shrinks) the bus to `n` drives; new drives are ready (`status`) at 0 and kNone.
  void Resize(size_t n, uint32_t status = control::drive_status::kReady) {
    const size_t old = at.feedback.size();
    at.feedback.resize(n);
    for (size_t d = old; d < n; ++d) at.feedback[d].status = status;
    mdt.setpoints.resize(n);
    drives.resize(n);
  }

  /// One drive tick's answer of every drive to the master telegram.
  void Answer() {
    for (size_t d = 0; d < drives.size(); ++d) Answer(d, drives[d]);
  }
  /// Drive `d` answers as `drive` describes (not necessarily its own description).
  void Answer(size_t d, const IdealDrive& drive) {
    using control::DriveMode;
    namespace status = control::drive_status;
    const control::DriveSetpoint& sp = mdt.setpoints[d];
    control::DriveFeedback& f = at.feedback[d];
    switch (drive.answer) {
      case IdealDrive::Answer::kNone:
        return;
      case IdealDrive::Answer::kFollow:
        if (sp.mode == DriveMode::kPosition) f.position = sp.value;
        if (sp.mode == DriveMode::kVelocity) f.position += sp.value * dt;
        return;
      case IdealDrive::Answer::kInstantSpindle:
        f.velocity = sp.mode == DriveMode::kVelocity ? sp.value : 0;
        f.status = status::kReady;
        f.status |= sp.value == 0 || sp.mode == DriveMode::kPosition ? status::kStandstill
                                                                     : status::kAtSpeed;
        if (sp.mode == DriveMode::kPosition) {
          f.position = sp.value;
          f.status |= status::kInPosition;
        }
        return;
      case IdealDrive::Answer::kServo:
        break;
    }
    if (sp.mode == DriveMode::kPosition) {
      f.velocity = drive.orients && !sp.interpolated ? 0 : (sp.value - f.position) / dt;
      f.position = sp.value;
    } else {
      const double target = sp.mode == DriveMode::kVelocity ? sp.value : 0;
      if (drive.acceleration > 0) {
        const double step = drive.acceleration * dt;
        f.velocity = std::clamp(target, f.velocity - step, f.velocity + step);
      } else {
        f.velocity = target;
      }
      f.position += f.velocity * dt;
    }
    f.status = status::kReady;
    if (drive.enabled && sp.mode != DriveMode::kOff) f.status |= status::kEnabled;
    if (std::abs(f.velocity) < drive.standstill_window) f.status |= status::kStandstill;
    if (drive.in_position && sp.mode == DriveMode::kPosition) f.status |= status::kInPosition;
    if (drive.at_speed && sp.mode == DriveMode::kVelocity && std::abs(f.velocity - sp.value) < 1)
      f.status |= status::kAtSpeed;
  }

  control::AmplifierTelegram at;  ///< what the kernel reads
  control::MasterTelegram mdt;    ///< what the kernel wrote
  std::vector<IdealDrive> drives;  ///< how each drive answers, in bus order
  double dt;                       ///< s between two answers
};

}  // namespace vmt::test_support
