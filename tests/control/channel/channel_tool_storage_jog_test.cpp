// The jog keys of an NC-controlled tool storage axis, PxxC.MGPOS / MGNEG (REPOS manual 3.4:
// the NC traverses it "as it would in jog mode whenever the jog buttons are pressed"): the
// channel's jog mode decides as for the feed axes - continuously at the jogging speed or its
// rapid, one increment (fixed or Cxx.022 parametric) per press, nothing in handwheel mode.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

/// An NC-controlled endless tool storage axis on drive 3 at 60 deg: a 12-station turret whose
/// parametric jogging distance is one station.
struct TurretMachine : Machine {
  TurretMachine()
      : Machine("N1 G01 X100 F600\nN2 RET\n", 0, 0, [](ChannelConfig& c) {
          c.tool_storage_drive = 3;
          c.tool_storage_nc = true;
          c.tool_storage.name = "T";
          c.tool_storage.rotary = true;  // no travel limits: endless
          c.tool_storage.jog_per_s = 30;
          c.tool_storage.jog_rapid_per_s = 180;
          c.tool_storage.jog_distance = 30;
          c.tool_storage.acceleration = 720;
          c.process.reposition_tool_storage = true;
        }) {
    at.feedback.resize(4);
    at.feedback[3].status = drive_status::kReady;
    at.feedback[3].position = 60;
    mdt.setpoints.resize(4);
  }
  /// One drive tick; the tool storage axis follows its setpoint.
  void TickAll() {
    Tick();
    if (mdt.setpoints[3].mode == DriveMode::kPosition) at.feedback[3].position = mdt.setpoints[3].value;
  }
  void RunFor(double s) {
    for (int i = 0; i < s / 250e-6; ++i) TickAll();
  }
  /// MGPOS (+1) or MGNEG (-1) held for `s`, then released; time for a station's increment
  /// (30 deg at 30 deg/s) to end.
  void Press(int direction, double s) {
    channel->JogToolStorage(direction);
    RunFor(s);
    channel->JogToolStorage(0);
    RunFor(1.2);
  }
  double T() const { return at.feedback[3].position; }
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
