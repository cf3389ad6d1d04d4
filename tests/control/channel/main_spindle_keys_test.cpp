// The main spindle's manual keys on their own: M3/M4/M5/M19, homing, and the jog keys in each
// jog mode.

#include "control/channel/main_spindle_keys.hpp"

#include <gtest/gtest.h>

namespace vmt::control::channel {
namespace {

axes::AxisParameters Spindle() {
  axes::AxisParameters s;
  s.name = "S1";
  s.rotary = true;
  s.jog_per_s = 600;         // 100 rpm
  s.jog_rapid_per_s = 3000;  // 500 rpm
  s.jog_distance = 15;
  s.jog_spindle_position = 90;
  s.reference_position = 30;
  return s;
}

TEST(MainSpindleKeysTest, MFunctionKeysTurnStopOrPosition) {
  const axes::AxisParameters s = Spindle();
  const auto m3 = SpindleMKey(3, s), m4 = SpindleMKey(4, s), m5 = SpindleMKey(5, s);
  const auto m19 = SpindleMKey(19, s);
  ASSERT_TRUE(m3 && m4 && m5 && m19);
  EXPECT_EQ(m3->command.mode, DriveMode::kVelocity);
  EXPECT_DOUBLE_EQ(m3->command.value, 600);
  EXPECT_DOUBLE_EQ(m4->command.value, -600);
  EXPECT_DOUBLE_EQ(m5->command.value, 0);
  EXPECT_FALSE(m3->referencing || m3->jogging);
  EXPECT_EQ(m19->command.mode, DriveMode::kPosition);
  EXPECT_DOUBLE_EQ(m19->command.value, 90);
  EXPECT_TRUE(m19->referencing);
  EXPECT_FALSE(SpindleMKey(8, s));
}

TEST(MainSpindleKeysTest, HomingPositionsToTheReferenceAndEstablishesIt) {
  const SpindleKeyMove home = SpindleHomeKey(Spindle());
  EXPECT_EQ(home.command.mode, DriveMode::kPosition);
  EXPECT_DOUBLE_EQ(home.command.value, 30);
  EXPECT_TRUE(home.referencing);
  EXPECT_FALSE(home.jogging);
}

TEST(MainSpindleKeysTest, JogKeysFollowTheJogMode) {
  const axes::AxisParameters s = Spindle();
  const auto held = SpindleJogKey(-1, {JogMode::kContinuous, 0, 0.5}, 10, s);
  ASSERT_TRUE(held);
  EXPECT_EQ(held->command.mode, DriveMode::kVelocity);
  EXPECT_DOUBLE_EQ(held->command.value, -600);  // the override acts on the drive, not here
  EXPECT_TRUE(held->jogging);
  const auto rapid = SpindleJogKey(1, {JogMode::kRapid, 0, 1}, 10, s);
  ASSERT_TRUE(rapid);
  EXPECT_DOUBLE_EQ(rapid->command.value, 3000);
  const auto step = SpindleJogKey(1, {JogMode::kIncrement1000, 1, 1}, 10, s);
  ASSERT_TRUE(step);
  EXPECT_EQ(step->command.mode, DriveMode::kPosition);
  EXPECT_DOUBLE_EQ(step->command.value, 11);
  EXPECT_FALSE(step->jogging || step->referencing);
  const auto parametric = SpindleJogKey(-1, {JogMode::kParametric, 0, 1}, 10, s);
  ASSERT_TRUE(parametric);
  EXPECT_DOUBLE_EQ(parametric->command.value, -5);
  EXPECT_FALSE(SpindleJogKey(1, {JogMode::kHandwheel, 0, 1}, 10, s));
}

TEST(MainSpindleKeysTest, WithoutARapidJoggingSpeedRapidTurnsAtTheJoggingSpeed) {
  axes::AxisParameters s = Spindle();
  s.jog_rapid_per_s = 0;
  const auto rapid = SpindleJogKey(1, {JogMode::kRapid, 0, 1}, 0, s);
  ASSERT_TRUE(rapid);
  EXPECT_DOUBLE_EQ(rapid->command.value, 600);
}

}  // namespace
}  // namespace vmt::control::channel
