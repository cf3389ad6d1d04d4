// The channel running the measuring instructions of the fast-measurement manual on an ideal
// lathe whose X drive latches the stylus' contact (7.3), with a stand-in for the PLC's measuring
// block QMFB1Axx on the events (6.2): MeasuringLathe.
#include <gtest/gtest.h>

#include "tests/control/channel/measuring_lathe.hpp"

namespace vmt::control::channel::testing {
namespace {

TEST(ChannelMeasuring, ProbeMeasuresADiameterAndEscapesToTheStart) {
  // 5.2 example 1, P1 as radius programming: the surface at X30 measured along -X from 2 mm
  // away, approached directly, with escape (variant 1).
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
      "N3 RET\n",
      30.0);
  l.m.channel->Start();
  l.RunUntilStopped();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kEnded) << l.m.channel->error();
  const measure::PointPage* p = l.pages.Point(0, 1);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->measuring_axis, 'X');
  EXPECT_NEAR(p->value.command, 30, 1e-9);
  EXPECT_NEAR(p->value.actual, 30, 1e-9);
  EXPECT_NEAR(p->value.deviation, 0, 1e-9);
  // SETTING issued Q9992 to the PLC (6.1); PROBE set 29 and 30 (6.2).
  ASSERT_FALSE(l.q_functions.empty());
  EXPECT_EQ(l.q_functions.front(), 9992);
  EXPECT_NE(std::find(l.raised.begin(), l.raised.end(), 29), l.raised.end());
  EXPECT_NE(std::find(l.raised.begin(), l.raised.end(), 30), l.raised.end());
  EXPECT_FALSE(l.events[30]);  // the measuring path monitoring is off again
  // With escape the stylus is back where it started.
  EXPECT_NEAR(l.m.X(), 50, 1e-9);
  EXPECT_NEAR(l.m.Z(), 5, 1e-9);
  ASSERT_TRUE(l.m.channel->measuring_setting());
  EXPECT_EQ(l.m.channel->measuring_setting()->axis[0], 'X');
}

TEST(ChannelMeasuring, AnOversizePartIsMeasuredAsSuch) {
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,3,0)\n"
      "N3 RET\n",
      30.25);
  l.m.channel->Start();
  l.RunUntilStopped();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kEnded) << l.m.channel->error();
  const measure::PointPage* p = l.pages.Point(0, 1);
  EXPECT_NEAR(p->value.actual, 30.25, 1e-9);
  EXPECT_NEAR(p->value.deviation, 0.25, 1e-9);
  // Without escape (variant 3) the stylus stays at the setup position: 2 mm from the nominal
  // surface, the sphere radius taken into account (4.2, 4.5).
  EXPECT_NEAR(l.m.X(), 30 + 2 + kSphereRadius, 1e-9);
}

TEST(ChannelMeasuring, NoContactOnTheMeasuringPathIsTestPointNotFound) {
  // The part is 3 mm smaller than the program thinks: the doubled path (4 mm) ends short.
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
      "N3 RET\n"
      ".HOME\n"
      "N10 G00 X80\n"
      "N11 RET\n",
      25.0);
  l.m.channel->Start();
  l.RunUntilStopped();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kError);
  EXPECT_EQ(l.m.channel->error_number(), kMsgMeasuringReverseOnly);
  EXPECT_NE(l.m.channel->error().find("TEST POINT NOT FOUND"), std::string::npos)
      << l.m.channel->error();
  EXPECT_NE(l.m.channel->error().find("p.mtc:2:"), std::string::npos) << l.m.channel->error();
  // Q9999 is out; the PLC acknowledges it only when the reverse program runs (7.2 network 9).
  ASSERT_EQ(l.m.channel->aux_output().size(), 1u);
  EXPECT_EQ(l.m.channel->aux_output()[0].value, 9999);
  EXPECT_FALSE(l.events[30]);
  // Fault category 1: no advance start, only the reverse program.
  l.m.channel->Start();
  EXPECT_EQ(l.m.channel->state(), ChannelState::kError);
  ASSERT_TRUE(l.m.channel->Reverse());
  EXPECT_TRUE(l.m.channel->reversing());
  ASSERT_EQ(l.m.channel->aux_output().size(), 1u);  // still waiting for its acknowledgement
  l.RunUntilStopped();
  EXPECT_EQ(l.m.channel->state(), ChannelState::kEnded) << l.m.channel->error();
  EXPECT_EQ(l.q_functions.back(), 9999);
  EXPECT_NEAR(l.m.X(), 80, 1e-9);
}

