#pragma once
// A headstock with a scripted PLC and ideal drives, for the changeover's tests: both machine
// kinds of the C-axis manual, a separate C servo engaged through a clutch (section 3) and one
// main spindle drive with a rotary parameter set (section 2).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "control/axes/headstock_changeover.hpp"
#include "tests/support/ideal_drive_bus.hpp"

namespace vmt::control::axes::headstock_rig {

constexpr double kDt = 1e-3;  // the NC cycle

enum class Kind { kServo, kFrameless };

// Section 3: spindle on drive 0, C servo on drive 1. Section 2: one drive 0 for both, the
// rotary axis mode in its parameter set 1.
inline HeadstockConfig ConfigOf(Kind kind) {
  HeadstockConfig c;
  c.spindle_drive = 0;
  c.rotary_drive = kind == Kind::kServo ? 1 : 0;
  c.rotary_parameter_set = kind == Kind::kServo ? 0 : 1;
  return c;
}

// The headstock with a scripted PLC and drives. Each drive follows its setpoint as a drive on
// the bus does: velocity ramped at kAccel, position reached at once, off coasts down.
// They report no in-position bit.
struct Rig : test_support::IdealDriveBus {
  static constexpr double kAccel = 3600;  // deg/s^2

  explicit Rig(Kind kind, bool rotmod_q = false, bool spmod_q = true)
      : IdealDriveBus(kind == Kind::kServo ? 2 : 1, drive_status::kReady, kDt),
        config(ConfigOf(kind)),
        hs(config) {
    for (test_support::IdealDrive& d : drives) {
      d = test_support::IdealDrive::Servo(kAccel);
      d.in_position = false;
    }
    plc.rotmod_q = rotmod_q;
    plc.spmod_q = spmod_q;
    hs.TakeModeFromPlc(plc);
    Settle();
  }

  // One NC cycle: the sequence, the setpoints, and the drives' answer.
  bool Cycle() {
    const bool ok = hs.Cycle(plc, at, kDt);
    hs.WriteSetpoints(spindle_cmd, rotary_cmd, mdt);
    Answer();
    return ok;
  }
  void Run(int cycles) {
    for (int i = 0; i < cycles; ++i) EXPECT_TRUE(Cycle()) << hs.error();
  }
  // Cycles until the phase is `phase`, at most `limit`; the number of cycles it took.
  int RunUntil(ChangeoverPhase phase, int limit = 10000) {
    int n = 0;
    while (hs.phase() != phase && n < limit) {
      EXPECT_TRUE(Cycle()) << hs.error();
      ++n;
    }
    EXPECT_EQ(hs.phase(), phase);
    return n;
  }
  void Settle() { Run(3); }

  // The PLC acknowledges `mode` (and only it), as a PLC without a mechanism does.
  void Acknowledge(HeadstockMode mode) {
    plc.rotmod_q = mode == HeadstockMode::kRotary;
    plc.spmod_q = mode == HeadstockMode::kSpindle;
  }
  const DriveSetpoint& Spindle() const { return mdt.setpoints[config.spindle_drive]; }
  const DriveSetpoint& Rotary() const { return mdt.setpoints[config.rotary_drive]; }
  const DriveFeedback& SpindleFb() const { return at.feedback[config.spindle_drive]; }
  const DriveFeedback& RotaryFb() const { return at.feedback[config.rotary_drive]; }

  HeadstockConfig config;
  HeadstockChangeover hs;
  HeadstockPlc plc;
  DriveSetpoint spindle_cmd{DriveMode::kVelocity, 0, 0};
  DriveSetpoint rotary_cmd{DriveMode::kPosition, 0, 0};
};

/// Puts the rig into the external phase of a changeover to rotary axis mode.
inline void ToExternal(Rig& r) {
  r.hs.Request(HeadstockMode::kRotary);
  r.RunUntil(ChangeoverPhase::kExternal);
}

/// Both machine kinds, for a parameterised suite.
inline std::string KindName(const ::testing::TestParamInfo<Kind>& info) {
  return info.param == Kind::kServo ? "SeparateServo" : "OneDrive";
}

}  // namespace vmt::control::axes::headstock_rig
