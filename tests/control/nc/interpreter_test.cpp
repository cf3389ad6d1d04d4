// The convert phase: control flow, variables and words of both dialects, run to prepared blocks.

#include "control/nc/interpreter.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "control/nc/parser.hpp"

namespace vmt::control::nc {
namespace {

using ::testing::HasSubstr;

struct ProgramRun {
  std::vector<ParseResult> parsed;
  std::vector<PreparedBlock> blocks;
  std::string error;
  std::unique_ptr<Interpreter> interpreter;
};

// Parses the programs (first = main) and runs the main one to its end or first error.
ProgramRun Execute(std::vector<std::pair<std::string, std::string>> files,
                   InterpreterConfig config = {}, std::function<bool(int)> events = {}) {
  ProgramRun run;
  std::vector<const Program*> programs;
  for (const auto& [name, text] : files) {
    run.parsed.push_back(ParseProgram(text, name, DetectDialect(text, name)));
    EXPECT_TRUE(run.parsed.back().ok())
        << name << ": " << Format(run.parsed.back().errors[0], run.parsed.back().program.files);
  }
  for (const ParseResult& r : run.parsed) programs.push_back(&r.program);
  run.interpreter = std::make_unique<Interpreter>(programs, config);
  if (events) run.interpreter->SetEventSource(events);
  PreparedBlock b;
  while (run.interpreter->Next(b)) {
    run.blocks.push_back(b);
    if (b.end) break;
  }
  if (run.interpreter->error())
    run.error = Format(*run.interpreter->error(), {run.interpreter->ErrorFile()});
  return run;
}

TEST(InterpreterTest, MotionModesAndTargets) {
  const ProgramRun r = Execute(
      {{"a.mtc",
        "N1 G00 X100 Z50\nN2 G01 X80 F200\nN3 G91 Z-10\nN4 G90 G02 X60 Z30 I-10 K0\nN5 RET\n"}});
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.blocks.size(), 5u);
  EXPECT_EQ(r.blocks[0].motion, Motion::kRapid);
  EXPECT_EQ(r.blocks[0].target, (std::vector<double>{100, 50, 0}));
  EXPECT_EQ(r.blocks[1].motion, Motion::kLinear);
  EXPECT_EQ(r.blocks[1].target, (std::vector<double>{80, 50, 0}));
  EXPECT_EQ(r.blocks[1].modal.feed, 200);
  EXPECT_EQ(r.blocks[2].target, (std::vector<double>{80, 40, 0}));  // G91: relative
  EXPECT_EQ(r.blocks[3].motion, Motion::kArcCw);
  EXPECT_TRUE(r.blocks[3].has_centre);
  EXPECT_EQ(r.blocks[3].centre[0], -10);
  EXPECT_TRUE(r.blocks[4].end);
}

TEST(InterpreterTest, Mtc200VariablesBranchesAndSubroutines) {
  // Count down @100 from 3 with a subroutine doing one move per pass.
  const ProgramRun r = Execute({{"a.mtc",
                                 "N0001 @100=3\n"
                                 "N0002 .LOOP\n"
                                 "N0003 JSR .MOVE\n"
                                 "N0004 @100=@100-1 BGT .LOOP\n"
                                 "N0005 RET\n"
                                 "N0006 .MOVE\n"
                                 "N0007 G01 X@100 F100 RTS\n"}});
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.blocks.size(), 4u);
  EXPECT_EQ(r.blocks[0].target[0], 3);
  EXPECT_EQ(r.blocks[1].target[0], 2);
  EXPECT_EQ(r.blocks[2].target[0], 1);
  EXPECT_TRUE(r.blocks[3].end);
  EXPECT_EQ(r.interpreter->Variable("@100"), 0);
}

