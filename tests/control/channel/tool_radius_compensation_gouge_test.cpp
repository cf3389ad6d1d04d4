// Tool nose radius compensation (G40/G41/G42, G18): gouges and arcs the nose does not fit in.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/channel/tool_radius_compensation.hpp"
#include "tool_radius_compensation_test_support.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing
using ::testing::HasSubstr;

// ---------------------------------------------------------------------------------------------
// Gouges and arcs the nose does not fit in.

// A groove of width w and depth 5 in the diameter 2*20, G42, edge 3.
Program Groove(double w) {
  Program p;
  p.From(110, 25).G42().Line(100, 20);  // 0
  p.Line(60, 20);                       // 1
  p.Line(60, 15);                       // 2: groove flank, -X (outer corner above)
  p.Line(60 - w, 15);                   // 3: groove bottom (inner corners at both ends)
  p.Line(60 - w, 20);                   // 4: flank, +X
  p.Line(30, 20);                       // 5
  p.G40().Line(25, 30);                 // 6
  return p;
}

TEST(ToolRadiusCompensationTest, GrooveWideEnoughForTheNose) {
  const Program p = Groove(2);
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  // Bottom: nose centre from Z 59.2 to 58.8 at X 15.8: 2 - 2 * 0.8 long.
  const ContourElement bottom = OfTag(run.out, 3).at(0);
  const Vec2 tip = TipFromCentre(3, 0.8);
  EXPECT_TRUE(Near(bottom.start - tip, {59.2, 15.8}));
  EXPECT_TRUE(Near(bottom.end - tip, {58.8, 15.8}));
  EXPECT_EQ(Inserted(run.out).size(), 2u);  // the outer corners at the groove's edges
}

TEST(ToolRadiusCompensationTest, GrooveNarrowerThanTheNoseIsAGouge) {
  const Program p = Groove(1);  // needs 1.6
  ToolRadiusCompensation trc;
  std::vector<ContourElement> out;
  ContourElement e;
  for (const ContourElement& b : p.blocks) {
    trc.Push(b);
    while (trc.Pop(e)) out.push_back(e);
  }
  trc.Flush();
  while (trc.Pop(e)) out.push_back(e);
  ASSERT_TRUE(trc.error());
  EXPECT_EQ(trc.error()->tag, 3);
  EXPECT_EQ(trc.error()->message,
            "contour violation (gouge): the block is too short for the tool nose radius 0.8 mm "
            "at an inner corner, the compensated path would run backwards");
  // What was final before the error stays: start-up, diameter, corner arc, flank.
  ASSERT_EQ(out.size(), 4u) << Csv(out);
  EXPECT_EQ(out.back().tag, 2);
  EXPECT_FALSE(trc.pending());
  for (size_t i = 1; i < out.size(); ++i) EXPECT_TRUE(Near(out[i].start, out[i - 1].end));
  // Stopped for good until Reset.
  trc.Push(p.blocks[0]);
  EXPECT_FALSE(trc.Pop(e));
  trc.Reset();
  EXPECT_FALSE(trc.error());
  trc.Push(p.blocks[0]);
  EXPECT_TRUE(trc.pending());
}

TEST(ToolRadiusCompensationTest, ShortBlockAfterAnOuterCornerIsAGouge) {
  // Outer corner then a block too short for the inner corner after it: the intersection lies
  // before the block's offset start.
  Program p;
  p.edge = 0;
  p.From(-10, 5).G41().Line(0, 0);  // 0
  p.Line(10, 0);                    // 1: +Z, tool at +X
  p.Line(10, -0.5);                 // 2: -X, outer corner; 0.5 long
  p.Line(20, -0.5);                 // 3: +Z, inner corner needs 0.8 on block 2
  p.G40().Line(25, 5);              // 4
  const Result run = Compensate(p.blocks);
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->tag, 2);
  EXPECT_THAT(run.error->message, HasSubstr("too short for the tool nose radius 0.8 mm"));
}

TEST(ToolRadiusCompensationTest, ArcSmallerThanTheNoseOnTheInnerSideIsAnError) {
  // +Z, then a G03 half circle R0.5 up and back -Z: G41 puts the nose inside it.
  auto program = [](Side side, double r) {
    Program p;
    p.edge = 0;
    p.r = r;
    p.side = side;
    p.From(-10, 0).Line(0, 0);  // 0: start-up
    p.Ccw(0, 1, 0, 0.5);        // 1
    p.Line(-10, 1);             // 2
    p.G40().Line(-15, 5);       // 3
    return p;
  };
  {
    const Result run = Compensate(program(Side::kLeft, 0.8).blocks);
    ASSERT_TRUE(run.error);
    EXPECT_EQ(run.error->tag, 1);
    EXPECT_EQ(run.error->message,
              "arc radius 0.5 mm smaller than the tool nose radius 0.8 mm on the inner side of "
              "the arc");
  }
  {
    // Outside it (G42) the nose runs on R 1.3.
    const Program p = program(Side::kRight, 0.8);
    const Result run = Compensate(p.blocks);
    ASSERT_FALSE(run.error) << run.error->message;
    EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
    EXPECT_NEAR(Norm(OfTag(run.out, 1).at(0).start - OfTag(run.out, 1).at(0).centre), 1.3, kTol);
  }
  {
    // Exactly the nose radius inside: the nose centre stands on the arc centre; the block
    // comes out as a zero-length line there.
    const Program p = program(Side::kLeft, 0.5);
    const Result run = Compensate(p.blocks);
    ASSERT_FALSE(run.error) << run.error->message;
    EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
    const ContourElement still = OfTag(run.out, 1).at(0);
    EXPECT_EQ(still.kind, Kind::kLine);
    EXPECT_TRUE(Near(still.start, {0, 0.5}));
    EXPECT_TRUE(Near(still.end, {0, 0.5}));
    EXPECT_TRUE(Inserted(run.out).empty());
  }
}

TEST(ToolRadiusCompensationTest, InnerCornerIntoATightArcWithoutIntersectionIsAGouge) {
  // +Z along X 0 with the tool above (G41), then a G03 R1 turning up steeply: the offset line
  // X 0.8 and the offset circle R 0.2 do not meet.
  Program p;
  p.edge = 0;
  p.From(-10, 5).G41().Line(-5, 0);  // 0
  p.Line(0, 0);                      // 1
  // Tangent at (0, 0) pointing up-left (turn 135 degrees left): centre at 1 * left of it.
  const Vec2 t = UnitOf({-1, 1});
  const Vec2 c = Vec2{0, 0} + LeftOf(t);
  const Vec2 end = c + Rotate(Vec2{0, 0} - c, kPi / 2);
  p.Ccw(end.z, end.x, c.z, c.x);  // 2
  const Result run = Compensate(p.blocks);
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->tag, 2);
  EXPECT_EQ(run.error->message,
            "contour violation (gouge): the offset contour has no intersection at the inner "
            "corner, the tool nose radius 0.8 mm does not fit");
}

}  // namespace
}  // namespace vmt::control::channel
