// Repositioning and NC-block restart on the channel (REPOS manual): the situation in which the
// PLC's call counts (2.1, 7.1), PxxS.REPOS and PxxS.CREST (7.2, 7.3), manual repositioning
// without passing the target and within the zone (3.2), the spindle keys (3.3), the REPOS
// subroutine with G77 and RTS (4.1, 4.2) and its errors, zero offset and tool edits (2.5),
// Cxx.086 (6.1), Bxx.032 / Bxx.036 (6.1), MTP, and PathGuard on the approach moves.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

// X from 0 to 100 at 10 mm/s, then Z to -50; the REPOS subroutine returns Z first, then X.
const char* kProgram =
    "N1 M3 S1000\n"
    "N2 G01 X100 F600\n"
    "N3 G01 Z-50\n"
    "N4 RET\n"
    ".REPOS\n"
    "N10 G77 S1=0\n"
    "N11 G77 Z0 F3000\n"
    "N12 G77 X0 F3000 RTS\n";

/// The ideal machine, with a spindle that reaches its command at once (at speed, in position).
void Tick(Machine& m) {
  m.Tick();
  m.Answer(2, test_support::IdealDrive::InstantSpindle());
}

void RunFor(Machine& m, double s) {
  for (int i = 0; i < s / 250e-6; ++i) Tick(m);
}

void JogFor(Machine& m, size_t axis, int direction, double s) {
  m.channel->Jog(axis, direction);
  RunFor(m, s);
  m.channel->Jog(axis, 0);
  RunFor(m, 0.1);
}

/// Runs the program 3 s (X at about 30), holds it, goes to manual mode and jogs Z away 5 mm.
double InterruptAndJogAway(Machine& m) {
  m.channel->Start();
  RunFor(m, 3.0);
  m.channel->Stop();
  RunFor(m, 0.2);
  const double x = m.X();
  EXPECT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  JogFor(m, 1, +1, 0.2);
  EXPECT_GT(m.Z(), 4);
  EXPECT_EQ(m.X(), x);
  return x;
}

void Call(Machine& m, bool repositioning, bool restart) {
  m.channel->SetReposition(repositioning, restart);
  RunFor(m, 0.01);
}

TEST(ChannelRepositioning, TheCallCountsOnlyAfterInterruptionAndJoggingAway) {
  Machine m(kProgram);
  // Nothing interrupted: ignored, PxxS.REPOS 0.
  Call(m, true, false);
  EXPECT_FALSE(m.channel->repos_allowed());
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kNone);
  m.channel->Start();
  RunFor(m, 1.0);
  EXPECT_FALSE(m.channel->repos_allowed());  // running
  m.channel->Stop();
  RunFor(m, 0.2);
  EXPECT_TRUE(m.channel->repos_allowed());  // 7.2: set at each interruption
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  // Interrupted, but the tool is still on the contour: ignored (2.1 warning).
  Call(m, true, false);
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kNone);
  EXPECT_FALSE(m.channel->conditions_restored());
  JogFor(m, 1, +1, 0.1);
  RunFor(m, 0.01);
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kRepositioning);
  // Both signals at once ask for neither; RESTA alone is the restart.
  Call(m, true, true);
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kNone);
  Call(m, false, true);
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kRestart);
  // Control-Reset ends the interruption: PxxS.REPOS 0, the call is ignored again.
  m.channel->Reset();
  RunFor(m, 0.01);
  EXPECT_FALSE(m.channel->repos_allowed());
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kNone);
}

TEST(ChannelRepositioning, ManualJogStopsAtTheTargetAndStaysInTheZone) {
  Machine m(kProgram);
  const double x = InterruptAndJogAway(m);
  const double z_away = m.Z();
  Call(m, true, false);
  ReposStatus s = m.channel->repos_status();
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_NEAR(s.axes[0].final_value, x, 1e-9);
  EXPECT_FALSE(s.axes[0].adjust);
  EXPECT_NEAR(s.axes[1].final_value, 0, 1e-9);
  EXPECT_NEAR(s.axes[1].distance_to_go, -z_away, 1e-9);
  EXPECT_TRUE(s.axes[1].adjust);
  EXPECT_FALSE(m.channel->conditions_restored());
  // 3.2: away from the target the zone ends where the function was called.
  JogFor(m, 1, +1, 0.5);
  EXPECT_NEAR(m.Z(), z_away, 1e-9);
  // Towards it the axis stops exactly on it, however long the key is held.
  JogFor(m, 1, -1, 1.0);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
  EXPECT_TRUE(m.channel->conditions_restored());  // 7.3: spindle still at M3 S1000
  EXPECT_FALSE(m.channel->repos_status().axes[1].adjust);
  // Increments are cut at the target too.
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  JogFor(m, 1, -1, 0.2);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
  // X is on its target: it may not move either way (the zone is one point).
  JogFor(m, 0, +1, 0.2);
  EXPECT_NEAR(m.X(), x, 1e-9);
  // 7.1: the PLC withdraws the call: jog mode again, the target may be passed; CREST is reset.
  Call(m, false, false);
  EXPECT_FALSE(m.channel->conditions_restored());
  JogFor(m, 1, -1, 0.2);
  EXPECT_NEAR(m.Z(), -1, 1e-9);
}

