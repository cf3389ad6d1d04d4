// An NC-controlled tool storage axis in the program (REPOS manual 4.2 Tool Storage Axis: "As in
// NC-program controlled mode, the tool storage axis can sometimes traverse asynchronously with
// the other axes ... MRY to synchronize"): a T word indexes the turret to its station while the
// next blocks run, MRY waits for it, MTP outside the REPOS subroutine adjusts it to the active
// tool's station, and the interruption keeps the station it was traversed to for REPOS's MTP.
// A turret the PLC controls is untouched by all this.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "block_search_steps.hpp"
#include "control/channel/channel.hpp"
#include "nc_turret_machine.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing
using ::testing::HasSubstr;

/// Ticks while the program runs, up to `limit` s; `each_tick` looks at the axes after every tick.
void RunWhileRunning(NcTurretMachine& m, double limit,
                     const std::function<void()>& each_tick = {}) {
  while (m.channel->state() == ChannelState::kRunning && m.t < limit) {
    m.TickAll();
    if (each_tick) each_tick();
  }
}

/// Runs until the program has ended (or failed), then until the turret stands still.
void RunToEnd(NcTurretMachine& m) {
  RunWhileRunning(m, 60);
  m.RunFor(3.0);
}

/// The start key, then RunToEnd.
void StartAndRunToEnd(NcTurretMachine& m) {
  m.channel->Start();
  RunToEnd(m);
}

/// Z jogged off in + for 0.2 s, and the time for a traverse still on its way to finish.
void JogZOff(NcTurretMachine& m) {
  m.channel->Jog(1, +1);
  m.RunFor(0.2);
  m.channel->Jog(1, 0);
  m.RunFor(2.0);
}

/// The turret jogged in `direction` for `s` s, then braked to rest.
void JogTurret(NcTurretMachine& m, int direction, double s) {
  m.channel->JogToolStorage(direction);
  m.RunFor(s);
  m.channel->JogToolStorage(0);
  m.RunFor(0.5);
}

// A T word starts the turret for its station (T6: 150 deg from station 1 at 0) and the block
// does not wait: X's move of the next block runs while the turret is still on its way.
TEST(ToolStorageProgram, ATWordIndexesTheTurretAsynchronously) {
  NcTurretMachine m("N1 T6\nN2 G01 X10 F6000\nN3 RET\n", 0);
  m.channel->Start();
  bool overlapped = false;
  RunWhileRunning(m, 10, [&] {
    if (m.X() > 0 && m.X() < 10 && m.T() > 1 && m.T() < 149) overlapped = true;
  });
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_TRUE(overlapped);
  EXPECT_LT(m.T(), 149);  // the program has ended, the turret is still indexing
  m.RunFor(3.0);
  EXPECT_NEAR(m.T(), 150, 1e-9);
  EXPECT_NEAR(m.X(), 10, 1e-9);
}

// At the jogging rapid (Cxx.021), as MTP in the REPOS subroutine: no speed is programmed.
TEST(ToolStorageProgram, TheTurretRunsAtTheJoggingRapid) {
  NcTurretMachine m("N1 T6\nN2 RET\n", 0);
  m.channel->Start();
  double fastest = 0, last = m.T();
  for (int i = 0; i < 8000; ++i) {
    m.TickAll();
    fastest = std::max(fastest, std::abs(m.T() - last) / 250e-6);
    last = m.T();
  }
  EXPECT_NEAR(fastest, 180, 1.0);
  EXPECT_NEAR(m.T(), 150, 1e-9);
}

// Endless: T12 from station 1 goes the short way round, 30 deg back, not 330 forward; the
// station is the same one (the adjust symbol and MTP compare modulo a turn).
TEST(ToolStorageProgram, AnEndlessTurretIndexesTheShortWayRound) {
  NcTurretMachine m("N1 T12\nN2 RET\n", 0);
  StartAndRunToEnd(m);
  EXPECT_NEAR(m.T(), -30, 1e-9);
  // From 420 (station 3 a turn on) to T4: 30 deg on.
  NcTurretMachine n("N1 T4\nN2 RET\n", 420);
  StartAndRunToEnd(n);
  EXPECT_NEAR(n.T(), 450, 1e-9);
  // Half a turn either way: the way the adjust symbol and REPOS's MTP measure it, backwards.
  NcTurretMachine k("N1 T7\nN2 RET\n", 0);
  StartAndRunToEnd(k);
  EXPECT_NEAR(k.T(), -180, 1e-9);
}

// With travel limits the turret goes to the station's angle itself, back the way it came (a
// turret whose cables must not wind up).
TEST(ToolStorageProgram, ATurretWithTravelLimitsGoesToTheStationsAngle) {
  NcTurretMachine m("N1 T12\nN2 RET\n", 0, true, [](ChannelConfig& c) {
    c.tool_storage.travel_min = -360;
    c.tool_storage.travel_max = 360;
  });
  StartAndRunToEnd(m);
  EXPECT_NEAR(m.T(), 330, 1e-9);
}

