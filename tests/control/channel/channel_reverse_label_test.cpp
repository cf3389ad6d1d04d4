// Reverse vectors a user programs (REV .LABEL; REPOS manual 4.1, fast measurement 4.4): a
// reverse branches to the reverse label valid at the interrupted block and runs from there,
// then `.HOME`; with none valid, `.HOME` at once. During the REPOS subroutine the subroutine's
// own reverse vector counts. Block search keeps the one its skipped part made valid.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "block_search_steps.hpp"
#include "control/channel/channel.hpp"
#include "tests/control/channel/channel_test_support.hpp"
#include "tests/control/channel/measuring_lathe.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

/// The ideal machine, with a spindle that reaches its command at once (at speed, in position).
void Tick(Machine& m) {
  m.Tick();
  m.Answer(2, test_support::IdealDrive::InstantSpindle());
}

void RunFor(Machine& m, double s) {
  for (int i = 0; i < s / 250e-6; ++i) Tick(m);
}

void Hold(Machine& m) {
  m.channel->Stop();
  RunFor(m, 0.2);
  ASSERT_EQ(m.channel->state(), ChannelState::kHold) << m.channel->error();
}

/// Where the reverse program went: the (X, Z) of every NC cycle until it ended.
struct ReverseRun {
  std::vector<std::pair<double, double>> path;
  bool Visited(double x, double z) const {
    for (const auto& [px, pz] : path)
      if (std::abs(px - x) < 1e-9 && std::abs(pz - z) < 1e-9) return true;
    return false;
  }
};

ReverseRun Reverse(Machine& m) {
  ReverseRun r;
  EXPECT_TRUE(m.channel->Reverse());
  EXPECT_TRUE(m.channel->reversing());
  while (m.channel->state() == ChannelState::kRunning && m.t < 200) {
    Tick(m);
    r.path.emplace_back(m.X(), m.Z());
  }
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_FALSE(m.channel->reversing());
  return r;
}

/// N2 makes .BACK the reverse vector for N3 on: it lifts Z to 20 where the tool stands, and
/// `.HOME` takes X to 0.
const std::string kAdvance =
    "N1 G01 X10 F600\n"
    "N2 REV .BACK\n"
    "N3 G01 X100\n"
    "N4 RET\n"
    ".BACK\n"
    "N10 G01 Z20 F3000\n"
    "N11 RTS\n"
    ".HOME\n"
    "N20 G00 X0\n"
    "N21 RET\n";

TEST(ChannelReverseLabel, AReverseRunsTheValidLabelThenHome) {
  Machine m(kAdvance);
  m.channel->Start();
  RunFor(m, 3.0);  // in N3
  Hold(m);
  const double x = m.X();
  ASSERT_GT(x, 15);
  const ReverseRun r = Reverse(m);
  EXPECT_TRUE(r.Visited(x, 20));  // .BACK lifts Z where the tool stands, then .HOME
  EXPECT_NEAR(m.X(), 0, 1e-9);
  EXPECT_NEAR(m.Z(), 20, 1e-9);
}

TEST(ChannelReverseLabel, BeforeItsBlockTheLabelIsNotValid) {
  Machine m(kAdvance);
  m.channel->Start();
  RunFor(m, 0.5);  // in N1
  Hold(m);
  const ReverseRun r = Reverse(m);
  for (const auto& [x, z] : r.path) ASSERT_EQ(z, 0);
  EXPECT_NEAR(m.X(), 0, 1e-9);
}

// A reverse after an error in the program: the reverse vector of the block the error stopped.
TEST(ChannelReverseLabel, AfterAnErrorTheFailedBlocksLabel) {
  Machine m(
      "N1 G01 X10 F600\nN2 REV .BACK\nN3 G01 X20\nN4 @1=0\nN5 @2=1/@1\nN6 G01 X30\nN7 RET\n"
      ".BACK\nN10 G01 Z20 F3000 RTS\n.HOME\nN20 G00 X0\nN21 RET\n");
  m.channel->Start();
  RunFor(m, 5.0);
  ASSERT_EQ(m.channel->state(), ChannelState::kError);
  const double x = m.X();
  const ReverseRun r = Reverse(m);
  EXPECT_TRUE(r.Visited(x, 20));
  EXPECT_NEAR(m.X(), 0, 1e-9);
}

