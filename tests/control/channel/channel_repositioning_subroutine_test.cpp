// The REPOS subroutine's end and its interruptions (REPOS manual 4.1, 4.2, 7.1, 7.2): RTS ends
// it, RET is refused at its word; an error inside it is a program interruption the operator
// can start the subroutine again from, the interruption point kept; a reverse during it goes
// back along the reverse vectors valid then (those of its own MOVE) before `.HOME`.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "control/channel/channel.hpp"
#include "tests/control/channel/channel_test_support.hpp"
#include "tests/control/channel/measuring_lathe.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing
using ::testing::HasSubstr;

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

void Call(Machine& m, bool repositioning, bool restart) {
  m.channel->SetReposition(repositioning, restart);
  RunFor(m, 0.01);
}

/// Runs the program 3 s (X at about 30), holds it, goes to manual mode and jogs Z away 5 mm;
/// the REPOS function called, back in automatic mode. Returns X at the interruption.
double InterruptJogAwayAndCall(Machine& m) {
  m.channel->Start();
  RunFor(m, 3.0);
  m.channel->Stop();
  RunFor(m, 0.2);
  const double x = m.X();
  EXPECT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  JogFor(m, 1, +1, 0.2);
  EXPECT_GT(m.Z(), 4);
  Call(m, true, false);
  EXPECT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  return x;
}

const std::string kMain = "N1 M3 S1000\nN2 G01 X100 F600\nN3 G01 Z-50\nN4 RET\n";

// 4.1: the subroutine must end with RTS, which keeps the interrupted program's state; RET is a
// program end. vmt refuses it at its word, and the program stays interrupted.
TEST(ReposSubroutineEnd, RetIsRefusedAtItsWordAndTheProgramStaysInterrupted) {
  Machine m(kMain + ".REPOS\nN10 G77 S1=0\nN11 G77 Z0 F3000\nN12 G77 X0 F3000 RET\n");
  const double x = InterruptJogAwayAndCall(m);
  m.channel->Start();
  RunFor(m, 3.0);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgProgramError);
  EXPECT_THAT(m.channel->error(), HasSubstr("p.mtc:8:18: error: RET ends a program"));
  EXPECT_THAT(m.channel->error(), HasSubstr("ends with RTS"));
  // 7.2: still interrupted, repositioning still allowed, the same interruption point.
  EXPECT_TRUE(m.channel->repos_allowed());
  const ReposStatus s = m.channel->repos_status();
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_NEAR(s.axes[0].final_value, x, 1e-9);
  EXPECT_NEAR(s.axes[1].final_value, 0, 1e-9);
}

TEST(ReposSubroutineEnd, RtsContinuesTheProgram) {
  Machine m(kMain + ".REPOS\nN10 G77 S1=0\nN11 G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n");
  InterruptJogAwayAndCall(m);
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
}

// 7.1 instruction: G77 with the function withdrawn is a program interruption with its message.
// The PLC calls the function again and Start runs the subroutine again from `.REPOS`, to the
// interruption point the program had: it goes on from there without a jump.
TEST(ReposSubroutineErrors, AfterG77WithoutTheFunctionStartRunsTheSubroutineAgain) {
  Machine m(kMain + ".REPOS\nN10 G04 F0.5\nN11 G77 S1=0\nN12 G77 Z0 F3000\n"
                    "N13 G77 X0 F3000 RTS\n");
  const double x = InterruptJogAwayAndCall(m);
  m.channel->Start();
  RunFor(m, 0.1);
  m.channel->SetReposition(false, false);
  RunFor(m, 1.0);
  ASSERT_EQ(m.channel->error_number(), kMsgReposNotActive);
  EXPECT_TRUE(m.channel->repos_allowed());  // 7.2: no Control-Reset, still interrupted
  EXPECT_TRUE(m.channel->repos_status().subroutine_running);
  // Start with the function still withdrawn meets the same G77 again.
  m.channel->Start();
  RunFor(m, 1.0);
  EXPECT_EQ(m.channel->error_number(), kMsgReposNotActive);
  Call(m, true, false);
  m.channel->Start();
  RunFor(m, 0.05);
  EXPECT_EQ(m.channel->state(), ChannelState::kRunning) << m.channel->error();
  EXPECT_EQ(m.channel->error_number(), 0);
  double step = 0, last_x = m.X(), last_z = m.Z();
  bool passed_the_point = false;
  while (m.channel->state() == ChannelState::kRunning && m.t < 60) {
    Tick(m);
    step = std::max({step, std::abs(m.X() - last_x), std::abs(m.Z() - last_z)});
    passed_the_point |= std::abs(m.X() - x) < 1e-9 && std::abs(m.Z()) < 1e-9;
    last_x = m.X(), last_z = m.Z();
  }
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_TRUE(passed_the_point);
  EXPECT_LT(step, 0.2);
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
}

// 4.2: G77 S1=0 restores the main spindle; in a channel without one it is refused, not passed
// over.
TEST(ReposSubroutineErrors, G77OfASpindleTheChannelDoesNotHaveIsRefused) {
  Machine m("N1 G01 X100 F600\nN2 RET\n.REPOS\nN10 G77 S1=0\nN11 G77 Z0 F3000 RTS\n", 0, 0,
            [](ChannelConfig& c) { c.spindle_drive = -1; });
  InterruptJogAwayAndCall(m);
  const double z = m.Z();
  m.channel->Start();
  RunFor(m, 0.5);
  EXPECT_EQ(m.channel->error_number(), kMsgNotAvailable);
  EXPECT_THAT(m.channel->error(),
              HasSubstr("p.mtc:4:1: error: G77 S1=0: the channel has no spindle S1 to restore"));
  EXPECT_EQ(m.Z(), z);
  EXPECT_TRUE(m.channel->repos_allowed());
}

