// Tool nose radius compensation (G40/G41/G42, G18): blocks without motion, stops at corners,
// streaming one element behind, and what passes through unchanged.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "control/channel/tool_radius_compensation.hpp"
#include "tool_radius_compensation_test_support.hpp"

namespace vmt::control::channel {
namespace {

using namespace testing;  // vmt::control::channel::testing

// ---------------------------------------------------------------------------------------------
// Blocks without motion, stops, streaming, pass-through.

TEST(ToolRadiusCompensationTest, ZeroLengthBlocksKeepTheirPlaceAndTheCorner) {
  const Program plain = OutsideDiameterAndShoulder();
  const Result reference = Compensate(plain.blocks);
  ASSERT_FALSE(reference.error);
  // The same contour with a block without motion at the inner corner (after block 2) and at
  // the outer corner (after block 3), and one under G41 before the start-up (the modal G42
  // takes effect on the next moving block).
  Program p;
  p.From(120, 30);
  p.rapid = true;
  p.Line(105, 25);  // 0
  p.rapid = false;
  p.G42().Line(105, 25);  // 1: no motion
  p.Line(100, 20);        // 2: start-up
  p.Line(50, 20);         // 3
  p.Line(50, 20);         // 4: no motion, inner corner
  p.Line(50, 30);         // 5
  p.Line(50, 30);         // 6: no motion, outer corner
  p.Line(20, 30);         // 7
  p.G40().Line(15, 40);   // 8
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error) << run.error->message;
  EXPECT_TRUE(CheckPath(p.blocks, run.out, true)) << Csv(run.out);
  ASSERT_EQ(run.out.size(), reference.out.size() + 3) << Csv(run.out);
  // Order: 0, 1 (unchanged), 2, 3, 4 (at the trimmed corner tip (50, 20)), 5, 6 (at the
  // shoulder's end tip (50, 29.2)), the corner arc (tag 7), 7, 8.
  const int64_t tags[] = {0, 1, 2, 3, 4, 5, 6, 7, 7, 8};
  for (size_t i = 0; i < run.out.size(); ++i) EXPECT_EQ(run.out[i].tag, tags[i]) << i;
  EXPECT_TRUE(run.out[7].inserted);
  EXPECT_TRUE(Near(run.out[1].start, {105, 25}));
  EXPECT_TRUE(Near(run.out[4].start, {50, 20}));
  EXPECT_TRUE(Near(run.out[6].start, {50, 29.2}));
  // Everything else as without them.
  const size_t map[] = {0, 2, 3, 5, 7, 8, 9};  // reference index -> index here
  for (size_t i = 0; i < reference.out.size(); ++i) {
    EXPECT_TRUE(Near(run.out[map[i]].start, reference.out[i].start)) << i;
    EXPECT_TRUE(Near(run.out[map[i]].end, reference.out[i].end)) << i;
  }
}

TEST(ToolRadiusCompensationTest, StreamingHoldsBackExactlyOneElement) {
  const Program p = OutsideDiameterAndShoulder();
  ToolRadiusCompensation trc;
  ContourElement e;
  std::vector<ContourElement> out;
  // Popped after each push: block 0 at once, then each compensated block when the next comes.
  const size_t expected_after[] = {1, 1, 2, 3, 5, 7};
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    trc.Push(p.blocks[i]);
    while (trc.Pop(e)) out.push_back(e);
    EXPECT_EQ(out.size(), expected_after[i]) << "after block " << i;
    EXPECT_EQ(trc.pending(), i >= 1 && i <= 4) << i;
    EXPECT_EQ(trc.active(), i >= 1 && i <= 4) << i;
  }
  trc.Flush();
  EXPECT_FALSE(trc.Pop(e));
  EXPECT_TRUE(CheckPath(p.blocks, out, true)) << Csv(out);
}

TEST(ToolRadiusCompensationTest, StopAtAnInnerCornerRunsBackAlongTheLastElement) {
  const Program p = OutsideDiameterAndShoulder();
  ToolRadiusCompensation trc;
  ContourElement e;
  std::vector<ContourElement> out;
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    trc.Push(p.blocks[i]);
    if (i == 2) trc.Flush();  // e.g. an M00 after the diameter
    while (trc.Pop(e)) out.push_back(e);
  }
  trc.Flush();
  while (trc.Pop(e)) out.push_back(e);
  ASSERT_FALSE(trc.error()) << trc.error()->message;
  // Not gouge-free: stopped perpendicular at the end of the diameter, the nose centre
  // (50, 20.8) stands on the line of the shoulder face, the nose overlaps it by r (the
  // shoulder was not known at the stop). Everything else holds.
  EXPECT_TRUE(CheckPath(p.blocks, out, false)) << Csv(out);
  EXPECT_NEAR(Norm(out[2].end - TipFromCentre(3, 0.8) - Vec2{50, 20.8}), 0, kTol);
  // The diameter ends perpendicular (tip (49.2, 20)), then runs back on its own offset to the
  // corner tip (50, 20), then the shoulder.
  ASSERT_EQ(out.size(), 8u) << Csv(out);
  EXPECT_TRUE(Near(out[2].end, {49.2, 20}));
  EXPECT_TRUE(out[3].inserted);
  EXPECT_EQ(out[3].tag, 3);
  EXPECT_EQ(out[3].kind, Kind::kLine);
  EXPECT_TRUE(Near(out[3].start, {49.2, 20}));
  EXPECT_TRUE(Near(out[3].end, {50, 20}));
  EXPECT_TRUE(Near(out[4].start, {50, 20}));
}

