// Repositioning and NC-block restart on the headstock lathe (REPOS manual 3.3, 4.2, 7.3, 8.3;
// C-axis manual 2-4): the mode the headstock had at the interruption decides whether the
// spindle (G77 S1=0, the spindle keys) or the rotary axis C (G77 C0, jogging, Cxx.086) is
// restored, and whether the spindle counts for PxxS.CREST.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "control/channel/channel.hpp"
#include "headstock_lathe.hpp"

namespace vmt::control::channel {
namespace {

using axes::HeadstockMode;
using headstock_test::kTick;
using headstock_test::Lathe;

constexpr size_t kX = 0, kZ = 1, kC = 2;

void RunFor(Lathe& m, double s) { m.Ticks(static_cast<int>(s / kTick)); }

void JogFor(Lathe& m, size_t axis, int direction, double s) {
  m.channel->Jog(axis, direction);
  RunFor(m, s);
  m.channel->Jog(axis, 0);
  RunFor(m, 0.1);
}

void Call(Lathe& m, bool repositioning, bool restart) {
  m.channel->SetReposition(repositioning, restart);
  RunFor(m, 0.01);
}

/// Runs the program for `s`, holds it and goes to manual mode.
void Interrupt(Lathe& m, double s) {
  m.channel->Start();
  RunFor(m, s);
  m.channel->Stop();
  RunFor(m, 0.2);
  ASSERT_EQ(m.channel->state(), ChannelState::kHold);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
}

double CommandOf(const Lathe& m, size_t axis) {
  return m.channel->repos_status().axes.at(axis).command_value;
}

/// Starts the REPOS subroutine in automatic mode.
void StartRepos(Lathe& m) {
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
}

/// The REPOS subroutine of the manual's example (8.3), as extracted from the manual.
std::string ManualReposSubroutine() {
  std::ifstream in(std::string(VMT_SOURCE_DIR) +
                   "/tests/control/nc/seed_programs/repos_subroutine_lathe.mtc");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_THAT(text.str(), ::testing::HasSubstr("G77 C0 F5000 S2=0"));
  return text.str();
}

// ---- Interrupted in spindle mode ----

// Turning with M3 S1000 (6000 deg/s): X from 0 to 100 at 10 mm/s, then Z to -50.
const std::string kTurning =
    "N1 M3 S1000\n"
    "N2 G01 X100 F600\n"
    "N3 G01 Z-50\n"
    "N4 RET\n";

TEST(ChannelReposHeadstock, SpindleModeGivesCNoTargetAndTheSpindleCounts) {
  Lathe m(kTurning);
  Interrupt(m, 3.0);
  JogFor(m, kZ, +1, 0.2);
  Call(m, true, false);
  const ReposStatus s = m.channel->repos_status();
  ASSERT_EQ(s.axes.size(), 3u);
  EXPECT_EQ(s.axes[kC].name, "C");
  EXPECT_FALSE(s.axes[kC].relevant);  // 7.3: the spindle, not the rotary axis, counts
  EXPECT_FALSE(s.axes[kC].adjust);
  EXPECT_TRUE(s.axes[kZ].adjust);
  EXPECT_TRUE(s.spindle.relevant);
  EXPECT_EQ(s.spindle.command_m, 3);
  EXPECT_DOUBLE_EQ(s.spindle.command_rpm, 1000);
  EXPECT_FALSE(s.spindle.adjust);  // still turning at 1000 rpm
}

TEST(ChannelReposHeadstock, G77OfCAfterSpindleModeFailsAtItsBlockStart) {
  Lathe m(kTurning +
          ".REPOS\n"
          "N10 G77 C0 F5000\n"
          "N11 G77 Z0 F3000\n"
          "N12 G77 X0 F3000 RTS\n");
  Interrupt(m, 3.0);
  JogFor(m, kZ, +1, 0.2);
  const double z = m.at.feedback[kZ].position;
  Call(m, true, false);
  StartRepos(m);
  RunFor(m, 0.5);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgReposMode);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("p.mtc:6:"));  // N10
  // Refused before any changeover: the spindle still turns, nothing moved.
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  EXPECT_FALSE(m.hs().busy());
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 6000);
  EXPECT_EQ(m.at.feedback[kZ].position, z);
}