TEST(InterpreterTest, ModalGroupReadsAndEvents) {
  // The REPOS subroutine's tests: G(2)-17 is 0 in G17; BES branches on a set event.
  const ProgramRun r = Execute({{"a.mtc",
                                 "N0 G17\n"
                                 "N1 @100=G(2)-17 BEQ .G17\n"
                                 "N2 G01 X1 F10\n"
                                 "N3 .G17\n"
                                 "   BES .EV 29\n"
                                 "N4 G01 X2 F10\n"
                                 "N5 .EV\n"
                                 "N6 G01 X3 F10 M=@100 RET\n"}},
                               {}, [](int e) { return e == 29; });
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.blocks.size(), 1u);
  EXPECT_EQ(r.blocks[0].target[0], 3);
  ASSERT_EQ(r.blocks[0].aux.size(), 1u);
  EXPECT_EQ(r.blocks[0].aux[0].letter, 'M');
  EXPECT_EQ(r.blocks[0].aux[0].value, 0);
  EXPECT_TRUE(r.blocks[0].end);
}

TEST(InterpreterTest, IsgStructuresLoopsAndSubprograms) {
  const ProgramRun r = Execute({{"main.isg",
                                 "%main\n"
                                 "N10 P1 = 0\n"
                                 "N20 $FOR P2 = 1, 4, 1\n"
                                 "N30 $IF P2 == 2\n"
                                 "N40 L sub.nc\n"
                                 "N50 $ELSEIF P2 == 3\n"
                                 "N60 G01 X[P2 * 10] F100\n"
                                 "N70 $ELSE\n"
                                 "N80 P1 = P1 + P2\n"
                                 "N90 $ENDIF\n"
                                 "N100 $ENDFOR\n"
                                 "N110 $WHILE P1 < 8\n"
                                 "N120 P1 = P1 + 1\n"
                                 "N130 Z[P1]\n"
                                 "N140 $ENDWHILE\n"
                                 "N150 M30\n"},
                                {"sub.isg", "%sub\nN10 G01 Z-5 F50\nN20 M17\n"}});
  ASSERT_EQ(r.error, "");
  // P2=1: else (P1=1); P2=2: sub (Z-5, M17); P2=3: X30; P2=4: else (P1=5); while: Z6 Z7 Z8.
  ASSERT_EQ(r.blocks.size(), 7u);
  EXPECT_EQ(r.blocks[0].target[1], -5);
  EXPECT_EQ(r.blocks[1].aux[0].value, 17);
  EXPECT_EQ(r.blocks[2].target[0], 30);
  EXPECT_EQ(r.blocks[3].target[1], 6);
  EXPECT_EQ(r.blocks[5].target[1], 8);
  EXPECT_TRUE(r.blocks[6].end);
  EXPECT_EQ(r.interpreter->Variable("P1"), 8);
}

TEST(InterpreterTest, DiameterProgrammingAndAuxFunctions) {
  const ProgramRun r =
      Execute({{"a.mtc", "N1 G16 G00 X60 Z10 M03 S1200 T1 D1\nN2 G15 X20\nN3 RET\n"}});
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.blocks[0].target[0], 30);
  EXPECT_EQ(r.blocks[0].modal.spindle, 3);
  EXPECT_EQ(r.blocks[0].modal.spindle_speed, 1200);
  EXPECT_EQ(r.blocks[0].aux.size(), 4u);
  EXPECT_EQ(r.blocks[1].target[0], 20);
}

TEST(InterpreterTest, RuntimeErrorsPointAtTheSource) {
  EXPECT_THAT(Execute({{"a.mtc", "N1 @1=0\nN2 @2=5/@1\n"}}).error,
              HasSubstr("a.mtc:2:8: error: division by zero"));
  EXPECT_THAT(Execute({{"a.isg", "%a\nN10 L missing\n"}}).error,
              HasSubstr("a.isg:2:5: error: subprogram MISSING is not in the program store"));
  EXPECT_THAT(Execute({{"a.mtc", "N1 G01 A5 F1\n"}}).error,
              HasSubstr("a.mtc:1:8: error: axis A is not in this channel"));
  EXPECT_THAT(Execute({{"a.mtc", "N1 G34 X1\n"}}).error,
              HasSubstr("a.mtc:1:4: error: G34 is not supported"));
  EXPECT_THAT(Execute({{"a.mtc", "N1 RTS\n"}}).error, HasSubstr("RTS without JSR"));
  InterpreterConfig tight;
  tight.max_steps_per_block = 1000;
  EXPECT_THAT(Execute({{"a.mtc", "N1 .L\nN2 @1=1 BRA .L\n"}}, tight).error,
              HasSubstr("endless loop"));
  EXPECT_THAT(Execute({{"a.mtc", "N1 .L JSR .L\n"}}).error, HasSubstr("nested deeper than 16"));
}

