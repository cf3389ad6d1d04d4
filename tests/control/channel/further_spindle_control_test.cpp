// The channel's further spindles (lathe-c1's driven tool S2): Sj= / Mj= in a program, their
// state at the interruption, G77 Sj=0 (REPOS manual 4.2), PxxS.CREST over all spindles (7.3)
// and the REPOS screen (2.2); a spindle the channel does not have is an error at its word.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/channel/further_spindle_control.hpp"
#include "control/nc/parser.hpp"
#include "tests/control/channel/channel_test_support.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing
using ::testing::HasSubstr;

constexpr int kS2 = 3;  // drives: X 0, Z 1, S1 2, S2 3

/// The channel of channel_test_support with the driven tool S2 on drive 3.
struct SpindleMachine : Machine {
  explicit SpindleMachine(const std::string& program)
      : Machine(program, 0, 0, [](ChannelConfig& c) {
          c.spindles = {{2, kS2, "S2"}};
        }) {
    Resize(4);
  }
  /// The spindles ramp at 24000 deg/s^2 (S2 from 0 to 3000 rpm in 0.75 s), at speed within
  /// 1 deg/s of their command. Their own answer, not the bus's servo: the velocity steps by the
  /// clamped difference and no position is integrated.
  void Step() {
    Tick();
    for (int d : {2, kS2}) {
      const DriveSetpoint& sp = mdt.setpoints[d];
      DriveFeedback& f = at.feedback[d];
      const double command = sp.mode == DriveMode::kVelocity ? sp.value : 0;
      const double dv = 24000 * 250e-6;
      f.velocity += std::clamp(command - f.velocity, -dv, dv);
      f.status = drive_status::kReady;
      if (std::abs(f.velocity - command) < 1) f.status |= drive_status::kAtSpeed;
      if (f.velocity == 0) f.status |= drive_status::kStandstill;
    }
  }
  void RunFor(double s) {
    for (int i = 0; i < s / 250e-6; ++i) Step();
  }
  void RunUntilEnd() {
    while (channel->state() != ChannelState::kEnded && channel->state() != ChannelState::kError &&
           t < 60)
      Step();
  }
  double S2Rpm() const { return at.feedback[kS2].velocity / 6; }
  /// Runs the program 2 s, holds it, jogs Z away in manual mode, calls repositioning and goes
  /// back to automatic mode.
  void InterruptAndCall() {
    channel->Start();
    RunFor(2.0);
    channel->Stop();
    RunFor(0.2);
    ASSERT_TRUE(channel->SetMode(ChannelMode::kManual));
    channel->Jog(1, +1);
    RunFor(0.2);
    channel->Jog(1, 0);
    RunFor(0.1);
    channel->SetReposition(true, false);
    RunFor(0.01);
    ASSERT_TRUE(channel->SetMode(ChannelMode::kAutomatic));
  }
};

// Sj= gives spindle j's speed, Mj=3 / 4 / 5 its direction; the main spindle's M3 and S are
// not touched by them, nor they by the main spindle's.
TEST(FurtherSpindles, SjAndMjCommandTheirSpindleOnly) {
  SpindleMachine m(
      "N1 M3 S1000\nN2 S2=2000 M2=4\nN3 G04 F1\nN4 S2=500\nN5 G04 F1\n"
      "N6 M2=3\nN7 G04 F1\nN8 M2=5\nN9 G04 F1\nN10 RET\n");
  m.channel->Start();
  m.RunFor(0.5);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 6000);  // S1 at 1000 rpm
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[kS2].value, -12000);
  m.RunFor(1.0);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[kS2].value, -3000);  // S2=500 alone: the same direction
  m.RunFor(1.0);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[kS2].value, 3000);
  m.RunFor(1.0);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[kS2].value, 0);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 6000);
  m.RunFor(1.0);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

// A spindle the channel does not have, or a function a further spindle cannot do, is an error
// at its word, never passed over.
TEST(FurtherSpindles, WordsTheChannelCannotDoAreErrorsAtTheWord) {
  struct Case {
    std::string program, error;
  };
  for (const Case& c : std::vector<Case>{
           {"N1 G01 X10 F600\nN2 M3 S3=1000\n",
            "p.mtc:2:7: error: S3=1000: the channel has no "
            "spindle S3"},
           {"N1 M2=19\n", "p.mtc:1:4: error: M2=19: spindle S2 has no position control (M19)"},
           {"N1 M2=8\n", "p.mtc:1:4: error: M2=8: only the spindle functions 3, 4 and 5"},
       }) {
    SpindleMachine m(c.program);
    m.channel->Start();
    m.RunFor(2.0);
    EXPECT_EQ(m.channel->state(), ChannelState::kError) << c.program;
    EXPECT_EQ(m.channel->error_number(), kMsgNotAvailable) << c.program;
    EXPECT_THAT(m.channel->error(), HasSubstr(c.error));
  }
}

