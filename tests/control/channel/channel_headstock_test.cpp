// The channel's side of the headstock changeover (C-axis manual 1.2, 2.3, 3.3, 4.2, 4.3): which
// blocks and keys select which mode, blocks that wait for the changeover, the look-ahead that
// stops before it, Control-Reset, reverse and mode changes during it. The machine is ideal
// (position = setpoint, speeds ramp), the PLC scripted: it acknowledges ROTMOD / SPMOD after a
// few NC cycles, as the C-axis manual's program does once its clutch has switched.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using axes::ChangeoverPhase;
using axes::HeadstockMode;
using testing::Axis;

constexpr int kX = 0, kZ = 1, kC = 2;  // channel axes
constexpr int kS1 = 2;                 // drive of the main spindle

enum class Kind { kServo, kOneDrive };

// X (drive 0), Z (1), main spindle S1 (2) and C: a servo on drive 3 through a clutch (section
// 3), or S1 itself in its rotary parameter set 1 (section 2).
struct Lathe : test_support::IdealDriveBus {
  explicit Lathe(const std::string& program, Kind kind = Kind::kServo,
                 HeadstockMode power_on = HeadstockMode::kSpindle)
      : IdealDriveBus(kind == Kind::kServo ? 4 : 3,
                      drive_status::kReady | drive_status::kStandstill) {
    parsed = nc::ParseProgram(program, "p.mtc", nc::Dialect::kMtc200);
    EXPECT_TRUE(parsed.ok()) << nc::Format(parsed.errors[0], parsed.program.files);
    c_drive = kind == Kind::kServo ? 3 : kS1;
    ChannelConfig config;
    ChannelAxis c = Axis("C", c_drive, 360);
    c.rotary = true;
    c.acceleration = 3600;
    config.axes = {Axis("X", 0, 400), Axis("Z", 1, 500), c};
    config.spindle_drive = kS1;
    axes::HeadstockConfig h;
    h.spindle_drive = kS1;
    h.rotary_drive = c_drive;
    h.rotary_parameter_set = kind == Kind::kServo ? 0 : 1;
    config.headstock = h;
    config.rotary_axis = kC;
    channel = std::make_unique<Channel>(config, std::vector<const nc::Program*>{&parsed.program});
    // Ideal drives whose velocity ramps at 7200 deg/s^2; an ideal position loop is on its
    // command: in position (M19's end, C-axis manual 2.3).
    for (test_support::IdealDrive& d : drives) d = test_support::IdealDrive::Servo(7200);
    plc.rotmod_q = power_on == HeadstockMode::kRotary;
    plc.spmod_q = power_on == HeadstockMode::kSpindle;
  }

  const axes::HeadstockChangeover& hs() const { return *channel->headstock(); }

  // One drive tick. At each NC cycle the PLC runs first (as the runner scans it before the
  // gateway): it answers ROTMOD / SPMOD after `plc_delay` cycles with that acknowledgement alone.
  void Tick() {
    if (tick % 4 == 0) {
      if (answering) {
        const bool want_rot = hs().rotmod() && !plc.rotmod_q;
        const bool want_sp = hs().spmod() && !plc.spmod_q;
        waited = want_rot || want_sp ? waited + 1 : 0;
        if (waited > plc_delay) {
          plc.rotmod_q = want_rot;
          plc.spmod_q = want_sp;
          waited = 0;
        }
      }
      channel->SetHeadstockPlc(plc);
    }
    channel->Tick(at, mdt);
    Answer();
    if (hs().busy()) changeover_ticks++;
    ++tick;
  }
  void Run(int ticks) {
    for (int i = 0; i < ticks; ++i) Tick();
  }
  void RunUntilEnd(int limit = 400000) {
    for (int i = 0; i < limit && channel->state() != ChannelState::kEnded &&
                    channel->state() != ChannelState::kError;
         ++i)
      Tick();
    ASSERT_EQ(channel->state(), ChannelState::kEnded) << channel->error();
  }
  void RunUntilBusy(int limit = 40000) {
    for (int i = 0; i < limit && !hs().busy(); ++i) Tick();
    ASSERT_TRUE(hs().busy());
  }
  double X() const { return at.feedback[0].position; }
  double C() const { return at.feedback[c_drive].position; }
  const DriveSetpoint& CSetpoint() const { return mdt.setpoints[c_drive]; }
  const DriveSetpoint& S1Setpoint() const { return mdt.setpoints[kS1]; }