TEST(InterpreterTest, EveryOperatorOnVariablesAndFolded) {
  // Each operator once on variables (evaluated from the code) and once on constants (folded
  // by the parser): both must give what the operator means, bit for bit the same.
  struct Case {
    const char* op;
    double a, b;
    double expected;
  };
  const Case cases[] = {
      {"+", 7, 2.5, 9.5}, {"-", 7, 2.5, 4.5},   {"*", 7, 2.5, 17.5},
      {"/", 7, 2, 3.5},   {"MOD", 7.5, 2, 1.5}, {"MOD", -7, 3, std::fmod(-7.0, 3.0)},
      {"^", 2, 10, 1024}, {"**", 9, 0.5, 3},    {"==", 2, 2, 1},
      {"==", 2, 3, 0},    {"<>", 2, 3, 1},      {"!=", 2, 2, 0},
      {"<", 2, 3, 1},     {"<", 3, 3, 0},       {"<=", 3, 3, 1},
      {">", 3, 2, 1},     {">", 2, 2, 0},       {">=", 2, 2, 1},
      {"AND", 2, -1, 1},  {"AND", 0, 5, 0},     {"AND", 5, 0, 0},
      {"OR", 0, 0, 0},    {"OR", 0, -2, 1},     {"OR", 3, 0, 1},
      {"XOR", 1, 1, 0},   {"XOR", 0, 4, 1},     {"XOR", -0.0, 0, 0},
  };
  for (const Case& c : cases) {
    const std::string a = std::to_string(c.a), b = std::to_string(c.b);
    const ProgramRun r =
        Execute({{"a.isg", "%a\nP1 = " + a + "\nP2 = " + b + "\nP3 = P1 " + c.op +
                               " P2\nP4 = " + a + " " + c.op + " " + b + "\nM30\n"}});
    ASSERT_EQ(r.error, "") << c.op;
    EXPECT_EQ(r.interpreter->Variable("P3"), c.expected) << a << " " << c.op << " " << b;
    EXPECT_EQ(r.interpreter->Variable("P4"), c.expected) << a << " " << c.op << " " << b;
  }
  const ProgramRun r = Execute({{"a.isg",
                                 "%a\nP1 = 3\nP2 = -P1\nP3 = NOT P1\nP4 = NOT [P1 - 3]\n"
                                 "P5 = -P1 ^ 2\nP6 = 2 ^ 3 ^ 2\nP7 = P1 - 1 - 1\n"
                                 "P8 = SQRT[P1 * 3] + ABS[-P1] + INT[2.7] + ROUND[2.5]\n"
                                 "P9 = SIN[30] + COS[60] + ATAN[1] + EXP[0] + LN[1]\nM30\n"}});
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.interpreter->Variable("P2"), -3);
  EXPECT_EQ(r.interpreter->Variable("P3"), 0);
  EXPECT_EQ(r.interpreter->Variable("P4"), 1);
  EXPECT_EQ(r.interpreter->Variable("P5"), -9);   // power before unary minus
  EXPECT_EQ(r.interpreter->Variable("P6"), 512);  // to the right
  EXPECT_EQ(r.interpreter->Variable("P7"), 1);    // to the left
  EXPECT_EQ(r.interpreter->Variable("P8"), 3 + 3 + 2 + 3);
  EXPECT_DOUBLE_EQ(r.interpreter->Variable("P9"), 0.5 + 0.5 + 45 + 1 + 0);
}

