// PathGuard of the NC turret and the spindle in the channel: a turret index (T word, MTP,
// MGPOS / MGNEG) is checked as the sweep of the turret drive before it starts, a spindle start
// (M3 in the program, G77 S1=0) as its sweep where the tools stand, and a move of the REPOS
// subroutine while the turret still indexes against the turret at its target station. A
// refusal is message 507 naming the move; a clear check is a record.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "control/channel/channel.hpp"
#include "nc_turret_machine.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing
using ::testing::HasSubstr;

/// Drives X 0, Z 1, spindle 2, turret 3 (deg). A tall part: with X below 50 the tools of the
/// turret between 100 and 110 deg reach it; station 4's long bar (turret at 90) reaches the
/// chuck below Z -5. A spindle start with X below 10 finds the tool in the jaws' sweep.
struct TurretScene : PathGuard {
  static bool Touches(const std::vector<double>& q) {
    const bool part = q[0] < 50 && q[3] >= 100 && q[3] <= 110;
    const bool chuck = q[1] < -5 && std::abs(q[3] - 90) < 2;
    return part || chuck;
  }
  PathCheck CheckMove(const std::vector<double>& from, const std::vector<double>& to) override {
    checks.push_back({from, to});
    PathCheck c;
    c.min_clearance = 1;
    c.closest_a = "tool", c.closest_b = "part";
    for (int i = 0; i <= 4000; ++i) {
      std::vector<double> q = from;
      for (size_t d = 0; d < q.size(); ++d) q[d] += (to[d] - from[d]) * i / 4000.0;
      if (!Touches(q)) continue;
      c.clear = false;
      c.part_a = "turret_tool", c.part_b = "part";
      c.position = q;
      c.min_clearance = 0;
      return c;
    }
    return c;
  }
  PathCheck CheckSpindleStart(const std::vector<double>& at, int spindle) override {
    ++spindle_checks;
    EXPECT_EQ(spindle, 2);
    PathCheck c;
    c.min_clearance = at[0] - 10;
    c.closest_a = "spindle_jaw1", c.closest_b = "tool";
    if (at[0] >= 10) return c;
    c.clear = false;
    c.part_a = "spindle_jaw1", c.part_b = "tool";
    c.position = at;
    c.min_clearance = 0;
    return c;
  }
  std::vector<std::pair<std::vector<double>, std::vector<double>>> checks;
  int spindle_checks = 0;
};

/// The turret machine at X `x`, turret `turret`, asking `guard`; its spindle reaches its
/// command at once.
struct Guarded : NcTurretMachine {
  Guarded(TurretScene& guard, const std::string& program, double x, double turret)
      : NcTurretMachine(program, turret) {
    at.feedback[0].position = x;
    channel->SetPathGuard(&guard);
  }
  void Step() {
    TickAll();
    Answer(2, test_support::IdealDrive::InstantSpindle());
  }
  void Run(double s) {
    for (int i = 0; i < s / 250e-6; ++i) Step();
  }
  std::vector<GuardRecord> Records(const std::string& move) {
    std::vector<GuardRecord> out;
    for (GuardRecord& r : channel->TakeGuardRecords())
      if (r.move == move) out.push_back(r);
    return out;
  }
};

TEST(TurretGuard, AnIndexSweepingThroughATallPartDoesNotStart) {
  // T5 (120 deg) from station 1: the turret would swing its tools through 100..110 at X 30.
  TurretScene scene;
  Guarded m(scene, "N1 T5\nN2 RET\n", 30, 0);
  m.channel->Start();
  m.Run(1.0);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgCollision);
  EXPECT_THAT(m.channel->error(), HasSubstr("collision ahead (turret index T5)"));
  EXPECT_THAT(m.channel->error(), HasSubstr("turret_tool would touch part"));
  EXPECT_THAT(m.channel->error(), HasSubstr("T100.0"));  // where the turret meets it
  EXPECT_EQ(m.T(), 0);                                  // never started
  const std::vector<GuardRecord> r = m.Records("turret index T5");
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(r[0].stopped);
  EXPECT_EQ(r[0].from[3], 0);
  EXPECT_EQ(r[0].to[3], 120);
}