/// A PathGuard with an obstacle the operator can take away: every move collides while it is
/// there.
struct Obstacle : PathGuard {
  PathCheck CheckMove(const std::vector<double>& from, const std::vector<double>&) override {
    PathCheck c;
    c.min_clearance = 1;
    if (!there) return c;
    c.clear = false;
    c.part_a = "tool", c.part_b = "clamp";
    c.position = from;
    c.min_clearance = 0;
    return c;
  }
  bool there = true;
};

// A collision PathGuard finds ahead of a G77 stops it before it starts (507); once the obstacle
// is gone, Start runs the subroutine again and the program continues. Manual mode in between
// is legal and keeps the interruption point.
TEST(ReposSubroutineErrors, AfterACollisionAheadStartRunsTheSubroutineAgain) {
  Obstacle guard;
  Machine m(kMain + ".REPOS\nN10 G77 S1=0\nN11 G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n");
  m.channel->SetPathGuard(&guard);
  guard.there = false;
  const double x = InterruptJogAwayAndCall(m);
  guard.there = true;
  const double z = m.Z();
  m.channel->Start();
  RunFor(m, 1.0);
  ASSERT_EQ(m.channel->error_number(), kMsgCollision);
  EXPECT_EQ(m.Z(), z);
  EXPECT_TRUE(m.channel->repos_allowed());
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  ASSERT_EQ(m.channel->repos_status().axes.size(), 2u);
  EXPECT_NEAR(m.channel->repos_status().axes[0].final_value, x, 1e-9);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  guard.there = false;
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 100, 1e-9);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
}

// A machine fault is no program interruption: after a drive's fault in the subroutine only
// Control-Reset goes on.
TEST(ReposSubroutineErrors, ADriveFaultStillNeedsControlReset) {
  Machine m(kMain + ".REPOS\nN10 G77 S1=0\nN11 G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n");
  InterruptJogAwayAndCall(m);
  m.channel->Start();
  RunFor(m, 0.1);
  m.at.feedback[1].status = 0;  // Z's drive drops its ready
  Tick(m);
  m.at.feedback[1].status = drive_status::kReady;
  ASSERT_EQ(m.channel->error_number(), kMsgDriveFault) << m.channel->error();
  m.channel->Start();
  RunFor(m, 0.5);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgDriveFault);
}

// 4.1: a reverse during the subroutine goes back along the reverse vectors valid at that moment
// (those its own MOVE recorded: the stylus returns to where the MOVE started) before `.HOME`.
TEST(ReposSubroutineReverse, TheSubroutinesReverseVectorsThenHome) {
  MeasuringLathe l(
      "N1 G01 X60 F600\n"
      "N2 G01 Z10\n"
      "N3 RET\n"
      ".REPOS\n"
      "N10 SETTING(X,Z,,18,48,15,1)\n"
      "N11 MOVE(90,45,,1,2)\n"
      "N12 G04 F5\n"
      "N13 G77 Z0 F3000\n"
      "N14 G77 X0 F3000 RTS\n"
      ".HOME\n"
      "N20 G00 X100\n"
      "N21 RET\n",
      0.0, 80, 30);
  Machine& m = l.m;
  m.channel->Start();
  for (int i = 0; i < 1.0 / 250e-6; ++i) l.Tick();  // X from 80 towards 60
  m.channel->Stop();
  for (int i = 0; i < 0.2 / 250e-6; ++i) l.Tick();
  ASSERT_EQ(m.channel->state(), ChannelState::kHold);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Jog(1, +1);
  for (int i = 0; i < 0.2 / 250e-6; ++i) l.Tick();
  m.channel->Jog(1, 0);
  for (int i = 0; i < 0.1 / 250e-6; ++i) l.Tick();
  const double x_from = m.X(), z_from = m.Z();
  ASSERT_GT(z_from, 33);
  m.channel->SetReposition(true, false);
  for (int i = 0; i < 40; ++i) l.Tick();
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  while (!(std::abs(m.X() - 90) < 1e-9 && std::abs(m.Z() - 45) < 1e-9) && m.t < 20) l.Tick();
  for (int i = 0; i < 0.5 / 250e-6; ++i) l.Tick();  // in N12's dwell
  ASSERT_TRUE(m.channel->repos_status().subroutine_running) << m.channel->error();
  m.channel->Stop();
  for (int i = 0; i < 40; ++i) l.Tick();
  ASSERT_TRUE(m.channel->Reverse());
  bool back_at_the_start = false;
  while (m.channel->state() == ChannelState::kRunning && m.t < 40) {
    l.Tick();
    back_at_the_start |= std::abs(m.X() - x_from) < 1e-9 && std::abs(m.Z() - z_from) < 1e-9;
  }
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_TRUE(back_at_the_start);
  EXPECT_NEAR(m.X(), 100, 1e-9);  // .HOME
  EXPECT_NEAR(m.Z(), z_from, 1e-9);
  EXPECT_FALSE(m.channel->repos_allowed());
}

}  // namespace
}  // namespace vmt::control::channel