TEST(InterpreterTest, ExpressionFaultsInTreeOrder) {
  // The first fault an expression meets is reported, in the order the interpreter has always
  // evaluated: left before right, but the divisor before the division before the dividend,
  // the exponent before the base; AND / OR do not evaluate a right side they do not need.
  // (The expected positions are what the tree evaluator before the postfix code reported.)
  auto error = [](const std::string& expression) {
    return Execute({{"a.mtc", "N1 @2=0\nN2 @1=" + expression + "\n"}}).error;
  };
  EXPECT_EQ(error("(1/@2) + (2 MOD @2)"), "a.mtc:2:9: error: division by zero");
  EXPECT_EQ(error("(1/@2) == (2 MOD @2)"), "a.mtc:2:9: error: division by zero");
  EXPECT_EQ(error("(1/@2) XOR (2 MOD @2)"), "a.mtc:2:9: error: division by zero");
  EXPECT_EQ(error("(1/@2) ^ (2 MOD @2)"), "a.mtc:2:19: error: MOD by zero");
  EXPECT_EQ(error("(1/@2) / (2 MOD @2)"), "a.mtc:2:19: error: MOD by zero");
  EXPECT_EQ(error("(1/@2) / @2"), "a.mtc:2:14: error: division by zero");
  EXPECT_EQ(error("(1/@2) MOD 0"), "a.mtc:2:14: error: MOD by zero");
  EXPECT_EQ(error("SQRT(-1) / (1/@2) / (2 MOD @2)"), "a.mtc:2:30: error: MOD by zero");
  EXPECT_EQ(error("@2 AND (1/@2)"), "");
  EXPECT_EQ(error("1 OR (1/@2)"), "");
  EXPECT_EQ(error("1 AND (1/@2)"), "a.mtc:2:15: error: division by zero");
  EXPECT_EQ(error("@2 OR (1/@2)"), "a.mtc:2:15: error: division by zero");
  EXPECT_EQ(error("(1/@2) AND (2 MOD @2)"), "a.mtc:2:9: error: division by zero");
  EXPECT_EQ(error("SIN(1/@2, 2 MOD @2)"), "a.mtc:2:12: error: division by zero");
  EXPECT_EQ(error("SIN(1, 2)"), "a.mtc:2:7: error: SIN takes one argument");
  EXPECT_EQ(error("SQRT(-1/@2)"), "a.mtc:2:14: error: division by zero");
  EXPECT_EQ(error("SQRT(-1) + LN(0)"), "a.mtc:2:7: error: SQRT of a negative number");
  EXPECT_EQ(error("LN(0) ^ SQRT(-1)"), "a.mtc:2:15: error: SQRT of a negative number");
  EXPECT_EQ(error("FOO(1/@2)"), "a.mtc:2:12: error: division by zero");
  EXPECT_EQ(error("FOO(1) + G(99)"), "a.mtc:2:7: error: function FOO is not supported by vmt (docs/conformance.md)");
  EXPECT_EQ(error("G(99)"), "a.mtc:2:7: error: G(99): no such modal group");
  EXPECT_EQ(error("5/(2-2)"), "a.mtc:2:8: error: division by zero");
  EXPECT_EQ(error("(1/@2) ^ (2 MOD @2) ^ (3/@2)"), "a.mtc:2:31: error: division by zero");
  EXPECT_EQ(error("-(1/@2) ^ -(2 MOD @2)"), "a.mtc:2:21: error: MOD by zero");
  EXPECT_EQ(error("NOT (1/@2) OR (2/@2)"), "a.mtc:2:13: error: division by zero");
  EXPECT_EQ(error("(1/@2)*(2/@2)/(3/@2)/(4/@2)"), "a.mtc:2:30: error: division by zero");
  EXPECT_EQ(error("@2 AND (1/@2) OR (2 MOD @2)"), "a.mtc:2:27: error: MOD by zero");
  EXPECT_EQ(error("1 AND @2 OR (3/@2) AND (4/@2)"), "a.mtc:2:21: error: division by zero");
  EXPECT_EQ(error("G(1/@2, 2/@2)"), "a.mtc:2:10: error: division by zero");
  EXPECT_EQ(error("TLD(1/@2) + 3 MOD @2"), "a.mtc:2:12: error: division by zero");
}

TEST(InterpreterTest, DeepAndWideExpressions) {
  // Right-nested sums and long argument lists need a deep value stack.
  std::string nested = "@1";
  for (int i = 0; i < 60; ++i) nested = "@1 + (" + nested + ")";
  std::string args = "SQRT(-1";
  for (int i = 0; i < 300; ++i) args += ", @1 * " + std::to_string(i);
  args += ")";
  const ProgramRun r = Execute({{"a.mtc", "N1 @1=2\nN2 @2=" + nested + "\nN3 @3=" + args + "\n"}});
  EXPECT_EQ(r.interpreter->Variable("@2"), 122);
  EXPECT_EQ(r.error, "a.mtc:3:7: error: SQRT takes one argument");
}

