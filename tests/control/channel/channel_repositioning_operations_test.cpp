// Repositioning and NC-block restart beyond the automatic interruption (REPOS manual): an MDI
// sequence ("execute in manual mode") and a single-block (semi-automatic) program as the
// interrupted program (2.1), a stop and jogging during the REPOS subroutine (2.3, 7.1-7.4), the
// subroutine's @ variables as the interrupted program's (4.1, 8.3), and the tool storage axis'
// jog keys PxxC.MGPOS / MGNEG on an NC-controlled tool storage axis (3.4, 4.2, 6.2).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "channel_test_support.hpp"
#include "nc_turret_machine.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

const char* kSubroutine =
    ".REPOS\n"
    "N10 G77 S1=0\n"
    "N11 G77 Z0 F3000\n"
    "N12 G77 X0 F3000 RTS\n";

/// The ideal machine, with a spindle that reaches its command at once.
void Tick(Machine& m) {
  m.Tick();
  m.Answer(2, test_support::IdealDrive::InstantSpindle());
  // The tool storage axis (drive 3) of the tests that have one follows its setpoint.
  if (m.mdt.setpoints.size() > 3) m.Answer(3, test_support::IdealDrive::Follow());
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

void Call(Machine& m, bool repositioning, bool restart) {
  m.channel->SetReposition(repositioning, restart);
  RunFor(m, 0.01);
}

/// Runs to the end, returning the largest step of X or Z between two drive ticks.
double RunToEndMeasuringSteps(Machine& m) {
  double step = 0, x = m.X(), z = m.Z();
  while (m.channel->state() == ChannelState::kRunning && m.t < 60) {
    Tick(m);
    step = std::max({step, std::abs(m.X() - x), std::abs(m.Z() - z)});
    x = m.X(), z = m.Z();
  }
  return step;
}

/// 2.1: an MDI sequence held with feed hold, left for manual mode and jogged away from.
double InterruptMdiAndJogAway(Machine& m) {
  EXPECT_TRUE(m.channel->SetMode(ChannelMode::kMdi));
  EXPECT_TRUE(m.channel->Mdi("G01 X100 F600\nG01 Z-50\n"));
  m.channel->Start();
  RunFor(m, 3.0);
  m.channel->Stop();
  RunFor(m, 0.2);
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_TRUE(m.channel->repos_allowed());
  const double x = m.X();
  EXPECT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  JogFor(m, 1, +1, 0.2);
  EXPECT_GT(m.Z(), 4);
  return x;
}

TEST(ReposExecuteInManualMode, AnMdiHoldIsLeftForManualModeAndRepositionedByTheSubroutine) {
  Machine m(std::string("N1 RET\n") + kSubroutine);
  const double x = InterruptMdiAndJogAway(m);
  EXPECT_GT(x, 10);
  Call(m, true, false);
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kRepositioning);
  const ReposStatus s = m.channel->repos_status();
  EXPECT_EQ(s.program, "MDI");
  EXPECT_NEAR(s.axes[0].final_value, x, 1e-9);
  // The interrupted MDI sequence goes on in MDI (2.3: the most recently active mode).
  EXPECT_FALSE(m.channel->SetMode(ChannelMode::kAutomatic));
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kMdi));
  m.channel->Start();
  RunFor(m, 0.05);
  EXPECT_TRUE(m.channel->repos_status().subroutine_running);
  EXPECT_LT(RunToEndMeasuringSteps(m), 0.2);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
  EXPECT_FALSE(m.channel->repos_allowed());
}

TEST(ReposExecuteInManualMode, AnMdiHoldIsRepositionedInManualModeAndContinued) {
  Machine m("N1 RET\n");
  const double x = InterruptMdiAndJogAway(m);
  Call(m, false, true);  // restart: the MDI block started at X0
  EXPECT_NEAR(m.channel->repos_status().axes[0].final_value, 0, 1e-9);
  Call(m, true, false);
  JogFor(m, 1, -1, 1.0);
  EXPECT_NEAR(m.Z(), 0, 1e-9);  // 3.2: never past its target
  EXPECT_TRUE(m.channel->conditions_restored());
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kMdi));
  m.channel->Start();
  RunFor(m, 0.05);
  EXPECT_GT(m.X(), x);  // on from the interruption point, no new start
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
}

