// The jog keys of an NC-controlled tool storage axis, PxxC.MGPOS / MGNEG (REPOS manual 3.4:
// the NC traverses it "as it would in jog mode whenever the jog buttons are pressed"): the
// channel's jog mode decides as for the feed axes - continuously at the jogging speed or its
// rapid, one increment (fixed or Cxx.022 parametric) per press, nothing in handwheel mode.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "nc_turret_machine.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

/// The shared NC turret (nc_turret_machine.hpp) at 60 deg.
struct TurretMachine : NcTurretMachine {
  TurretMachine() : NcTurretMachine("N1 G01 X100 F600\nN2 RET\n") {}
  /// MGPOS (+1) or MGNEG (-1) held for `s`, then released; time for a station's increment
  /// (30 deg at 30 deg/s) to end.
  void Press(int direction, double s) {
    channel->JogToolStorage(direction);
    RunFor(s);
    channel->JogToolStorage(0);
    RunFor(1.2);
  }
};

TEST(ToolStorageJog, EachFixedIncrementModeMovesOneIncrementPerPress) {
  TurretMachine m;
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  double t = 60;
  const struct {
    JogMode mode;
    double increment;
  } modes[] = {{JogMode::kIncrement1, 0.001},
               {JogMode::kIncrement10, 0.01},
               {JogMode::kIncrement100, 0.1},
               {JogMode::kIncrement1000, 1}};
  for (const auto& [mode, increment] : modes) {
    m.channel->SetJogMode(static_cast<int>(mode));
    // Held for a second: one increment, not a continuous jog of 30 deg.
    m.Press(+1, 1.0);
    t += increment;
    EXPECT_NEAR(m.T(), t, 1e-9) << static_cast<int>(mode);
    m.Press(+1, 0.1);
    m.Press(-1, 0.1);
    EXPECT_NEAR(m.T(), t, 1e-9) << static_cast<int>(mode);
  }
}

TEST(ToolStorageJog, ParametricModeMovesCxx022PerPress) {
  TurretMachine m;
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kParametric));
  m.Press(+1, 3.0);  // held: still one station
  EXPECT_NEAR(m.T(), 90, 1e-9);
  m.Press(+1, 0.05);
  m.Press(+1, 0.05);
  EXPECT_NEAR(m.T(), 150, 1e-9);
  m.Press(-1, 0.05);
  EXPECT_NEAR(m.T(), 120, 1e-9);
}

TEST(ToolStorageJog, RapidModeJogsContinuouslyAtCxx021) {
  TurretMachine m;
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kRapid));
  m.Press(+1, 1.0);  // 180 deg/s, reached after 0.25 s at 720 deg/s^2, braking as long
  EXPECT_NEAR(m.T(), 60 + 180, 0.5);
}

TEST(ToolStorageJog, HandwheelModeKeysDoNothing) {
  TurretMachine m;
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  m.Press(+1, 1.0);
  m.Press(-1, 1.0);
  EXPECT_EQ(m.T(), 60);
}

// Parametric mode selected right after MGPOS was let go: the turret brakes to a stop, and no
// speed is left over for when continuous jogging is selected again.
TEST(ToolStorageJog, IncrementsSelectedWhileAJogBrakesLetItBrakeToAStop) {
  TurretMachine m;
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->JogToolStorage(+1);
  m.RunFor(1.0);  // 30 deg/s
  m.channel->JogToolStorage(0);
  m.RunFor(0.001);
  const double released = m.T();
  m.channel->SetJogMode(static_cast<int>(JogMode::kParametric));
  m.RunFor(0.5);
  EXPECT_NEAR(m.T(), released + 30 * 30 / (2 * 720.0), 0.05);  // its braking distance
  const double stopped = m.T();
  m.channel->SetJogMode(static_cast<int>(JogMode::kContinuous));
  m.RunFor(0.5);
  EXPECT_EQ(m.T(), stopped);
}

// 3.4 during repositioning: an increment may pass the target like a continuous jog; a
// station's increment brings the turret back onto its station, and its adjust symbol goes.
TEST(ToolStorageJog, IncrementsDuringRepositioningPassAndReachTheTarget) {
  TurretMachine m;
  m.channel->Start();
  m.RunFor(3.0);
  m.channel->Stop();
  m.RunFor(0.2);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kParametric));
  m.Press(+1, 0.05);
  m.Press(+1, 0.05);
  EXPECT_NEAR(m.T(), 120, 1e-9);
  m.channel->SetReposition(true, false);
  m.RunFor(0.01);
  EXPECT_TRUE(m.channel->repos_status().tool_storage_adjust);
  m.Press(-1, 0.05);
  m.Press(-1, 0.05);
  m.Press(-1, 0.05);  // past the station at 60
  EXPECT_NEAR(m.T(), 30, 1e-9);
  EXPECT_TRUE(m.channel->repos_status().tool_storage_adjust);
  m.Press(+1, 0.05);
  EXPECT_NEAR(m.T(), 60, 1e-9);
  EXPECT_FALSE(m.channel->repos_status().tool_storage_adjust);
}

}  // namespace
}  // namespace vmt::control::channel