TEST(ChannelReposHeadstock, G77S1RestoresM3AfterCWasJoggedInRotaryMode) {
  Lathe m(kTurning +
          ".REPOS\n"
          "N10 G77 S1=0\n"
          "N11 G77 Z0 F3000\n"
          "N12 G77 X0 F3000 RTS\n");
  Interrupt(m, 3.0);
  const double x = m.at.feedback[kX].position;
  JogFor(m, kZ, +1, 0.2);
  // C-axis manual 4.2: jogging C selects rotary axis mode; the spindle stops for it.
  JogFor(m, kC, +1, 0.2);
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kPosition);
  Call(m, true, false);
  EXPECT_TRUE(m.channel->repos_status().spindle.adjust);
  EXPECT_FALSE(m.channel->repos_status().axes[kC].relevant);  // C was jogged freely
  EXPECT_FALSE(m.channel->conditions_restored());
  StartRepos(m);
  // G77 S1=0 switches back to spindle mode and waits for the programmed speed.
  ASSERT_TRUE(m.RunUntil([&] { return m.hs().mode() == HeadstockMode::kSpindle; }, 2.0));
  ASSERT_TRUE(m.RunUntil([&] { return m.mdt.setpoints[2].value == 6000; }, 2.0));
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kVelocity);
  EXPECT_TRUE(m.channel->repos_status().subroutine_running);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 6000);
  EXPECT_NEAR(m.at.feedback[kX].position, 100, 1e-9);
  EXPECT_NEAR(m.at.feedback[kZ].position, -50, 1e-9);
  EXPECT_GT(x, 20);
}

TEST(ChannelReposHeadstock, ManualExampleSubroutineRestoresTheSpindleInSpindleMode) {
  Lathe m(kTurning + ManualReposSubroutine());
  bool rotary_at_interruption = true;
  // The PLC stores the headstock's mode at the interruption (4.2 instruction) as event 30,
  // which the example's BES .ROTMOD 30 tests; event 29 "tool drive connected" skips MTP.
  m.channel->SetEventSource([&](int n) { return n == 29 || (n == 30 && rotary_at_interruption); });
  Interrupt(m, 3.0);
  rotary_at_interruption = m.hs().mode() == HeadstockMode::kRotary;
  EXPECT_FALSE(rotary_at_interruption);
  JogFor(m, kZ, +1, 0.2);
  m.channel->ManualSpindle(5);
  RunFor(m, 0.01);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 0);
  Call(m, true, false);
  StartRepos(m);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 6000);
  EXPECT_NEAR(m.at.feedback[kX].position, 100, 1e-9);
  EXPECT_NEAR(m.at.feedback[kZ].position, -50, 1e-9);
}

// ---- Interrupted in rotary axis mode ----

// A C-axis program: C from 0 to 300 deg at 3000 deg/min (50 deg/s).
const std::string kRotary =
    "N1 G00 X10 C0\n"
    "N2 G01 C300 F3000\n"
    "N3 RET\n";

void CWindow(ChannelConfig& c) { c.axes[kC].repos_window = 1.5; }  // Cxx.086 [deg]

