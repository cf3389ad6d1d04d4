#include "control/channel/path_memory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "tests/control/channel/straight_motion.hpp"

namespace vmt::control::channel {
namespace {

// A quarter circle of radius 10 about (0, 0) in axes 0 and 1, from (10, 0) to (0, 10), with axis
// 2 rising from 0 to 5 (a helix).
BlockMotion QuarterArc() {
  BlockMotion m = StraightMotion({10, 0, 0}, {0, 10, 5});
  m.arc_axes[0] = 0;
  m.arc_axes[1] = 1;
  m.arc_radius = 10;
  m.arc_start_angle = 0;
  m.arc_sweep = std::numbers::pi / 2;
  m.length = std::hypot(10 * std::numbers::pi / 2, 5.0);
  return m;
}

TEST(PathMemory, KeepsTheLastThousandBlocksOldestFirst) {
  PathMemory memory;
  EXPECT_TRUE(memory.empty());
  const size_t pushed = PathMemory::kBlocks + 250;
  for (size_t i = 0; i < pushed; ++i)
    memory.Push(StraightMotion({double(i)}, {double(i + 1)}), i % 2 == 0, i % 3 == 0);
  ASSERT_EQ(memory.size(), PathMemory::kBlocks);
  // The first 250 are forgotten: the oldest kept is block 250, the last block pushed-1.
  EXPECT_DOUBLE_EQ(memory[0].motion.start[0], 250);
  EXPECT_DOUBLE_EQ(memory[memory.size() - 1].motion.start[0], double(pushed - 1));
  EXPECT_DOUBLE_EQ(memory.back().motion.end[0], double(pushed));
  for (size_t k = 0; k < memory.size(); ++k) {
    const size_t i = k + 250;
    ASSERT_DOUBLE_EQ(memory[k].motion.start[0], double(i)) << k;
    EXPECT_EQ(memory[k].rapid, i % 2 == 0) << k;
    EXPECT_EQ(memory[k].decoded, i % 3 == 0) << k;
  }
}

TEST(PathMemory, ClearForgetsAndRecordsAfresh) {
  PathMemory memory;
  for (int i = 0; i < 5; ++i) memory.Push(StraightMotion({0.0 + i}, {1.0 + i}), false, false);
  memory.Clear();
  EXPECT_TRUE(memory.empty());
  memory.Push(StraightMotion({7}, {9}), true, false);
  ASSERT_EQ(memory.size(), 1u);
  EXPECT_DOUBLE_EQ(memory[0].motion.start[0], 7);
  EXPECT_TRUE(memory[0].rapid);
}

TEST(PathMemory, PieceOfALineBackwardsKeepsThePathAndScalesItsLimits) {
  const BlockMotion m = StraightMotion({0, 0}, {30, 40});  // 50 long
  const BlockMotion back = PieceOf(m, 0.8, 0.2);
  ASSERT_TRUE(back.moves);
  EXPECT_NEAR(back.start[0], 24, 1e-12);
  EXPECT_NEAR(back.start[1], 32, 1e-12);
  EXPECT_NEAR(back.end[0], 6, 1e-12);
  EXPECT_NEAR(back.end[1], 8, 1e-12);
  EXPECT_NEAR(back.length, 30, 1e-12);
  // The same feed, acceleration and jerk along the path in mm: the limits over u scale with
  // the piece's share of the block.
  EXPECT_NEAR(back.max_rate * back.length, m.max_rate * m.length, 1e-9);
  EXPECT_NEAR(back.max_accel * back.length, m.max_accel * m.length, 1e-9);
  EXPECT_NEAR(back.max_jerk * back.length, m.max_jerk * m.length, 1e-9);
  std::vector<double> p;
  back.PointAt(0.5, p);  // the middle of the piece is the middle of the block
  EXPECT_NEAR(p[0], 15, 1e-12);
  EXPECT_NEAR(p[1], 20, 1e-12);
}

TEST(PathMemory, PieceOfAnArcStaysOnTheCircle) {
  const BlockMotion m = QuarterArc();
  const BlockMotion back = PieceOf(m, 1.0, 0.5);  // from (0, 10) back to 45 deg
  ASSERT_TRUE(back.moves);
  EXPECT_LT(back.arc_sweep, 0);  // clockwise: the arc backwards
  std::vector<double> p, q;
  for (double u = 0; u <= 1.0; u += 0.125) {
    back.PointAt(u, p);
    m.PointAt(1.0 - 0.5 * u, q);
    EXPECT_NEAR(std::hypot(p[0], p[1]), 10, 1e-9) << u;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(p[a], q[a], 1e-9) << u << " axis " << a;
  }
  back.PointAt(1, p);
  EXPECT_NEAR(p[0], 10 * std::cos(std::numbers::pi / 4), 1e-9);
  EXPECT_NEAR(p[2], 2.5, 1e-9);
}

TEST(PathMemory, APieceOfNoLengthDoesNotMove) {
  const BlockMotion m = StraightMotion({0, 0}, {10, 0});
  EXPECT_FALSE(PieceOf(m, 0.3, 0.3).moves);
  EXPECT_TRUE(PieceOf(m, 0.3, 0.3 + 1e-9).moves);
}

TEST(PathMemory, FaceTransformedBlocksAreNotRetraced) {
  BlockMotion m = StraightMotion({0, 0}, {10, 0});
  EXPECT_TRUE(Retraceable(m));
  m.face_axes[0] = 0;
  m.face_axes[1] = 1;
  EXPECT_FALSE(Retraceable(m));
}

}  // namespace
}  // namespace vmt::control::channel