// 7.1 instruction: withdrawn in manual mode, repositioning ends after the motion under way: the
// jog still moving when the PLC withdraws PxxC.REPOS stops at the target as repositioning's
// does; only the next jog is a plain jog that may pass it.
TEST(ChannelRepositioning, WithdrawnInManualModeItEndsAfterTheCurrentMotion) {
  Machine m(kProgram);
  InterruptAndJogAway(m);
  Call(m, true, false);
  m.channel->Jog(1, -1);  // Z back towards its target 0, the key held
  RunFor(m, 0.03);
  ASSERT_GT(m.Z(), 2);  // on its way
  Call(m, false, false);
  EXPECT_FALSE(m.channel->conditions_restored());  // 7.3: reset when withdrawn
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kRepositioning);  // the motion goes on
  RunFor(m, 1.0);
  EXPECT_NEAR(m.Z(), 0, 1e-9);  // stopped at the target, the key still held
  EXPECT_FALSE(m.channel->conditions_restored());
  m.channel->Jog(1, 0);
  RunFor(m, 0.1);
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kNone);  // the press is over: jog mode
  EXPECT_FALSE(m.channel->conditions_restored());
  JogFor(m, 1, -1, 0.2);  // the next jog passes the target
  EXPECT_LT(m.Z(), -1);
}

TEST(ChannelRepositioning, ContinuingAfterManualRepositioningNeedsNoSubroutineAndNoJump) {
  // No REPOS subroutine: the operator restores everything, Start continues at the point.
  Machine m("N1 G01 X100 F600\nN2 RET\n");
  const double x = InterruptAndJogAway(m);
  Call(m, true, false);
  m.channel->SetJogMode(0);
  JogFor(m, 1, -1, 1.0);
  ASSERT_TRUE(m.channel->conditions_restored());
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  RunFor(m, 0.05);
  EXPECT_FALSE(m.channel->repos_allowed());  // 7.2: reset when the program resumes
  EXPECT_GT(m.X(), x);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
}

TEST(ChannelRepositioning, StartWithoutSubroutineAndNotRestoredIsRefused) {
  Machine m("N1 G01 X100 F600\nN2 RET\n");
  InterruptAndJogAway(m);
  Call(m, true, false);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  const double z = m.Z();
  m.channel->Start();
  RunFor(m, 0.1);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgReposNoSubroutine);
  EXPECT_EQ(m.Z(), z);
}

TEST(ChannelRepositioning, SubroutineReturnsTheAxesAndTheProgramGoesOnWithoutANewStart) {
  Machine m(kProgram);
  const double x = InterruptAndJogAway(m);
  // The operator stopped the spindle while the program was interrupted.
  m.channel->ManualSpindle(5);
  RunFor(m, 0.01);
  EXPECT_EQ(m.mdt.setpoints[2].value, 0);
  Call(m, true, false);
  EXPECT_FALSE(m.channel->conditions_restored());
  EXPECT_TRUE(m.channel->repos_status().spindle.adjust);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  RunFor(m, 0.05);
  EXPECT_TRUE(m.channel->repos_allowed());  // the subroutine runs: still 1 (7.4)
  EXPECT_TRUE(m.channel->repos_status().subroutine_running);
  EXPECT_EQ(m.mdt.setpoints[2].value, 6000);  // G77 S1=0: M3 S1000 again
  // G77 Z0 first: X stays until Z is back.
  double z_first = 1e9;
  while (m.channel->repos_allowed() && m.t < 30) {
    Tick(m);
    if (std::abs(m.X() - x) > 1e-9) z_first = std::min(z_first, std::abs(m.Z()));
  }
  EXPECT_LT(z_first, 1e-9);
  EXPECT_EQ(m.channel->state(), ChannelState::kRunning);  // went on at RTS
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
}