TEST(ReposExecuteInManualMode, ControlResetEndsTheInterruptedMdiSequence) {
  Machine m("N1 RET\n");
  InterruptMdiAndJogAway(m);
  m.channel->Reset();
  RunFor(m, 0.01);
  EXPECT_FALSE(m.channel->repos_allowed());
  Call(m, true, false);
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kNone);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));  // nothing interrupted any more
}

TEST(ReposSemiAutomatic, ASingleBlockHoldIsAnInterruption) {
  Machine m("N1 G01 X100 F600\nN2 G01 Z-50\nN3 RET\n");
  m.channel->SetSingleBlock(true);
  m.channel->Start();
  RunFor(m, 11.0);
  ASSERT_EQ(m.channel->state(), ChannelState::kHold);  // after N1
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_TRUE(m.channel->repos_allowed());  // 7.2
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  JogFor(m, 0, +1, 0.2);
  Call(m, false, true);  // between blocks the block start is the point
  EXPECT_NEAR(m.channel->repos_status().axes[0].final_value, 100, 1e-9);
  JogFor(m, 0, -1, 1.0);
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_TRUE(m.channel->conditions_restored());
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  // 2.4 instruction: with single block the NC holds after the repositioning too; the next
  // start runs N2, then a hold.
  m.channel->Start();
  RunFor(m, 0.5);
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
  m.channel->Start();
  RunFor(m, 6.0);
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
  EXPECT_FALSE(m.channel->repos_status().left_contour);  // a new interruption, not left
}

/// The program of ChannelRepositioning (X to 100, Z to -50) interrupted at X about 30 and Z
/// jogged away, then the REPOS subroutine started and stopped in its G77 Z0.
double StopInTheSubroutine(Machine& m) {
  m.channel->Start();
  RunFor(m, 3.0);
  m.channel->Stop();
  RunFor(m, 0.2);
  const double x = m.X();
  EXPECT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  JogFor(m, 1, +1, 0.4);  // Z about 20
  Call(m, true, false);
  EXPECT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  RunFor(m, 0.1);
  m.channel->Stop();
  RunFor(m, 0.2);
  EXPECT_TRUE(m.channel->repos_status().subroutine_running);
  EXPECT_GT(m.Z(), 1);  // G77 Z0 held on its way
  EXPECT_LT(m.Z(), 19);
  return x;
}

const std::string kRepos = std::string("N1 M3 S1000\nN2 G01 X100 F600\nN3 G01 Z-50\nN4 RET\n") +
                           kSubroutine;

TEST(ReposStopDuringTheSubroutine, JoggingThenKeepsTheInterruptionPointAsTheTarget) {
  Machine m(kRepos);
  const double x = StopInTheSubroutine(m);
  // 7.2: still allowed; manual mode is legal (2.5), the subroutine's hold is no new interruption.
  EXPECT_TRUE(m.channel->repos_allowed());
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  // 7.1: to jog away further the PLC withdraws the function (jog mode), then calls it again.
  Call(m, false, false);
  EXPECT_FALSE(m.channel->conditions_restored());
  JogFor(m, 0, +1, 0.2);
  JogFor(m, 1, +1, 0.2);
  EXPECT_TRUE(m.channel->repos_allowed());
  Call(m, true, false);
  const ReposStatus s = m.channel->repos_status();
  EXPECT_NEAR(s.axes[0].final_value, x, 1e-9);  // the original interruption point
  EXPECT_NEAR(s.axes[1].final_value, 0, 1e-9);
  EXPECT_TRUE(s.axes[0].adjust);
  EXPECT_FALSE(m.channel->conditions_restored());  // 7.3: left the contour again
  // Start runs the subroutine again from .REPOS: Z first, then X, no jump, the program goes on.
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  double z_first = 1e9, step = 0, last_x = m.X(), last_z = m.Z();
  while (m.channel->repos_allowed() && m.t < 60) {
    Tick(m);
    if (m.X() < last_x - 1e-12) z_first = std::min(z_first, std::abs(m.Z()));
    step = std::max({step, std::abs(m.X() - last_x), std::abs(m.Z() - last_z)});
    last_x = m.X(), last_z = m.Z();
  }
  EXPECT_LT(z_first, 1e-9);
  EXPECT_LT(step, 0.2);
  EXPECT_EQ(m.channel->state(), ChannelState::kRunning) << m.channel->error();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
}