TEST(ToolRadiusCompensationTest, StopAtAnInnerCornerAfterAnArcRunsBackOnTheArc) {
  const double h = 5 * std::sqrt(3.0);
  Program p;
  p.edge = 0;
  p.From(-5, 15).G41().Line(-5, h);  // 0
  p.Cw(5, h, 0, 0);                  // 1
  p.Cw(15, h, 10, 0);                // 2
  p.G40().Line(20, 15);              // 3
  ToolRadiusCompensation trc;
  ContourElement e;
  std::vector<ContourElement> out;
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    trc.Push(p.blocks[i]);
    if (i == 1) trc.Flush();
    while (trc.Pop(e)) out.push_back(e);
  }
  trc.Flush();
  while (trc.Pop(e)) out.push_back(e);
  ASSERT_FALSE(trc.error()) << trc.error()->message;
  EXPECT_TRUE(CheckPath(p.blocks, out, false)) << Csv(out);  // the stop overlaps block 2
  const std::vector<ContourElement> inserted = Inserted(out);
  ASSERT_EQ(inserted.size(), 1u);
  EXPECT_EQ(inserted[0].kind, Kind::kArcCcw);  // back along the G02
  EXPECT_TRUE(Near(inserted[0].centre, {0, 0}));
  EXPECT_TRUE(Near(inserted[0].start, {5.4, 0.54 * 2 * h}));
  EXPECT_TRUE(Near(inserted[0].end, {5, std::sqrt(10.8 * 10.8 - 25)}));
}

TEST(ToolRadiusCompensationTest, StopAtAnOuterCornerInsertsTheArcAfterwards) {
  const Program p = OutsideDiameterAndShoulder();
  const Result reference = Compensate(p.blocks);
  ToolRadiusCompensation trc;
  ContourElement e;
  std::vector<ContourElement> out;
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    trc.Push(p.blocks[i]);
    if (i == 3) trc.Flush();  // stop after the shoulder face: its end is perpendicular anyway
    while (trc.Pop(e)) out.push_back(e);
  }
  trc.Flush();
  while (trc.Pop(e)) out.push_back(e);
  ASSERT_FALSE(trc.error());
  ASSERT_EQ(out.size(), reference.out.size());
  for (size_t i = 0; i < out.size(); ++i) {
    EXPECT_TRUE(Near(out[i].start, reference.out[i].start)) << i;
    EXPECT_TRUE(Near(out[i].end, reference.out[i].end)) << i;
    EXPECT_EQ(out[i].inserted, reference.out[i].inserted) << i;
  }
}

TEST(ToolRadiusCompensationTest, FlagsPassThroughAndTransitionsTakeTheNextBlocks) {
  Program p = OutsideDiameterAndShoulder();
  p.blocks[4].rapid = true;  // the block after the outer corner
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error);
  for (const ContourElement& e : run.out) {
    EXPECT_EQ(e.rapid, e.tag == 0 || e.tag == 4) << e.tag;
    EXPECT_EQ(e.nose_radius_mm, p.blocks[e.tag].nose_radius_mm);
    EXPECT_EQ(e.side, p.blocks[e.tag].side);
  }
}

TEST(ToolRadiusCompensationTest, G40ContourPassesUnchanged) {
  Program p;
  p.From(0, 0).Line(10, 0).Cw(20, 10, 10, 10).Line(20, 30).Ccw(0, 50, 0, 30);
  const Result run = Compensate(p.blocks);
  ASSERT_FALSE(run.error);
  ASSERT_EQ(run.out.size(), p.blocks.size());
  for (size_t i = 0; i < p.blocks.size(); ++i) {
    EXPECT_EQ(run.out[i].kind, p.blocks[i].kind);
    EXPECT_TRUE(Near(run.out[i].start, p.blocks[i].start));
    EXPECT_TRUE(Near(run.out[i].end, p.blocks[i].end));
    EXPECT_TRUE(Near(run.out[i].centre, p.blocks[i].centre));
    EXPECT_FALSE(run.out[i].inserted);
  }
}

}  // namespace
}  // namespace vmt::control::channel
