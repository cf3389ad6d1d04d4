// Repositioning and NC-block restart through the gateway (REPOS manual 7.1-7.4): the PLC sets
// PxxC.REPOS / PxxC.RESTA in the signal image, the NC answers with PxxS.REPOS
// 'Reposition.Restart allowed' and PxxS.CREST 'Conditions restored'. X A01 (drive 0), Z A02
// (drive 1), main spindle A03 (drive 2) on an ideal machine.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "control/channel/channel_messages.hpp"
#include "control/gateway/channel_gateway.hpp"
#include "control/nc/parser.hpp"
#include "tests/control/gateway/gateway_rig.hpp"

namespace vmt::control::gateway {
namespace {

// X from 0 to 100 at 10 mm/s with the spindle at 1000 rpm, then Z to -50.
const char* kProgram =
    "N1 M3 S1000\n"
    "N2 G01 X100 F600\n"
    "N3 G01 Z-50\n"
    "N4 RET\n"
    ".REPOS\n"
    "N10 G77 S1=0\n"
    "N11 G04 F0.5\n"
    "N12 G77 Z0 F3000\n"
    "N13 G77 X0 F3000 RTS\n";

struct ReposRig : testing::GatewayRig {
  explicit ReposRig(const std::string& program = kProgram)
      : GatewayRig(program, /*handshake=*/false, /*spindle_at_speed=*/true) {}
  // Fixed increments of 1 mm: JOGM code 6 (JOGM1, JOGM2).
  void IncrementJog() {
    Set("P00C.JOGM0", false);
    Set("P00C.JOGM1", true);
    Set("P00C.JOGM2", true);
    Cycle();
  }
  // One jog key press; an increment runs to its end.
  void Jog(const char* key, int presses = 1) {
    for (int k = 0; k < presses; ++k) {
      Set(key, true);
      Cycle(5);
      Set(key, false);
      Cycle(300);
    }
  }
  // Runs the program 3 s (X at about 30) and holds it with PxxC.STOP; STOP is released again.
  void Interrupt() {
    Press("P00C.START");
    Cycle(3000);
    Set("P00C.STOP", true);
    Cycle(200);
    Set("P00C.STOP", false);
    Cycle();
  }
  double X() const { return at.feedback[0].position; }
  double Z() const { return at.feedback[1].position; }
};

// 7.2 / 7.4: set each time the program is interrupted, reset when it resumes.
TEST(ChannelGatewayRepos, ReposSetAtEachInterruptionAndResetWhenTheProgramResumes) {
  ReposRig r;
  r.Cycle();
  EXPECT_FALSE(r.Get("P00S.REPOS"));  // power-on: nothing interrupted
  r.Press("P00C.START");
  r.Cycle(500);
  EXPECT_TRUE(r.Get("P00S.RUN"));
  EXPECT_FALSE(r.Get("P00S.REPOS"));
  r.Set("P00C.STOP", true);
  r.Cycle(100);
  EXPECT_TRUE(r.Get("P00S.REPOS"));
  EXPECT_FALSE(r.Get("P00S.CREST"));
  r.Set("P00C.STOP", false);
  r.Press("P00C.START");  // resumed on the contour
  r.Cycle();
  EXPECT_TRUE(r.Get("P00S.RUN"));
  EXPECT_FALSE(r.Get("P00S.REPOS"));
  r.Set("P00C.STOP", true);  // a second interruption sets it again
  r.Cycle(100);
  EXPECT_TRUE(r.Get("P00S.REPOS"));
  r.Set("P00C.STOP", false);
  r.Press("P00C.START");
  r.Cycle(20000);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded);
  EXPECT_FALSE(r.Get("P00S.REPOS"));  // the end of the program is no interruption
}

// 7.4 in full: interruption, jogging away, the PLC calls repositioning, the operator adjusts,
// CREST; Start runs the REPOS subroutine, PxxS.REPOS stays 1 until the program resumes, and
// the PLC withdraws PxxC.REPOS only then (7.4 instruction).
TEST(ChannelGatewayRepos, SignalSequenceOfFigure71) {
  ReposRig r;
  r.Interrupt();
  ASSERT_TRUE(r.Get("P00S.REPOS"));
  r.Press("P00C.MANU");
  r.IncrementJog();
  r.Jog("A02C.JGPOS", 3);
  EXPECT_NEAR(r.Z(), 3, 1e-9);
  EXPECT_TRUE(r.Get("P00S.REPOS"));  // jogging keeps it
  r.Set("P00C.REPOS", true);
  r.Cycle();
  EXPECT_EQ(r.ch->repos_function(), channel::ReposFunction::kRepositioning);
  EXPECT_FALSE(r.Get("P00S.CREST"));
  r.Jog("A02C.JGNEG", 5);  // cut at the target (3.2)
  EXPECT_NEAR(r.Z(), 0, 1e-9);
  EXPECT_TRUE(r.Get("P00S.CREST"));
  r.Press("P00C.AUTO");
  r.Press("P00C.START");
  r.Cycle(100);  // in the subroutine's dwell
  EXPECT_TRUE(r.ch->repos_status().subroutine_running);
  EXPECT_TRUE(r.Get("P00S.REPOS"));
  EXPECT_TRUE(r.Get("P00S.RUN"));
  int cycles = 0;
  while (r.Get("P00S.REPOS") && cycles++ < 20000) r.Cycle();
  EXPECT_FALSE(r.Get("P00S.REPOS"));
  EXPECT_TRUE(r.Get("P00S.RUN"));  // resumed without a new start
  EXPECT_FALSE(r.Get("P00S.CREST"));
  r.Set("P00C.REPOS", false);
  r.Cycle(20000);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded) << r.ch->error();
  EXPECT_NEAR(r.X(), 100, 1e-9);
  EXPECT_NEAR(r.Z(), -50, 1e-9);
}