TEST(ReposStopDuringTheSubroutine, ManualRepositioningThenStartContinues) {
  Machine m(kRepos);
  const double x = StopInTheSubroutine(m);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  // 3.2: the function still called, the axes go back by hand, never past the target.
  JogFor(m, 1, -1, 1.0);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
  EXPECT_NEAR(m.X(), x, 1e-9);
  EXPECT_TRUE(m.channel->conditions_restored());
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 100, 1e-9);
}

TEST(ReposStopDuringTheSubroutine, StartWithTheFunctionWithdrawnFailsAtG77) {
  Machine m(kRepos);
  StopInTheSubroutine(m);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  Call(m, false, false);
  JogFor(m, 1, +1, 0.1);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  RunFor(m, 0.1);
  // 7.1 instruction: G77 without PxxC.REPOS / RESTA interrupts with its message; the program
  // is still interrupted (an error the reverse program or Control-Reset leaves).
  EXPECT_EQ(m.channel->error_number(), kMsgReposNotActive);
}

TEST(ReposStopDuringTheSubroutine, ControlResetEndsEverything) {
  Machine m(kRepos);
  StopInTheSubroutine(m);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  JogFor(m, 1, +1, 0.1);
  m.channel->Reset();
  RunFor(m, 0.01);
  EXPECT_FALSE(m.channel->repos_allowed());
  EXPECT_FALSE(m.channel->repos_status().subroutine_running);
  Call(m, true, false);
  EXPECT_EQ(m.channel->repos_function(), ReposFunction::kNone);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();  // the program from its first block
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
}

TEST(ReposSubroutineVariables, TheSubroutineSharesTheProgramsVariableSet) {
  // @102 written by the program before the interruption is read by the subroutine; @104
  // written by the subroutine is read by the program after RTS.
  Machine m(
      "N1 @102=7\nN2 G01 X100 F600\nN3 G04 F0.1\nN4 G01 X@104\nN5 RET\n"
      ".REPOS\nN10 @104=@102+3\nN11 G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n");
  m.channel->Start();
  RunFor(m, 3.0);
  m.channel->Stop();
  RunFor(m, 0.2);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  JogFor(m, 1, +1, 0.2);
  Call(m, true, false);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 10, 1e-9);
}

TEST(ReposSubroutineVariables, DataAccessReadsTheInterruptedProgramsState) {
  // 8.3: @100=M(5) and @100=G(2)-17 in the subroutine read the interrupted program's coolant
  // and plane (M8, G17 here, not the initial M9, G18), into the program's variables.
  Machine m(
      "N1 M8 G17\nN2 G01 X100 F600\nN3 G04 F0.1\nN4 G18 G01 X@100 Z@101\nN5 RET\n"
      ".REPOS\nN10 @100=M(5)\nN11 @101=G(2)-17\nN12 G77 Z0 F3000\nN13 G77 X0 F3000 RTS\n");
  m.channel->Start();
  RunFor(m, 3.0);
  m.channel->Stop();
  RunFor(m, 0.2);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  JogFor(m, 1, +1, 0.2);
  Call(m, true, false);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 8, 1e-9);
  EXPECT_NEAR(m.Z(), 0, 1e-9);
}

/// The shared NC turret (nc_turret_machine.hpp) at 60 deg; this file's Tick moves it.
struct ToolStorageMachine : NcTurretMachine {
  ToolStorageMachine(const std::string& program, bool bxx045)
      : NcTurretMachine(program, 60, bxx045) {}
};

void JogToolStorageFor(Machine& m, int direction, double s) {
  m.channel->JogToolStorage(direction);
  RunFor(m, s);
  m.channel->JogToolStorage(0);
  RunFor(m, 0.2);
}

double InterruptAndJogAway(Machine& m) {
  m.channel->Start();
  RunFor(m, 3.0);
  m.channel->Stop();
  RunFor(m, 0.2);
  EXPECT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  JogFor(m, 1, +1, 0.2);
  return m.X();
}