TEST(ChannelRepositioning, RestartRunsTheInterruptedBlockFromItsStart) {
  Machine m(kProgram);
  InterruptAndJogAway(m);
  Call(m, false, true);
  const ReposStatus s = m.channel->repos_status();
  EXPECT_NEAR(s.axes[0].final_value, 0, 1e-9);  // N2 started at X0
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  double x_min = 1e9;
  while (m.channel->state() == ChannelState::kRunning && m.t < 60) {
    Tick(m);
    x_min = std::min(x_min, m.X());
  }
  EXPECT_NEAR(x_min, 0, 1e-9);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
}

TEST(ChannelRepositioning, ZeroOffsetEditMovesTheInterruptionPointAndTheContour) {
  Machine m(
      "N0 G54 G00 X0 Z0\nN1 G01 X100 F600\nN2 G01 Z-50\nN3 RET\n"
      ".REPOS\nN11 G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n",
      5, 100, WithOffsetsAndTools);
  const double x = InterruptAndJogAway(m);
  // 2.5: the operator shifts G54 by 1 mm in Z and -0.5 in X.
  ASSERT_TRUE(m.channel->SetZeroOffset(54, 1, 101));
  ASSERT_TRUE(m.channel->SetZeroOffset(54, 0, 4.5));
  Call(m, true, false);
  const ReposStatus s = m.channel->repos_status();
  EXPECT_NEAR(s.axes[0].final_value, x - 0.5, 1e-9);
  EXPECT_NEAR(s.axes[1].final_value, 101, 1e-9);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 104.5, 1e-9);  // the rest of the contour moved with the offset
  EXPECT_NEAR(m.Z(), 51, 1e-9);
}

TEST(ChannelRepositioning, ToolWearEditShiftsTheTargets) {
  Machine m(
      "N0 T2 D1 G48 G00 X1.5 Z-4\nN1 G01 X100 F600\nN2 RET\n"
      ".REPOS\nN11 G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n",
      0, 0, WithOffsetsAndTools);
  const double x = InterruptAndJogAway(m);
  // The measured part is 0.1 mm too large in X: the tool's X length grows by 0.05.
  ASSERT_TRUE(m.channel->SetToolLength(2, 1, 0, 1.55));
  Call(m, true, false);
  EXPECT_NEAR(m.channel->repos_status().axes[0].final_value, x - 0.05, 1e-9);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 100 - 1.55, 1e-9);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
}

TEST(ChannelRepositioning, G77ErrorsAtTheBlockStart) {
  {  // 4.2: a feed axis without F
    Machine m("N1 G01 X100 F600\nN2 RET\n.REPOS\nN11 G77 Z0\nN12 RTS\n");
    InterruptAndJogAway(m);
    const double z = m.Z();
    Call(m, true, false);
    ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
    m.channel->Start();
    RunFor(m, 0.1);
    EXPECT_EQ(m.channel->error_number(), kMsgReposNoFeed);
    EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("p.mtc:4:"));
    EXPECT_EQ(m.Z(), z);
  }
  {  // 7.1: the PLC withdrew the call while the subroutine runs
    Machine m("N1 G01 X100 F600\nN2 RET\n.REPOS\nN10 G04 F0.5\nN11 G77 Z0 F3000 RTS\n");
    InterruptAndJogAway(m);
    Call(m, true, false);
    ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
    m.channel->Start();
    RunFor(m, 0.1);
    m.channel->SetReposition(false, false);
    RunFor(m, 1.0);
    EXPECT_EQ(m.channel->error_number(), kMsgReposNotActive);
    EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("p.mtc:5:"));
  }
  {  // G77 in a program that nothing interrupted
    Machine m("N1 G77 X0 F1000\nN2 RET\n");
    m.channel->Start();
    RunFor(m, 0.1);
    EXPECT_EQ(m.channel->error_number(), kMsgReposNotActive);
  }
}

TEST(ChannelRepositioning, SubroutineWithoutTheSpindleIsRefusedAtItsReturn) {
  Machine m("N1 M3 S1000\nN2 G01 X100 F600\nN3 RET\n.REPOS\nN11 G77 Z0 F3000 RTS\n");
  InterruptAndJogAway(m);
  m.channel->ManualSpindle(5);
  Call(m, true, false);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  RunFor(m, 2.0);
  EXPECT_EQ(m.channel->error_number(), kMsgReposNotRestored);
  EXPECT_NEAR(m.Z(), 0, 1e-9);  // the subroutine's own moves ran
}

