// Backward travel on its own: back along the recorded blocks to the oldest, forward again to
// the interruption point, feed hold on the path, PathGuard's check of a decoded G00 leg only,
// and what forgets the path.

#include "control/channel/backward_travel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/control/channel/straight_motion.hpp"

namespace vmt::control::channel {
namespace {

constexpr double kDt = 1e-3;

struct Guard {
  std::vector<std::string> asked;
  bool stop = false;
  ReplayGuard Check() {
    return [this](const std::string& move, const std::vector<double>&) {
      asked.push_back(move);
      return stop;
    };
  }
};

/// Three blocks (0,0) -> (10,0) -> (10,10) -> (0,10); the axes at the last one's end.
BackwardTravel ThreeBlocks(bool decoded_rapid_middle = false) {
  BackwardTravel t;
  t.Record(StraightMotion({0, 0}, {10, 0}), false, false);
  t.Record(StraightMotion({10, 0}, {10, 10}), decoded_rapid_middle, decoded_rapid_middle);
  t.Record(StraightMotion({10, 10}, {0, 10}), false, false);
  return t;
}

/// Cycles until the travel stands (or arrives); returns the last step.
ReplayStep RunLeg(BackwardTravel& t, std::vector<double>& commanded, const ReplayGuard& guard,
                  int max_cycles = 100000) {
  ReplayStep step = ReplayStep::kMoving;
  for (int i = 0; i < max_cycles && t.moving(); ++i)
    step = t.Cycle(kDt, 1.0, true, commanded, guard);
  return step;
}

TEST(BackwardTravelTest, BackToTheOldestBlockAndForwardToTheInterruptionPoint) {
  BackwardTravel t = ThreeBlocks();
  Guard g;
  std::vector<double> commanded{0, 10};
  ASSERT_TRUE(t.AtLastStepEnd(commanded));
  ASSERT_TRUE(t.CanGoBackFrom(1));
  t.BeginAt(commanded, 1);
  t.Request(true);
  EXPECT_EQ(t.Back(commanded, g.Check()), ReplayStep::kMoving);
  EXPECT_TRUE(t.moving());
  RunLeg(t, commanded, g.Check());
  // Block by block back to where the oldest began.
  EXPECT_NEAR(commanded[0], 0, 1e-9);
  EXPECT_NEAR(commanded[1], 0, 1e-9);
  EXPECT_TRUE(t.away());
  EXPECT_EQ(t.blocks_back(), 2u);
  t.Request(false);
  EXPECT_EQ(t.Forward(commanded, g.Check()), ReplayStep::kMoving);
  EXPECT_EQ(RunLeg(t, commanded, g.Check()), ReplayStep::kArrived);
  EXPECT_EQ(commanded, (std::vector<double>{0, 10}));
  EXPECT_FALSE(t.away());
  EXPECT_TRUE(g.asked.empty());  // travelled blocks are not checked
}

TEST(BackwardTravelTest, FeedHoldStopsOnThePathAndTheStartGoesOn) {
  BackwardTravel t = ThreeBlocks();
  Guard g;
  std::vector<double> commanded{0, 10};
  t.BeginAt(commanded, 1);
  t.Back(commanded, g.Check());
  for (int i = 0; i < 60; ++i) t.Cycle(kDt, 1.0, true, commanded, g.Check());
  t.Hold();
  RunLeg(t, commanded, g.Check());
  EXPECT_FALSE(t.moving());
  // At rest inside the last block, on its line y = 10.
  EXPECT_GT(commanded[0], 0.1);
  EXPECT_LT(commanded[0], 9.9);
  EXPECT_NEAR(commanded[1], 10, 1e-9);
  t.Back(commanded, g.Check());
  RunLeg(t, commanded, g.Check());
  EXPECT_NEAR(commanded[0], 0, 1e-9);
  EXPECT_NEAR(commanded[1], 0, 1e-9);
}

TEST(BackwardTravelTest, AProgramNoLongerHeldEndsTheTravel) {
  BackwardTravel t = ThreeBlocks();
  Guard g;
  std::vector<double> commanded{0, 10};
  t.BeginAt(commanded, 1);
  t.Back(commanded, g.Check());
  t.Cycle(kDt, 1.0, false, commanded, g.Check());
  EXPECT_FALSE(t.moving());
}

TEST(BackwardTravelTest, ADecodedRapidLegIsCheckedAndAStopEndsTheTravelBeforeIt) {
  BackwardTravel t = ThreeBlocks(true);
  Guard g;
  g.stop = true;
  std::vector<double> commanded{0, 10};
  t.BeginAt(commanded, 1);
  t.Back(commanded, g.Check());
  RunLeg(t, commanded, g.Check());
  ASSERT_EQ(g.asked.size(), 1u);
  EXPECT_EQ(g.asked[0], "backward travel");
  // Stopped at the start of the checked block: the end of the decoded G00.
  EXPECT_NEAR(commanded[0], 10, 1e-9);
  EXPECT_NEAR(commanded[1], 10, 1e-9);
}

TEST(BackwardTravelTest, WhereTheAxesMayStartFrom) {
  BackwardTravel t;
  EXPECT_FALSE(t.CanGoBackFrom(-1));
  const BlockMotion only = StraightMotion({0, 0}, {5, 0});
  t.Record(only, false, false);
  EXPECT_TRUE(t.LastStepIs(only));
  EXPECT_FALSE(t.LastStepIs(StraightMotion({0, 0}, {6, 0})));
  EXPECT_TRUE(t.CanGoBackFrom(0.5));
  EXPECT_FALSE(t.CanGoBackFrom(0));  // at the start of the only block: nothing behind
  t.Record(StraightMotion({5, 0}, {5, 5}), false, false);
  EXPECT_TRUE(t.CanGoBackFrom(0));
}

TEST(BackwardTravelTest, LeavingAndResetForgetTheTravel) {
  BackwardTravel t = ThreeBlocks();
  Guard g;
  std::vector<double> commanded{0, 10};
  EXPECT_FALSE(t.Leave());
  t.BeginAt(commanded, 1);
  const auto home = t.Leave();
  ASSERT_TRUE(home);
  EXPECT_EQ(*home, commanded);
  EXPECT_FALSE(t.away());
  t.Request(true);
  t.Reset();
  EXPECT_TRUE(t.empty());
  EXPECT_TRUE(t.backward_requested());  // the operator's choice stays
  t.Record(StraightMotion({0, 0}, {1, 0}), false, false);
  t.Forget();
  EXPECT_TRUE(t.empty());
}

}  // namespace
}  // namespace vmt::control::channel