TEST(ReposToolStorageAxis, MgposAndMgnegJogAnNcControlledToolStorageAxis) {
  ToolStorageMachine m("N1 G01 X100 F600\nN2 RET\n", true);
  InterruptAndJogAway(m);
  // 2.5: jogged off its station during the interruption (PxxC.MGPOS).
  JogToolStorageFor(m, +1, 1.0);
  EXPECT_GT(m.at.feedback[3].position, 80);
  EXPECT_EQ(m.mdt.setpoints[3].mode, DriveMode::kPosition);
  // Outside manual mode the keys do nothing.
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  const double t = m.at.feedback[3].position;
  JogToolStorageFor(m, -1, 0.5);
  EXPECT_EQ(m.at.feedback[3].position, t);
}

TEST(ReposToolStorageAxis, TheTargetMayBePassedAndTheAdjustSymbolFollows) {
  ToolStorageMachine m("N1 G01 X100 F600\nN2 RET\n", true);
  InterruptAndJogAway(m);
  JogToolStorageFor(m, -1, 0.5);  // about 15 deg below its station at 60
  Call(m, true, false);
  JogFor(m, 1, -1, 1.0);  // Z back
  EXPECT_TRUE(m.channel->repos_status().tool_storage_adjust);
  EXPECT_FALSE(m.channel->conditions_restored());
  // 3.4 instruction: MGPOS runs on past the target; the symbol goes when it is reached and
  // comes back when it is passed.
  m.channel->JogToolStorage(+1);
  bool reached = false, crest = false;
  for (int i = 0; i < 4000; ++i) {
    Tick(m);
    if (i % 4 == 3 && !m.channel->repos_status().tool_storage_adjust) reached = true;
    crest = crest || m.channel->conditions_restored();
  }
  m.channel->JogToolStorage(0);
  RunFor(m, 0.2);
  EXPECT_TRUE(reached);
  EXPECT_TRUE(crest);
  EXPECT_GT(m.at.feedback[3].position, 60.5);  // passed
  EXPECT_TRUE(m.channel->repos_status().tool_storage_adjust);
  EXPECT_FALSE(m.channel->conditions_restored());
  // A whole turn later it is the same station (endless: the short way round).
  JogToolStorageFor(m, +1, 12.5);
  EXPECT_GT(m.at.feedback[3].position, 430);
  m.channel->JogToolStorage(-1);
  for (int i = 0; i < 20000 && m.channel->repos_status().tool_storage_adjust; ++i) Tick(m);
  m.channel->JogToolStorage(0);
  EXPECT_NEAR(m.at.feedback[3].position, 420, 0.1);  // 60 + one turn
}

TEST(ReposToolStorageAxis, Bxx045DecidesWhetherItCountsForCrest) {
  ToolStorageMachine m("N1 G01 X100 F600\nN2 RET\n", false);
  InterruptAndJogAway(m);
  JogToolStorageFor(m, +1, 0.5);
  Call(m, true, false);
  JogFor(m, 1, -1, 1.0);
  EXPECT_TRUE(m.channel->conditions_restored());  // 6.2 'no': not taken into account
  EXPECT_FALSE(m.channel->repos_status().tool_storage_relevant);
}

TEST(ReposToolStorageAxis, MtpReturnsAnNcControlledToolStorageAxisAndMryWaits) {
  ToolStorageMachine m(
      "N1 G01 X100 F600\nN2 RET\n.REPOS\nN10 MTP\nN11 MRY G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n",
      true);
  InterruptAndJogAway(m);
  JogToolStorageFor(m, +1, 3.0);  // about 90 deg on: 150
  const double z = m.Z();
  Call(m, true, false);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  RunFor(m, 0.1);
  EXPECT_LT(m.at.feedback[3].position, 149);  // on its way back
  EXPECT_EQ(m.Z(), z);                         // MRY: the G77 waits for it
  while (m.channel->state() == ChannelState::kRunning && m.t < 60) {
    Tick(m);
    if (m.at.feedback[3].position > 60 + kToolStorageWindow) {
      EXPECT_EQ(m.Z(), z);
    }
  }
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.at.feedback[3].position, 60, 1e-9);
  EXPECT_NEAR(m.X(), 100, 1e-9);
}

}  // namespace
}  // namespace vmt::control::channel