TEST(ChannelRepositioning, SpindleKeysRestoreTheStateOfTheTable) {
  Machine m(kProgram, 0, 0, [](ChannelConfig& c) { c.spindle.jog_per_s = 600; });
  InterruptAndJogAway(m);
  m.channel->ManualSpindle(5);
  RunFor(m, 0.01);
  // Without the function the keys are jog keys: M4 at the jogging speed.
  m.channel->ManualSpindle(4);
  RunFor(m, 0.01);
  EXPECT_EQ(m.mdt.setpoints[2].value, -600);
  Call(m, true, false);
  // 3.3: M03 before: AxxC.M4 restores it too, at the programmed speed.
  m.channel->ManualSpindle(4);
  RunFor(m, 0.01);
  EXPECT_EQ(m.mdt.setpoints[2].value, 6000);
  EXPECT_FALSE(m.channel->repos_status().spindle.adjust);
  // M5 is not in the table for M03: a jog key again.
  m.channel->ManualSpindle(5);
  RunFor(m, 0.01);
  EXPECT_EQ(m.mdt.setpoints[2].value, 0);
  EXPECT_TRUE(m.channel->repos_status().spindle.adjust);
  m.channel->ManualSpindle(3);
  JogFor(m, 1, -1, 1.0);
  EXPECT_TRUE(m.channel->conditions_restored());
}

TEST(ChannelRepositioning, WindowCxx086DecidesWhenAnAxisIsAdjusted) {
  auto configure = [](ChannelConfig& c) {
    c.axes[0].repos_window = 0;  // X ignored
    c.axes[1].repos_window = 2;
  };
  Machine m("N1 G01 X100 F600\nN2 RET\n", 0, 0, configure);
  const double x = InterruptAndJogAway(m);
  JogFor(m, 0, +1, 0.1);  // X off its point too: ignored by CREST
  Call(m, true, false);
  EXPECT_FALSE(m.channel->conditions_restored());
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement1000));
  while (m.Z() > 1.5) JogFor(m, 1, -1, 0.1);
  EXPECT_TRUE(m.channel->conditions_restored());  // within 2 mm
  const ReposStatus s = m.channel->repos_status();
  EXPECT_FALSE(s.axes[0].relevant);
  EXPECT_FALSE(s.axes[1].adjust);
  // Start closes the rest to the exact point before the block goes on: no jump.
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  double step = 0, last_x = m.X(), last_z = m.Z();
  while (m.channel->state() == ChannelState::kRunning && m.t < 60) {
    Tick(m);
    step = std::max({step, std::abs(m.X() - last_x), std::abs(m.Z() - last_z)});
    last_x = m.X(), last_z = m.Z();
  }
  EXPECT_LT(step, 0.2);  // below 800 mm/s at the drive tick
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
  (void)x;
}

TEST(ChannelRepositioning, ProcessParametersBxx032AndBxx036) {
  {  // Bxx.036 yes: jogging the interrupted program resets it
    Machine m(kProgram, 0, 0, [](ChannelConfig& c) { c.process.jogging_causes_reset = true; });
    m.channel->Start();
    RunFor(m, 1.0);
    m.channel->Stop();
    RunFor(m, 0.2);
    ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
    JogFor(m, 1, +1, 0.1);
    EXPECT_FALSE(m.channel->repos_allowed());
    Call(m, true, false);
    EXPECT_EQ(m.channel->repos_function(), ReposFunction::kNone);
  }
  {  // Bxx.032 yes: only the reverse program continues it
    Machine m(kProgram, 0, 0, [](ChannelConfig& c) { c.process.reverse_program_required = true; });
    InterruptAndJogAway(m);
    Call(m, true, false);
    EXPECT_TRUE(m.channel->repos_allowed());
    EXPECT_EQ(m.channel->repos_function(), ReposFunction::kNone);
  }
}

