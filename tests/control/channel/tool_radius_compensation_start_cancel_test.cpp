// Tool nose radius compensation (G40/G41/G42, G18): start-up, cancel, side and correction
// changes, and the errors of bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/channel/tool_radius_compensation.hpp"
#include "tool_radius_compensation_test_support.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

// ---------------------------------------------------------------------------------------------
// Start-up, cancel, side and correction changes.

TEST(ToolRadiusCompensationTest, StartUpEndsPerpendicularToTheFollowingArc) {
  Program p;
  p.edge = 0;
  p.From(0, 20).G42().Line(0, 10);  // 0: start-up, -X
  p.Cw(-5, 5, -5, 10);              // 1: G02 R5, starts moving -X, tool inside: R 4.2
  p.G40().Line(-10, 20);            // 2
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  const ContourElement start_up = OfTag(run.out, 0).at(0);
  EXPECT_TRUE(Near(start_up.start, {0, 20}));
  EXPECT_TRUE(Near(start_up.end, {-0.8, 10}));
  const ContourElement arc = OfTag(run.out, 1).at(0);
  EXPECT_TRUE(Near(arc.start, {-0.8, 10}));
  EXPECT_TRUE(Near(arc.end, {-5, 5.8}));
  EXPECT_NEAR(ArcSweep(arc), -kPi / 2, 1e-12);
  EXPECT_TRUE(Inserted(run.out).empty());
}

TEST(ToolRadiusCompensationTest, StartUpOnAnArcIsAnError) {
  Program p;
  p.From(10, 10).Line(0, 10);
  p.G41().Cw(-10, 10, -5, 10);
  const Result run = Compensate(p.blocks);
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->tag, 1);
  EXPECT_EQ(run.error->message,
            "G41/G42 start-up on an arc: the block that starts tool nose radius compensation "
            "must be a straight line (G00/G01)");
  ASSERT_EQ(run.out.size(), 1u);  // the G40 block before it
}

TEST(ToolRadiusCompensationTest, CancelOnAnArcIsAnError) {
  Program p;
  p.From(10, 10).G41().Line(0, 10);
  p.Line(-10, 10);
  p.G40().Ccw(-20, 10, -15, 10);
  const Result run = Compensate(p.blocks);
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->tag, 2);
  EXPECT_EQ(run.error->message,
            "G40 cancel on an arc: the block that cancels tool nose radius compensation must be "
            "a straight line (G00/G01)");
}

TEST(ToolRadiusCompensationTest, SideChangeIsCancelAndStartUpInOneBlock) {
  Program p;
  p.edge = 0;
  p.From(-20, 5).G41().Line(-10, 10);  // 0: start-up
  p.Line(0, 10);                       // 1: +Z, tool on +X: X 10.8
  p.G42();
  p.r = 0.4;             // a new correction may come with the side change
  p.Line(10, 10);        // 2: side change
  p.Line(20, 10);        // 3: +Z, tool on -X: X 9.6
  p.G40().Line(25, 15);  // 4
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  ASSERT_EQ(run.out.size(), 5u) << Csv(run.out);
  EXPECT_TRUE(Near(run.out[1].end, {0, 10.8}));    // ends perpendicular before the change
  EXPECT_TRUE(Near(run.out[2].start, {0, 10.8}));  // side change from there ...
  EXPECT_TRUE(Near(run.out[2].end, {10, 9.6}));    // ... to the new side, perpendicular
  EXPECT_TRUE(Near(run.out[3].start, {10, 9.6}));  // to the next block
  EXPECT_TRUE(Near(run.out[4].start, {20, 9.6}));
  EXPECT_TRUE(Near(run.out[4].end, {25, 15}));
}

TEST(ToolRadiusCompensationTest, SideChangeOnAnArcIsAnError) {
  Program p;
  p.From(-20, 5).G41().Line(-10, 10);
  p.Line(0, 10);
  p.G42().Cw(10, 10, 5, 10);
  const Result run = Compensate(p.blocks);
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->tag, 2);
  EXPECT_EQ(run.error->message,
            "G41/G42 side change on an arc: the block that changes the compensation side must "
            "be a straight line (G00/G01)");
}

