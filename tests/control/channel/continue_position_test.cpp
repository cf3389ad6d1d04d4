// Where machining goes on after block search, decided block by block on its own: the covered
// distance splits the continue block (4.1.1), a block without motion is not split, the distance
// from program start searches on across blocks (4.1.2) and never back into blocks passed, and
// under G41/G42 the per mille lies on the block's own piece, not on an inserted corner.

#include "control/channel/continue_position.hpp"

#include <gtest/gtest.h>

namespace vmt::control::channel {
namespace {

BlockMotion Moving(double length) {
  BlockMotion m;
  m.moves = true;
  m.length = length;
  return m;
}

BlockSearchParameters PerMille(double permille) {
  BlockSearchParameters p;
  p.covered_distance = permille;
  return p;
}

BlockSearchParameters FromProgramStart(double mm) {
  BlockSearchParameters p;
  p.distance_prog_start = mm * 1e4;  // 0.1 um
  return p;
}

TEST(ContinuePosition, TheCoveredDistanceSplitsTheContinueBlock) {
  const BlockSearchParameters p = PerMille(250);
  BlockSearchRun s(p);
  // Blocks before the continue block pass.
  ContinueStep step = DecideContinue(s, p, Moving(40), 40, 0, false);
  EXPECT_FALSE(step.found);
  EXPECT_FALSE(s.found);
  step = DecideContinue(s, p, Moving(40), 40, 40, true);
  EXPECT_TRUE(step.found);
  EXPECT_DOUBLE_EQ(step.u, 0.25);
  EXPECT_TRUE(s.found);
  EXPECT_FALSE(step.distance_passed);
}

TEST(ContinuePosition, ABlockWithoutMotionIsNotSplit) {
  const BlockSearchParameters p = PerMille(500);
  BlockSearchRun s(p);
  const ContinueStep step = DecideContinue(s, p, BlockMotion{}, 0, 12, true);
  EXPECT_TRUE(step.found);
  EXPECT_EQ(step.u, 0);
}

TEST(ContinuePosition, TheDistanceFromProgramStartSearchesOnAcrossBlocks) {
  const BlockSearchParameters p = FromProgramStart(75);
  BlockSearchRun s(p);
  // The continue block ends at 60 mm: the search goes on by distance.
  ContinueStep step = DecideContinue(s, p, Moving(20), 20, 40, true);
  EXPECT_FALSE(step.found);
  EXPECT_TRUE(s.by_distance);
  // A block without motion on the way counts nothing.
  step = DecideContinue(s, p, BlockMotion{}, 0, 60, false);
  EXPECT_FALSE(step.found);
  // 60 .. 80 mm holds 75 mm, three quarters along.
  step = DecideContinue(s, p, Moving(20), 20, 60, false);
  EXPECT_TRUE(step.found);
  EXPECT_DOUBLE_EQ(step.u, 0.75);
}

TEST(ContinuePosition, ADistanceAtABlocksEndIsFoundInThatBlock) {
  const BlockSearchParameters p = FromProgramStart(30);
  BlockSearchRun s(p);
  const ContinueStep step = DecideContinue(s, p, Moving(30), 30, 0, true);
  EXPECT_TRUE(step.found);
  EXPECT_DOUBLE_EQ(step.u, 1);
}

TEST(ContinuePosition, ADistanceBeforeTheContinueBlockContinuesAtItsStartWithAWarning) {
  const BlockSearchParameters p = FromProgramStart(10);
  BlockSearchRun s(p);
  const ContinueStep step = DecideContinue(s, p, Moving(20), 20, 40, true);
  EXPECT_TRUE(step.found);
  EXPECT_EQ(step.u, 0);
  EXPECT_TRUE(step.distance_passed);
  const std::string warning = DistancePassedWarning(p, 40);
  EXPECT_NE(warning.find("10.0000 mm"), std::string::npos);
  EXPECT_NE(warning.find("40.0000 mm"), std::string::npos);
  EXPECT_FALSE(s.by_distance);
}

TEST(ContinuePosition, UnderG41ThePerMilleLiesOnTheBlocksOwnPiece) {
  const BlockSearchParameters p = PerMille(500);
  BlockSearchRun s(p);
  // The continue block begins with a corner the compensation inserted: not there.
  s.inserted_piece = true;
  ContinueStep step = DecideContinue(s, p, Moving(1.2), 1.2, 10, true);
  EXPECT_FALSE(step.found);
  EXPECT_TRUE(s.await_own_piece);
  // Its own piece: half of it.
  s.inserted_piece = false;
  step = DecideContinue(s, p, Moving(8), 8, 11.2, false);
  EXPECT_TRUE(step.found);
  EXPECT_DOUBLE_EQ(step.u, 0.5);
  EXPECT_FALSE(s.await_own_piece);
}

}  // namespace
}  // namespace vmt::control::channel