TEST(ToolStorageProgram, MryWaitsForTheTurret) {
  NcTurretMachine m("N1 T6\nN2 MRY G01 X10 F6000\nN3 RET\n", 0);
  m.channel->Start();
  bool moved_early = false;
  RunWhileRunning(m, 10, [&] {
    if (m.X() > 0 && std::abs(m.T() - 150) > kToolStorageWindow) moved_early = true;
  });
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_FALSE(moved_early);
  EXPECT_NEAR(m.T(), 150, 1e-9);
  EXPECT_NEAR(m.X(), 10, 1e-9);
}

// MRY waits for the drive, not only for its command: a turret held back (clamped, lagging)
// holds the program until it stands at the station.
TEST(ToolStorageProgram, MryWaitsForTheDriveNotTheCommand) {
  NcTurretMachine m("N1 T2\nN2 G01 X10 F6000\nN3 MRY G01 X20\nN4 RET\n", 0);
  m.channel->Start();
  for (int i = 0; i < 8000; ++i) m.Tick();  // 2 s: the drive does not follow
  EXPECT_NEAR(m.channel->tool_storage_command(), 30, 1e-9);
  EXPECT_EQ(m.T(), 0);
  EXPECT_NEAR(m.X(), 10, 1e-9);
  EXPECT_EQ(m.channel->state(), ChannelState::kRunning);
  RunToEnd(m);  // now it follows
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 20, 1e-9);
}

// Control-Reset brakes an index to a stop between stations; an MRY after it has nothing to
// wait for.
TEST(ToolStorageProgram, ControlResetStopsTheIndex) {
  NcTurretMachine m("N1 T6\nN2 G01 X100 F600\nN3 RET\n", 0);
  m.channel->Start();
  m.RunFor(0.5);
  m.channel->Reset();
  m.RunFor(1.0);
  const double stopped = m.T();
  EXPECT_GT(stopped, 30);
  EXPECT_LT(stopped, 140);
  m.RunFor(1.0);
  EXPECT_EQ(m.T(), stopped);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kMdi));
  ASSERT_TRUE(m.channel->Mdi("MRY G01 X5 F6000\n"));
  StartAndRunToEnd(m);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 5, 1e-9);
  EXPECT_EQ(m.T(), stopped);
}

// C-axis manual 2.3: without the process enabling signal the axes come to a standstill, the
// turret's index among them; it goes on to its station when the signal is back.
TEST(ToolStorageProgram, RemovingTheProcessEnableBrakesTheIndex) {
  NcTurretMachine m("N1 T6\nN2 MRY\nN3 RET\n", 0);
  m.channel->Start();
  m.RunFor(0.5);  // at 180 deg/s
  m.channel->SetProcessEnable(false);
  m.RunFor(0.5);
  const double stopped = m.T();
  EXPECT_GT(stopped, 75);  // braked at 720 deg/s^2 (some 22 deg), not stopped dead
  EXPECT_LT(stopped, 140);
  m.RunFor(1.0);
  EXPECT_EQ(m.T(), stopped);
  // The removal held the program; the index goes on at once, as through a feed hold.
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  m.channel->SetProcessEnable(true);
  m.RunFor(2.0);
  EXPECT_NEAR(m.T(), 150, 1e-9);
  StartAndRunToEnd(m);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

// MRY in a block of its own, and MRY with the turret at its station: no wait at all.
TEST(ToolStorageProgram, MryWithTheTurretInPlaceDoesNotWait) {
  NcTurretMachine m("N1 T3\nN2 MRY\nN3 G01 X10 F6000\nN4 MRY\nN5 RET\n", 60);
  m.channel->Start();
  RunWhileRunning(m, 10);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.T(), 60, 1e-9);
  EXPECT_NEAR(m.X(), 10, 1e-9);
  // As long as without the MRY blocks, but for their own NC cycles.
  NcTurretMachine n("N1 T3\nN3 G01 X10 F6000\nN5 RET\n", 60);
  n.channel->Start();
  RunWhileRunning(n, 10);
  EXPECT_NEAR(m.t, n.t, 0.005);
}