// A reverse during the part at the reverse label goes to `.HOME` only: the label brought the
// reverse program there, and the part programs no reverse vector of its own.
TEST(ChannelReverseLabel, ASecondReverseInThePartGoesHome) {
  Machine m(
      "N1 G01 X10 F600\nN2 REV .BACK\nN3 G01 X100\nN4 RET\n"
      ".BACK\nN10 G01 Z20 F600\nN11 G01 Z40 RTS\n.HOME\nN20 G00 X0\nN21 RET\n");
  m.channel->Start();
  RunFor(m, 3.0);
  Hold(m);
  ASSERT_TRUE(m.channel->Reverse());
  RunFor(m, 1.0);  // N10: Z on its way to 20
  ASSERT_GT(m.Z(), 1);
  ASSERT_LT(m.Z(), 19);
  Hold(m);
  const double z = m.Z();
  const ReverseRun r = Reverse(m);
  for (const auto& [px, pz] : r.path) ASSERT_NEAR(pz, z, 1e-9);
  EXPECT_NEAR(m.X(), 0, 1e-9);
}

// Fast measurement 4.4: the interrupted MOVE's way back comes before the user's reverse
// program, which is the valid reverse label's part and then `.HOME`.
TEST(ChannelReverseLabel, AMeasuringInstructionsWayBackFirst) {
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 REV .BACK\n"
      "N3 MOVE(60,20,,1,0)\n"
      "N4 RET\n"
      ".BACK\n"
      "N10 G00 Z50\n"
      "N11 RTS\n"
      ".HOME\n"
      "N20 G00 X90\n"
      "N21 RET\n",
      0.0, 80, 30);
  Machine& m = l.m;
  m.channel->Start();
  while (m.X() > 70 && m.t < 10) l.Tick();  // on the MOVE's way from X80 Z30 to X60 Z20
  m.channel->Stop();
  for (int i = 0; i < 0.2 / 250e-6; ++i) l.Tick();
  ASSERT_EQ(m.channel->state(), ChannelState::kHold);
  ASSERT_TRUE(m.channel->Reverse());
  bool back_at_the_start = false, lifted_before = false;
  while (m.channel->state() == ChannelState::kRunning && m.t < 40) {
    l.Tick();
    lifted_before |= !back_at_the_start && m.Z() > 30 + 1e-9;
    back_at_the_start |= std::abs(m.X() - 80) < 1e-9 && std::abs(m.Z() - 30) < 1e-9;
  }
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_TRUE(back_at_the_start);
  EXPECT_FALSE(lifted_before);
  EXPECT_NEAR(m.X(), 90, 1e-9);
  EXPECT_NEAR(m.Z(), 50, 1e-9);
}

/// Runs the program 3 s, holds it, jogs Z away 5 mm in manual mode and calls repositioning;
/// back in automatic mode, Start runs the REPOS subroutine 1 s (into its dwell) and holds it.
void IntoTheReposSubroutine(Machine& m) {
  m.channel->Start();
  RunFor(m, 3.0);
  Hold(m);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Jog(1, +1);
  RunFor(m, 0.2);
  m.channel->Jog(1, 0);
  RunFor(m, 0.1);
  ASSERT_GT(m.Z(), 4);
  m.channel->SetReposition(true, false);
  RunFor(m, 0.01);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  RunFor(m, 1.0);
  ASSERT_TRUE(m.channel->repos_status().subroutine_running) << m.channel->error();
  Hold(m);
}

const std::string kHome = ".HOME\nN20 G00 X0\nN21 RET\n";

// 4.1: a reverse during the REPOS subroutine branches to the subroutine's valid reverse label
// and runs from there, then `.HOME`.
TEST(ChannelReverseLabel, DuringTheReposSubroutineItsLabelThenHome) {
  Machine m("N1 G01 X100 F600\nN2 RET\n"
            ".REPOS\nN10 REV .RBACK\nN11 G04 F5\nN12 G77 Z0 F3000\nN13 G77 X0 F3000 RTS\n"
            ".RBACK\nN30 G01 Z40 F3000 RTS\n" +
            kHome);
  IntoTheReposSubroutine(m);
  const double x = m.X();
  const ReverseRun r = Reverse(m);
  EXPECT_TRUE(r.Visited(x, 40));
  EXPECT_NEAR(m.X(), 0, 1e-9);
  EXPECT_NEAR(m.Z(), 40, 1e-9);
  EXPECT_FALSE(m.channel->repos_allowed());
}