TEST(ChannelReposHeadstock, RotaryModeMakesCAFeedAxisWithItsWindow) {
  Lathe m(kRotary, false, CWindow);
  Interrupt(m, 3.0);
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  const double c = CommandOf(m, kC);
  EXPECT_GT(c, 50);
  EXPECT_LT(c, 250);
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));  // 1 deg a press
  for (int k = 0; k < 5; ++k) JogFor(m, kC, +1, 0.05);
  EXPECT_NEAR(CommandOf(m, kC), c + 5, 1e-9);
  Call(m, true, false);
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kRepositioning);
  ReposStatus s = m.channel->repos_status();
  EXPECT_TRUE(s.axes[kC].relevant);
  EXPECT_NEAR(s.axes[kC].final_value, c, 1e-9);
  EXPECT_NEAR(s.axes[kC].distance_to_go, -5, 1e-9);
  EXPECT_TRUE(s.axes[kC].adjust);
  EXPECT_FALSE(s.spindle.relevant);  // 7.3: spindle mode was not there before
  EXPECT_FALSE(m.channel->conditions_restored());
  // Manual repositioning of C by jogging (3.3 instruction): 2 deg to go is outside 1.5 ...
  for (int k = 0; k < 3; ++k) JogFor(m, kC, -1, 0.05);
  EXPECT_TRUE(m.channel->repos_status().axes[kC].adjust);
  EXPECT_FALSE(m.channel->conditions_restored());
  // ... 1 deg is within it (6.1).
  JogFor(m, kC, -1, 0.05);
  EXPECT_FALSE(m.channel->repos_status().axes[kC].adjust);
  EXPECT_TRUE(m.channel->conditions_restored());
  // C is endless: it may pass its target, and then it must be adjusted again (3.2).
  for (int k = 0; k < 3; ++k) JogFor(m, kC, -1, 0.05);
  EXPECT_NEAR(CommandOf(m, kC), c - 2, 1e-9);
  EXPECT_TRUE(m.channel->repos_status().axes[kC].adjust);
  EXPECT_FALSE(m.channel->conditions_restored());
}

TEST(ChannelReposHeadstock, CWithTravelLimitsStopsAtItsTargetWhenJogged) {
  Lathe m(kRotary, false, [](ChannelConfig& c) {
    c.axes[kC].travel_min = -1000;
    c.axes[kC].travel_max = 1000;
  });
  Interrupt(m, 3.0);
  const double c = CommandOf(m, kC);
  JogFor(m, kC, +1, 0.2);
  EXPECT_GT(CommandOf(m, kC), c + 10);
  Call(m, true, false);
  // 3.2: held towards the target, the axis stops on it.
  JogFor(m, kC, -1, 1.0);
  EXPECT_NEAR(CommandOf(m, kC), c, 1e-9);
  EXPECT_TRUE(m.channel->conditions_restored());
  // Continuing needs no subroutine: the program finishes its C move from there.
  StartRepos(m);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.at.feedback[2].position, 300, 1e-9);
}

TEST(ChannelReposHeadstock, G77S1AfterRotaryModeFailsAtItsBlockStart) {
  Lathe m(kRotary +
          ".REPOS\n"
          "N10 G77 S1=0\n"
          "N11 G77 C0 F5000 RTS\n");
  Interrupt(m, 3.0);
  JogFor(m, kC, +1, 0.2);
  const double c = CommandOf(m, kC);
  Call(m, true, false);
  StartRepos(m);
  RunFor(m, 0.5);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgReposMode);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("p.mtc:5:"));  // N10
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);  // no changeover to spindle mode
  EXPECT_FALSE(m.hs().busy());
  EXPECT_NEAR(m.at.feedback[2].position, c, 1e-9);
}

TEST(ChannelReposHeadstock, ManualExampleSubroutineReturnsCWithG77C0) {
  Lathe m(kRotary + ManualReposSubroutine(), false, CWindow);
  bool rotary_at_interruption = false;
  m.channel->SetEventSource([&](int n) { return n == 29 || (n == 30 && rotary_at_interruption); });
  Interrupt(m, 3.0);
  rotary_at_interruption = m.hs().mode() == HeadstockMode::kRotary;
  ASSERT_TRUE(rotary_at_interruption);
  const double c = CommandOf(m, kC);
  JogFor(m, kX, +1, 0.2);
  JogFor(m, kC, +1, 0.2);
  EXPECT_GT(CommandOf(m, kC), c + 10);
  Call(m, true, false);
  StartRepos(m);
  // N0014 G77 C0 F5000 S2=0 returns C (S2 is no spindle of this channel: nothing to restore),
  // then the feed axes; at RTS the program goes on with its C move.
  double c_seen_min = 1e9;
  while (m.channel->repos_status().subroutine_running && m.t < 30) {
    m.Tick();
    c_seen_min = std::min(c_seen_min, m.at.feedback[2].position);
  }
  EXPECT_NEAR(c_seen_min, c, 1e-6);  // back to the interruption point, not past it
  EXPECT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.at.feedback[2].position, 300, 1e-9);
  EXPECT_NEAR(m.at.feedback[kX].position, 10, 1e-9);
}