// 7.3: CREST is updated only while a control signal is 1, and reset when the PLC withdraws
// it or the operator moves an axis off the contour again.
TEST(ChannelGatewayRepos, CrestOnlyWhileAControlSignalIsSet) {
  ReposRig r;
  r.Interrupt();
  const double x = r.X();
  r.Press("P00C.MANU");
  r.IncrementJog();
  r.Jog("A02C.JGPOS", 2);
  r.Jog("A02C.JGNEG", 2);  // back on the interruption point by plain jogging
  EXPECT_NEAR(r.Z(), 0, 1e-9);
  EXPECT_FALSE(r.Get("P00S.CREST"));  // no control signal: not updated
  r.Set("P00C.REPOS", true);
  r.Cycle();
  EXPECT_TRUE(r.Get("P00S.CREST"));
  r.Set("P00C.REPOS", false);  // withdrawn
  r.Cycle();
  EXPECT_FALSE(r.Get("P00S.CREST"));
  // NC-block restart: the block start (X 0) is the target, X stands at the interruption point.
  r.Set("P00C.RESTA", true);
  r.Cycle();
  EXPECT_EQ(r.ch->repos_function(), channel::ReposFunction::kRestart);
  EXPECT_FALSE(r.Get("P00S.CREST"));
  EXPECT_NEAR(r.ch->repos_status().axes[0].final_value, 0, 1e-9);
  // Both signals at once call neither function.
  r.Set("P00C.REPOS", true);
  r.Cycle();
  EXPECT_EQ(r.ch->repos_function(), channel::ReposFunction::kNone);
  EXPECT_FALSE(r.Get("P00S.CREST"));
  r.Set("P00C.RESTA", false);
  r.Cycle();
  EXPECT_TRUE(r.Get("P00S.CREST"));
  EXPECT_NEAR(r.X(), x, 1e-9);
  // The operator withdraws Z again: the PLC withdrew nothing, yet CREST drops. The call came
  // with Z on its target, so first out of repositioning and in again with Z away.
  r.Set("P00C.REPOS", false);
  r.Cycle();
  r.Jog("A02C.JGPOS", 2);
  r.Set("P00C.REPOS", true);
  r.Cycle();
  r.Jog("A02C.JGNEG", 2);
  EXPECT_TRUE(r.Get("P00S.CREST"));
  r.Jog("A02C.JGPOS");  // within the zone (3.2), off the contour
  EXPECT_NEAR(r.Z(), 1, 1e-9);
  EXPECT_FALSE(r.Get("P00S.CREST"));
  r.Jog("A02C.JGNEG");
  EXPECT_TRUE(r.Get("P00S.CREST"));
}