TEST(ChannelMeasuring, OneInstructionPerBlockAndNothingElse) {
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 G00 X60 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
      "N3 RET\n",
      30.0);
  l.m.channel->Start();
  l.RunUntilStopped();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kError);
  EXPECT_EQ(l.m.channel->error_number(), kMsgMeasuringInstruction);
  EXPECT_NE(l.m.channel->error().find("p.mtc:2:"), std::string::npos) << l.m.channel->error();
}

TEST(ChannelMeasuring, ToolNoseRadiusCompensationMustBeOffBeforeProbe) {
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 G41\n"
      "N3 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
      "N4 RET\n",
      30.0);
  l.m.channel->Start();
  l.RunUntilStopped();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kError);
  EXPECT_EQ(l.m.channel->error_number(), kMsgMeasuringInstruction) << l.m.channel->error();
  EXPECT_NE(l.m.channel->error().find("p.mtc:3:"), std::string::npos) << l.m.channel->error();
}

TEST(ChannelMeasuring, OversizeHoldsTheProgramAndStartContinuesIt) {
  // A point comparison of a part 0.05 mm oversize against a tolerance of +-0.01: OVERSIZE
  // (Q9998, 4.6 dimensional accuracy 1); the new start continues (6.1 fault category 2).
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
      "N3 COMPARE(1,0,1,)\n"
      "N4 CORRECTION(1,0.01,-0.01,0.4,0.3,0,1,100,0.005,0.001)\n"
      "N5 RET\n",
      30.05);
  l.m.channel->Start();
  l.RunUntilStopped();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kHold) << l.m.channel->error();
  EXPECT_EQ(l.m.channel->error_number(), kMsgMeasuringContinuable);
  EXPECT_NE(l.m.channel->error().find("OVERSIZE"), std::string::npos) << l.m.channel->error();
  EXPECT_EQ(l.q_functions.back(), 9998);
  // Block search 5.6: a fault in the channel holds the program, not a feed hold.
  EXPECT_EQ(l.m.channel->block_search().stop_conditions, stop_condition::kChannelError);
  const measure::ErgebnisPage* r = l.pages.Result(0, 1);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->dimensional_accuracy, 1);
  EXPECT_NEAR(r->correction_value, 0.05, 1e-9);
  l.m.channel->Start();
  l.RunUntilStopped();
  EXPECT_EQ(l.m.channel->state(), ChannelState::kEnded) << l.m.channel->error();
}

TEST(ChannelMeasuring, SaveAndRestoreGiveTheVariablesBack) {
  MeasuringLathe l(
      "N1 @100 = 7\n"
      "N2 SETTING(X,Z,,18,48,15,1)\n"
      "N3 SAVE(1,0,0)\n"
      "N4 @100 = 9\n"
      "N5 RESTORE()\n"
      "N6 BRA .CHECK\n"
      ".CHECK\n"
      "N7 @101 = @100 - 7\n"
      "N8 BEQ .OK\n"
      "N9 G00 X99\n"
      ".OK\n"
      "N10 RET\n",
      30.0);
  l.m.channel->Start();
  l.RunUntilStopped();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kEnded) << l.m.channel->error();
  EXPECT_NEAR(l.m.X(), 50, 1e-9);  // @100 was 7 again: no G00 X99
}

