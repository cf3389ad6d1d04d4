// Repositioning on its own, without a channel (REPOS manual): the rules of one axis or key
// (window 6.1, zone 3.2, spindle keys 3.3), and the function's state fed a ReposView: the PLC's
// call counts only for an interrupted program left by jogging (7.1), PxxS.CREST follows the
// relevant axes' windows (7.3), an operator's zero offset edit moves the targets (2.5), a
// withdrawn call stays while a jog is under way (7.1 instruction), the REPOS screen (2.2).

#include "control/channel/repositioning.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/channel/channel_config.hpp"
#include "control/channel/further_spindle_control.hpp"
#include "control/nc/modal_g_codes.hpp"

namespace vmt::control::channel {
namespace {

ChannelAxis Axis(const char* name, double window) {
  ChannelAxis a;
  a.name = name;
  a.repos_window = window;
  return a;
}

// Channel axes X and Z, no spindle; the program interrupted at X 40, Z 100 (block from X 40,
// Z 120) under G54, whose X offset is 5.
struct Interrupted : ::testing::Test {
  ChannelConfig config;
  std::vector<double> shift{0, 0};
  std::vector<double> commanded{40, 100};
  MainSpindleState spindle;
  FurtherSpindleControl further{{}};
  Repositioning repos;
  AmplifierTelegram at;

  Interrupted() {
    config.axes = {Axis("X", 0.2), Axis("Z", 0.5)};
    config.zero_offsets.g54_to_g59[0] = {5, 0};
    Interruption i;
    i.point = commanded;
    i.block_start = {40, 120};
    i.modal.zero_offset = 54;
    i.translation = {5, 0};
    repos.Interrupt(i, commanded);
  }
  ReposView View() const {
    return {config, config.zero_offsets, config.tools, shift, commanded, nullptr, spindle, further};
  }
  void Cycle(bool interrupted = true, bool motion = false) {
    repos.Cycle(View(), at, interrupted, motion);
  }
};

TEST(ReposRules, WindowAndZoneOfALinearAndAnEndlessAxis) {
  ChannelAxis x = Axis("X", 0.2);
  EXPECT_TRUE(WithinReposWindow(x, 10, 10.19));
  EXPECT_FALSE(WithinReposWindow(x, 10, 10.21));
  ChannelAxis c = Axis("C", 0.1);
  c.rotary = true;  // no travel limits: endless, the short way round
  EXPECT_NEAR(ReposDistanceToGo(c, 5, 355), 10, 1e-9);
  EXPECT_TRUE(WithinReposWindow(c, 0, 359.95));
  const ReposZone z = ZoneOf(x, 10, 30);
  EXPECT_TRUE(z.limited);
  EXPECT_EQ(z.low, 10);
  EXPECT_EQ(z.high, 30);
  EXPECT_FALSE(ZoneOf(c, 10, 30).limited);
}

TEST(ReposRules, SpindleKeysThatRestoreTheStateBefore) {
  EXPECT_TRUE(KeyRestoresSpindle(3, 4));
  EXPECT_TRUE(KeyRestoresSpindle(4, 3));
  EXPECT_FALSE(KeyRestoresSpindle(5, 3));
  EXPECT_TRUE(KeyRestoresSpindle(19, 19));
  EXPECT_FALSE(KeyRestoresSpindle(19, 5));
  DriveSetpoint positioned;
  positioned.mode = DriveMode::kPosition;
  EXPECT_EQ(SpindleMOf(positioned), 19);
}

TEST_F(Interrupted, TheCallCountsOnlyOnceAnAxisHasLeftTheContour) {
  repos.Request(true, false);
  Cycle();
  EXPECT_EQ(repos.function(), ReposFunction::kNone);  // 7.1: not left yet
  commanded[0] = 60;                                  // jogged away in X
  Cycle();
  EXPECT_EQ(repos.function(), ReposFunction::kRepositioning);
  EXPECT_FALSE(repos.conditions_restored());
  EXPECT_EQ(repos.start(), (std::vector<double>{60, 100}));  // where it stood when called
  commanded[0] = 40.15;                                      // back within X's window
  Cycle();
  EXPECT_TRUE(repos.conditions_restored());
  // Both signals at once ask for neither; so does a program no longer interrupted.
  repos.Request(true, true);
  Cycle();
  EXPECT_EQ(repos.function(), ReposFunction::kNone);
  EXPECT_FALSE(repos.conditions_restored());
  repos.Request(false, true);
  Cycle(false);
  EXPECT_EQ(repos.function(), ReposFunction::kNone);
}

TEST_F(Interrupted, RestartReturnsToTheBlockStartAndAnEditMovesTheTarget) {
  commanded = {60, 130};
  repos.Request(false, true);
  Cycle();
  const std::vector<double> target = repos.Target(View());
  EXPECT_EQ(target, (std::vector<double>{40, 120}));
  config.zero_offsets.g54_to_g59[0][0] = 7;  // the operator edits G54 X (2.5)
  EXPECT_EQ(repos.Target(View()), (std::vector<double>{42, 120}));
  commanded = {42.1, 120.4};  // within both windows of the moved target
  Cycle();
  EXPECT_TRUE(repos.conditions_restored());
}

TEST_F(Interrupted, AWithdrawnCallStaysWhileAJogIsUnderWay) {
  commanded[1] = 110;
  repos.Request(true, false);
  Cycle();
  ASSERT_TRUE(repos.called());
  repos.Request(false, false);
  Cycle(true, true);  // the key is still held
  EXPECT_TRUE(repos.called());
  Cycle(true, false);
  EXPECT_FALSE(repos.called());
}

TEST_F(Interrupted, TheScreenShowsTargetsAndAdjustSymbols) {
  commanded = {40, 103};
  repos.Request(true, false);
  Cycle();
  const ReposStatus s = repos.Status(View(), &at, true);
  EXPECT_EQ(s.function, ReposFunction::kRepositioning);
  EXPECT_TRUE(s.left_contour);
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_EQ(s.axes[0].name, "X");
  EXPECT_FALSE(s.axes[0].adjust);  // X stands at its target
  EXPECT_TRUE(s.axes[1].adjust);
  EXPECT_NEAR(s.axes[1].distance_to_go, -3, 1e-12);
  EXPECT_FALSE(s.spindle.relevant);  // the channel has no spindle
  EXPECT_EQ(s.g_codes, nc::ActiveGCodes(repos.interruption()->modal));
  repos.Clear();
  EXPECT_EQ(repos.interruption(), nullptr);
  EXPECT_TRUE(repos.Status(View(), &at, true).axes.empty());
}

}  // namespace
}  // namespace vmt::control::channel
