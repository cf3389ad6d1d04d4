// G group 17, the coordinate transformations (coordinate_transformation.hpp): G30/G31/G32,
// G(17) data access, and the fictive axis words X1/Y1, which only G31/G32 allow.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/nc/interpreter.hpp"
#include "control/nc/parser.hpp"

namespace vmt::control::nc {
namespace {

using ::testing::HasSubstr;

struct ProgramRun {
  ParseResult parsed;
  std::vector<PreparedBlock> blocks;
  std::string error;
  std::unique_ptr<Interpreter> interpreter;
};

ProgramRun Execute(const std::string& text, std::vector<double> start = {0, 0, 0}) {
  ProgramRun run;
  run.parsed = ParseProgram(text, "t.mtc", Dialect::kMtc200);
  EXPECT_TRUE(run.parsed.ok()) << Format(run.parsed.errors[0], run.parsed.program.files);
  InterpreterConfig config;  // X Z C
  run.interpreter = std::make_unique<Interpreter>(std::vector<const Program*>{&run.parsed.program},
                                                  config);
  run.interpreter->SetPosition(start);
  PreparedBlock b;
  while (run.interpreter->Next(b)) {
    run.blocks.push_back(b);
    if (b.end) break;
  }
  if (run.interpreter->error())
    run.error = Format(*run.interpreter->error(), {run.interpreter->ErrorFile()});
  return run;
}

TEST(InterpreterTransformation, GroupSeventeenIsModalAndReadable) {
  const ProgramRun r = Execute(
      "N1 @100=G(17)\nN2 G31\nN3 @101=G(17)\nN4 G00 X20\nN5 G32\nN6 @102=G(17)\nN7 G30\n"
      "N8 @103=G(17)\nN9 RET\n");
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.interpreter->Variable("@100"), 30);
  EXPECT_EQ(r.interpreter->Variable("@101"), 31);
  EXPECT_EQ(r.interpreter->Variable("@102"), 32);
  EXPECT_EQ(r.interpreter->Variable("@103"), 30);
}

TEST(InterpreterTransformation, FictiveWordsWithoutTransformationAreErrors) {
  const ProgramRun r = Execute("N1 G00 X10\nN2 G01 Y1=5 F100\nN3 RET\n");
  EXPECT_THAT(r.error, HasSubstr("t.mtc:2:8: error: axis Y1 is a fictive axis"));
  EXPECT_THAT(r.error, HasSubstr("G31 or G32"));
  const ProgramRun g77 = Execute("N1 G77 X1=0 Y1=0 F5000\nN2 RET\n");
  EXPECT_THAT(g77.error, HasSubstr("t.mtc:1:8: error: axis X1 is a fictive axis"));
}

TEST(InterpreterTransformation, G31NeedsXAndC) {
  ProgramRun run;
  run.parsed = ParseProgram("N1 G31\nN2 RET\n", "t.mtc", Dialect::kMtc200);
  InterpreterConfig config;
  config.axes = {"X", "Z"};
  Interpreter in({&run.parsed.program}, config);
  PreparedBlock b;
  while (in.Next(b) && !b.end) {
  }
  ASSERT_TRUE(in.error());
  EXPECT_THAT(Format(*in.error(), {in.ErrorFile()}),
              HasSubstr("t.mtc:1:4: error: G31 (coordinate transformation) needs the axes X and C"));
}

TEST(InterpreterTransformation, FaceWordsBecomeXAndC) {
  // From X20 C0 (X1 20 Y1 0) to X1 20 Y1 20: X = 28.28, C = 45; then incremental Y1 -40.
  const ProgramRun r = Execute("N1 G31 G01 X1=20 Y1=20 F600\nN2 G91 Y1=-40\nN3 G90 X1=-20\nN4 RET\n",
                        {20, 5, 0});
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.blocks.size(), 4u);
  const PreparedBlock& b = r.blocks[0];
  EXPECT_TRUE(b.fictive);
  EXPECT_EQ(b.motion, Motion::kLinear);
  EXPECT_EQ(b.programmed, 0b101u);  // X and C, not Z
  EXPECT_NEAR(b.target[0], std::hypot(20, 20), 1e-12);
  EXPECT_NEAR(b.target[1], 5, 0);
  EXPECT_NEAR(b.target[2], 45, 1e-12);
  EXPECT_NEAR(r.blocks[1].target[2], -45, 1e-12);  // X1 20 Y1 -20
  // X1 -20 Y1 -20 from X1 20 Y1 -20: C continues clockwise past -90 to -135.
  EXPECT_NEAR(r.blocks[2].target[0], std::hypot(20, 20), 1e-12);
  EXPECT_NEAR(r.blocks[2].target[2], -135, 1e-12);
}

TEST(InterpreterTransformation, FaceUnwrapsCFromWhereItStands) {
  // C stands at 720 + 10: the move to 90 deg turns 80 deg, it does not unwind two turns.
  const ProgramRun r = Execute("N1 G31 G01 X1=0 Y1=30 F600\nN2 RET\n",
                        {30 / std::cos(10 * std::numbers::pi / 180), 0, 730});
  ASSERT_EQ(r.error, "");
  EXPECT_NEAR(r.blocks[0].target[2], 810, 1e-9);
}

TEST(InterpreterTransformation, X1FollowsDiameterProgramming) {
  const ProgramRun r = Execute("N1 G16 G31 G01 X1=40 Y1=0 F600\nN2 RET\n", {10, 0, 0});
  ASSERT_EQ(r.error, "");
  EXPECT_NEAR(r.blocks[0].target[0], 20, 1e-12);  // X1 is a diameter like X under G16
}