  nc::ParseResult parsed;
  std::unique_ptr<Channel> channel;
  axes::HeadstockPlc plc;
  int c_drive = 3;
  bool answering = true;
  int plc_delay = 20;
  int waited = 0;
  int64_t tick = 0;
  int64_t changeover_ticks = 0;
};

class ChannelHeadstockKinds : public ::testing::TestWithParam<Kind> {};
INSTANTIATE_TEST_SUITE_P(Machine, ChannelHeadstockKinds,
                         ::testing::Values(Kind::kServo, Kind::kOneDrive), [](const auto& info) {
                           return info.param == Kind::kServo ? "SeparateServo" : "OneDrive";
                         });

// ---- Which blocks select which mode (4.2) ----------------------------------------------------

TEST_P(ChannelHeadstockKinds, InterpolatingTheRotaryAxisSelectsRotaryMode) {
  for (const std::string block : {"G00 C90", "G01 C90 F3000", "G01 X10 C90 F600",
                                  "G02 X10 Z10 R10 C90 F600", "G03 X10 Z10 R10 C90 F600"}) {
    SCOPED_TRACE(block);
    Lathe m("N1 " + block + "\nN2 RET\n", GetParam());
    m.channel->Start();
    m.RunUntilEnd();
    EXPECT_GT(m.changeover_ticks, 0);
    EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);
    EXPECT_NEAR(m.C(), 90, 1e-9);
    EXPECT_EQ(m.CSetpoint().mode, DriveMode::kPosition);
    EXPECT_EQ(m.CSetpoint().parameter_set, GetParam() == Kind::kServo ? 0 : 1);
  }
}

TEST_P(ChannelHeadstockKinds, SpindleFunctionsSelectSpindleMode) {
  struct Case {
    const char* block;
    DriveMode mode;
    double value;
  };
  for (const Case& c :
       {Case{"M3 S100", DriveMode::kVelocity, 600}, Case{"M4 S50", DriveMode::kVelocity, -300},
        Case{"M5", DriveMode::kVelocity, 0}, Case{"M19", DriveMode::kPosition, 0}}) {
    SCOPED_TRACE(c.block);
    Lathe m(std::string("N1 ") + c.block + "\nN2 G04 F0.5\nN3 RET\n", GetParam(),
            HeadstockMode::kRotary);
    m.channel->Start();
    m.RunUntilEnd();
    EXPECT_GT(m.changeover_ticks, 0);
    EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
    EXPECT_EQ(m.S1Setpoint().mode, c.mode);
    EXPECT_EQ(m.S1Setpoint().value, c.value);
    EXPECT_EQ(m.S1Setpoint().parameter_set, 0);
  }
}

TEST_P(ChannelHeadstockKinds, BlocksThatNeedTheCurrentModeRunWithoutAChangeover) {
  Lathe rot("N1 G01 X10 C90 F600\nN2 G00 C0\nN3 G01 X0\nN4 RET\n", GetParam(),
            HeadstockMode::kRotary);
  rot.channel->Start();
  rot.RunUntilEnd();
  EXPECT_EQ(rot.changeover_ticks, 0);
  EXPECT_NEAR(rot.C(), 0, 1e-9);

  Lathe sp("N1 M3 S100\nN2 G01 X10 F600\nN3 M5\nN4 M19\nN5 RET\n", GetParam());
  sp.channel->Start();
  sp.RunUntilEnd();
  EXPECT_EQ(sp.changeover_ticks, 0);
  EXPECT_EQ(sp.hs().mode(), HeadstockMode::kSpindle);

  // Blocks without the rotary axis or a spindle function leave even "neither" alone.
  Lathe none("N1 G01 X10 Z5 F600\nN2 RET\n", GetParam(), HeadstockMode::kNone);
  none.channel->Start();
  none.RunUntilEnd();
  EXPECT_EQ(none.changeover_ticks, 0);
  EXPECT_EQ(none.hs().mode(), HeadstockMode::kNone);
}

TEST(ChannelHeadstockTest, ThreadCuttingAndTappingSelectSpindleMode) {
  // 4.2: G33, G63 and G64 select spindle mode: the block waits for the changeover, and only
  // then finds that no M3/M4 turns the spindle (channel_thread_test.cpp has the threads).
  for (const char* g : {"G33 Z-10 F1.5", "G63 Z-10 F1.5", "G64 Z-10 F1.5"}) {
    SCOPED_TRACE(g);
    Lathe m(std::string("N1 ") + g + "\nN2 RET\n", Kind::kServo, HeadstockMode::kRotary);
    m.channel->Start();
    m.Run(4000);
    EXPECT_EQ(m.channel->state(), ChannelState::kError);
    EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("spindle not turning for G"));
    EXPECT_EQ(m.channel->error_number(), kMsgSpindleStill);
    EXPECT_GT(m.changeover_ticks, 0);
    EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  }
}