const std::string kMain =
    "N1 M3 S1000 M2=3 S2=3000\nN2 G04 F1\nN3 G01 X100 F600\nN4 G01 Z-50\nN5 RET\n";

// 4.2: G77 S2=0 restores S2's most recent speed and direction and waits until it is at speed;
// until then PxxS.CREST stays 0 and the REPOS screen shows S2 with its adjust symbol (2.2,
// 7.3: all spindles count). The subroutine here stops S2 itself before restoring it.
TEST(FurtherSpindles, G77S2RestoresTheDrivenToolSpindle) {
  SpindleMachine m(kMain +
                   ".REPOS\nN10 M2=5\nN11 G04 F1\nN12 G77 S1=0\nN13 G77 S2=0\n"
                   "N14 G77 Z0 F3000\nN15 G77 X0 F3000 RTS\n");
  m.InterruptAndCall();
  EXPECT_NEAR(m.S2Rpm(), 3000, 1e-9);
  ReposStatus s = m.channel->repos_status(&m.at);
  ASSERT_EQ(s.further_spindles.size(), 1u);
  EXPECT_EQ(s.further_spindles[0].name, "S2");
  EXPECT_EQ(s.further_spindles[0].command_m, 3);
  EXPECT_DOUBLE_EQ(s.further_spindles[0].command_rpm, 3000);
  EXPECT_FALSE(s.further_spindles[0].adjust);
  m.channel->Start();
  m.RunFor(0.9);  // M2=5 and the dwell: S2 has stopped
  EXPECT_NEAR(m.S2Rpm(), 0, 1e-9);
  s = m.channel->repos_status(&m.at);
  EXPECT_TRUE(s.further_spindles[0].adjust);
  EXPECT_EQ(s.further_spindles[0].actual_m, 5);
  EXPECT_FALSE(s.conditions_restored);
  const double z = m.Z();
  m.RunFor(0.5);  // G77 S2=0 after the dwell: S2 runs up, Z waits for it
  EXPECT_GT(m.S2Rpm(), 100);
  EXPECT_LT(m.S2Rpm(), 3000);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[kS2].value, 18000);
  EXPECT_EQ(m.Z(), z);
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.S2Rpm(), 3000, 1e-9);
  EXPECT_NEAR(m.Z(), -50, 1e-9);
}