TEST(InterpreterTransformation, CylinderUnrollsAtTheActivationRadius) {
  // G32 at X 20: Y1 = 2 pi 20 / 4 is a quarter turn.
  const ProgramRun r = Execute("N1 G32\nN2 G01 Y1=31.41592653589793 F600\nN3 X1=18\nN4 RET\n",
                        {20, 0, 0});
  ASSERT_EQ(r.error, "");
  EXPECT_NEAR(r.blocks[0].target[2], 90, 1e-9);
  EXPECT_NEAR(r.blocks[0].target[0], 20, 0);
  EXPECT_NEAR(r.blocks[0].modal.cylinder_radius, 20, 0);
  EXPECT_EQ(r.blocks[0].has_effective_distance & 1, 1);
  EXPECT_NEAR(r.blocks[0].effective_distance[0], 20, 0);
  EXPECT_NEAR(r.blocks[1].target[0], 18, 0);  // X1 is X
  EXPECT_NEAR(r.blocks[1].target[2], 90, 1e-9);
  const ProgramRun arc = Execute("N1 G32\nN2 G02 Y1=31.4 I0 K5 F600\nN3 RET\n", {20, 0, 0});
  EXPECT_THAT(arc.error, HasSubstr("t.mtc:2:8: error: G32 G02/G03: arcs in the cylinder surface "
                                   "are not offered"));
  const ProgramRun zero = Execute("N1 G32\nN2 RET\n", {0, 0, 0});
  EXPECT_THAT(zero.error, HasSubstr("t.mtc:1:4: error: G32 (cylinder surface transformation)"));
}

TEST(InterpreterTransformation, G77TakesTheFictiveAxesWithoutTheirValues) {
  const ProgramRun r = Execute("N1 G31\nN2 G77 X1=0 Y1=0 F5000\nN3 RET\n", {20, 0, 30});
  ASSERT_EQ(r.error, "");
  const PreparedBlock& b = r.blocks[0];
  EXPECT_TRUE(b.repos);
  EXPECT_TRUE(b.fictive);
  EXPECT_EQ(b.programmed, 0b101u);
  EXPECT_EQ(b.target[0], 20);  // G77: the channel supplies the targets
  EXPECT_EQ(b.target[2], 30);
}

// ---- G02/G03 in the face ----

TEST(InterpreterTransformation, FaceArcsUnwindCTheWayTheArcGoes) {
  // From X20 C0 (X1 20 Y1 0): half a circle about the centre, counter-clockwise (C 180) and
  // back clockwise (C 0); a full circle about it (C one turn on); a full circle beside it (C
  // stays); R.
  const ProgramRun r = Execute(
      "N1 G31 G03 X1=-20 Y1=0 I-20 J0 F600\nN2 G02 X1=20 Y1=0 I20\nN3 G03 X1=20 Y1=0 I-20\n"
      "N4 G02 X1=20 Y1=0 J5\nN5 G02 X1=20 Y1=20 R30\nN6 G91 G03 Y1=-20 J-10\nN7 RET\n",
      {20, 5, 0});
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.blocks.size(), 7u);
  EXPECT_TRUE(r.blocks[0].fictive);
  EXPECT_EQ(r.blocks[0].motion, Motion::kArcCcw);
  EXPECT_EQ(r.blocks[0].programmed, 0b101u);  // X and C, not Z
  EXPECT_NEAR(r.blocks[0].target[0], 20, 1e-12);
  EXPECT_NEAR(r.blocks[0].target[1], 5, 0);
  EXPECT_NEAR(r.blocks[0].target[2], 180, 1e-9);
  // I20 relative to X1 -20: the centre again; J unprogrammed is 0.
  EXPECT_NEAR(r.blocks[1].target[2], 0, 1e-9);
  EXPECT_NEAR(r.blocks[2].target[2], 360, 1e-9);
  EXPECT_NEAR(r.blocks[3].target[0], 20, 1e-9);
  EXPECT_NEAR(r.blocks[3].target[2], 360, 1e-9);
  EXPECT_NEAR(r.blocks[4].target[0], std::hypot(20, 20), 1e-9);
  EXPECT_NEAR(r.blocks[4].target[2], 405, 1e-9);
  // G91: Y1 -20 from X1 20 Y1 20, centre 10 below: counter-clockwise on the side towards the
  // centre (not round it), back to C 360.
  EXPECT_NEAR(r.blocks[5].target[0], 20, 1e-9);
  EXPECT_NEAR(r.blocks[5].target[2], 360, 1e-9);
}

TEST(InterpreterTransformation, BadFaceArcWordsAreErrorsAtTheirPlace) {
  const ProgramRun k = Execute("N1 G31 G03 X1=-20 Y1=0 I-20 K1 F600\nN2 RET\n", {20, 5, 0});
  EXPECT_THAT(k.error, HasSubstr("t.mtc:1:29: error: K in an arc of G31"));
  const ProgramRun radius = Execute("N1 G31 G03 X1=-20 Y1=0 R5 F600\nN2 RET\n", {20, 5, 0});
  EXPECT_THAT(radius.error,
              HasSubstr("t.mtc:1:12: error: G31 G02/G03: radius R too small for the end point"));
  const ProgramRun off = Execute("N1 G31 G02 X1=-20 Y1=0 I-15 F600\nN2 RET\n", {20, 5, 0});
  EXPECT_THAT(off.error, HasSubstr("t.mtc:1:12: error: G31 G02/G03: end point not on the arc"));
  const ProgramRun none = Execute("N1 G31 G02 X1=-20 Y1=0 F600\nN2 RET\n", {20, 5, 0});
  EXPECT_THAT(none.error, HasSubstr("needs a centre (I for X1, J for Y1) or a radius R"));
}

}  // namespace
}  // namespace vmt::control::nc