// 7.2 / 7.4: Control-Reset ends the interruption: PxxS.REPOS and PxxS.CREST go to 0 and the
// control signals are ignored from then on (2.1).
TEST(ChannelGatewayRepos, ControlResetEndsRepositioning) {
  ReposRig r;
  r.Interrupt();
  r.Press("P00C.MANU");
  r.IncrementJog();
  r.Jog("A02C.JGPOS", 2);
  r.Set("P00C.REPOS", true);
  r.Cycle();
  r.Jog("A02C.JGNEG", 2);
  ASSERT_TRUE(r.Get("P00S.CREST"));
  r.Press("P00C.RESET");
  r.Cycle();
  EXPECT_FALSE(r.Get("P00S.REPOS"));
  EXPECT_FALSE(r.Get("P00S.CREST"));
  EXPECT_EQ(r.ch->repos_function(), channel::ReposFunction::kNone);
  // PxxC.REPOS still 1: ignored. Jogging is plain jogging again (no target to stop at).
  r.Jog("A02C.JGNEG", 2);
  EXPECT_NEAR(r.Z(), -2, 1e-9);
  r.Jog("A02C.JGPOS", 2);
  EXPECT_FALSE(r.Get("P00S.CREST"));
  EXPECT_FALSE(r.Get("P00S.REPOS"));
}

// 2.1 / 7.1: in every other situation the NC ignores the control signals.
TEST(ChannelGatewayRepos, SignalsIgnoredOutsideTheInitialSituation) {
  {  // power-on, nothing interrupted
    ReposRig r;
    r.Set("P00C.REPOS", true);
    r.Press("P00C.MANU");
    r.IncrementJog();
    r.Jog("A02C.JGPOS", 2);
    EXPECT_EQ(r.ch->repos_function(), channel::ReposFunction::kNone);
    EXPECT_FALSE(r.Get("P00S.CREST"));
    EXPECT_FALSE(r.Get("P00S.REPOS"));
  }
  {  // interrupted, but the axes are still on the contour: every axis "restored", yet no CREST
    ReposRig r;
    r.Interrupt();
    r.Press("P00C.MANU");
    r.Set("P00C.REPOS", true);
    r.Set("P00C.RESTA", false);
    r.Cycle(10);
    EXPECT_TRUE(r.Get("P00S.REPOS"));
    EXPECT_EQ(r.ch->repos_function(), channel::ReposFunction::kNone);
    EXPECT_FALSE(r.Get("P00S.CREST"));
    // Once an axis leaves the contour the call counts (the level is still 1).
    r.IncrementJog();
    r.Jog("A02C.JGPOS");
    EXPECT_EQ(r.ch->repos_function(), channel::ReposFunction::kRepositioning);
  }
  {  // while the program runs
    ReposRig r;
    r.Press("P00C.START");
    r.Set("P00C.RESTA", true);
    r.Cycle(500);
    EXPECT_TRUE(r.Get("P00S.RUN"));
    EXPECT_EQ(r.ch->repos_function(), channel::ReposFunction::kNone);
    EXPECT_FALSE(r.Get("P00S.CREST"));
  }
  {  // after the end of the program, axes jogged away
    ReposRig r("N1 G01 X10 F3000\nN2 RET\n");
    r.Press("P00C.START");
    r.Cycle(2000);
    ASSERT_EQ(r.ch->state(), channel::ChannelState::kEnded);
    r.Press("P00C.MANU");
    r.IncrementJog();
    r.Jog("A01C.JGPOS");
    r.Set("P00C.REPOS", true);
    r.Cycle(10);
    EXPECT_EQ(r.ch->repos_function(), channel::ReposFunction::kNone);
    EXPECT_FALSE(r.Get("P00S.REPOS"));
    EXPECT_FALSE(r.Get("P00S.CREST"));
  }
}