TEST(TurretGuard, AClearIndexRunsWithItsRecord) {
  // The same index with X at 80, above the part: checked, clear, it runs.
  TurretScene scene;
  Guarded m(scene, "N1 T5\nN2 RET\n", 80, 0);
  m.channel->Start();
  m.Run(2.0);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.T(), 120, 1e-9);
  const std::vector<GuardRecord> r = m.Records("turret index T5");
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(r[0].check.clear);
  EXPECT_FALSE(r[0].stopped);
}

TEST(TurretGuard, AContinuousTurretJogStopsBeforeThePart) {
  // MGPOS from 60 at X 30: the tools reach the part at 100; the jog brakes before it.
  TurretScene scene;
  Guarded m(scene, "N1 RET\n", 30, 60);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->JogToolStorage(+1);
  m.Run(2.0);
  EXPECT_GT(m.T(), 60);
  EXPECT_LT(m.T(), 100);
  EXPECT_EQ(m.channel->error_number(), kMsgCollision);
  EXPECT_THAT(m.channel->error(), HasSubstr("collision ahead (turret index MGPOS)"));
  // Held: it stays; the other way is free.
  const double t = m.T();
  m.Run(0.5);
  EXPECT_EQ(m.T(), t);
  m.channel->JogToolStorage(-1);
  m.Run(0.5);
  EXPECT_LT(m.T(), t - 5);
  m.channel->JogToolStorage(0);
  m.Run(0.5);
}

TEST(TurretGuard, ATurretIncrementIntoThePartDoesNotStart) {
  // Parametric jog mode, one station (30 deg) per press: 80 -> 110 passes 100.
  TurretScene scene;
  Guarded m(scene, "N1 RET\n", 30, 80);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(2);
  m.channel->JogToolStorage(+1);
  m.Run(1.0);
  m.channel->JogToolStorage(0);
  EXPECT_EQ(m.T(), 80);
  EXPECT_EQ(m.channel->error_number(), kMsgCollision);
  EXPECT_THAT(m.channel->error(), HasSubstr("turret index MGPOS"));
}

TEST(TurretGuard, ASpindleStartWithTheToolInTheJawsSweepIsRefused) {
  TurretScene scene;
  Guarded m(scene, "N1 M3 S1000\nN2 G01 X100 F600\nN3 RET\n", 5, 0);
  m.channel->Start();
  m.Run(0.5);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgCollision);
  EXPECT_THAT(m.channel->error(),
              HasSubstr("collision ahead (spindle start): spindle_jaw1 would touch tool"));
  EXPECT_EQ(m.mdt.setpoints[2].value, 0);  // the spindle never started
  EXPECT_EQ(scene.spindle_checks, 1);
  // Away from the jaws it starts, checked once; an S word of the turning spindle is no start.
  TurretScene clear;
  Guarded n(clear, "N1 M3 S1000\nN2 S2000\nN3 G01 X100 F600\nN4 RET\n", 50, 0);
  n.channel->Start();
  n.Run(20);
  EXPECT_EQ(n.channel->state(), ChannelState::kEnded) << n.channel->error();
  EXPECT_EQ(clear.spindle_checks, 1);
  const std::vector<GuardRecord> r = n.Records("spindle start");
  ASSERT_EQ(r.size(), 1u);
  EXPECT_TRUE(r[0].check.clear);
}

/// Runs the program 3 s (at F600 X has gone about 30 mm), holds it and goes to manual mode.
void Interrupt(Guarded& m) {
  m.channel->Start();
  m.Run(3.0);
  m.channel->Stop();
  m.Run(0.2);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
}

