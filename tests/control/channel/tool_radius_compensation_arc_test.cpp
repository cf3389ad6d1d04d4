// Tool nose radius compensation (G40/G41/G42, G18): corners with arcs, exact paths of
// hand-computed contours with fillets, coves, reversals and full circles.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/channel/tool_radius_compensation.hpp"
#include "tool_radius_compensation_test_support.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

// ---------------------------------------------------------------------------------------------
// Corners with arcs.

// A stepped shaft under G42: a G02 fillet into a shoulder and a G03 fillet onto the next
// diameter (both tangent), a G03 that starts at an inner corner (not tangent), a G02 cove
// that starts at an outer corner.
Program SteppedShaft() {
  Program p;
  p.From(105, 12).G42().Line(100, 10);  // 0: start-up
  p.Line(60, 10);                       // 1: diameter
  p.Cw(58, 12, 60, 12);                 // 2: concave fillet R2, tangent
  p.Line(58, 18);                       // 3: shoulder face
  p.Ccw(56, 20, 56, 18);                // 4: convex fillet R2, tangent
  p.Line(30, 20);                       // 5: diameter
  p.Ccw(25, 25, 25, 20);                // 6: R5, starts at an inner corner
  p.Line(10, 25);                       // 7: tangent
  p.Cw(5, 20, 5, 25);                   // 8: cove R5, starts at an outer corner
  p.Line(0, 20);                        // 9: tangent
  p.G40().Line(-5, 30);                 // 10: cancel
  return p;
}

TEST(ToolRadiusCompensationTest, SteppedShaftWithFillets) {
  const Program p = SteppedShaft();
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  const Vec2 tip = TipFromCentre(3, 0.8);
  // Tangent fillets: nothing inserted; offset arcs concentric, R 2 - 0.8 inside the concave
  // one, 2 + 0.8 outside the convex one.
  const ContourElement fillet_in = OfTag(run.out, 2).at(0);
  EXPECT_EQ(fillet_in.kind, Kind::kArcCw);
  EXPECT_TRUE(Near(fillet_in.centre - tip, {60, 12}));
  EXPECT_NEAR(Norm(fillet_in.start - fillet_in.centre), 1.2, kTol);
  EXPECT_TRUE(Near(fillet_in.start - tip, {60, 10.8}));
  EXPECT_TRUE(Near(fillet_in.end - tip, {58.8, 12}));
  const ContourElement fillet_out = OfTag(run.out, 4).at(0);
  EXPECT_EQ(fillet_out.kind, Kind::kArcCcw);
  EXPECT_NEAR(Norm(fillet_out.start - fillet_out.centre), 2.8, kTol);
  EXPECT_TRUE(Near(fillet_out.end - tip, {56, 20.8}));
  // Inner corner line -> arc at (30, 20): the line X 20.8 meets the circle R 5.8 around
  // (25, 20) at Z 25 + sqrt(5.8^2 - 0.8^2).
  const Vec2 meet{25 + std::sqrt(5.8 * 5.8 - 0.8 * 0.8), 20.8};
  EXPECT_TRUE(Near(OfTag(run.out, 5).at(0).end - tip, meet));
  EXPECT_TRUE(Near(OfTag(run.out, 6).at(0).start - tip, meet));
  EXPECT_NEAR(Norm(OfTag(run.out, 6).at(0).start - OfTag(run.out, 6).at(0).centre), 5.8, kTol);
  // Outer corner line -> arc at (10, 25): one transition arc, G03 under G42, from above the
  // corner to the cove's offset start (9.2, 25), which is on the cove's inner offset R 4.2.
  const std::vector<ContourElement> inserted = Inserted(run.out);
  ASSERT_EQ(inserted.size(), 1u) << Csv(run.out);
  EXPECT_EQ(inserted[0].tag, 8);
  EXPECT_EQ(inserted[0].kind, Kind::kArcCcw);
  EXPECT_TRUE(Near(inserted[0].centre - tip, {10, 25}));
  EXPECT_TRUE(Near(inserted[0].start - tip, {10, 25.8}));
  EXPECT_TRUE(Near(inserted[0].end - tip, {9.2, 25}));
  const ContourElement cove = OfTag(run.out, 8).at(0);
  EXPECT_NEAR(Norm(cove.start - cove.centre), 4.2, kTol);
  EXPECT_TRUE(Near(cove.end - tip, {5, 20.8}));
}