TEST(ChannelRepositioning, MtpOutputsTheToolOfTheInterruption) {
  Machine m("N1 T5\nN2 G01 X100 F600\nN3 RET\n.REPOS\nN10 MTP\nN11 MRY G77 Z0 F3000 RTS\n", 0, 0,
            [](ChannelConfig& c) { c.aux_handshake = true; });
  m.channel->Start();
  RunFor(m, 0.01);
  ASSERT_EQ(m.channel->aux_output().size(), 1u);
  m.channel->AcknowledgeAux();
  InterruptAndJogAway(m);  // Start again: the program already runs
  Call(m, true, false);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  RunFor(m, 0.05);
  ASSERT_EQ(m.channel->aux_output().size(), 1u);
  EXPECT_EQ(m.channel->aux_output()[0].letter, 'T');
  EXPECT_EQ(m.channel->aux_output()[0].value, 5);
  const double z = m.Z();
  RunFor(m, 0.2);
  EXPECT_EQ(m.Z(), z);  // waits for the turret
  m.channel->AcknowledgeAux();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

/// A wall at Z = 2 for the X axis' tool below X = 50: the Z return must come after X.
struct Shoulder : PathGuard {
  PathCheck CheckMove(const std::vector<double>& from, const std::vector<double>& to) override {
    ++checks;
    PathCheck c;
    c.min_clearance = 1;
    const bool crosses = to[1] < 2 && from[1] >= 2 && std::min(from[0], to[0]) < 50;
    if (!crosses) return c;
    c.clear = false;
    c.part_a = "tool", c.part_b = "shoulder";
    c.position = from;
    c.position[1] = 2;
    c.min_clearance = 0;
    return c;
  }
  int checks = 0;
};

TEST(ChannelRepositioning, PathGuardStopsAG77MoveBeforeItStarts) {
  Shoulder guard;
  Machine m(kProgram);
  m.channel->SetPathGuard(&guard);
  InterruptAndJogAway(m);
  guard.checks = 0;
  Call(m, true, false);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  const double z = m.Z();
  m.channel->Start();
  RunFor(m, 1.0);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgCollision);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("collision ahead (G77)"));
  EXPECT_EQ(m.Z(), z);  // never started
  EXPECT_GE(guard.checks, 1);
  const auto records = m.channel->TakeGuardRecords();
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(records.back().move, "G77");
  EXPECT_TRUE(records.back().stopped);
}

/// kProgram with the REPOS subroutine `subroutine` (its blocks from `.REPOS` on).
std::string WithSubroutine(const std::string& subroutine) {
  const std::string program = kProgram;
  return program.substr(0, program.find(".REPOS")) + subroutine;
}

// Issue 6: the REPOS subroutine's own moves are approach moves, checked whole before they start
// as G77's are: X up out of the way is clear, Z down onto the shoulder is not.
TEST(ChannelRepositioning, PathGuardChecksTheSubroutinesOwnMoves) {
  Shoulder guard;
  Machine clear(WithSubroutine(".REPOS\nN10 G77 S1=0\nN11 G00 X60\nN12 G77 Z0 F3000\n"
                               "N13 G77 X0 F3000 RTS\n"));
  clear.channel->SetPathGuard(&guard);
  const double x = InterruptAndJogAway(clear);
  Call(clear, true, false);
  ASSERT_TRUE(clear.channel->SetMode(ChannelMode::kAutomatic));
  clear.channel->TakeGuardRecords();
  clear.channel->Start();
  RunFor(clear, 3.0);
  EXPECT_NE(clear.channel->state(), ChannelState::kError) << clear.channel->error();
  const auto records = clear.channel->TakeGuardRecords();
  ASSERT_GE(records.size(), 3u);
  EXPECT_EQ(records[0].move, "REPOS subroutine");
  EXPECT_TRUE(records[0].check.clear);
  EXPECT_NEAR(records[0].from[0], x, 1e-9);
  EXPECT_NEAR(records[0].to[0], 60, 1e-9);
  EXPECT_EQ(records[1].move, "G77");

  Machine hit(WithSubroutine(".REPOS\nN10 G77 S1=0\nN11 G01 Z1 F1000\nN12 G77 Z0 F3000\n"
                             "N13 G77 X0 F3000 RTS\n"));
  hit.channel->SetPathGuard(&guard);
  InterruptAndJogAway(hit);
  Call(hit, true, false);
  ASSERT_TRUE(hit.channel->SetMode(ChannelMode::kAutomatic));
  const double z = hit.Z();
  hit.channel->Start();
  RunFor(hit, 1.0);
  EXPECT_EQ(hit.channel->error_number(), kMsgCollision);
  EXPECT_THAT(hit.channel->error(), ::testing::HasSubstr("collision ahead (REPOS subroutine)"));
  EXPECT_EQ(hit.Z(), z);  // never started
}

