// G33 thread cutting, G63 and G64 tapping in the interpreter: modal group 1, the lead (MTC200
// F, ISG K) kept apart from the feed, and the lead's errors at file:line:column.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>

#include "control/nc/interpreter.hpp"
#include "control/nc/parser.hpp"

namespace vmt::control::nc {
namespace {

using ::testing::HasSubstr;

struct Run {
  ParseResult parsed;
  std::unique_ptr<Interpreter> interpreter;
  std::vector<PreparedBlock> blocks;
  std::string error;
};

std::unique_ptr<Run> Execute(const std::string& name, const std::string& text) {
  auto run = std::make_unique<Run>();
  run->parsed = ParseProgram(text, name, DetectDialect(text, name));
  EXPECT_TRUE(run->parsed.ok()) << Format(run->parsed.errors[0], run->parsed.program.files);
  run->interpreter = std::make_unique<Interpreter>(
      std::vector<const Program*>{&run->parsed.program}, InterpreterConfig{});
  PreparedBlock b;
  while (run->interpreter->Next(b)) {
    run->blocks.push_back(b);
    if (b.end) break;
  }
  if (run->interpreter->error())
    run->error = Format(*run->interpreter->error(), {run->interpreter->ErrorFile()});
  return run;
}

TEST(InterpreterThreadTest, Mtc200FIsTheLeadInG33G63G64AndTheFeedStays) {
  const auto r = Execute("t.mtc",
                         "N1 G95 G01 X20 F0.2\n"
                         "N2 G33 Z-30 F1.5\n"
                         "N3 Z-60\n"
                         "N4 G01 X25\n"
                         "N5 G63 Z-10 F1.25\n"
                         "N6 G64 Z0 F0.8\n"
                         "N7 G01 Z5\n"
                         "N8 RET\n");
  ASSERT_EQ(r->error, "");
  ASSERT_EQ(r->blocks.size(), 8u);
  EXPECT_EQ(r->blocks[1].motion, Motion::kThread);
  EXPECT_EQ(r->blocks[1].modal.lead, 1.5);
  EXPECT_EQ(r->blocks[1].modal.feed, 0.2);          // the G95 feed is not disturbed
  EXPECT_EQ(r->blocks[2].motion, Motion::kThread);  // modal
  EXPECT_EQ(r->blocks[2].modal.lead, 1.5);          // and so is the lead
  EXPECT_EQ(r->blocks[3].motion, Motion::kLinear);
  EXPECT_EQ(r->blocks[3].modal.feed, 0.2);
  EXPECT_EQ(r->blocks[4].motion, Motion::kTapping);
  EXPECT_EQ(r->blocks[4].modal.lead, 1.25);
  EXPECT_EQ(r->blocks[5].motion, Motion::kRigidTapping);
  EXPECT_EQ(r->blocks[5].modal.lead, 0.8);
  EXPECT_EQ(r->blocks[6].modal.feed, 0.2);
  EXPECT_EQ(r->blocks[6].target[1], 5);
}

TEST(InterpreterThreadTest, FBeforeTheGCodeInTheBlockIsStillTheLead) {
  const auto r = Execute("t.mtc", "N1 G01 X10 F100\nN2 F2 G33 Z-20\nN3 RET\n");
  ASSERT_EQ(r->error, "");
  EXPECT_EQ(r->blocks[1].modal.lead, 2);
  EXPECT_EQ(r->blocks[1].modal.feed, 100);
}

TEST(InterpreterThreadTest, IsgKIsTheLeadAndFTheFeed) {
  const auto r = Execute("t.isg",
                         "%t\n"
                         "N10 G01 X20 F300\n"
                         "N20 G33 Z-30 K1.5\n"
                         "N30 G64 Z-40 K0.7 F500\n"
                         "N40 G01 Z0\n"
                         "N50 M30\n");
  ASSERT_EQ(r->error, "");
  EXPECT_EQ(r->blocks[1].motion, Motion::kThread);
  EXPECT_EQ(r->blocks[1].modal.lead, 1.5);
  EXPECT_FALSE(r->blocks[1].has_centre);  // K is no arc centre here
  EXPECT_EQ(r->blocks[1].modal.feed, 300);
  EXPECT_EQ(r->blocks[2].motion, Motion::kRigidTapping);
  EXPECT_EQ(r->blocks[2].modal.lead, 0.7);
  EXPECT_EQ(r->blocks[2].modal.feed, 500);
  EXPECT_EQ(r->blocks[3].modal.feed, 500);
}

TEST(InterpreterThreadTest, ModalGroupOneReadsThirtyThreeSixtyThreeSixtyFour) {
  const auto r = Execute("t.mtc",
                         "N1 G33 Z-5 F1\n@1=G(1)\nN2 G63 Z-6\n@2=G(1)\nN3 G64 Z-7\n@3=G(1)\n"
                         "N4 G01 Z-8 F10\n@4=G(1)\nN5 RET\n");
  ASSERT_EQ(r->error, "");
  EXPECT_EQ(r->interpreter->Variable("@1"), 33);
  EXPECT_EQ(r->interpreter->Variable("@2"), 63);
  EXPECT_EQ(r->interpreter->Variable("@3"), 64);
  EXPECT_EQ(r->interpreter->Variable("@4"), 1);
}

TEST(InterpreterThreadTest, MissingLeadIsAnErrorAtTheBlock) {
  EXPECT_THAT(Execute("t.mtc", "N1 G01 X10 F100\nN2 G33 Z-20\nN3 RET\n")->error,
              HasSubstr("t.mtc:2:1: error: G33/G63/G64 without a lead: program F"));
  EXPECT_THAT(Execute("t.isg", "%t\nN10 G63 Z-20 F100\nN20 M30\n")->error,
              HasSubstr("t.isg:2:1: error: G33/G63/G64 without a lead: program K"));
}

TEST(InterpreterThreadTest, LeadNotPositiveIsAnErrorAtTheWord) {
  EXPECT_THAT(Execute("t.mtc", "N1 G33 Z-20 F0\nN2 RET\n")->error,
              HasSubstr("t.mtc:1:13: error: lead F 0.000000 of G33/G63/G64 must be > 0"));
  EXPECT_THAT(Execute("t.mtc", "N1 G64 Z-20 F-1.5\nN2 RET\n")->error,
              HasSubstr("t.mtc:1:13: error: lead F -1.500000"));
  EXPECT_THAT(Execute("t.isg", "%t\nN10 G33 Z-20 K-1\nN20 M30\n")->error,
              HasSubstr("t.isg:2:14: error: lead K -1.000000"));
}

TEST(InterpreterThreadTest, TheOtherDialectsLeadWordIsRefused) {
  EXPECT_THAT(Execute("t.mtc", "N1 G33 Z-20 K1.5\nN2 RET\n")->error,
              HasSubstr("t.mtc:1:13: error: K in G33/G63/G64: the lead is F"));
  EXPECT_THAT(Execute("t.isg", "%t\nN10 G33 Z-20 I1 K1\nN20 M30\n")->error,
              HasSubstr("t.isg:2:14: error: I in G33/G63/G64: the lead is K"));
}

TEST(InterpreterThreadTest, LeadAloneWithoutAxesSetsItForLater) {
  const auto r = Execute("t.mtc", "N1 G33 F2\nN2 Z-10\nN3 RET\n");
  ASSERT_EQ(r->error, "");
  ASSERT_EQ(r->blocks.size(), 2u);  // N1 moves nothing: no block of its own
  EXPECT_EQ(r->blocks[0].motion, Motion::kThread);
  EXPECT_EQ(r->blocks[0].modal.lead, 2);
  EXPECT_EQ(r->blocks[0].target[1], -10);
}

}  // namespace
}  // namespace vmt::control::nc