TEST(InterpreterTest, SeedCAxisProgramRuns) {
  // C-axis manual, spiral groove at the face end, with RX as the effective distance.
  InterpreterConfig config;
  config.axes = {"X", "Y", "Z", "C"};
  const ProgramRun r =
      Execute({{"s.mtc",
                "N0140 G90 G06 G17\nN0144 G00 X-30 Y0 Z501 C90\nN0145 G01 Z497 F500\n"
                "N0146 G01 X-70 C-270 RX50 F1200\nN0170 RET\n"}},
              config);
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.blocks.size(), 4u);
  EXPECT_EQ(r.blocks[2].target, (std::vector<double>{-70, 0, 497, -270}));
  EXPECT_EQ(r.blocks[2].has_effective_distance, 1);
  EXPECT_EQ(r.blocks[2].effective_distance[0], 50);
  EXPECT_TRUE(r.blocks[2].modal.low_lag);
}

// The channel sets one axis where it stands (the rotary axis after a changeover to rotary axis
// mode): increments and unprogrammed targets start there, the other axes keep theirs.
TEST(InterpreterTest, SetAxisPositionMovesTheStartOfOneAxis) {
  const ParseResult parsed = ParseProgram(
      "N1 G90 G00 X10 C90\nN2 G91 C10\nN3 X5\nN4 G90 C45\nN5 RET\n", "p.mtc", Dialect::kMtc200);
  ASSERT_TRUE(parsed.ok());
  Interpreter interpreter({&parsed.program}, {});
  PreparedBlock b;
  ASSERT_TRUE(interpreter.Next(b));
  EXPECT_EQ(b.target, (std::vector<double>{10, 0, 90}));
  interpreter.SetAxisPosition(2, 200.5);  // the spindle turned C to 200.5
  interpreter.SetAxisPosition(7, 1);      // not a channel axis: ignored
  ASSERT_TRUE(interpreter.Next(b));
  EXPECT_EQ(b.target, (std::vector<double>{10, 0, 210.5}));
  ASSERT_TRUE(interpreter.Next(b));
  EXPECT_EQ(b.target, (std::vector<double>{15, 0, 210.5}));
  ASSERT_TRUE(interpreter.Next(b));
  EXPECT_EQ(b.target, (std::vector<double>{15, 0, 45}));
}

}  // namespace
}  // namespace vmt::control::nc