TEST(ToolRadiusCompensationTest, ArcArcInnerCorner) {
  // Two G02 bumps R10 meeting in a valley at (5, 5*sqrt(3)), tool above (G41): the offset
  // circles R10.8 around (0, 0) and (10, 0) meet at (5, sqrt(10.8^2 - 25)).
  const double h = 5 * std::sqrt(3.0);
  Program p;
  p.edge = 0;
  p.From(-5, 15).G41().Line(-5, h);  // 0: start-up
  p.Cw(5, h, 0, 0);                  // 1
  p.Cw(15, h, 10, 0);                // 2
  p.G40().Line(20, 15);              // 3
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  EXPECT_TRUE(Inserted(run.out).empty());
  const Vec2 meet{5, std::sqrt(10.8 * 10.8 - 25)};
  EXPECT_TRUE(Near(OfTag(run.out, 1).at(0).end, meet));
  EXPECT_TRUE(Near(OfTag(run.out, 2).at(0).start, meet));
  EXPECT_TRUE(Near(OfTag(run.out, 1).at(0).start, {-5.4, 0.54 * 2 * h}));
}

TEST(ToolRadiusCompensationTest, ArcArcOuterCornerInsertsAnArc) {
  // Two G03 dips R10 meeting at a peak (5, -5*sqrt(3)), tool above (G41, inside the circles):
  // the tool goes over the peak on an arc of the nose radius, G02 under G41.
  const double h = 5 * std::sqrt(3.0);
  Program p;
  p.edge = 0;
  p.r = 0.5;
  p.From(-5, -15).G41().Line(-5, -h);  // 0: start-up
  p.Ccw(5, -h, 0, 0);                  // 1: from 240 to 300 degrees
  p.Ccw(15, -h, 10, 0);                // 2
  p.G40().Line(20, -15);               // 3
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  const std::vector<ContourElement> inserted = Inserted(run.out);
  ASSERT_EQ(inserted.size(), 1u);
  EXPECT_EQ(inserted[0].kind, Kind::kArcCw);
  EXPECT_TRUE(Near(inserted[0].centre, {5, -h}));
  EXPECT_NEAR(ArcSweep(inserted[0]), -kPi / 3, 1e-12);
  EXPECT_NEAR(Norm(OfTag(run.out, 1).at(0).start - OfTag(run.out, 1).at(0).centre), 9.5, kTol);
}

TEST(ToolRadiusCompensationTest, ReversalGoesAroundTheEndOnASemicircle) {
  Program p;
  p.edge = 0;
  p.r = 1;
  p.From(-10, 5).G41().Line(0, 0);  // 0
  p.Line(10, 0);                    // 1: +Z, tool at +X
  p.Line(0, 0);                     // 2: back, tool at -X
  p.G40().Line(-5, 5);              // 3
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  const std::vector<ContourElement> inserted = Inserted(run.out);
  ASSERT_EQ(inserted.size(), 1u);
  EXPECT_EQ(inserted[0].kind, Kind::kArcCw);
  EXPECT_TRUE(Near(inserted[0].start, {10, 1}));
  EXPECT_TRUE(Near(inserted[0].end, {10, -1}));
  EXPECT_TRUE(Near(Samples(inserted[0], 2)[1], {11, 0}));
}

TEST(ToolRadiusCompensationTest, FullCircleStaysAFullCircle) {
  Program p;
  p.edge = 0;
  p.From(-10, -5).G42().Line(-5, 0);  // 0
  p.Line(0, 0);                       // 1: +Z, tool below
  p.Ccw(0, 0, 0, 5);                  // 2: full circle above, tool outside: R 5.8
  p.Line(5, 0);                       // 3
  p.G40().Line(10, -5);               // 4
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  // A full circle closes on itself and passes within r of the line before it, which one
  // element of look-ahead cannot see: only the element's own distance is checked.
  EXPECT_TRUE(CheckPath(p.blocks, run.out, false)) << Csv(run.out);
  const ContourElement circle = OfTag(run.out, 2).at(0);
  EXPECT_EQ(circle.kind, Kind::kArcCcw);
  EXPECT_TRUE(Near(circle.start, {0, -0.8}));
  EXPECT_TRUE(Near(circle.end, {0, -0.8}));
  EXPECT_NEAR(ArcSweep(circle), 2 * kPi, 1e-12);
  EXPECT_TRUE(Inserted(run.out).empty());
}

}  // namespace
}  // namespace vmt::control::channel