TEST(ChannelMeasuring, ReverseTakesTheStylusBackTheWayItCameBeforeHome) {
  // Indirect approach (variant 2, 4.2): X to the plane of the setup position first, then Z to
  // the measurement start point. Stopped on the second leg, the reverse program first takes the
  // stylus back along the legs it travelled (4.4, single point), never on towards the part.
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,2,0)\n"
      "N3 RET\n"
      ".HOME\n"
      "N10 G00 X80\n"
      "N11 RET\n",
      30.0, 50, 20);
  l.m.channel->Start();
  while (l.m.Z() > 12 && l.m.t < 10) l.Tick();
  ASSERT_NEAR(l.m.X(), 35, 1e-9);  // on the second leg
  l.m.channel->Stop();
  for (int i = 0; i < 4000; ++i) l.Tick();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kHold);
  const double z_stop = l.m.Z();
  ASSERT_TRUE(l.m.channel->Reverse());
  double z_min = z_stop, x_min = l.m.X();
  bool at_setup_plane_corner = false;
  while (l.m.channel->state() == ChannelState::kRunning && l.m.t < 30) {
    l.Tick();
    z_min = std::min(z_min, l.m.Z());
    x_min = std::min(x_min, l.m.X());
    at_setup_plane_corner |= std::abs(l.m.X() - 35) < 1e-9 && std::abs(l.m.Z() - 20) < 1e-9;
  }
  EXPECT_EQ(l.m.channel->state(), ChannelState::kEnded) << l.m.channel->error();
  EXPECT_GE(z_min, z_stop - 1e-9);  // not on to the measurement start point
  EXPECT_GE(x_min, 35 - 1e-9);
  EXPECT_TRUE(at_setup_plane_corner);  // back along the second leg first
  EXPECT_NEAR(l.m.Z(), 20, 1e-9);      // then the first: the start
  EXPECT_NEAR(l.m.X(), 80, 1e-9);      // and .HOME's G00 X80
}

// 6.1, 7.2 Q_MTstKol: the probe displaced on the way to the setup position (event 29 set) is a
// collision the NC reports with Q9999 itself, whatever the PLC does: the axes stop at once, the
// program fails with fault category 1, and the reverse program takes the stylus back.
TEST(ChannelMeasuring, AProbeDisplacedOnTheApproachStopsWithQ9999) {
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,2,0)\n"
      "N3 RET\n"
      ".HOME\n"
      "N10 G00 X80\n"
      "N11 RET\n",
      30.0, 50, 20);
  l.m.channel->Start();
  while (l.m.Z() > 12 && l.m.t < 10) l.Tick();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kRunning);
  ASSERT_TRUE(l.events[29]);
  l.probe_level = true;  // a normally open contact closes: displaced
  // The next NC cycle sees it (the stand-in PLC acknowledges Q9999 only in the tick after).
  const double t_displaced = l.m.t;
  while (l.m.channel->state() == ChannelState::kRunning && l.m.t < 10) l.Tick();
  EXPECT_LT(l.m.t - t_displaced, 0.01);
  ASSERT_EQ(l.m.channel->state(), ChannelState::kError);
  EXPECT_EQ(l.m.channel->error_number(), kMsgMeasuringReverseOnly);
  EXPECT_NE(l.m.channel->error().find("p.mtc:2:"), std::string::npos) << l.m.channel->error();
  EXPECT_NE(l.m.channel->error().find("probe displaced outside the measuring path"),
            std::string::npos)
      << l.m.channel->error();
  ASSERT_EQ(l.m.channel->aux_output().size(), 1u);
  EXPECT_EQ(l.m.channel->aux_output()[0].value, 9999);
  EXPECT_FALSE(l.events[30]);  // the measuring path never began
  const double x_stop = l.m.X(), z_stop = l.m.Z();
  for (int i = 0; i < 400; ++i) l.Tick();
  EXPECT_EQ(l.m.X(), x_stop);  // nothing moves on
  EXPECT_EQ(l.m.Z(), z_stop);
  l.m.channel->Start();  // fault category 1: no advance start
  EXPECT_EQ(l.m.channel->state(), ChannelState::kError);
  // The reverse program runs with the stylus still deflected (unwatched) and acknowledges.
  ASSERT_TRUE(l.m.channel->Reverse());
  l.RunUntilStopped();
  EXPECT_EQ(l.m.channel->state(), ChannelState::kEnded) << l.m.channel->error();
  EXPECT_EQ(l.q_functions.back(), 9999);
  EXPECT_NEAR(l.m.Z(), 20, 1e-9);  // back along the leg it travelled
  EXPECT_NEAR(l.m.X(), 80, 1e-9);
}