// ---- Block preparation and execution wait (1.2) ----------------------------------------------

TEST_P(ChannelHeadstockKinds, ABlockWaitsUntilTheChangeoverEnds) {
  Lathe m("N1 G01 X10 C90 F600\nN2 RET\n", GetParam());
  m.plc_delay = 500;  // 0.5 s for the clutch
  m.channel->Start();
  m.RunUntilBusy();
  int64_t moved_at = -1, rotary_at = -1;
  bool rotmod_seen = false;
  while (m.channel->state() == ChannelState::kRunning && m.tick < 40000) {
    m.Tick();
    rotmod_seen = rotmod_seen || m.hs().rotmod();
    if (rotary_at < 0 && m.hs().mode() == HeadstockMode::kRotary) rotary_at = m.tick;
    if (moved_at < 0 && (std::abs(m.X()) > 1e-9 || std::abs(m.C()) > 1e-9)) moved_at = m.tick;
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_TRUE(rotmod_seen);
  ASSERT_GT(rotary_at, 0);
  EXPECT_GE(moved_at, rotary_at);  // nothing moved before rotary axis mode
  EXPECT_GT(m.changeover_ticks, 4 * 500);
  EXPECT_NEAR(m.X(), 10, 1e-9);
  EXPECT_NEAR(m.C(), 90, 1e-9);
}

TEST_P(ChannelHeadstockKinds, ASpindleBlockWaitsAndThenRunsTheSpindle) {
  Lathe m("N1 G01 X20 F1200 M3 S100\nN2 G04 F0.5\nN3 RET\n", GetParam(), HeadstockMode::kRotary);
  m.plc_delay = 300;
  m.channel->Start();
  m.RunUntilBusy();
  while (m.hs().busy()) {
    m.Tick();
    if (m.hs().busy()) {
      ASSERT_EQ(m.X(), 0);  // (the cycle that ends it may start the block)
    }
  }
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  m.RunUntilEnd();
  EXPECT_NEAR(m.X(), 20, 1e-9);
  EXPECT_EQ(m.S1Setpoint().value, 600);
  EXPECT_NEAR(m.at.feedback[kS1].velocity, 600, 1e-9);
}

TEST_P(ChannelHeadstockKinds, LookAheadDoesNotBlendIntoAChangeover) {
  // N1 -> N2 is a straight continuation: with C already in rotary axis mode the path runs
  // through the join at speed; needing the changeover, N1 ends at rest.
  const std::string program = "N1 G01 X10 F1200\nN2 G01 X20 C10\nN3 RET\n";
  for (const HeadstockMode start : {HeadstockMode::kRotary, HeadstockMode::kSpindle}) {
    SCOPED_TRACE(ToString(start));
    Lathe m(program, GetParam(), start);
    m.channel->Start();
    int ticks_at_join = 0;  // drive ticks with X standing at the join
    while (m.channel->state() == ChannelState::kRunning && m.tick < 40000) {
      m.Tick();
      if (std::abs(m.X() - 10) < 1e-9) ++ticks_at_join;
    }
    ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
    if (start == HeadstockMode::kRotary) {
      EXPECT_EQ(m.changeover_ticks, 0);
      EXPECT_LE(ticks_at_join, 1);
    } else {
      EXPECT_GT(m.changeover_ticks, 0);
      EXPECT_GE(ticks_at_join, m.changeover_ticks);
    }
    EXPECT_NEAR(m.X(), 20, 1e-9);
    EXPECT_NEAR(m.C(), 10, 1e-9);
  }
}

// ---- Manual mode (4.2: AxxCJGPOS / AxxCJGNEG) ------------------------------------------------

TEST_P(ChannelHeadstockKinds, JoggingTheRotaryAxisSelectsRotaryMode) {
  Lathe m("N1 RET\n", GetParam());
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Jog(kX, +1);  // another axis: no changeover
  m.Run(400);
  m.channel->Jog(kX, 0);
  m.Run(400);
  EXPECT_EQ(m.changeover_ticks, 0);
  const double c0 = m.C();
  m.channel->Jog(kC, +1);
  m.RunUntilBusy();
  while (m.hs().busy()) {
    m.Tick();
    if (m.hs().busy()) {
      ASSERT_EQ(m.C(), c0);  // the key waits for rotary axis mode
    }
  }
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  m.Run(4000);
  EXPECT_GT(m.C(), c0 + 10);  // Cxx.020 default: a tenth of the rapid
  EXPECT_EQ(m.channel->AxisMotion(kC), 1);
  m.channel->Jog(kC, 0);
  m.Run(2000);
  EXPECT_EQ(m.channel->AxisMotion(kC), 0);
  m.channel->Jog(kC, -1);  // in rotary axis mode already: no changeover
  const int64_t before = m.changeover_ticks;
  m.Run(400);
  EXPECT_EQ(m.changeover_ticks, before);
  EXPECT_EQ(m.channel->AxisMotion(kC), -1);
}

// ---- Control-Reset, reverse, mode change, process error (2.3, 3.3) --------------------------

TEST_P(ChannelHeadstockKinds, ControlResetAbortsAChangeover) {
  Lathe m("N1 G01 X10 C90 F600\nN2 RET\n", GetParam());
  m.answering = false;  // the clutch never arrives
  m.channel->Start();
  m.RunUntilBusy();
  m.Run(4000);
  ASSERT_TRUE(m.hs().rotmod());
  m.channel->Reset();
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);
  EXPECT_FALSE(m.hs().busy());
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);  // what the PLC acknowledges
  m.Run(400);
  EXPECT_FALSE(m.hs().rotmod());
  EXPECT_TRUE(m.hs().spmod());
  EXPECT_EQ(m.X(), 0);
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);
  // The program runs from its start again, with a PLC that answers.
  m.answering = true;
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_NEAR(m.C(), 90, 1e-9);
}

