// A spindle-synchronous block on its own: G63 at lead x S whatever the spindle does, G64 taking
// the spindle into position control and leading it along the path, G33 waiting for the
// spindle's speed, and the errors it reports for the channel to fail with.

#include "control/channel/synchronous_block.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/channel/channel_messages.hpp"

namespace vmt::control::channel {
namespace {

constexpr double kDt = 1e-3;
constexpr int kSpindle = 2;

std::vector<axes::AxisParameters> LatheAxes() {
  axes::AxisParameters x, z;
  x.name = "X";
  x.rapid_per_s = 200;
  x.acceleration = 2000;
  x.travel_min = -10;
  x.travel_max = 300;
  z = x;
  z.name = "Z";
  z.travel_max = 500;
  return {x, z};
}

axes::AxisParameters Spindle() {
  axes::AxisParameters s;
  s.rapid_per_s = 36000;  // 6000 rpm
  s.acceleration = 72000;
  return s;
}

/// A block along Z from 100 to 60 with lead 2 mm at S `rpm`, M3.
nc::PreparedBlock Tapping(nc::Motion motion, double rpm) {
  nc::PreparedBlock b;
  b.motion = motion;
  b.target = {0, 60};
  b.programmed = 0b10;
  b.modal.lead = 2;
  b.modal.spindle = 3;
  b.modal.spindle_speed = rpm;
  return b;
}

struct Fixture {
  nc::PreparedBlock block;
  BlockMotion motion;
  PathProfile profile;
  std::vector<double> commanded{0, 100};
  std::vector<double> translation{0, 0};
  MainSpindleState spindle;
  AmplifierTelegram at;
  SynchronousBlock sync{LatheAxes(), kSpindle, Spindle()};
  explicit Fixture(nc::PreparedBlock b) : block(std::move(b)) {
    at.feedback.resize(3);
    spindle.command = {DriveMode::kVelocity, 6 * block.modal.spindle_speed, 0};
  }
  SynchronousContext Context() { return {block, motion, profile, commanded, spindle}; }
};

TEST(SynchronousBlockTest, G63RunsAtLeadTimesSpeedToTheProgrammedPoint) {
  Fixture f(Tapping(nc::Motion::kTapping, 600));  // 2 mm x 10 rev/s = 20 mm/s
  bool moves = false;
  ASSERT_FALSE(f.sync.Start(f.Context(), f.translation, 0, f.at, moves));
  ASSERT_TRUE(moves);
  ASSERT_TRUE(f.sync.active());
  EXPECT_NEAR(f.profile.max_rate * f.motion.length, 20, 1e-9);
  int cycles = 0;
  while (f.sync.active() && cycles < 100000) {
    ASSERT_FALSE(f.sync.Cycle(f.Context(), f.at, kDt, 3600));
    ++cycles;
  }
  EXPECT_FALSE(f.sync.active());
  EXPECT_EQ(f.commanded, (std::vector<double>{0, 60}));
  EXPECT_NEAR(cycles * kDt, 40.0 / 20, 0.05);  // 40 mm at 20 mm/s and its ramps
}

TEST(SynchronousBlockTest, G64TakesTheStandingSpindleIntoPositionAndLeadsIt) {
  Fixture f(Tapping(nc::Motion::kRigidTapping, 600));
  bool moves = false;
  ASSERT_FALSE(f.sync.Start(f.Context(), f.translation, 0, f.at, moves));
  // First the spindle brakes to a stop.
  EXPECT_EQ(f.spindle.command.mode, DriveMode::kVelocity);
  EXPECT_EQ(f.spindle.command.value, 0);
  f.at.feedback[kSpindle].position = 90;
  f.at.feedback[kSpindle].velocity = 0;
  ASSERT_FALSE(f.sync.Cycle(f.Context(), f.at, kDt, 0));
  EXPECT_EQ(f.spindle.command.mode, DriveMode::kPosition);
  while (f.sync.active()) ASSERT_FALSE(f.sync.Cycle(f.Context(), f.at, kDt, 0));
  // 40 mm at 2 mm per turn: 20 turns (M3: positive) on from where it stood.
  EXPECT_NEAR(f.spindle.command.value, 90 + 20 * 360, 1e-6);
  EXPECT_EQ(f.spindle.command.velocity_feedforward, 0);
  EXPECT_EQ(f.commanded, (std::vector<double>{0, 60}));
}

TEST(SynchronousBlockTest, G33WaitsForTheSpindleSpeedBeforeTheThreadStarts) {
  Fixture f(Tapping(nc::Motion::kThread, 600));
  bool moves = false;
  ASSERT_FALSE(f.sync.Start(f.Context(), f.translation, 0, f.at, moves));
  f.at.feedback[kSpindle].velocity = 1000;  // far from 3600 deg/s
  for (int i = 0; i < 10; ++i) ASSERT_FALSE(f.sync.Cycle(f.Context(), f.at, kDt, 3600));
  EXPECT_EQ(f.commanded, (std::vector<double>{0, 100}));  // nothing moved
  // At speed, the axes follow the spindle's position until the thread's end.
  f.at.feedback[kSpindle].velocity = 3600;
  double phi = 0;
  for (int i = 0; i < 100000 && f.sync.active(); ++i) {
    phi += 3600 * kDt;
    f.at.feedback[kSpindle].position = std::fmod(phi, 360);
    ASSERT_FALSE(f.sync.Cycle(f.Context(), f.at, kDt, 3600));
  }
  EXPECT_FALSE(f.sync.active());
  EXPECT_EQ(f.commanded, (std::vector<double>{0, 60}));
}

TEST(SynchronousBlockTest, ErrorsAreReportedNotActedOn) {
  Fixture still(Tapping(nc::Motion::kTapping, 600));
  still.spindle.command = {DriveMode::kVelocity, 0, 0};
  bool moves = true;
  auto error = still.sync.Start(still.Context(), still.translation, 0, still.at, moves);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->number, kMsgSpindleStill);
  EXPECT_FALSE(moves);
  EXPECT_FALSE(still.sync.active());

  Fixture fast(Tapping(nc::Motion::kTapping, 12000));  // 400 mm/s > the axes' 200
  error = fast.sync.Start(fast.Context(), fast.translation, 0, fast.at, moves);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->number, kMsgLeadTooFast);

  Fixture compensated(Tapping(nc::Motion::kThread, 600));
  compensated.block.modal.compensation = nc::Compensation::kLeft;
  error = compensated.sync.Start(compensated.Context(), compensated.translation, 0, compensated.at,
                                 moves);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->number, kMsgNotAvailable);

  SynchronousBlock none({}, -1, Spindle());
  Fixture f(Tapping(nc::Motion::kThread, 600));
  error = none.Start(f.Context(), f.translation, 0, f.at, moves);
  ASSERT_TRUE(error);
  EXPECT_NE(error->text.find("needs a main spindle"), std::string::npos);
}

}  // namespace
}  // namespace vmt::control::channel