// 2.1 / 2.3: the operator jogs away in manual mode and selects automatic mode to start
// repositioning there; until Start the axes stay where he left them (the held block does not
// pull them back onto its path).
TEST(ChannelGatewayRepos, AutomaticModeLeavesTheJoggedAxesWhereTheyAre) {
  ReposRig r;
  r.Interrupt();
  const double x = r.X();
  r.Press("P00C.MANU");
  r.IncrementJog();
  r.Jog("A02C.JGPOS", 3);
  r.Set("P00C.REPOS", true);
  r.Press("P00C.AUTO");
  ASSERT_TRUE(r.Get("P00S.AUTO"));
  r.Cycle(500);
  EXPECT_NEAR(r.Z(), 3, 1e-9);
  EXPECT_NEAR(r.X(), x, 1e-9);
  EXPECT_TRUE(r.Get("P00S.REPOS"));
  EXPECT_FALSE(r.Get("P00S.CREST"));
  // Start: the REPOS subroutine brings Z back with G77 at F3000, no step bigger than 50 mm/s
  // allows in one NC cycle.
  r.Press("P00C.START");
  double step = 0, last = r.Z();
  for (int k = 0; k < 2000 && r.Get("P00S.REPOS"); ++k) {
    r.Cycle();
    step = std::max(step, std::abs(r.Z() - last));
    last = r.Z();
  }
  EXPECT_LE(step, 0.05 + 1e-9);
  EXPECT_FALSE(r.Get("P00S.REPOS"));
  EXPECT_NEAR(r.Z(), 0, 1e-9);
}

// 7.1 / 7.4 instruction: the PLC withdraws PxxC.REPOS too soon, while the REPOS subroutine still
// has a G77 to run: the program is interrupted with an error message.
TEST(ChannelGatewayRepos, WithdrawnTooSoonInterruptsTheSubroutine) {
  ReposRig r;
  r.Interrupt();
  r.Press("P00C.MANU");
  r.IncrementJog();
  r.Jog("A02C.JGPOS", 3);
  r.Set("P00C.REPOS", true);
  r.Cycle();
  r.Press("P00C.AUTO");
  r.Press("P00C.START");
  r.Cycle(100);  // in the dwell N11
  ASSERT_TRUE(r.ch->repos_status().subroutine_running);
  r.Set("P00C.REPOS", false);
  r.Cycle(1000);
  EXPECT_TRUE(r.Get("P00S.ERROR"));
  EXPECT_EQ(r.GetInt("P00S.ERRNR"), channel::kMsgReposNotActive);
  EXPECT_NEAR(r.Z(), 3, 1e-9);  // N12 never moved
}

// 3.4: PxxC.MGPOS / PxxC.MGNEG jog an NC-controlled tool storage axis (drive 3) in manual
// mode; both at once: no motion.
TEST(ChannelGatewayRepos, MgposAndMgnegJogTheToolStorageAxis) {
  ReposRig r;
  channel::ChannelConfig config;
  for (int d = 0; d < 2; ++d) {
    channel::ChannelAxis a;
    a.name = d == 0 ? "X" : "Z";
    a.number = d + 1;
    a.drive = d;
    a.rapid_per_s = 400;
    a.acceleration = 4000;
    config.axes.push_back(a);
  }
  config.spindle_drive = 2;
  config.tool_storage_drive = 3;
  config.tool_storage_nc = true;
  config.tool_storage.rotary = true;
  config.tool_storage.jog_per_s = 30;
  config.tool_storage.acceleration = 720;
  r.ch = std::make_unique<channel::Channel>(config,
                                            std::vector<const nc::Program*>{&r.parsed.program});
  r.at.feedback.resize(4);
  r.at.feedback[3].status = drive_status::kReady;
  r.at.feedback[3].position = 90;
  r.mdt.setpoints.resize(4);
  r.Press("P00C.MANU");
  ASSERT_TRUE(r.Get("P00S.MANU"));
  r.Set("P00C.MGPOS", true);
  r.Cycle(1000);
  EXPECT_GT(r.mdt.setpoints[3].value, 115);  // about 30 deg in 1 s
  r.Set("P00C.MGNEG", true);                  // both: the axis brakes
  r.Cycle(100);
  const double t = r.mdt.setpoints[3].value;
  r.Cycle(100);
  EXPECT_EQ(r.mdt.setpoints[3].value, t);
  r.Set("P00C.MGPOS", false);  // MGNEG alone: back
  r.Cycle(1000);
  EXPECT_LT(r.mdt.setpoints[3].value, t - 25);
  r.Set("P00C.MGNEG", false);
}

}  // namespace
}  // namespace vmt::control::gateway