// The subroutine in another program of the store (program 99 or the cycle memory): its
// reverse label is in that program; `.HOME` is the main program's.
TEST(ChannelReverseLabel, TheReposSubroutinesLabelInAnotherProgram) {
  Machine m(std::vector<std::string>{
      "N1 G01 X100 F600\nN2 RET\n" + kHome,
      ".REPOS\nN10 REV .RBACK\nN11 G04 F5\nN12 G77 Z0 F3000\nN13 G77 X0 F3000 RTS\n"
      ".RBACK\nN30 G01 Z40 F3000 RTS\n"});
  IntoTheReposSubroutine(m);
  const double x = m.X();
  const ReverseRun r = Reverse(m);
  EXPECT_TRUE(r.Visited(x, 40));
  EXPECT_NEAR(m.X(), 0, 1e-9);
  EXPECT_NEAR(m.Z(), 40, 1e-9);
}

// vmt's reading of 4.1: the reverse vector valid during the subroutine is the one it programs;
// the interrupted program's, written for the contour, does not count where the operator has
// moved the axes away from it. Once the subroutine has returned, the program's counts again.
TEST(ChannelReverseLabel, TheInterruptedProgramsLabelIsNotTheSubroutines) {
  const std::string program =
      "N1 REV .BACK\nN2 G01 X100 F600\nN3 RET\n"
      ".REPOS\nN11 G04 F5\nN12 G77 Z0 F3000\nN13 G77 X0 F3000 RTS\n"
      ".BACK\nN30 G01 Z40 F3000 RTS\n" +
      kHome;
  {
    Machine m(program);
    IntoTheReposSubroutine(m);
    const double z = m.Z();
    const ReverseRun r = Reverse(m);
    for (const auto& [px, pz] : r.path) ASSERT_NEAR(pz, z, 1e-9);
    EXPECT_NEAR(m.X(), 0, 1e-9);
  }
  Machine m(program);
  IntoTheReposSubroutine(m);
  m.channel->Start();
  while (std::abs(m.Z()) > 1e-9 && m.t < 30) Tick(m);  // the subroutine has returned Z
  RunFor(m, 2.0);
  ASSERT_FALSE(m.channel->repos_status().subroutine_running);
  Hold(m);
  const double x = m.X();
  const ReverseRun r = Reverse(m);
  EXPECT_TRUE(r.Visited(x, 40));
  EXPECT_NEAR(m.Z(), 40, 1e-9);
}

// Block search decodes the skipped part, REV included: the continued program's reverse goes to
// the label the skipped part made valid.
TEST(ChannelReverseLabel, BlockSearchKeepsTheSkippedPartsLabel) {
  BlockSearchSteps<Machine> m(kAdvance);
  m.Search(BlockNumberSearch(3, 200));
  ASSERT_TRUE(m.ToContour()) << m.channel->error();
  m.channel->Start();
  ASSERT_TRUE(m.RunUntil([&] { return m.X() > 40; })) << m.channel->error();
  Hold(m);
  const double x = m.X();
  const ReverseRun r = Reverse(m);
  EXPECT_TRUE(r.Visited(x, 20));
  EXPECT_NEAR(m.X(), 0, 1e-9);
}

// A reverse while the search waits at the continue position for the return to the contour:
// the found block's reverse vector, which the skipped part made valid.
TEST(ChannelReverseLabel, BlockSearchWaitingForTheReturnReversesToTheLabel) {
  BlockSearchSteps<Machine> m(kAdvance);
  m.Search(BlockNumberSearch(3, 200));
  ASSERT_TRUE(m.Waits(BlockSearchState::kWaitReturnToContour)) << m.channel->error();
  ASSERT_EQ(m.channel->state(), ChannelState::kHold);
  const ReverseRun r = Reverse(m);
  EXPECT_TRUE(r.Visited(0, 20));  // the axes never left X0: the return had not started
  EXPECT_NEAR(m.X(), 0, 1e-9);
  EXPECT_EQ(m.channel->block_search().state, BlockSearchState::kInactive);
}

}  // namespace
}  // namespace vmt::control::channel
