// The return to the contour after block search, on its own: the automatic return is one
// straight move at the rapid limits with every axis ending together (4.2), C turns alone first
// under #CAX TRACK (4.2.2), and a manual return is accepted within mc_cmd_bs_deviation_max_w of
// the continue position, measured over X, Y and Z, with the program shifted by where the axes
// stand (4.2, 8).

#include "control/channel/return_to_contour.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace vmt::control::channel {
namespace {

std::vector<ChannelAxis> Axes() {
  std::vector<ChannelAxis> axes(3);
  axes[0].name = "X";
  axes[0].rapid_per_s = 100;
  axes[0].acceleration = 1000;
  axes[1].name = "Z";
  axes[1].rapid_per_s = 200;
  axes[1].acceleration = 4000;
  axes[2].name = "C";
  axes[2].rapid_per_s = 720;
  axes[2].acceleration = 3600;
  return axes;
}

TEST(ReturnToContour, TheStraightReturnEndsEveryAxisTogether) {
  const StraightReturn r = PlanStraightReturn({0, 0, 0}, {50, 300, 0}, Axes());
  ASSERT_TRUE(r.motion.moves);
  EXPECT_DOUBLE_EQ(r.motion.length, std::hypot(50, 300));
  // X needs 0.5 s at its rapid rate, Z 1.5 s: Z sets the path's rate, 1/1.5 of the move per
  // second; the accelerations likewise (X 1000/50 = 20, Z 4000/300 = 13.3 per s^2).
  EXPECT_DOUBLE_EQ(r.rate, 200.0 / 300);
  EXPECT_DOUBLE_EQ(r.accel, 4000.0 / 300);
  EXPECT_EQ(r.motion.start, (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(r.motion.end, (std::vector<double>{50, 300, 0}));
}

TEST(ReturnToContour, AxesStandingThereHaveNoMove) {
  const StraightReturn r = PlanStraightReturn({1, 2, 3}, {1, 2, 3}, Axes());
  EXPECT_FALSE(r.motion.moves);
  EXPECT_EQ(r.rate, 0);
}

TEST(ReturnToContour, UnderCaxTrackCTurnsAloneFirst) {
  const std::vector<double> at = {10, 20, 0}, restart = {40, 5, 90};
  const ReturnLeg first = FirstReturnLeg(at, restart, Axes(), true);
  EXPECT_TRUE(first.c_alignment);
  EXPECT_EQ(first.to, (std::vector<double>{10, 20, 90}));
  // C aligned: the second leg brings the other axes, C staying.
  const ReturnLeg second = FirstReturnLeg(first.to, restart, Axes(), true);
  EXPECT_FALSE(second.c_alignment);
  EXPECT_EQ(second.to, restart);
  // Without tracking every axis returns at once.
  const ReturnLeg plain = FirstReturnLeg(at, restart, Axes(), false);
  EXPECT_FALSE(plain.c_alignment);
  EXPECT_EQ(plain.to, restart);
}

TEST(ReturnToContour, AManualReturnIsMeasuredOverTheMainAxes) {
  // 3 mm off in X and 4 in Z: 5 mm; C's 30 degrees are not part of the deviation.
  const std::vector<double> at = {43, 9, 120}, restart = {40, 5, 90};
  const ManualReturn refused = CheckManualReturn(at, restart, Axes(), 49999);  // 4.9999 mm
  EXPECT_FALSE(refused.within);
  EXPECT_DOUBLE_EQ(refused.deviation_mm, 5);
  EXPECT_DOUBLE_EQ(refused.allowed_mm, 4.9999);
  EXPECT_TRUE(refused.offset.empty());
  const ManualReturn accepted = CheckManualReturn(at, restart, Axes(), 50000);
  EXPECT_TRUE(accepted.within);
  EXPECT_EQ(accepted.offset, (std::vector<double>{3, 4, 30}));
}

}  // namespace
}  // namespace vmt::control::channel
