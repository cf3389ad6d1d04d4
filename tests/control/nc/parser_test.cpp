// The NC language front ends: each construct of both dialects, and the errors bad input gets.

#include "control/nc/parser.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "parse_support.hpp"

namespace vmt::control::nc {
namespace {

using ::testing::HasSubstr;

double Value(const Program& p, const Word& w) {
  return w.value == kNoExpr ? w.number : Eval(p, w.value);
}

TEST(Mtc200Test, SignedAndComputedValues) {
  const ParseResult r = Mtc("N1 X-3 Z-3*2 Y+.5 C-@100\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const auto w = r.program.Words(r.program.blocks[0]);
  EXPECT_EQ(w[0].value, kNoExpr);
  EXPECT_DOUBLE_EQ(w[0].number, -3);
  EXPECT_NE(w[1].value, kNoExpr);
  EXPECT_DOUBLE_EQ(Value(r.program, w[1]), -6);
  EXPECT_DOUBLE_EQ(Value(r.program, w[2]), 0.5);
  EXPECT_EQ(r.program.ExprText(w[3].value), "-@100");
}

TEST(Mtc200Test, WordsNumbersLabelsAndComments) {
  const ParseResult r =
      Mtc("N0001 .START ; begin\nN0002 G01 X-30.5 Z.5 RX50 F1200 ; cut\n\n; only a comment\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Program& p = r.program;
  ASSERT_EQ(p.blocks.size(), 2u);
  EXPECT_EQ(p.blocks[0].number, 1);
  EXPECT_EQ(p.symbols.Name(p.blocks[0].label), "START");
  const Block& b = p.blocks[1];
  EXPECT_EQ(b.number, 2);
  EXPECT_EQ(b.counter, 2u);
  EXPECT_EQ(b.pos.line, 2u);
  EXPECT_EQ(b.pos.column, 1u);
  EXPECT_EQ(b.pos.offset, 21u);
  const auto words = p.Words(b);
  ASSERT_EQ(words.size(), 5u);
  const char* addresses[] = {"G", "X", "Z", "RX", "F"};
  const double values[] = {1, -30.5, 0.5, 50, 1200};
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(p.symbols.Name(words[i].address), addresses[i]);
    EXPECT_DOUBLE_EQ(Value(p, words[i]), values[i]);
  }
  EXPECT_EQ(p.PosAt(words[1].offset).column, 11u);
  EXPECT_EQ(p.PosAt(words[1].offset).line, 2u);
  EXPECT_EQ(p.labels.at(p.symbols.Find("START")), 0);
}

TEST(Mtc200Test, IndexedAddressesAndAssignedValues) {
  const ParseResult r = Mtc("N0017 G77 X1=0 Y1=0 F5000 S1=0 S1000 M=@100\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Program& p = r.program;
  const auto w = p.Words(p.blocks[0]);
  ASSERT_EQ(w.size(), 7u);
  EXPECT_EQ(p.symbols.Name(w[1].address), "X1");
  EXPECT_EQ(p.symbols.Name(w[4].address), "S1");
  EXPECT_EQ(p.symbols.Name(w[5].address), "S");
  EXPECT_DOUBLE_EQ(Value(p, w[5]), 1000);
  EXPECT_EQ(p.symbols.Name(w[6].address), "M");
  EXPECT_EQ(p.ExprText(w[6].value), "@100");
}

TEST(Mtc200Test, VariablesBranchesAndCalls) {
  const ParseResult r =
      Mtc("N0001 .A\n"
          "      BES .B 29 ;event set?\n"
          "N0002 @100=G(2)-17 BEQ .A\n"
          "N0003 @101=(@100+2)*3^2 JSR .B\n"
          "N0004 .B\n"
          "      SE 30 MTP MRY RTS\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Program& p = r.program;
  const Statement& bes = p.Statements(p.blocks[1])[0];
  EXPECT_EQ(bes.kind, Statement::Kind::kEventBranch);
  EXPECT_EQ(bes.jump, 4);
  EXPECT_DOUBLE_EQ(Eval(p, bes.value), 29);
  const Statement& assign = p.Statements(p.blocks[2])[0];
  EXPECT_EQ(assign.kind, Statement::Kind::kAssign);
  EXPECT_EQ(p.symbols.Name(assign.name), "@100");
  EXPECT_EQ(p.ExprText(assign.value), "(G(2) - 17)");
  EXPECT_EQ(p.Statements(p.blocks[2])[1].kind, Statement::Kind::kBranch);
  EXPECT_EQ(p.Statements(p.blocks[2])[1].jump, 0);
  // (@100+2)*3^2: power binds tighter than * (and 3^2 is folded), parentheses group.
  EXPECT_EQ(p.ExprText(p.Statements(p.blocks[3])[0].value), "((@100 + 2) * 9)");
  EXPECT_EQ(p.Statements(p.blocks[3])[1].kind, Statement::Kind::kCall);
  const auto& last = p.Statements(p.blocks[5]);
  ASSERT_EQ(last.size(), 4u);
  EXPECT_EQ(p.symbols.Name(last[0].name), "SE");
  EXPECT_EQ(p.symbols.Name(last[1].name), "MTP");
  EXPECT_EQ(last[3].kind, Statement::Kind::kReturn);
}

// Fast measurement 4.4: REV labels are the reverse vectors' only where MOVE / PROBE make them.
TEST(Mtc200Test, RevLabelsAreFreeWithoutMoveOrProbe) {
  EXPECT_TRUE(Mtc("N0001 SETTING(X,Z,,18,48,16,1)\n.REVERSE\nN0002 RET\n").ok());
  EXPECT_TRUE(Mtc("N0001 MOVE(1,2,,1,0)\n.BACK\nN0002 RET\n.HOME\nN0003 RET\n").ok());
  EXPECT_FALSE(Mtc("N0001 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n.REV1\nN0002 RET\n").ok());
}

// Reverse vectors (REPOS manual 4.1, fast measurement 4.4): REV names the reverse label valid
// from its block on; the label is resolved as a branch's is, in the program that programs it.
TEST(Mtc200Test, ReverseVectorNamesALabel) {
  const ParseResult r = Mtc("N1 G01 X10 F100 REV .BACK\nN2 RET\n.BACK\nN10 G01 Z5 RTS\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Program& p = r.program;
  const auto st = p.Statements(p.blocks[0]);
  ASSERT_EQ(st.size(), 1u);
  EXPECT_EQ(st[0].kind, Statement::Kind::kReverse);
  EXPECT_EQ(p.symbols.Name(st[0].target), "BACK");
  EXPECT_EQ(st[0].jump, 2);
  EXPECT_EQ(p.Words(p.blocks[0]).size(), 3u);  // the block's words stay its own
}

TEST(Mtc200Test, ReverseVectorToAMissingLabelIsAnErrorAtItsWord) {
  const ParseResult r = Mtc("N1 G01 X10 F100\nN2   REV .NOWHERE\nN3 RET\n.HOME\nN4 RET\n");
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(Errors(r), HasSubstr("t.mtc:2:6: error: REV: the reverse label .NOWHERE is not "
                                   "defined"));
  const ParseResult bare = Mtc("N1 REV\n");
  ASSERT_FALSE(bare.ok());
  EXPECT_THAT(Errors(bare), HasSubstr("t.mtc:1:7: error: expected a label (.NAME) after REV"));
}

TEST(Mtc200Test, MeasuringInstructionsWithOmittedArguments) {
  const ParseResult r =
      Mtc("N0010 SETTING (X, Z, , 18, 48, 16, 3)\nN0020 COMPARE (10, 1, 2, 8)\nN0030 SAVE ()\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Program& p = r.program;
  const Statement& st = p.Statements(p.blocks[0])[0];
  EXPECT_EQ(p.symbols.Name(st.name), "SETTING");
  // Seven arguments, the third omitted.
  EXPECT_EQ(p.ExprText(st.value), "SETTING(X, Z, , 18, 48, 16, 3)");
  EXPECT_EQ(p.ExprText(p.Statements(p.blocks[1])[0].value), "COMPARE(10, 1, 2, 8)");
  EXPECT_EQ(p.Statements(p.blocks[2])[0].value, kNoExpr);
}

TEST(IsgTest, HeaderParametersStructuresAndCommands) {
  const ParseResult r =
      Isg("%example\n"
          "N05 #DISTANCE   PROG START OFF ; comment\n"
          "N10 P1 = 10 (a comment) P2 = P1 * [2 + 1]\n"
          "N20 $IF P1 == 10\n"
          "N30 G01 X[P1*2] Y-5 F1000\n"
          "N40 $ELSEIF P1 > 3\n"
          "N50 $ELSE\n"
          "N60 $ENDIF\n"
          "N70 $FOR P3 = 1, 10, 2\n"
          "N80 L sub_1\n"
          "N90 $ENDFOR\n"
          "N100 $WHILE P1 < 100\n"
          "N110 P1 = P1 + 1\n"
          "N120 $ENDWHILE\n"
          "N130 G74 X1 Y2\n"
          "M30\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Program& p = r.program;
  EXPECT_EQ(p.name, "EXAMPLE");
  EXPECT_EQ(p.Statements(p.blocks[1])[0].kind, Statement::Kind::kHashCommand);
  EXPECT_EQ(p.texts[p.Statements(p.blocks[1])[0].text], "DISTANCE PROG START OFF");
  // Typed once, here: the channel switches on it (block search 4.1.2).
  EXPECT_EQ(p.Statements(p.blocks[1])[0].hash, HashCommand::kDistanceProgStart);
  ASSERT_EQ(p.Statements(p.blocks[2]).size(), 2u);
  EXPECT_EQ(p.symbols.Name(p.Statements(p.blocks[2])[1].name), "P2");
  // $IF -> $ELSEIF -> $ELSE -> $ENDIF chain, loops close back on their heads.
  EXPECT_EQ(p.Statements(p.blocks[3])[0].jump, 5);
  EXPECT_EQ(p.Statements(p.blocks[5])[0].jump, 6);
  EXPECT_EQ(p.Statements(p.blocks[6])[0].jump, 7);
  EXPECT_EQ(p.Statements(p.blocks[8])[0].jump, 10);
  EXPECT_EQ(p.Statements(p.blocks[10])[0].jump, 8);
  const Statement& loop = p.Statements(p.blocks[8])[0];
  EXPECT_DOUBLE_EQ(Eval(p, loop.limit), 10);
  EXPECT_DOUBLE_EQ(Eval(p, loop.step), 2);
  EXPECT_EQ(p.Statements(p.blocks[9])[0].kind, Statement::Kind::kCall);
  EXPECT_EQ(p.symbols.Name(p.Statements(p.blocks[9])[0].target), "SUB_1");
  const Word& x = p.Words(p.blocks[4])[1];
  EXPECT_DOUBLE_EQ(Value(p, p.Words(p.blocks[4])[2]), -5);
  EXPECT_EQ(p.ExprText(x.value), "(P1 * 2)");
  EXPECT_EQ(p.blocks.back().number, -1);
}

struct BadCase {
  Dialect dialect;
  const char* text;
  const char* where;  // "line:column"
  const char* message;
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << ToString(c.dialect) << ": " << c.text; }

class BadInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInputTest, ReportsFileLineColumnAndText) {
  const BadCase c = GetParam();
  const ParseResult r = ParseProgram(c.text, "bad.nc", c.dialect);
  ASSERT_FALSE(r.ok()) << c.text;
  const std::string first = Format(r.errors[0], r.program.files);
  EXPECT_THAT(first, HasSubstr(std::string("bad.nc:") + c.where + ": error: "));
  EXPECT_THAT(first, HasSubstr(c.message));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadInputTest,
    ::testing::Values(
        BadCase{Dialect::kMtc200, "N0001 G01 X\n", "1:11", "address X needs a value"},
        BadCase{Dialect::kMtc200, "N0001 BRA .NOPE\n", "1:7", "label .NOPE is not defined"},
        BadCase{Dialect::kMtc200, "N0001 .A\nN0002 .A\n", "2:1",
                "label .A is already defined on line 1"},
        BadCase{Dialect::kMtc200, "N0001 FOO\n", "1:7", "unknown word 'FOO'"},
        BadCase{Dialect::kMtc200, "N0001 MOVE(1,2,,1,0)\n.REVERSE\nN0002 RET\n", "2:1",
                "label .REVERSE: labels beginning with REV are the reverse vectors' (fast "
                "measurement 4.4)"},
        BadCase{Dialect::kMtc200, "N0001 @100=(1+2\n", "1:16", "expected ')'"},
        BadCase{Dialect::kMtc200, "N0001 @=3\n", "1:8", "expected a variable number"},
        BadCase{Dialect::kMtc200, "N0001 BEQ REPOS\n", "1:11",
                "expected a label (.NAME) after BEQ"},
        BadCase{Dialect::kMtc200, "N0001 SETTING (X, Z\n", "1:20", "expected ',' or ')'"},
        BadCase{Dialect::kMtc200, "N0001 X10 ! \n", "1:11", "unexpected '!'"},
        BadCase{Dialect::kIsg, "N10 $IF P1 == 1\nN20 X1\n", "1:5", "missing $ENDIF"},
        BadCase{Dialect::kIsg, "N10 $ENDFOR\n", "1:5", "$ENDFOR without its opening statement"},
        BadCase{Dialect::kIsg, "N10 $LOOP\n", "1:5", "unknown control statement '$LOOP'"},
        BadCase{Dialect::kIsg, "N10 X10 (open comment\n", "1:9", "comment '(' is not closed"},
        BadCase{Dialect::kIsg, "N10 P1 10\n", "1:8", "expected '=' after P1"},
        BadCase{Dialect::kIsg, "N10 $FOR P1 = 1\n", "1:16", "expected ', limit' in $FOR"},
        BadCase{Dialect::kIsg, "N10 X[1+\n", "1:9",
                "expected a value, found the end of the block"}));

TEST(ParserTest, DeepNestingIsAnErrorNotACrash) {
  const std::string deep = "N1 @1=" + std::string(100000, '(') + "1\n";
  const ParseResult r = Mtc(deep);
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(Errors(r), HasSubstr("nested too deeply"));
  // The 65th level is the fault, where it starts (before its unary plus).
  const ParseResult at = Mtc("N1 @1=" + std::string(64, '(') + " +1\n");
  EXPECT_THAT(Errors(at), HasSubstr("t.mtc:1:72: error: expression nested too deeply"));
  // Unary plus is no nesting, and a long run of it no deep recursion either.
  EXPECT_TRUE(Mtc("N1 @1=" + std::string(1000000, '+') + "1\n").ok());
  EXPECT_THAT(Errors(Mtc("N1 @1=" + std::string(65, '-') + "1\n")), HasSubstr("nested too deeply"));
}

TEST(ParserTest, ReportsEveryBadBlockAndKeepsTheGoodOnes) {
  const ParseResult r = Mtc("N1 X\nN2 G01 X10\nN3 Y\n");
  ASSERT_EQ(r.errors.size(), 2u);
  EXPECT_EQ(r.errors[0].pos.line, 1u);
  EXPECT_EQ(r.errors[1].pos.line, 3u);
  EXPECT_EQ(r.program.blocks.size(), 3u);
}

TEST(ParserTest, DetectsTheDialect) {
  EXPECT_EQ(DetectDialect("%prog\nN10 X1\n", "a.nc"), Dialect::kIsg);
  EXPECT_EQ(DetectDialect("N0001 .REPOS\n", "a.nc"), Dialect::kMtc200);
  EXPECT_EQ(DetectDialect("N10 $IF P1 == 1\n", "a.nc"), Dialect::kIsg);
  EXPECT_EQ(DetectDialect("anything", "a.isg"), Dialect::kIsg);
  EXPECT_EQ(DetectDialect("%x", "a.mtc"), Dialect::kMtc200);
  EXPECT_EQ(DetectDialect("\xEF\xBB\xBF%prog\nN10 X1\n", "a.nc"), Dialect::kIsg);
}

// A UTF-8 byte order mark (Windows editors write one) is no part of the program: the first
// line parses, and its columns count from after the mark.
TEST(ParserTest, SkipsAUtf8ByteOrderMark) {
  const ParseResult r = Mtc("\xEF\xBB\xBFN1 G01 X10\nN2 M30\n");
  EXPECT_TRUE(r.ok()) << Errors(r);
  EXPECT_EQ(r.program.blocks.size(), 2u);
  EXPECT_THAT(Errors(Mtc("\xEF\xBB\xBFN1 G01 X\n")), HasSubstr("t.mtc:1:8: error"));
}

}  // namespace
}  // namespace vmt::control::nc
