// The timeline player at drive level: its trapezoid profile, and the order in which it plays the
// steps of a scene (each step once, blocking steps holding the ones after them).
#include "sim/runner/timeline_player.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../sim_test_support.hpp"

namespace vmt::sim {
namespace {

TEST(TimelinePlayerTest, ATrapezoidReachesItsSpeedAndEndsAtRest) {
  // 100 mm at 50 mm/s and 500 mm/s^2: 0.1 s up, 1.9 s at speed, 0.1 s down.
  const TrapezoidProfile p{20, 120, 50, 500, 1.0};
  EXPECT_NEAR(p.Duration(), 2.1, 1e-12);
  EXPECT_EQ(p.At(0.5), 20);  // before its start
  EXPECT_EQ(p.At(1.0), 20);
  EXPECT_NEAR(p.At(1.1), 20 + 0.5 * 500 * 0.01, 1e-12);  // end of the ramp: 2.5 mm
  EXPECT_NEAR(p.At(2.05), 20 + 50, 1e-9);                  // the middle
  EXPECT_NEAR(p.At(3.0), 120 - 0.5 * 500 * 0.01, 1e-9);   // start of the ramp down
  EXPECT_EQ(p.At(3.1), 120);
  EXPECT_EQ(p.At(100), 120);
  // Speed never above the limit, acceleration never above its limit (finite differences).
  const double h = 1e-4;
  double last_v = 0;
  for (double t = 1.0; t < 3.1; t += h) {
    const double v = (p.At(t + h) - p.At(t)) / h;
    EXPECT_LE(v, 50 + 1e-6) << t;
    EXPECT_LE(std::abs(v - last_v) / h, 500 * 1.01) << t;
    last_v = v;
  }
}

TEST(TimelinePlayerTest, AShortMoveIsATriangleAndBackwardsIsTheMirror) {
  // 2 mm at 50 mm/s and 500 mm/s^2: the speed is never reached (peak sqrt(d a) = 31.6 mm/s).
  const TrapezoidProfile fwd{0, 2, 50, 500, 0};
  EXPECT_NEAR(fwd.Duration(), 2 * std::sqrt(2.0 / 500), 1e-12);
  EXPECT_NEAR(fwd.At(fwd.Duration() / 2), 1, 1e-12);
  const TrapezoidProfile back{2, 0, 50, 500, 0};
  EXPECT_EQ(back.Duration(), fwd.Duration());
  for (double t = 0; t <= fwd.Duration(); t += 0.001)
    EXPECT_NEAR(back.At(t), 2 - fwd.At(t), 1e-12);
  const TrapezoidProfile none{5, 5, 50, 500, 0};
  EXPECT_EQ(none.Duration(), 0);
  EXPECT_EQ(none.At(0.1), 5);
}

// An ideal machine under the player: every servo stands where it is commanded.
struct Player {
  Scene scene;
  control::AmplifierTelegram at;
  control::MasterTelegram mdt;
  std::vector<ClutchState> clutches;
  std::vector<ProgramEvent> events;
  TimelinePlayer player;
  double t = 0;
  static control::AmplifierTelegram Initial(const Scene& s) {
    control::AmplifierTelegram at;
    at.feedback.resize(s.model->drives.size());
    at.inputs.assign(s.model->io.size(), 0);
    return at;
  }
  explicit Player(const std::string& timeline)
      : scene(LoadScene(testing::WriteLatheScene("timeline_player", "player",
                                                 "backend: kinematic\nduration: 5\n"
                                                 "timeline:\n" +
                                                     timeline))),
        at(Initial(scene)),
        clutches(scene.model->clutches.size(), ClutchState::kReleased),
        player(scene, at) {}
  void Tick() {
    player.Tick(t, at, clutches, mdt, events);
    player.WriteSetpoints(mdt, [](size_t) { return false; });  // no channel
    for (size_t d = 0; d < mdt.setpoints.size(); ++d)
      if (mdt.setpoints[d].mode == control::DriveMode::kPosition)
        at.feedback[d].position = mdt.setpoints[d].value;
    t += kDriveTickS;
  }
  void RunTo(double until) {
    while (t < until - 1e-9) Tick();
  }
  int Drive(const std::string& name) const {
    for (size_t d = 0; d < scene.model->drives.size(); ++d)
      if (scene.model->drives[d].info.name == name) return static_cast<int>(d);
    return -1;
  }
};

TEST(TimelinePlayerTest, StepsPlayInOrderAndAWaitHoldsTheNext) {
  Player p(
      "  - move: {axis: Z, to: 150, feed: 3000}\n"
      "  - wait: 0.5\n"
      "  - move: {axis: X, to: 60, feed: 3000}\n");
  const int z = p.Drive("Z"), x = p.Drive("X");
  ASSERT_GE(z, 0);
  ASSERT_GE(x, 0);
  const double z0 = p.at.feedback[z].position, x0 = p.at.feedback[x].position;
  p.RunTo(0.25);
  // Z is under way, X has not been told to move: the wait holds its step.
  EXPECT_NE(p.at.feedback[z].position, z0);
  EXPECT_EQ(p.at.feedback[x].position, x0);
  ASSERT_EQ(p.events.size(), 2u);
  EXPECT_EQ(p.events[0].kind, "step");
  EXPECT_EQ(p.events[0].t_s, 0);
  EXPECT_EQ(p.events[1].kind, "step");  // the wait began with the move, in the same tick
  p.RunTo(0.6);
  EXPECT_EQ(p.events.size(), 3u);
  EXPECT_NEAR(p.events[2].t_s, 0.5, kDriveTickS / 2);  // X's move began when the wait ended
  EXPECT_NE(p.at.feedback[x].position, x0);
  p.RunTo(5);
  EXPECT_TRUE(p.player.finished());
  EXPECT_NEAR(p.at.feedback[z].position, 150, 1e-9);
  EXPECT_NEAR(p.at.feedback[x].position, 60, 1e-9);
  EXPECT_TRUE(p.player.failures().empty());
}

TEST(TimelinePlayerTest, AWaitThatTimesOutIsAFailureAndTheRestStillRuns) {
  Player p(
      "  - wait_until: {input: IROTMODE, timeout: 0.2}\n"
      "  - move: {axis: Z, to: 150, feed: 3000}\n");
  p.RunTo(0.1);
  EXPECT_TRUE(p.player.failures().empty());
  p.RunTo(0.3);
  ASSERT_EQ(p.player.failures().size(), 1u);
  EXPECT_NE(p.player.failures()[0].find("timed out after 0.2"), std::string::npos)
      << p.player.failures()[0];
  bool timeout = false;
  for (const ProgramEvent& e : p.events) timeout = timeout || e.kind == "timeout";
  EXPECT_TRUE(timeout);
  p.RunTo(5);
  EXPECT_NEAR(p.at.feedback[p.Drive("Z")].position, 150, 1e-9);
}

TEST(TimelinePlayerTest, ItLeavesTheDrivesAChannelWritesAlone) {
  Player p("  - move: {axis: Z, to: 150, feed: 3000}\n");
  const int z = p.Drive("Z"), x = p.Drive("X");
  ASSERT_GE(z, 0);
  ASSERT_GE(x, 0);
  p.RunTo(0.1);
  const control::DriveSetpoint channel_x{control::DriveMode::kPosition, 42, 0};
  p.mdt.setpoints[x] = channel_x;
  p.player.Tick(p.t, p.at, p.clutches, p.mdt, p.events);
  p.player.WriteSetpoints(p.mdt, [x, z](size_t d) { return d == size_t(x) || d == size_t(z); });
  EXPECT_EQ(p.mdt.setpoints[x].value, 42);  // the channel's, as it wrote it
  const double z_before = p.mdt.setpoints[z].value;
  p.player.WriteSetpoints(p.mdt, [x](size_t d) { return d == size_t(x); });
  EXPECT_GT(p.mdt.setpoints[z].value, z_before);  // Z moves on: the timeline writes it again
  EXPECT_EQ(p.mdt.setpoints[x].value, 42);
}

TEST(TimelinePlayerTest, AServoOnAnEncoderBeyondAReleasedClutchIsInFollowUp) {
  // lathe-c1's C reads the spindle's encoder through clutch K: released, its controller enable
  // is off and its command follows the encoder; engaged, it holds where it stands.
  Player p("  - wait: 1\n  - move: {axis: C, to: 90, feed: 3600}\n");
  const int c = p.Drive("C"), z = p.Drive("Z");
  ASSERT_GE(c, 0);
  p.at.feedback[c].position = 123.4;  // the spindle turned C's encoder
  p.Tick();
  EXPECT_EQ(p.mdt.setpoints[c].mode, control::DriveMode::kOff);
  EXPECT_EQ(p.mdt.setpoints[c].value, 123.4);
  EXPECT_EQ(p.mdt.setpoints[z].mode, control::DriveMode::kPosition);  // no clutch: held
  p.clutches[0] = ClutchState::kEngaging;
  p.Tick();
  EXPECT_EQ(p.mdt.setpoints[c].mode, control::DriveMode::kOff);
  p.clutches[0] = ClutchState::kEngaged;
  p.Tick();
  EXPECT_EQ(p.mdt.setpoints[c].mode, control::DriveMode::kPosition);
  EXPECT_EQ(p.mdt.setpoints[c].value, 123.4);
  // A step that commands C takes over, whatever the clutch does.
  p.RunTo(1.01);
  p.clutches[0] = ClutchState::kReleased;
  p.RunTo(5);
  EXPECT_EQ(p.mdt.setpoints[c].mode, control::DriveMode::kPosition);
  EXPECT_NEAR(p.mdt.setpoints[c].value, 90, 1e-9);
}

TEST(TimelinePlayerTest, AServoAChannelMayWriteIsLeftToItsHeadstock) {
  Player p("  - wait: 1\n");
  const int c = p.Drive("C");
  p.player.LeaveEnableToChannel(c);
  p.Tick();
  EXPECT_EQ(p.mdt.setpoints[c].mode, control::DriveMode::kPosition);  // held until it starts
}

}  // namespace
}  // namespace vmt::sim