// A MOVE leaves event 29 set: the stylus stays watched until the next PROBE's setup position,
// also in the blocks between (here a dwell, the block the error names).
TEST(ChannelMeasuring, AfterAMoveTheProbeStaysWatched) {
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 MOVE(45,5,,1,0)\n"
      "N3 G04 F1\n"
      "N4 RET\n",
      30.0);
  l.m.channel->Start();
  while (l.m.t < 0.5) l.Tick();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kRunning);
  ASSERT_NEAR(l.m.X(), 45, 1e-9);
  l.probe_level = true;
  while (l.m.channel->state() == ChannelState::kRunning && l.m.t < 10) l.Tick();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kError);
  EXPECT_NE(l.m.channel->error().find("p.mtc:3:"), std::string::npos) << l.m.channel->error();
  ASSERT_EQ(l.m.channel->aux_output().size(), 1u);
  EXPECT_EQ(l.m.channel->aux_output()[0].value, 9999);
}

// A normally closed contact reads 0 while the probe is off (the fail-safe "displaced"): the NC
// counts a displacement only after the drive has shown the probe free since event 29.
TEST(ChannelMeasuring, ANormallyClosedProbeCountsOnlyAfterItWasFree) {
  const char* program =
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
      "N3 RET\n";
  {
    MeasuringLathe l(program, 30.0);
    l.pages.stylus[0].normally_closed = true;
    l.probe_level = false;  // never switched on: reads 0 all along
    l.m.channel->Start();
    l.RunUntilStopped();
    EXPECT_EQ(l.m.channel->state(), ChannelState::kEnded) << l.m.channel->error();
  }
  {
    MeasuringLathe l(program, 30.0);
    l.pages.stylus[0].normally_closed = true;
    l.probe_level = true;  // on and free: the contact is closed
    l.m.channel->Start();
    for (int i = 0; i < 40; ++i) l.Tick();
    ASSERT_EQ(l.m.channel->state(), ChannelState::kRunning);
    ASSERT_TRUE(l.events[29]);
    l.probe_level = false;  // opens: displaced
    const double t_open = l.m.t;
    while (l.m.channel->state() == ChannelState::kRunning && l.m.t < 10) l.Tick();
    EXPECT_LT(l.m.t - t_open, 0.01);  // within an NC cycle or two
    ASSERT_EQ(l.m.channel->state(), ChannelState::kError);
    EXPECT_NE(l.m.channel->error().find("TEST POINT NOT FOUND"), std::string::npos);
  }
}

TEST(ChannelMeasuring, ReverseRetracesALinearPathSequenceWithEachLegsSphere) {
  // 4.4 linear path sequence 2 over three MOVEs that change the sphere (figure 4-9 blocks 54, 55
  // do): sphere 2's centre is 4 mm lower in X and 6 mm further in Z than sphere 1's (tool
  // lengths -4, 6: the axes stand at the centre minus them). Stopped on the third
  // leg, the reverse program takes the axes back through the very axis positions the legs
  // started from, each point with the sphere it was reached with, then runs .HOME.
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 MOVE(60,20,,1,2)\n"
      "N3 MOVE(60,10,,2,2)\n"
      "N4 MOVE(40,10,,2,2)\n"
      "N5 RET\n"
      ".HOME\n"
      "N10 G00 X90\n"
      "N11 RET\n",
      0.0, 80, 30, [](ChannelConfig& c) {
        c.tools.edges.push_back({3, 2, {-4, 6}, 2, 0});
      });
  l.pages.stylus[0].sphere_radius[1] = 2;
  l.m.channel->Start();
  while (l.m.X() > 50 && l.m.t < 10) l.Tick();  // on N4's leg: axes X 64 -> 44 at Z4
  ASSERT_NEAR(l.m.Z(), 4, 1e-9);
  l.m.channel->Stop();
  for (int i = 0; i < 4000; ++i) l.Tick();
  ASSERT_EQ(l.m.channel->state(), ChannelState::kHold);
  const double x_stop = l.m.X();
  const measure::ReverseVectors& r = l.m.channel->reverse_vectors();
  ASSERT_EQ(r.active, 2);
  ASSERT_EQ(r.sequence[1].size(), 4u);  // the start and the three MOVEs' points, recorded
  ASSERT_TRUE(l.m.channel->Reverse());
  // The corners the axes must pass: N4's start (sphere 2 at X60 Z10: axes X64 Z4, not X60 Z10
  // as sphere 1 would put them), N3's start (sphere 1 at X60 Z20), the sequence's start X80 Z30.
  const std::array<std::array<double, 2>, 3> corners = {{{64, 4}, {60, 20}, {80, 30}}};
  size_t next = 0;
  double x_min = l.m.X();
  while (l.m.channel->state() == ChannelState::kRunning && l.m.t < 40) {
    l.Tick();
    x_min = std::min(x_min, l.m.X());
    if (next < corners.size() && std::abs(l.m.X() - corners[next][0]) < 1e-9 &&
        std::abs(l.m.Z() - corners[next][1]) < 1e-9)
      ++next;
  }
  EXPECT_EQ(l.m.channel->state(), ChannelState::kEnded) << l.m.channel->error();
  EXPECT_EQ(next, corners.size()) << "corner " << next << " not passed";
  EXPECT_GE(x_min, x_stop - 1e-9);  // never on along N4's leg
  EXPECT_NEAR(l.m.X(), 90, 1e-9);
  EXPECT_NEAR(l.m.Z(), 30, 1e-9);
}