TEST_P(ChannelHeadstockKinds, ReverseRestoresTheOriginalModeAndRunsHome) {
  Lathe m("N1 G01 X10 C90 F600\nN2 RET\n.HOME\nN10 G00 X-5\nN11 RET\n", GetParam());
  m.answering = false;
  m.channel->Start();
  m.RunUntilBusy();
  m.Run(2000);
  ASSERT_TRUE(m.hs().rotmod());
  m.channel->Stop();
  m.Run(400);
  ASSERT_TRUE(m.channel->Reverse());
  EXPECT_EQ(m.hs().target(), HeadstockMode::kSpindle);
  m.answering = true;
  m.RunUntilEnd();
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  EXPECT_NEAR(m.X(), -5, 1e-9);
  EXPECT_EQ(m.C(), 0);
}

TEST_P(ChannelHeadstockKinds, ModeChangeDuringAChangeoverIsAnImmediateStop) {
  Lathe m("N1 G01 X10 C90 F600\nN2 RET\n", GetParam());
  m.answering = false;
  m.channel->Start();
  m.RunUntilBusy();
  m.Run(2000);
  ASSERT_EQ(m.channel->state(), ChannelState::kRunning);
  // The PLC hunts (65012 bit 0) while it waits for the clutch.
  m.plc.spindle_axd[axes::kAxdFunction] = axes::axd::kHunting;
  m.Run(400);
  ASSERT_NE(m.hs().SpindleFunctionWord() & axes::axd::kHuntingAck, 0);
  EXPECT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  EXPECT_EQ(m.channel->mode(), ChannelMode::kManual);
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  m.Run(8);
  // Immediate stop: the motion functions halt, the changeover stays pending.
  EXPECT_EQ(m.hs().SpindleFunctionWord() & axes::axd::kHuntingAck, 0);
  EXPECT_EQ(m.S1Setpoint().value, 0);
  EXPECT_TRUE(m.hs().busy());
  m.Run(400);
  // Back in automatic, cycle start finishes the changeover and the block.
  m.plc.spindle_axd = {};
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  EXPECT_EQ(m.channel->state(), ChannelState::kRunning) << m.channel->error();
  m.answering = true;
  m.RunUntilEnd();
  EXPECT_NEAR(m.C(), 90, 1e-9);
  EXPECT_NEAR(m.X(), 10, 1e-9);
}