// 7.3: PxxS.CREST counts every spindle: with S2 stopped it stays 0 though the axes and S1 are
// back; G77 S2=0 makes it 1.
TEST(FurtherSpindles, ConditionsRestoredNeedsEverySpindle) {
  SpindleMachine m(kMain +
                   ".REPOS\nN10 M2=5\nN11 G77 Z0 F3000\nN12 G04 F1\nN13 G77 S2=0\n"
                   "N14 G04 F1\nN15 G77 X0 F3000 RTS\n");
  m.InterruptAndCall();
  m.channel->Start();
  m.RunFor(1.0);  // Z back, S2 stopped
  EXPECT_NEAR(m.Z(), 0, 1e-9);
  EXPECT_NEAR(m.S2Rpm(), 0, 1e-9);
  EXPECT_FALSE(m.channel->conditions_restored());
  EXPECT_TRUE(m.channel->repos_status(&m.at).further_spindles[0].adjust);
  m.RunFor(1.5);  // S2 at speed again, in N14's dwell
  EXPECT_NEAR(m.S2Rpm(), 3000, 1e-9);
  EXPECT_FALSE(m.channel->repos_status(&m.at).further_spindles[0].adjust);
  EXPECT_TRUE(m.channel->conditions_restored());
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

// The subroutine may not return with a spindle off its former state: the program would go on
// with the driven tool stopped.
TEST(FurtherSpindles, RtsWithS2NotRestoredIsAnError) {
  SpindleMachine m(kMain + ".REPOS\nN10 M2=5\nN11 G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n");
  m.InterruptAndCall();
  m.channel->Start();
  m.RunFor(3.0);
  EXPECT_EQ(m.channel->error_number(), kMsgReposNotRestored);
  EXPECT_THAT(m.channel->error(), HasSubstr("further spindle"));
  EXPECT_TRUE(m.channel->repos_allowed());
}

// G77 Sj=0 of a spindle the channel does not have is an error at its word; so is Mj= in a G77
// block (G77 restores the direction itself).
TEST(FurtherSpindles, G77OfAnUnknownSpindleIsAnErrorAtItsWord) {
  struct Case {
    std::string subroutine, error;
  };
  for (const Case& c : std::vector<Case>{
           {".REPOS\nN10 G77 S1=0 S3=0\n",
            "p.mtc:7:14: error: S3=0: G77: the channel has no "
            "spindle S3 to restore"},
           {".REPOS\nN10 G77 S2=0 M2=3\n",
            "p.mtc:7:14: error: M2=3: G77 restores spindle S2's "
            "direction itself"},
       }) {
    SpindleMachine m(kMain + c.subroutine + "N11 G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n");
    m.InterruptAndCall();
    const double z = m.Z();
    m.channel->Start();
    m.RunFor(0.5);
    EXPECT_EQ(m.channel->error_number(), kMsgNotAvailable) << c.subroutine;
    EXPECT_THAT(m.channel->error(), HasSubstr(c.error));
    EXPECT_EQ(m.Z(), z);
    EXPECT_TRUE(m.channel->repos_allowed());
  }
}

// The function alone, with only what the channel hands it: the block, the states at the
// interruption and the drives' feedback.
struct FurtherSpindleControlTest : ::testing::Test {
  FurtherSpindleControl control{{{2, kS2, "S2"}}};
  nc::ParseResult parsed = nc::ParseProgram("N1 S2=1500 M2=4\nN2 S3=100\nN3 M2=19\n", "p.mtc",
                                            nc::Dialect::kMtc200);
  /// Block `index` of the program with the S/M words `aux`, as the interpreter prepares it.
  nc::PreparedBlock Block(int32_t index, std::vector<nc::AuxFunction> aux) const {
    nc::PreparedBlock b;
    b.block = index;
    b.aux = std::move(aux);
    return b;
  }
  AmplifierTelegram Feedback(double velocity, bool at_speed) const {
    AmplifierTelegram at;
    at.feedback.resize(4);
    at.feedback[kS2].velocity = velocity;
    at.feedback[kS2].status = at_speed ? drive_status::kAtSpeed : 0;
    return at;
  }
};

TEST_F(FurtherSpindleControlTest, WordsSetSpeedAndDirectionAndTheCommand) {
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(control.TakeWords(parsed.program, Block(0, {{'S', 2, 1500}, {'M', 2, 4}})), "");
  EXPECT_EQ(control.states()[0].rpm, 1500);
  EXPECT_EQ(control.states()[0].m, 4);
  MasterTelegram mdt;
  mdt.setpoints.resize(4);
  control.WriteSetpoints(mdt);
  EXPECT_EQ(mdt.setpoints[kS2].mode, DriveMode::kVelocity);
  EXPECT_EQ(mdt.setpoints[kS2].value, -1500 * 6);  // M4: negative, deg/s
  control.Reset();
  control.WriteSetpoints(mdt);
  EXPECT_EQ(mdt.setpoints[kS2].value, 0);
}

TEST_F(FurtherSpindleControlTest, AnErrorNamesTheWordAndItsColumn) {
  EXPECT_EQ(control.TakeWords(parsed.program, Block(1, {{'S', 3, 100}})),
            "p.mtc:2:4: error: S3=100: the channel has no spindle S3");
  EXPECT_THAT(control.TakeWords(parsed.program, Block(2, {{'M', 2, 19}})),
              HasSubstr("M2=19: spindle S2 has no position control (M19)"));
  EXPECT_THAT(control.CheckRepos(parsed.program, Block(0, {{'M', 2, 4}})),
              HasSubstr("G77 restores spindle S2's direction itself"));
  EXPECT_EQ(control.CheckRepos(parsed.program, Block(0, {{'S', 2, 0}})), "");
}

TEST_F(FurtherSpindleControlTest, RestoreWaitsUntilTheSpindleRunsAtItsFormerSpeed) {
  const std::vector<FurtherSpindleState> before = {{1000, 3}};
  EXPECT_FALSE(control.Restored(0, before, nullptr));  // stopped, was at 1000 rpm
  control.Restore(Block(0, {{'S', 2, 0}}), before, Feedback(0, false));
  EXPECT_TRUE(control.restoring());
  EXPECT_TRUE(control.Restored(0, before, nullptr));  // the command is back
  EXPECT_TRUE(control.UpdateRestoring(Feedback(3000, false)));
  EXPECT_FALSE(control.AllRestored(before, Feedback(3000, false)));
  EXPECT_FALSE(control.UpdateRestoring(Feedback(6000, true)));
  EXPECT_TRUE(control.AllRestored(before, Feedback(6000, true)));
  const std::vector<ReposFurtherSpindleStatus> screen =
      control.ReposStatus(before, nullptr);
  ASSERT_EQ(screen.size(), 1u);
  EXPECT_EQ(screen[0].name, "S2");
  EXPECT_EQ(screen[0].command_rpm, 1000);
  EXPECT_EQ(screen[0].actual_m, 3);
  EXPECT_FALSE(screen[0].adjust);
}

}  // namespace
}  // namespace vmt::control::channel
