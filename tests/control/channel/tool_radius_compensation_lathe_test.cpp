// Tool nose radius compensation (G40/G41/G42, G18): the tip and arc conventions, and exact
// paths of hand-computed outside-turning contours with lines only.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "control/channel/tool_radius_compensation.hpp"
#include "tool_radius_compensation_test_support.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

// ---------------------------------------------------------------------------------------------
// Conventions.

TEST(ToolRadiusCompensationTest, TipFromCentreTable) {
  const double r = 0.8;
  const Vec2 expected[10] = {{0, 0}, {r, r},  {-r, r}, {-r, -r}, {r, -r},
                             {0, r}, {-r, 0}, {0, -r}, {r, 0},   {0, 0}};
  for (int edge = 0; edge <= 9; ++edge)
    EXPECT_TRUE(Near(TipFromCentre(edge, r), expected[edge])) << "edge " << edge;
  EXPECT_TRUE(Near(TipFromCentre(10, r), {0, 0}));
  EXPECT_TRUE(Near(TipFromCentre(-1, r), {0, 0}));
}

TEST(ToolRadiusCompensationTest, ArcSweepConvention) {
  ContourElement arc;
  arc.kind = Kind::kArcCcw;  // counter-clockwise: from +Z towards +X
  arc.centre = {0, 0};
  arc.start = {1, 0};
  arc.end = {0, 1};
  EXPECT_NEAR(ArcSweep(arc), kPi / 2, 1e-15);
  arc.kind = Kind::kArcCw;
  EXPECT_NEAR(ArcSweep(arc), -3 * kPi / 2, 1e-15);
  arc.end = arc.start;
  EXPECT_NEAR(ArcSweep(arc), -2 * kPi, 1e-15);
  arc.kind = Kind::kArcCcw;
  EXPECT_NEAR(ArcSweep(arc), 2 * kPi, 1e-15);
  arc.kind = Kind::kLine;
  EXPECT_EQ(ArcSweep(arc), 0);
}

// ---------------------------------------------------------------------------------------------
// Outside turning on a lathe, G42, edge position 3 (tip at (-r, -r) from the nose centre).

TEST(ToolRadiusCompensationTest, OutsideDiameterG42Edge3PutsTheTipOnTheContour) {
  // Moving -Z, the left (+90 degrees) is -X, the material; the tool is on the right: G42.
  const Program p = OutsideDiameterAndShoulder();
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  ASSERT_EQ(run.out.size(), 7u) << Csv(run.out);
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);

  // G40 rapid unchanged.
  EXPECT_TRUE(Near(run.out[0].start, {120, 30}));
  EXPECT_TRUE(Near(run.out[0].end, {105, 25}));
  EXPECT_TRUE(run.out[0].rapid);
  // Start-up: from the programmed start to the nose centre (100, 20.8) perpendicular to the
  // diameter, i.e. the tip (99.2, 20.0).
  EXPECT_EQ(run.out[1].tag, 1);
  EXPECT_TRUE(Near(run.out[1].start, {105, 25}));
  EXPECT_TRUE(Near(run.out[1].end, {99.2, 20}));
  // The diameter: nose centre at X 20.8, tip at X 20.0, exactly the programmed diameter; it
  // ends at the inner shoulder corner, nose centre (50.8, 20.8), tip (50, 20).
  EXPECT_EQ(run.out[2].tag, 2);
  EXPECT_TRUE(Near(run.out[2].start, {99.2, 20}));
  EXPECT_TRUE(Near(run.out[2].end, {50, 20}));
  EXPECT_TRUE(Near(run.out[2].start - TipFromCentre(3, 0.8), {100, 20.8}));
  // The shoulder face (+X at Z 50, tool on +Z): nose centre at Z 50.8, tip at Z 50.0.
  EXPECT_EQ(run.out[3].tag, 3);
  EXPECT_TRUE(Near(run.out[3].start, {50, 20}));
  EXPECT_TRUE(Near(run.out[3].end, {50, 29.2}));
  // Outer corner at (50, 30): transition arc r 0.8 around the corner (centre (50, 30) + tip
  // offset), G03 under G42, tagged with the block after it.
  const ContourElement& arc = run.out[4];
  EXPECT_TRUE(arc.inserted);
  EXPECT_EQ(arc.tag, 4);
  EXPECT_EQ(arc.kind, Kind::kArcCcw);
  EXPECT_TRUE(Near(arc.centre, {49.2, 29.2}));
  EXPECT_TRUE(Near(arc.start, {50, 29.2}));
  EXPECT_TRUE(Near(arc.end, {49.2, 30}));
  EXPECT_NEAR(ArcSweep(arc), kPi / 2, 1e-12);
  // The second diameter: tip at X 30.0; it ends perpendicular before the cancel.
  EXPECT_EQ(run.out[5].tag, 4);
  EXPECT_TRUE(Near(run.out[5].start, {49.2, 30}));
  EXPECT_TRUE(Near(run.out[5].end, {19.2, 30}));
  // Cancel: from the offset end to the programmed end point.
  EXPECT_EQ(run.out[6].tag, 5);
  EXPECT_TRUE(Near(run.out[6].start, {19.2, 30}));
  EXPECT_TRUE(Near(run.out[6].end, {15, 40}));
}