// MTP outside the REPOS subroutine ("Adjust tool turret", 8.3): the active tool's station,
// here after the turret stood between stations, and with the block's MRY waiting for it.
TEST(ToolStorageProgram, MtpAdjustsTheTurretToTheActiveToolsStation) {
  NcTurretMachine m("N1 MTP\nN2 MRY G01 X10 F6000\nN3 RET\n", 100, true,
                    [](ChannelConfig& c) { c.initial.tool = 3; });
  m.channel->Start();
  bool moved_early = false;
  RunWhileRunning(m, 10, [&] {
    if (m.X() > 0 && std::abs(m.T() - 60) > kToolStorageWindow) moved_early = true;
  });
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_FALSE(moved_early);
  EXPECT_NEAR(m.T(), 60, 1e-9);
  // T0 selects no tool: MTP leaves the turret where it is.
  NcTurretMachine n("N1 T0 MTP\nN2 RET\n", 100);
  StartAndRunToEnd(n);
  EXPECT_EQ(n.channel->state(), ChannelState::kEnded) << n.channel->error();
  EXPECT_NEAR(n.T(), 100, 1e-9);
}

TEST(ToolStorageProgram, ATWordWithoutAStationIsAnErrorAtItsBlock) {
  NcTurretMachine m("N1 G01 X10 F6000\nN2 T13\nN3 RET\n", 0);
  StartAndRunToEnd(m);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_THAT(m.channel->error(), HasSubstr("p.mtc:2:"));
  EXPECT_THAT(m.channel->error(), HasSubstr("T13 has no station on the tool storage axis T"));
  EXPECT_EQ(m.channel->error_number(), kMsgProgramError);
  EXPECT_NEAR(m.T(), 0, 1e-9);
}

// The manual describes MMP, MRF, MHP, MFP and MOP only by name (4.2): they stay unavailable.
TEST(ToolStorageProgram, TheOtherTurretCommandsStayUnavailable) {
  for (const char* name : {"MMP", "MRF", "MHP", "MFP", "MOP"}) {
    NcTurretMachine m(std::string("N1 ") + name + "\nN2 RET\n", 0);
    StartAndRunToEnd(m);
    EXPECT_EQ(m.channel->state(), ChannelState::kError) << name;
    EXPECT_THAT(m.channel->error(), HasSubstr(std::string("instruction ") + name +
                                              " is not supported by vmt (docs/conformance.md)"));
  }
  // Without stations the NC cannot know where MTP would go.
  NcTurretMachine n("N1 MTP\nN2 RET\n", 0, true,
                    [](ChannelConfig& c) { c.tool_storage_stations = 0; });
  StartAndRunToEnd(n);
  EXPECT_THAT(n.channel->error(), HasSubstr("instruction MTP is not supported"));
}

const char* kReposProgram =
    "N1 T6\nN2 G01 X100 F600\nN3 RET\n"
    ".REPOS\nN10 MTP\nN11 MRY G77 Z0 F3000\nN12 G77 X0 F3000 RTS\n";

/// Feed hold at `at` s, manual mode, Z jogged off, the turret jogged on for `jog` s.
void InterruptAndJogOff(NcTurretMachine& m, double at, double jog) {
  m.channel->Start();
  m.RunFor(at);
  m.channel->Stop();
  m.RunFor(0.05);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  JogZOff(m);
  JogTurret(m, +1, jog);
}

/// Repositioning, the REPOS subroutine (MTP, MRY, G77) and the rest of the program.
void Reposition(NcTurretMachine& m) {
  m.channel->SetReposition(true, false);
  m.RunFor(0.01);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  const double z = m.Z();
  RunWhileRunning(m, 60, [&] {
    if (std::abs(m.T() - 150) > kToolStorageWindow) {
      EXPECT_EQ(m.Z(), z);  // MRY
    }
  });
}

// Interrupted after T6's indexing has ended: REPOS's MTP brings the turret back to station 6
// from where the operator jogged it.
TEST(ToolStorageProgram, ReposReturnsToTheStationATWordIndexed) {
  NcTurretMachine m(kReposProgram, 0);
  InterruptAndJogOff(m, 2.0, 1.0);
  EXPECT_GT(m.T(), 170);
  EXPECT_TRUE(m.channel->repos_status().tool_storage_adjust);
  Reposition(m);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.T(), 150, 1e-9);
  EXPECT_NEAR(m.X(), 100, 1e-9);
}

// 4.2: "the location which had been traversed to prior to the interruption" - interrupted while
// T6's indexing is still on its way, the interruption keeps station 6, not where the turret
// had got to.
TEST(ToolStorageProgram, AnInterruptionDuringTheIndexKeepsItsStation) {
  NcTurretMachine m(kReposProgram, 0);
  m.channel->Start();
  m.RunFor(0.5);
  m.channel->Stop();
  m.RunFor(0.05);
  ASSERT_LT(m.T(), 140);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.RunFor(0.01);
  EXPECT_TRUE(m.channel->repos_status().tool_storage_adjust);  // not yet at station 6
  JogZOff(m);
  EXPECT_NEAR(m.T(), 150, 1e-9);  // the index ran on in manual mode
  JogTurret(m, -1, 1.0);          // back towards where it was at the interruption
  EXPECT_LT(m.T(), 130);
  Reposition(m);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.T(), 150, 1e-9);
  EXPECT_NEAR(m.X(), 100, 1e-9);
}

