// The distance from program start (block search 4.1.2) and the breakpoint (3.5) on their own:
// ON / OFF / CLEAR, a breakpoint that cuts the block reaching it and holds the path until the
// rest of the block runs, a breakpoint at a block's very start, and the continue block after a
// search cut the same way from the continue position on.

#include "control/channel/program_distance.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace vmt::control::channel {
namespace {

std::vector<axes::AxisParameters> AxesXZ() {
  std::vector<axes::AxisParameters> axes(2);
  axes[0].name = "X";
  axes[1].name = "Z";
  return axes;
}

// A straight move of Z from `z0` to `z1` (u proportional to the path).
BlockMotion LineZ(double z0, double z1) {
  BlockMotion m;
  m.start = {10, z0};
  m.end = {10, z1};
  m.length = z1 > z0 ? z1 - z0 : z0 - z1;
  m.max_rate = 2;
  m.moves = true;
  return m;
}

// A block of Z from `z0` to `z1` starts: its motion as the distance left it (perhaps cut).
BlockMotion Starts(ProgramDistance& d, double z0, double z1) {
  BlockMotion m = LineZ(z0, z1);
  d.BlockStarts(m, AxesXZ());
  return m;
}

TEST(ProgramDistance, CountsWhileOnAndClears) {
  const auto axes = AxesXZ();
  ProgramDistance d;
  BlockMotion m = LineZ(0, 30);
  d.BlockStarts(m, axes);
  EXPECT_DOUBLE_EQ(d.distance(), 30);
  EXPECT_DOUBLE_EQ(d.DistanceAt(0.5), 15);
  d.Command(nc::DistanceCommand::kOff);
  BlockMotion uncounted = LineZ(30, 50);
  d.BlockStarts(uncounted, axes);
  EXPECT_DOUBLE_EQ(d.distance(), 30);
  d.Command(nc::DistanceCommand::kOn);
  d.Pass(d.LengthOf(LineZ(50, 55), axes));  // a block search passes
  EXPECT_DOUBLE_EQ(d.distance(), 35);
  d.Command(nc::DistanceCommand::kClear);
  EXPECT_DOUBLE_EQ(d.distance(), 0);
  d.Restart();
  EXPECT_DOUBLE_EQ(d.LengthOf(LineZ(0, 4), axes), 4);  // ON again at a program start
}

TEST(ProgramDistance, TheBreakpointCutsTheBlockAndItsRestRunsAfterTheHold) {
  ProgramDistance d;
  d.SetBreakpoint(40);
  Starts(d, 0, 30);
  EXPECT_FALSE(d.pending());  // not reached in the first 30 mm
  const BlockMotion second = Starts(d, 30, 70);
  ASSERT_TRUE(d.pending());
  EXPECT_DOUBLE_EQ(second.end[1], 40);  // the motion ends at the breakpoint
  EXPECT_DOUBLE_EQ(second.max_rate, 2 / 0.25);
  EXPECT_DOUBLE_EQ(d.CutFraction(), 0.25);
  EXPECT_DOUBLE_EQ(d.breakpoint(), 0);  // passed: it stops once
  d.Hold();
  EXPECT_TRUE(d.holding());
  EXPECT_FALSE(d.pending());
  double u = 0;
  const std::optional<BlockMotion> rest = d.Resume(u);
  ASSERT_TRUE(rest.has_value());
  EXPECT_DOUBLE_EQ(rest->end[1], 70);  // the whole block, run on from u
  EXPECT_DOUBLE_EQ(u, 0.25);
  EXPECT_FALSE(d.holding());
  EXPECT_DOUBLE_EQ(d.CutFraction(), 1);
}

TEST(ProgramDistance, ABreakpointAtABlocksEndHoldsAfterItWithNothingLeft) {
  ProgramDistance d;
  d.SetBreakpoint(30);
  const BlockMotion first = Starts(d, 0, 30);
  // At the end of the first block: that block runs whole and the path holds after it.
  EXPECT_TRUE(d.pending());
  EXPECT_DOUBLE_EQ(first.end[1], 30);
  d.Hold();
  double u = 0;
  EXPECT_FALSE(d.Resume(u).has_value());
}

TEST(ProgramDistance, BreakpointBeforeTheContinuePositionAndInTheContinueBlock) {
  ProgramDistance d;
  d.SetBreakpoint(25);
  EXPECT_TRUE(d.BreakpointBefore(30));  // 3.5: must lie after the continue position
  EXPECT_FALSE(d.BreakpointBefore(25));
  EXPECT_FALSE(d.BreakpointBefore(20));
  // The continue block starts at 20 mm, 10 mm long; machining goes on at u 0.2 (22 mm) and
  // the breakpoint at 25 mm cuts the rest at u 0.5: on the cut motion the continue position
  // lies at 0.2 / 0.5.
  BlockMotion m = LineZ(100, 110);
  const double u = d.ContinueInBlock(20, 10, 0.2, m);
  EXPECT_TRUE(d.pending());
  EXPECT_DOUBLE_EQ(u, 0.4);
  EXPECT_DOUBLE_EQ(m.end[1], 105);
  EXPECT_DOUBLE_EQ(d.distance(), 30);
  d.Drop();
  EXPECT_FALSE(d.pending());
  EXPECT_DOUBLE_EQ(d.CutFraction(), 1);
}

}  // namespace
}  // namespace vmt::control::channel