TEST_P(ChannelHeadstockKinds, JogDuringAnInterruptedChangeoverTurnsItRoundAndTheBlockAsksAgain) {
  // 2.3 Jogging Movements: AxxCJGPOS / JGNEG abort an interrupted changeover before the NC
  // commands the new one. Back in automatic, the block that waited for spindle mode must ask for
  // it again, not wait for ever.
  Lathe m("N1 M3 S100\nN2 G04 F0.2\nN3 RET\n", GetParam(), HeadstockMode::kRotary);
  m.answering = false;
  m.channel->Start();
  m.RunUntilBusy();
  m.Run(400);
  ASSERT_EQ(m.hs().target(), HeadstockMode::kSpindle);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.answering = true;
  m.channel->Jog(kC, +1);
  EXPECT_EQ(m.hs().target(), HeadstockMode::kRotary);
  for (int i = 0; i < 40000 && m.hs().busy(); ++i) m.Tick();
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  m.Run(2000);
  m.channel->Jog(kC, 0);
  m.Run(2000);
  EXPECT_GT(m.C(), 1);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  EXPECT_EQ(m.channel->state(), ChannelState::kRunning) << m.channel->error();
  m.RunUntilEnd(40000);
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  EXPECT_EQ(m.S1Setpoint().value, 600);
}

TEST_P(ChannelHeadstockKinds, ModeChangeWithoutAChangeoverChangesNoHeadstockMode) {
  // 2.3: "Changing the mode ... does not lead to any changes in main spindle or rotary spindle
  // operation."
  Lathe m("N1 G01 C90 F3000\nN2 RET\n", GetParam());
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.Run(400);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.Run(400);
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  EXPECT_FALSE(m.hs().busy());
}

TEST_P(ChannelHeadstockKinds, AcknowledgementRemovedIsMessage506) {
  Lathe m("N1 G01 C90 F3000\nN2 G04 F5\nN3 RET\n", GetParam(), HeadstockMode::kRotary);
  m.channel->Start();
  m.Run(4000);
  ASSERT_EQ(m.channel->state(), ChannelState::kRunning);
  m.plc.rotmod_q = false;
  m.Run(8);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgChangeoverAck);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("ROTMOD_Q"));
}

// ---- The rotary axis where the NC does not position it (3.3, 4.3) ----------------------------

TEST(ChannelHeadstockTest, SeparateServoInFollowUpTakesItsPositionOver) {
  // Spindle mode, the servo's enable off (4.3: follow-up): its command value tracks the actual
  // position, so rotary axis mode starts where the servo stands, without a jump (5).
  Lathe m("N1 G04 F0.1\nN2 G01 C90 F3000\nN3 RET\n", Kind::kServo);
  m.plc.rotary_ready = false;
  m.channel->Start();
  m.Run(40);
  EXPECT_EQ(m.CSetpoint().mode, DriveMode::kOff);
  m.at.feedback[3].position = 33.5;  // moved while torque-free
  m.Run(40);
  EXPECT_EQ(m.channel->position(kC), 33.5);  // the command follows
  m.plc.rotary_ready = true;
  m.plc.spindle_ready = false;
  m.RunUntilBusy();
  while (m.hs().busy()) {
    m.Tick();
    if (m.hs().busy()) {
      ASSERT_EQ(m.C(), 33.5);
    }
  }
  m.RunUntilEnd();
  EXPECT_NEAR(m.C(), 90, 1e-9);
  EXPECT_EQ(m.S1Setpoint().mode, DriveMode::kOff);
}

TEST(ChannelHeadstockTest, OneDriveSwitchesItsParameterSetAndControlMode) {
  Lathe m(
      "N1 M3 S100\nN2 G04 F0.5\nN3 G01 C45 F3000\nN4 G04 F0.2\nN5 M3 S50\nN6 G04 F0.5\nN7 RET\n",
      Kind::kOneDrive);
  m.channel->Start();
  bool spun = false, positioned = false;
  while (m.channel->state() == ChannelState::kRunning && m.tick < 100000) {
    m.Tick();
    const DriveSetpoint& sp = m.S1Setpoint();
    if (!m.hs().busy() && m.hs().mode() == HeadstockMode::kSpindle) {
      ASSERT_EQ(sp.mode, DriveMode::kVelocity);
      ASSERT_EQ(sp.parameter_set, 0);
      spun = spun || sp.value == 600;
    }
    if (!m.hs().busy() && m.hs().mode() == HeadstockMode::kRotary) {
      ASSERT_EQ(sp.mode, DriveMode::kPosition);
      ASSERT_EQ(sp.parameter_set, 1);
      positioned = positioned || std::abs(sp.value - m.channel->position(kC)) < 1e-9;
    }
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_TRUE(spun);
  EXPECT_TRUE(positioned);
  EXPECT_EQ(m.S1Setpoint().value, 300);
}

}  // namespace
}  // namespace vmt::control::channel