// Block search outputs the skipped part's technology as a run does: the T words it passes
// index the turret, which ends at the station of the last one (T6) while the axes return.
TEST(ToolStorageProgram, BlockSearchIndexesTheTurretAtTheTWordsItPasses) {
  BlockSearchSteps<NcTurretMachine> m(
      "N10 T3\nN20 G01 X10 F600\nN30 T6\nN40 G01 X20\nN50 G01 X30\nN60 RET\n", 0);
  BlockSearchParameters p;
  p.type = BlockSearchType::kBlockNumber;
  p.block_number = 50;
  p.covered_distance = 500;
  p.auto_return = true;
  m.Search(p);
  ASSERT_TRUE(m.ToContour()) << m.channel->error();
  m.RunFor(2.0);
  EXPECT_NEAR(m.channel->tool_storage_command(), 150, 1e-9);
  EXPECT_NEAR(m.X(), 25, 1e-6);
}

// Interrupted after the command has reached the station but before the drive has (it lags,
// or is held): the interruption keeps the station, so the turret is restored once it stands
// there and REPOS's MTP would not take it back to where it lagged.
TEST(ToolStorageProgram, AnInterruptionWhileTheDriveLagsKeepsTheStation) {
  NcTurretMachine m("N1 T6\nN2 G01 X100 F600\nN3 RET\n", 0);
  m.channel->Start();
  for (int i = 0; i < 8000; ++i) m.Tick();  // 2 s: the drive held back
  m.channel->Stop();
  for (int i = 0; i < 200; ++i) m.Tick();
  ASSERT_NEAR(m.channel->tool_storage_command(), 150, 1e-9);
  ASSERT_EQ(m.T(), 0);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.RunFor(0.5);  // now it follows
  EXPECT_NEAR(m.T(), 150, 1e-9);
  EXPECT_FALSE(m.channel->repos_status().tool_storage_adjust);
}

/// The same turret, controlled by the PLC (tool_storage_nc off), with the T handshake.
struct PlcTurretMachine : NcTurretMachine {
  explicit PlcTurretMachine(const std::string& program)
      : NcTurretMachine(program, 0, true, [](ChannelConfig& c) {
          c.tool_storage_nc = false;
          c.aux_handshake = true;
        }) {}
};

// 5: as before - T goes to the PLC and the block waits for its acknowledgement, the NC
// commands nothing on the turret's drive, and MTP / MRY outside REPOS are not available.
TEST(ToolStorageProgram, APlcTurretIsUnchanged) {
  PlcTurretMachine m("N1 T7\nN2 G01 X10 F6000\nN3 RET\n");
  m.channel->Start();
  m.RunFor(0.2);
  ASSERT_EQ(m.channel->aux_output().size(), 1u);
  EXPECT_EQ(m.channel->aux_output()[0].letter, 'T');
  EXPECT_EQ(m.channel->aux_output()[0].value, 7);
  EXPECT_EQ(m.X(), 0);  // the block waits for the PLC
  EXPECT_NE(m.mdt.setpoints[3].mode, DriveMode::kPosition);
  EXPECT_TRUE(std::isnan(m.channel->tool_storage_command()));
  m.channel->AcknowledgeAux();
  RunToEnd(m);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_EQ(m.T(), 0);
  EXPECT_NEAR(m.X(), 10, 1e-9);
  for (const char* name : {"MTP", "MRY"}) {
    PlcTurretMachine n(std::string("N1 ") + name + "\nN2 RET\n");
    StartAndRunToEnd(n);
    EXPECT_THAT(n.channel->error(), HasSubstr(std::string("instruction ") + name +
                                              " is not supported by vmt (docs/conformance.md)"));
  }
}

// The NC turret's T word still goes to the PLC (its tool number), which acknowledges it as any
// T; the turret does not wait for that, nor the block for the turret.
TEST(ToolStorageProgram, AnNcTurretsTWordStillGoesToThePlc) {
  NcTurretMachine m("N1 T6\nN2 G01 X10 F6000\nN3 RET\n", 0, true,
                    [](ChannelConfig& c) { c.aux_handshake = true; });
  m.channel->Start();
  m.RunFor(0.2);
  ASSERT_EQ(m.channel->aux_output().size(), 1u);
  EXPECT_EQ(m.channel->aux_output()[0].letter, 'T');
  EXPECT_GT(m.T(), 1);  // already on its way
  m.channel->AcknowledgeAux();
  RunToEnd(m);
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.T(), 150, 1e-9);
}

}  // namespace
}  // namespace vmt::control::channel
