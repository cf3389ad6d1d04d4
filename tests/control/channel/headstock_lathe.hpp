#pragma once
// The lathe of the headstock's operating-state tests (C-axis manual 2.3, 3.3): a channel with
// X, Z and C, a main spindle S1 whose rotary axis mode C is a separate servo (section 3) or S1
// itself (section 2), on ideal drives (position: actual = command; velocity: the speed at once)
// and a PLC that acknowledges every changeover at once unless a test takes the
// acknowledgements in hand.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/nc/parser.hpp"
#include "tests/support/ideal_drive_bus.hpp"

namespace vmt::control::channel::headstock_test {

using axes::HeadstockMode;
inline constexpr uint32_t kTrips =
    drive_status::kOverload | drive_status::kOverspeed | drive_status::kParameterSetError;
inline constexpr double kTick = 250e-6;

// Drives: 0 X, 1 Z, 2 main spindle S1, 3 C servo (section 3), 4 the driven tool spindle S2 (as
// lathe-c1's, which the REPOS subroutine of the repositioning manual's 8.3 restores). Section 2
// (a spindle with rotary axis capability) puts C on drive 2. Channel axes: X, Z, C.
struct Lathe : test_support::IdealDriveBus {
  explicit Lathe(const std::string& program, bool separate_servo = false,
                 const std::function<void(ChannelConfig&)>& configure = {},
                 HeadstockMode power_on = HeadstockMode::kSpindle)
      : IdealDriveBus(5, drive_status::kReady | drive_status::kStandstill) {
    parsed = nc::ParseProgram(program, "p.mtc", nc::Dialect::kMtc200);
    EXPECT_TRUE(parsed.ok()) << nc::Format(parsed.errors[0], parsed.program.files);
    ChannelConfig config;
    for (int a = 0; a < 3; ++a) {
      ChannelAxis axis;
      axis.name = a == 0 ? "X" : a == 1 ? "Z" : "C";
      axis.number = a + 1;
      axis.drive = a < 2 ? a : separate_servo ? 3 : 2;
      axis.rotary = a == 2;
      axis.rapid_per_s = a == 2 ? 3600 : 400;
      axis.acceleration = a == 2 ? 36000 : 4000;
      config.axes.push_back(axis);
    }
    config.spindle_drive = 2;
    config.spindle.name = "S1";
    config.spindle.jog_per_s = 600;  // 100 rpm
    config.spindle.jog_spindle_position = 90;
    axes::HeadstockConfig h;
    h.spindle_drive = 2;
    h.rotary_drive = separate_servo ? 3 : 2;
    config.headstock = h;
    config.rotary_axis = 2;
    config.spindles = {{2, 4, "S2"}};
    if (configure) configure(config);
    channel = std::make_unique<Channel>(config, std::vector<const nc::Program*>{&parsed.program});
    for (test_support::IdealDrive& d : drives) {
      d = test_support::IdealDrive::Servo();  // the command at once
      d.standstill_window = 1e-9;
      d.at_speed = true;
    }
    plc.spmod_q = power_on == HeadstockMode::kSpindle;
    plc.rotmod_q = power_on == HeadstockMode::kRotary;
  }

  const axes::HeadstockChangeover& hs() const { return *channel->headstock(); }

  void Tick() {
    if (acknowledge && channel->headstock()) {
      // As the runner's default PLC: every request acknowledged at once; at power-on (neither
      // mode) the mode the PLC had.
      if (hs().busy() || hs().mode() != HeadstockMode::kNone) {
        plc.rotmod_q = hs().rotmod();
        plc.spmod_q = hs().spmod();
      }
    }
    channel->SetHeadstockPlc(plc);
    channel->Tick(at, mdt);
    for (int d = 0; d < 5; ++d) Drive(d);
    t += kTick;
  }
  void Ticks(int n) {
    for (int i = 0; i < n; ++i) Tick();
  }
  // An ideal drive; a trip latches (power stage off) until a kOff setpoint resets it, unless
  // its cause persists.
  void Drive(int d) {
    DriveFeedback& f = at.feedback[d];
    const DriveSetpoint& sp = mdt.setpoints[d];
    if (f.status & kTrips) {
      if (sp.mode == DriveMode::kOff && !persisting[d]) f.status = drive_status::kReady;
      f.velocity = 0;
      if (f.status & kTrips) return;
    }
    Answer(d, drives[d]);
  }
  void Trip(int d, uint32_t bits, bool persist = false) {
    at.feedback[d].status = bits;  // kReady and kEnabled clear
    persisting[d] = persist;
  }
  // Single block: runs the next block to its end (the channel holds after it).
  void Block(double limit_s = 10) {
    channel->Start();
    const double until = t + limit_s;
    do Tick();
    while (channel->state() == ChannelState::kRunning && t < until);
    Ticks(8);  // the drives reach the last fine interpolation point
  }
  double RunUntilEnd(double limit_s = 20) {
    const double until = t + limit_s;
    while (channel->state() != ChannelState::kEnded && channel->state() != ChannelState::kError &&
           t < until)
      Tick();
    Ticks(8);
    return t;
  }
  template <typename Done>
  bool RunUntil(Done done, double limit_s = 5) {
    const double until = t + limit_s;
    while (!done() && t < until) Tick();
    return done();
  }
  double Drive2Velocity() const { return at.feedback[2].velocity; }

  nc::ParseResult parsed;
  std::unique_ptr<Channel> channel;
  axes::HeadstockPlc plc;
  bool acknowledge = true;
  bool persisting[5] = {false, false, false, false, false};
  double t = 0;
};

}  // namespace vmt::control::channel::headstock_test