TEST(ChannelReposHeadstock, SubroutineLeavingCInSpindleModeIsRefusedAtItsReturn) {
  Lathe m(kRotary +
          ".REPOS\n"
          "N10 G77 Z0 F3000\n"
          "N11 G77 X0 F3000 RTS\n");
  Interrupt(m, 3.0);
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  JogFor(m, kZ, +1, 0.2);
  m.channel->ManualSpindle(5);  // spindle mode: C is no positioned axis any more
  RunFor(m, 0.05);
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  Call(m, true, false);
  StartRepos(m);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgReposNotRestored);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("C not in rotary axis mode"));
  EXPECT_NEAR(m.at.feedback[kZ].position, 0, 1e-9);  // the subroutine's own moves ran
}

TEST(ChannelReposHeadstock, StartWithCInSpindleModeAndNoSubroutineIsRefused) {
  Lathe m(kRotary);
  Interrupt(m, 3.0);
  JogFor(m, kZ, +1, 0.2);
  Call(m, true, false);
  JogFor(m, kZ, -1, 1.0);
  ASSERT_TRUE(m.channel->conditions_restored());
  m.channel->ManualSpindle(5);
  RunFor(m, 0.05);
  EXPECT_FALSE(m.channel->conditions_restored());
  StartRepos(m);
  RunFor(m, 0.1);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgReposNoSubroutine);
}

// ---- The spindle keys (3.3) ----

TEST(ChannelReposHeadstock, SpindleKeysRestoreM3OnlyByM3OrM4) {
  Lathe m(kTurning);
  Interrupt(m, 3.0);
  JogFor(m, kZ, +1, 0.2);
  m.channel->ManualSpindle(5);
  RunFor(m, 0.01);
  Call(m, true, false);
  EXPECT_TRUE(m.channel->repos_status().spindle.adjust);
  // M19 is not in the table for M03: it is the jog key (the jogging spindle position, 90).
  m.channel->ManualSpindle(19);
  RunFor(m, 0.05);
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kPosition);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 90);
  EXPECT_TRUE(m.channel->repos_status().spindle.adjust);
  // M4 restores M03 at the programmed speed, forwards.
  m.channel->ManualSpindle(4);
  RunFor(m, 0.05);
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kVelocity);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 6000);
  EXPECT_FALSE(m.channel->repos_status().spindle.adjust);
  JogFor(m, kZ, -1, 1.0);
  EXPECT_TRUE(m.channel->conditions_restored());
}

TEST(ChannelReposHeadstock, SpindleKeyM5RestoresAStoppedSpindle) {
  Lathe m(
      "N1 M5\n"
      "N2 G01 X100 F600\n"
      "N3 RET\n");
  Interrupt(m, 3.0);
  JogFor(m, kZ, +1, 0.2);
  m.channel->ManualSpindle(3);  // the operator turns the spindle to look at the part
  RunFor(m, 0.05);
  Call(m, true, false);
  JogFor(m, kZ, -1, 1.0);
  EXPECT_FALSE(m.channel->conditions_restored());  // the spindle turns: not as before
  m.channel->ManualSpindle(3);                     // M3 does not restore M05
  RunFor(m, 0.05);
  EXPECT_FALSE(m.channel->conditions_restored());
  m.channel->ManualSpindle(5);
  RunFor(m, 0.05);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 0);
  EXPECT_TRUE(m.channel->conditions_restored());
}