namespace vmt::control::nc {
namespace {

TEST(InterpreterTest, MeasuringInstructionsCarryTheirArgumentsAsWritten) {
  // Axis designations stay names, omitted places stay omitted, values are evaluated where the
  // program stands (@100 before the call changes it again).
  const ProgramRun r = Execute({{"a.mtc",
                                 "N1 @100 = 4\n"
                                 "N2 SETTING (X, Z, , 18, 48, 16, 3)\n"
                                 "N3 PROBE(5, 1, @100 * 5, -10, , Z, -(1), 100, 1, 3, 0)\n"
                                 "N4 @100 = 5\n"
                                 "N5 RESTORE()\n"
                                 "N6 RET\n"}});
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.blocks.size(), 4u);
  using Kind = InstructionArg::Kind;
  ASSERT_EQ(r.blocks[0].calls.size(), 1u);
  const InstructionCall& setting = r.blocks[0].calls[0];
  EXPECT_EQ(setting.instruction, Instruction::kSetting);
  ASSERT_EQ(setting.args.size(), 7u);
  EXPECT_EQ(setting.args[0].kind, Kind::kName);
  EXPECT_EQ(setting.args[0].name, "X");
  EXPECT_EQ(setting.args[1].name, "Z");
  EXPECT_EQ(setting.args[2].kind, Kind::kOmitted);
  EXPECT_EQ(setting.args[3].kind, Kind::kValue);
  EXPECT_EQ(setting.args[3].value, 18);
  EXPECT_EQ(setting.args[6].value, 3);
  const InstructionCall& probe = r.blocks[1].calls[0];
  ASSERT_EQ(probe.args.size(), 11u);
  EXPECT_EQ(probe.args[2].kind, Kind::kValue);
  EXPECT_EQ(probe.args[2].value, 20);
  EXPECT_EQ(probe.args[3].value, -10);
  EXPECT_EQ(probe.args[4].kind, Kind::kOmitted);
  EXPECT_EQ(probe.args[5].kind, Kind::kName);
  EXPECT_EQ(probe.args[5].name, "Z");
  EXPECT_EQ(probe.args[6].value, -1);
  EXPECT_EQ(r.blocks[2].calls[0].instruction, Instruction::kRestore);
  EXPECT_TRUE(r.blocks[2].calls[0].args.empty());
}

TEST(InterpreterTest, DataAccessReachesTheChannelWithOmittedPlacesKept) {
  std::vector<std::pair<std::string, std::vector<InstructionArg>>> reads, writes;
  std::vector<double> written;
  ProgramRun run;
  run.parsed.push_back(ParseProgram("N1 TLD(1,3,,1,11,) = TLD(1,3,,1,11,) + MTD(105,,1,13)\n"
                                    "N2 @100 = MTD(105,,3,11) - 2\n"
                                    "N3 BEQ .OK\n"
                                    "N4 G00 X99\n"
                                    ".OK\n"
                                    "N5 OTD(,,4,1) = 7 / 0\n"
                                    "N6 RET\n",
                                    "a.mtc", Dialect::kMtc200));
  ASSERT_TRUE(run.parsed[0].ok());
  Interpreter in({&run.parsed[0].program}, {});
  in.SetDataAccess({[&](Instruction data, const std::vector<InstructionArg>& args,
                        double& value) {
                      reads.emplace_back(InstructionName(data), args);
                      value = data == Instruction::kTld ? 0.5 : args[2].value == 3 ? 2 : 0.25;
                      return std::string();
                    },
                    [&](Instruction data, const std::vector<InstructionArg>& args,
                        double value) {
                      writes.emplace_back(InstructionName(data), args);
                      written.push_back(value);
                      return std::string();
                    }});
  PreparedBlock b;
  std::vector<PreparedBlock> blocks;
  while (in.Next(b)) blocks.push_back(b);
  ASSERT_TRUE(in.error());
  // N5's value fails before anything is written; N4 was branched over.
  EXPECT_EQ(in.error()->pos.line, 6u);
  EXPECT_THAT(in.error()->message, HasSubstr("division by zero"));
  EXPECT_TRUE(blocks.empty());
  ASSERT_EQ(writes.size(), 1u);
  EXPECT_EQ(writes[0].first, "TLD");
  ASSERT_EQ(writes[0].second.size(), 6u);
  EXPECT_EQ(writes[0].second[0].value, 1);
  EXPECT_EQ(writes[0].second[2].kind, InstructionArg::Kind::kOmitted);
  EXPECT_EQ(writes[0].second[4].value, 11);
  EXPECT_EQ(writes[0].second[5].kind, InstructionArg::Kind::kOmitted);
  EXPECT_EQ(written[0], 0.75);
  ASSERT_EQ(reads.size(), 3u);
  EXPECT_EQ(reads[1].first, "MTD");
  EXPECT_EQ(reads[1].second[1].kind, InstructionArg::Kind::kOmitted);
  EXPECT_EQ(reads[1].second[3].value, 13);
}

TEST(InterpreterTest, DataAccessErrorsStopAtTheCall) {
  ProgramRun run;
  run.parsed.push_back(
      ParseProgram("N1 @100 = 1\nN2 @101 = 2 + MTD(999,,1,13)\nN3 RET\n", "a.mtc",
                   Dialect::kMtc200));
  Interpreter in({&run.parsed[0].program}, {});
  in.SetDataAccess({[](Instruction, const std::vector<InstructionArg>&, double&) {
                      return std::string("MTD: no page 999");
                    },
                    {}});
  PreparedBlock b;
  while (in.Next(b)) {
  }
  ASSERT_TRUE(in.error());
  EXPECT_EQ(in.error()->pos.line, 2u);
  EXPECT_EQ(in.error()->pos.column, 15u);
  EXPECT_THAT(in.error()->message, HasSubstr("no page 999"));
}

}  // namespace
}  // namespace vmt::control::nc