// An arc of the REPOS subroutine is checked along its curve, as chords within 1 um of it: the
// half circles start and end above the shoulder (which ends at X50); the one that dips 5 mm
// into it on the way is refused, the other is clear chord by chord.
TEST(ChannelRepositioning, PathGuardChecksASubroutineArcAlongItsCurve) {
  int refused = 0;
  for (const char* arc : {"G02", "G03"}) {
    Shoulder guard;
    Machine m(WithSubroutine(std::string(".REPOS\nN10 G77 S1=0\nN11 G00 X40 Z5\nN12 G18 ") +
                             arc + " X50 Z5 R5 F1000\nN13 G77 Z0 F3000\nN14 G77 X0 F3000 RTS\n"));
    m.channel->SetPathGuard(&guard);
    InterruptAndJogAway(m);
    Call(m, true, false);
    ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
    m.channel->TakeGuardRecords();
    m.channel->Start();
    RunFor(m, 1.5);
    const auto records = m.channel->TakeGuardRecords();
    ASSERT_GE(records.size(), 2u) << arc << ": " << m.channel->error();
    EXPECT_EQ(records[1].move, "REPOS subroutine");
    if (records[1].stopped) {
      ++refused;
      EXPECT_EQ(m.channel->error_number(), kMsgCollision);
      EXPECT_NEAR(m.X(), 40, 1e-9);  // never started
      EXPECT_NEAR(m.Z(), 5, 1e-9);
      continue;
    }
    EXPECT_GE(records[1].checks, 78) << arc;  // 15.7 mm in chords of 0.2 mm at most
    EXPECT_TRUE(records[1].check.clear);
    EXPECT_NE(m.channel->state(), ChannelState::kError) << m.channel->error();
  }
  EXPECT_EQ(refused, 1);
}

TEST(ChannelRepositioning, SubroutineFromProgram99AndReverseDuringIt) {
  auto main = nc::ParseProgram("N1 G01 X100 F600\nN2 RET\n.HOME\nN90 G00 X0\nN91 RET\n", "p.mtc",
                               nc::Dialect::kMtc200);
  auto p99 = nc::ParseProgram(".REPOS\nN10 G04 F5\nN11 G77 Z0 F3000 RTS\n", "99.mtc",
                              nc::Dialect::kMtc200);
  ASSERT_TRUE(main.ok() && p99.ok());
  Machine m("N1 RET\n");
  ChannelConfig config;
  config.axes = {Axis("X", 0, 400), Axis("Z", 1, 500)};
  config.spindle_drive = 2;
  m.channel = std::make_unique<Channel>(
      config, std::vector<const nc::Program*>{&main.program, &p99.program});
  InterruptAndJogAway(m);
  Call(m, true, false);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  RunFor(m, 0.5);  // in program 99's dwell
  EXPECT_TRUE(m.channel->repos_status().subroutine_running);
  // 4.1: a reverse in the REPOS subroutine goes to the reverse program.
  m.channel->Stop();
  RunFor(m, 0.01);
  ASSERT_TRUE(m.channel->Reverse());
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 0, 1e-9);
  EXPECT_FALSE(m.channel->repos_allowed());
}

TEST(ChannelRepositioning, ToolStorageAxisCountsWithBxx045) {
  for (const bool bxx045 : {false, true}) {
    Machine m(kProgram, 0, 0, [&](ChannelConfig& c) {
      c.tool_storage_drive = 3;
      c.process.reposition_tool_storage = bxx045;
    });
    m.Resize(4);  // the PLC's turret: the test moves it
    m.at.feedback[3].position = 60;  // at station 3
    InterruptAndJogAway(m);
    m.at.feedback[3].position = 90;  // the operator indexed the turret on (PxxC.MGPOS)
    Call(m, true, false);
    JogFor(m, 1, -1, 1.0);  // Z back: the feed axes and the spindle are restored
    EXPECT_EQ(m.channel->conditions_restored(), !bxx045) << "Bxx.045 " << bxx045;
    EXPECT_EQ(m.channel->repos_status().tool_storage_adjust, bxx045);
    m.at.feedback[3].position = 60.01;  // back at its station
    RunFor(m, 0.01);
    EXPECT_TRUE(m.channel->conditions_restored());
    EXPECT_FALSE(m.channel->repos_status().tool_storage_adjust);
  }
}

}  // namespace
}  // namespace vmt::control::channel