TEST(TurretGuard, G77S1RestoringTheSpindleIntoTheToolIsRefused) {
  // Interrupted with the spindle turning; stopped (M5 key) and X jogged in to below 10, where
  // the tool stands in the jaws' sweep: G77 S1=0 does not start the spindle.
  TurretScene scene;
  Guarded m(scene,
            "N1 M3 S1000\nN2 G01 X100 F600\nN3 RET\n"
            ".REPOS\nN10 G77 S1=0\nN11 G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n",
            50, 0);
  Interrupt(m);
  m.channel->ManualSpindle(5);
  m.Run(0.2);
  m.channel->Jog(0, -1);
  while (m.X() > 5 && m.t < 30) m.Step();
  m.channel->Jog(0, 0);
  m.Run(0.3);
  ASSERT_LT(m.X(), 10);
  m.channel->SetReposition(true, false);
  m.Run(0.01);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.Run(0.5);
  EXPECT_EQ(m.channel->error_number(), kMsgCollision);
  EXPECT_THAT(m.channel->error(), HasSubstr("collision ahead (spindle start G77 S1)"));
  EXPECT_EQ(m.mdt.setpoints[2].value, 0);
}

/// Station 4 (90 deg) active, interrupted at X about 30: X jogged up to 60, the turret jogged
/// on to about 150 (clear up there), then X back down to `x`; repositioning called and started.
void TurretJoggedOffAndRepos(Guarded& m, double x) {
  Interrupt(m);
  m.channel->Jog(0, +1);
  while (m.X() < 60 && m.t < 30) m.Step();
  m.channel->Jog(0, 0);
  m.Run(0.3);
  m.channel->JogToolStorage(+1);
  while (m.T() < 150 && m.t < 30) m.Step();
  m.channel->JogToolStorage(0);
  m.Run(1.0);
  m.channel->Jog(0, -1);
  while (m.X() > x && m.t < 30) m.Step();
  m.channel->Jog(0, 0);
  m.Run(0.3);
  ASSERT_NE(m.channel->state(), ChannelState::kError) << m.channel->error();
  ASSERT_GT(m.T(), 140);
  m.channel->SetReposition(true, false);
  m.Run(0.01);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->TakeGuardRecords();
  m.channel->Start();
  m.Run(0.5);
}

TEST(TurretGuard, MtpSweepingThroughThePartDoesNotStart) {
  // X jogged back down to 40 beside the turret at 150: MTP back to 90 would sweep 110..100.
  TurretScene scene;
  Guarded m(scene,
            "N1 G01 X30 F600\nN2 G01 X100\nN3 RET\n"
            ".REPOS\nN10 MTP\nN11 MRY\nN12 G77 X0 F3000\nN13 G77 Z0 F3000 RTS\n",
            0, 90);
  TurretJoggedOffAndRepos(m, 40);
  EXPECT_EQ(m.channel->error_number(), kMsgCollision) << m.channel->error();
  EXPECT_THAT(m.channel->error(), HasSubstr("collision ahead (turret index MTP)"));
  EXPECT_GT(m.T(), 140);  // never started
}

TEST(TurretGuard, AMoveWhileTheTurretIndexesIsCheckedAtItsTargetStation) {
  // The REPOS subroutine's MTP starts the turret back from about 150 to station 4 (90), and
  // without MRY its next move (Z to -20) would run while it turns. Where the turret stands then (above 100) Z -20 is clear; at its target
  // station the long bar reaches the chuck below Z -5: the move never starts.
  TurretScene scene;
  Guarded m(scene,
            "N1 G01 X30 F600\nN2 G01 X100\nN3 RET\n"
            ".REPOS\nN10 MTP\nN11 G00 Z-20\nN12 MRY\nN13 G77 Z0 F3000\nN14 G77 X0 F3000 RTS\n",
            0, 90);
  TurretJoggedOffAndRepos(m, 60);
  EXPECT_EQ(m.channel->error_number(), kMsgCollision) << m.channel->error();
  EXPECT_THAT(m.channel->error(), HasSubstr("collision ahead (REPOS subroutine)"));
  EXPECT_THAT(m.channel->error(), HasSubstr("T90.000"));  // the turret at its target
  EXPECT_GT(m.Z(), -5);                                 // the move never started
  // The index itself (at Z where it stands) was clear.
  bool index_clear = false;
  for (const GuardRecord& r : m.channel->TakeGuardRecords())
    if (r.move == "turret index MTP") index_clear = r.check.clear;
  EXPECT_TRUE(index_clear);
}

}  // namespace
}  // namespace vmt::control::channel