TEST(ToolRadiusCompensationTest, CorrectionChangeWhileActiveIsAnError) {
  {
    Program p;
    p.From(-20, 5).G41().Line(-10, 10);
    p.Line(0, 10);
    p.r = 0.4;
    p.Line(10, 10);
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->tag, 2);
    EXPECT_EQ(run.error->message,
              "tool nose radius changed while G41/G42 is active (r 0.8 -> 0.4 mm): cancel with "
              "G40 first");
  }
  {
    Program p;
    p.From(-20, 5).G41().Line(-10, 10);
    p.Line(0, 10);
    p.edge = 2;
    p.Line(10, 10);
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->tag, 2);
    EXPECT_EQ(run.error->message,
              "cutting edge position changed while G41/G42 is active (3 -> 2): cancel with G40 "
              "first");
  }
  {
    // A new correction on the cancel block and at the next start-up is fine.
    Program p;
    p.From(-20, 5).G41().Line(-10, 10);
    p.Line(0, 10);
    p.r = 0.4;
    p.G40().Line(5, 15);
    p.G42().Line(10, 10);
    p.Line(20, 10);
    p.G40().Line(25, 15);
    const Result run = Compensate(p.blocks);
    ASSERT_FALSE(run.error) << run.error->message;
    EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  }
}

TEST(ToolRadiusCompensationTest, BadInputIsAnError) {
  {
    Program p;
    p.edge = 12;
    p.From(0, 5).G41().Line(0, 10);
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->message, "invalid cutting edge position 12 (0..9)");
  }
  {
    Program p;
    p.r = -0.4;
    p.From(0, 5).G41().Line(0, 10);
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->message, "negative tool nose radius -0.4 mm");
  }
  {
    Program p;
    p.From(0, 5).G41().Line(0, 10);
    p.From(0.5, 10).Line(20, 10);
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->tag, 1);
    EXPECT_EQ(run.error->message,
              "contour not continuous under G41/G42: the block starts 0.5 mm away from the "
              "previous end point");
  }
  {
    Program p;
    p.From(0, 5).G41().Line(0, 10);
    p.Cw(5, 15, 0, 10);  // centre on the start point
    const Result run = Compensate(p.blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->tag, 1);
    EXPECT_EQ(run.error->message, "arc centre on the arc start point");
  }
  {
    // Under G40 nothing is checked: the blocks pass unchanged.
    Program p;
    p.edge = 12;
    p.From(0, 5).Line(0, 10);
    p.From(3, 3).Cw(5, 5, 3, 3);
    const Result run = Compensate(p.blocks);
    ASSERT_FALSE(run.error);
    ASSERT_EQ(run.out.size(), 2u);
    EXPECT_TRUE(Near(run.out[1].start, {3, 3}));
    EXPECT_EQ(run.out[1].kind, Kind::kArcCw);
  }
}

TEST(ToolRadiusCompensationTest, ArcEndPointOffTheCircleIsPutOnIt) {
  // End point 0.005 mm off the circle (the channel accepts 0.01): the radius is taken at the
  // start, the path stays continuous.
  Program p;
  p.edge = 0;
  p.From(-10, 5).G42().Line(-5, 0);  // 0
  p.Line(0, 0);                      // 1
  p.Ccw(5, 5.005, 0, 5);             // 2: R5 quarter, end 0.005 off
  p.Line(5, 10);                     // 3
  p.G40().Line(10, 15);              // 4
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  for (size_t i = 1; i < run.out.size(); ++i)
    EXPECT_TRUE(Near(run.out[i].start, run.out[i - 1].end)) << i;
  const ContourElement arc = OfTag(run.out, 2).at(0);
  EXPECT_NEAR(Norm(arc.start - arc.centre), 5.8, kTol);
  EXPECT_NEAR(Norm(arc.end - arc.centre), 5.8, kTol);
}

}  // namespace
}  // namespace vmt::control::channel