// Feed hold during a PROBE (the manual says nothing of it): the axes brake on the path and
// stand; the instruction keeps its place in the plan and the measuring path stays armed (event
// 30 set, nothing re-armed), so a start continues it to the same measured value.
void HoldAndContinue(MeasuringLathe& l, const std::function<bool()>& where, bool on_measuring_path,
                     bool measured_before = false) {
  l.m.channel->Start();
  while (!where() && l.m.t < 10) l.Tick();
  ASSERT_LT(l.m.t, 10);
  EXPECT_EQ(l.events[30], on_measuring_path);
  l.m.channel->Stop();
  for (int i = 0; i < 2000; ++i) l.Tick();  // braked
  ASSERT_EQ(l.m.channel->state(), ChannelState::kHold);
  const double x = l.m.X(), z = l.m.Z();
  for (int i = 0; i < 8000; ++i) l.Tick();  // two seconds held
  EXPECT_EQ(l.m.X(), x);
  EXPECT_EQ(l.m.Z(), z);
  EXPECT_EQ(l.events[30], on_measuring_path);  // measuring path monitoring as it was
  ASSERT_NE(l.pages.Point(0, 1), nullptr);
  // Before the contact nothing is measured yet; after it the latch has given the value.
  EXPECT_EQ(l.pages.Point(0, 1)->measuring_axis, measured_before ? 'X' : 0);
  l.m.channel->Start();
  l.RunUntilStopped(40);
  ASSERT_EQ(l.m.channel->state(), ChannelState::kEnded) << l.m.channel->error();
}

TEST(ChannelMeasuring, FeedHoldDuringTheApproachThenStartMeasures) {
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
      "N3 RET\n",
      30.1);
  HoldAndContinue(
      l, [&] { return l.m.X() < 42; }, false);
  const measure::PointPage* p = l.pages.Point(0, 1);
  EXPECT_NEAR(p->value.actual, 30.1, 1e-9);
  EXPECT_NEAR(l.m.X(), 50, 1e-9);  // escaped to the start
  EXPECT_FALSE(l.events[30]);
}

TEST(ChannelMeasuring, FeedHoldOnTheMeasuringPathThenStartMeasures) {
  // The measuring path runs from the setup position X35 towards X31 at 100 mm/min; the hold
  // comes half a millimetre along it, before the sphere (surface 30.1: contact at X33.1).
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
      "N3 RET\n",
      30.1);
  HoldAndContinue(
      l, [&] { return l.events[30] && l.m.X() < 34.5; }, true);
  const measure::PointPage* p = l.pages.Point(0, 1);
  EXPECT_NEAR(p->value.actual, 30.1, 1e-9);
  EXPECT_NEAR(l.m.X(), 50, 1e-9);
  EXPECT_FALSE(l.events[30]);
  EXPECT_TRUE(l.events[7]);  // the contact was reported on the continued path
}

TEST(ChannelMeasuring, FeedHoldAfterTheContactKeepsTheMeasuredValue) {
  // The hold in the cycle of the contact: the latch has ended the measuring path and given the
  // value; the hold stops the way back, a start takes the stylus on to the start.
  MeasuringLathe l(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n"
      "N3 RET\n",
      30.1);
  HoldAndContinue(
      l, [&] { return l.m.at.feedback[0].probe.probe1.positive.latched; }, true, true);
  EXPECT_NEAR(l.pages.Point(0, 1)->value.actual, 30.1, 1e-9);
  EXPECT_NEAR(l.m.X(), 50, 1e-9);
}

}  // namespace
}  // namespace vmt::control::channel::testing