TEST(ChannelReposHeadstock, SpindleKeyM19PositionsToTheInterruptedPositionAndCrestWaits) {
  // M19 orients the spindle to 0 deg, then X runs.
  Lathe m(
      "N1 M19\n"
      "N2 G01 X100 F600\n"
      "N3 RET\n");
  Interrupt(m, 3.0);
  ASSERT_EQ(m.mdt.setpoints[2].mode, DriveMode::kPosition);
  ASSERT_DOUBLE_EQ(m.mdt.setpoints[2].value, 0);
  JogFor(m, kZ, +1, 0.2);
  m.channel->ManualSpindle(3);
  RunFor(m, 0.05);
  Call(m, true, false);
  JogFor(m, kZ, -1, 1.0);
  EXPECT_EQ(m.channel->repos_status().spindle.command_m, 19);
  EXPECT_FALSE(m.channel->conditions_restored());
  // M4 is not in the table for M19: the jog key.
  m.channel->ManualSpindle(4);
  RunFor(m, 0.05);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, -600);
  EXPECT_FALSE(m.channel->conditions_restored());
  // AxxC.M19 positions to the position of the interruption (0), not the jogging position (90);
  // CREST waits until the drive reports it in position.
  m.channel->ManualSpindle(19);
  for (int k = 0; k < 400; ++k) {
    m.Tick();
    m.at.feedback[2].status &= ~drive_status::kInPosition;  // still positioning
  }
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kPosition);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 0);
  EXPECT_FALSE(m.channel->conditions_restored());
  EXPECT_TRUE(m.channel->repos_status(&m.at).spindle.adjust);
  RunFor(m, 0.01);  // in position now
  EXPECT_TRUE(m.channel->conditions_restored());
  EXPECT_FALSE(m.channel->repos_status(&m.at).spindle.adjust);
}

// ---- 7.3: the spindle does not count after rotary axis mode ----

TEST(ChannelReposHeadstock, CrestIgnoresTheSpindleAfterRotaryMode) {
  // The spindle turned before the C program, which stopped it for rotary axis mode.
  Lathe m("N0 M3 S1000\nN01 G04 F0.1\n" + kRotary, false, CWindow);
  Interrupt(m, 3.5);
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  const double c = CommandOf(m, kC);
  JogFor(m, kZ, +1, 0.2);
  Call(m, true, false);
  EXPECT_FALSE(m.channel->repos_status(&m.at).spindle.relevant);
  EXPECT_FALSE(m.channel->repos_status(&m.at).spindle.adjust);
  JogFor(m, kZ, -1, 1.0);
  // Restored with the spindle not turning (its drive positions C): it does not count.
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kPosition);
  EXPECT_TRUE(m.channel->conditions_restored());
  // M5 is no restore key here: it selects spindle mode (C-axis manual 4.2) and stops the
  // spindle; C is then no longer the positioned rotary axis it was: not restored.
  m.channel->ManualSpindle(5);
  RunFor(m, 0.05);
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kSpindle);
  EXPECT_FALSE(m.channel->conditions_restored());
  EXPECT_TRUE(m.channel->repos_status().axes[kC].adjust);
  // Jogging C selects rotary axis mode again; one degree there and back: restored.
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  JogFor(m, kC, +1, 0.05);
  ASSERT_EQ(m.hs().mode(), HeadstockMode::kRotary);
  JogFor(m, kC, -1, 0.05);
  EXPECT_NEAR(CommandOf(m, kC), c, 1.5);
  EXPECT_TRUE(m.channel->conditions_restored());
  // A spindle key that would have restored M03 had the headstock been in spindle mode is a
  // jog key: the spindle turns at its jogging speed, not at 1000 rpm.
  m.channel->ManualSpindle(3);
  RunFor(m, 0.05);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 600);
}

}  // namespace
}  // namespace vmt::control::channel