TEST(ToolRadiusCompensationTest, FrontFaceMovingMinusXIsG41ForAnEdge3Tool) {
  // Facing the front face at Z 50 towards the axis (-X): the left of -X is +Z, where the tool
  // is, so this is G41; with edge position 3 the tip runs at Z 50.0 (nose centre Z 50.8).
  Program p;
  p.From(60, 25).G41().Line(50, 20);  // 0: start-up
  p.Line(50, 0);                      // 1: face
  p.G40().Line(60, 2);                // 2: cancel
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  ASSERT_EQ(run.out.size(), 3u) << Csv(run.out);
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  EXPECT_TRUE(Near(run.out[1].start, {50, 19.2}));
  EXPECT_TRUE(Near(run.out[1].end, {50, -0.8}));
  EXPECT_TRUE(Near(run.out[1].start - TipFromCentre(3, 0.8), {50.8, 20}));
}

TEST(ToolRadiusCompensationTest, DescendingShoulderUnderG42PutsTheNoseOnMinusZ) {
  // Under G42 a face moving -X has the tool on its right, -Z: a step down towards the chuck.
  // The corner at its top is outer, at its foot inner. An edge-3 tool does not fit that face:
  // its nose centre runs at Z 49.2 and its theoretical tip at Z 48.4 (by the table; a tool for
  // that face would be edge position 4).
  Program p;
  p.From(110, 35).G42().Line(100, 30);  // 0: start-up
  p.Line(50, 30);                       // 1
  p.Line(50, 20);                       // 2: face, -X
  p.Line(20, 20);                       // 3
  p.G40().Line(15, 30);                 // 4
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  const std::vector<ContourElement> face = OfTag(run.out, 2);
  ASSERT_EQ(face.size(), 1u);
  const Vec2 tip = TipFromCentre(3, 0.8);
  EXPECT_TRUE(Near(face[0].start - tip, {49.2, 30}));
  EXPECT_TRUE(Near(face[0].end - tip, {49.2, 20.8}));
  EXPECT_NEAR(face[0].start.z, 48.4, kTol);
  const std::vector<ContourElement> arcs = Inserted(run.out);
  ASSERT_EQ(arcs.size(), 1u);  // only the outer corner at (50, 30)
  EXPECT_EQ(arcs[0].tag, 2);
  EXPECT_EQ(arcs[0].kind, Kind::kArcCcw);
  EXPECT_TRUE(Near(arcs[0].centre - tip, {50, 30}));
}

TEST(ToolRadiusCompensationTest, EdgePositionsOnlyShiftTheNoseCentrePath) {
  const Result reference = Compensate(OutsideDiameterAndShoulder(0).blocks);
  ASSERT_FALSE(reference.error);
  for (int edge = 1; edge <= 9; ++edge) {
    SCOPED_TRACE("edge position " + std::to_string(edge));
    const Program p = OutsideDiameterAndShoulder(edge);
    const Result run = Compensate(p.blocks);
    ASSERT_FALSE(run.error) << run.error->message;
    EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
    ASSERT_EQ(run.out.size(), reference.out.size());
    const Vec2 tip = TipFromCentre(edge, 0.8);
    for (size_t i = 1; i < run.out.size(); ++i) {
      const ContourElement &a = run.out[i], &b = reference.out[i];
      EXPECT_EQ(a.kind, b.kind);
      EXPECT_EQ(a.tag, b.tag);
      // The start-up starts and the cancel ends at programmed (uncompensated) points.
      EXPECT_TRUE(Near(a.start - (i == 1 ? Vec2{} : tip), b.start)) << i;
      EXPECT_TRUE(Near(a.end - (i == run.out.size() - 1 ? Vec2{} : tip), b.end)) << i;
      if (a.kind != Kind::kLine) {
        EXPECT_TRUE(Near(a.centre - tip, b.centre)) << i;
      }
    }
  }
  // Edge 3 puts the tip on the diameters and faces of this contour; edge 9 is the centre.
  const Result edge9 = Compensate(OutsideDiameterAndShoulder(9).blocks);
  EXPECT_TRUE(Near(edge9.out[2].start, {100, 20.8}));
}

}  // namespace
}  // namespace vmt::control::channel
