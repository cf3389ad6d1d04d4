// The typed names of the NC language: each instruction and built-in function resolves to its
// enum value once, when the program is parsed, and a name that is none keeps the error it
// has always had, at its place.

#include "control/nc/instruction.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "control/nc/interpreter.hpp"
#include "parse_support.hpp"

namespace vmt::control::nc {
namespace {

using I = Instruction;
using F = Function;

TEST(InstructionTest, EveryNameResolvesToItsValueAndBack) {
  const std::vector<std::pair<const char*, Instruction>> names = {
      {"BRA", I::kBra},         {"BEQ", I::kBeq},         {"BNE", I::kBne},
      {"BGT", I::kBgt},         {"BLT", I::kBlt},         {"BGE", I::kBge},
      {"BLE", I::kBle},         {"BES", I::kBes},         {"BEC", I::kBec},
      {"JSR", I::kJsr},         {"RTS", I::kRts},         {"RET", I::kRet},
      {"REV", I::kRev},         {"L", I::kL},             {"MTP", I::kMtp},
      {"MMP", I::kMmp},         {"MRF", I::kMrf},         {"MHP", I::kMhp},
      {"MFP", I::kMfp},         {"MOP", I::kMop},         {"MRY", I::kMry},
      {"SE", I::kSe},           {"RE", I::kRe},           {"TLD", I::kTld},
      {"OTD", I::kOtd},         {"MTD", I::kMtd},         {"SETTING", I::kSetting},
      {"SAVE", I::kSave},       {"MOVE", I::kMove},       {"PROBE", I::kProbe},
      {"COMPARE", I::kCompare}, {"CORRECTION", I::kCorrection}, {"RESTORE", I::kRestore}};
  for (const auto& [name, instruction] : names) {
    EXPECT_EQ(InstructionOf(name), instruction) << name;
    EXPECT_STREQ(InstructionName(instruction), name);
  }
  // The front ends intern names upper case; anything else is no instruction.
  for (const char* other : {"", "mtp", "MTPX", "X", "SIN", "G", "BLOCKSEARCH"})
    EXPECT_EQ(InstructionOf(other), I::kNone) << other;
  EXPECT_STREQ(InstructionName(I::kNone), "");
}

TEST(InstructionTest, KindsOfInstructions) {
  for (Instruction i : {I::kTld, I::kOtd, I::kMtd}) {
    EXPECT_TRUE(IsDataAccess(i)) << InstructionName(i);
    EXPECT_FALSE(IsMeasuringCall(i)) << InstructionName(i);
  }
  for (Instruction i : {I::kSetting, I::kSave, I::kMove, I::kProbe, I::kCompare, I::kCorrection,
                        I::kRestore}) {
    EXPECT_TRUE(IsMeasuringCall(i)) << InstructionName(i);
    EXPECT_FALSE(IsDataAccess(i)) << InstructionName(i);
  }
  for (Instruction i : {I::kNone, I::kMtp, I::kMry, I::kSe, I::kBeq, I::kL}) {
    EXPECT_FALSE(IsMeasuringCall(i)) << InstructionName(i);
    EXPECT_FALSE(IsDataAccess(i)) << InstructionName(i);
  }
}

TEST(InstructionTest, EveryFunctionResolvesToItsValue) {
  const std::vector<std::pair<const char*, Function>> names = {
      {"G", F::kG},       {"M", F::kM},       {"SIN", F::kSin},     {"COS", F::kCos},
      {"TAN", F::kTan},   {"ASIN", F::kAsin}, {"ACOS", F::kAcos},   {"ATAN", F::kAtan},
      {"ABS", F::kAbs},   {"INT", F::kInt},   {"ROUND", F::kRound}, {"EXP", F::kExp},
      {"SQRT", F::kSqrt}, {"LN", F::kLn},     {"TLD", F::kTld},     {"OTD", F::kOtd},
      {"MTD", F::kMtd}};
  for (const auto& [name, function] : names) EXPECT_EQ(FunctionOf(name), function) << name;
  for (const char* other : {"", "sin", "FOO", "SETTING", "SINUS", "ATAN2", "P1"})
    EXPECT_EQ(FunctionOf(other), F::kNone) << other;
  EXPECT_EQ(DataAccessOf(F::kTld), I::kTld);
  EXPECT_EQ(DataAccessOf(F::kOtd), I::kOtd);
  EXPECT_EQ(DataAccessOf(F::kMtd), I::kMtd);
  EXPECT_EQ(DataAccessOf(F::kSin), I::kNone);
  EXPECT_EQ(DataAccessOf(F::kNone), I::kNone);
}

std::vector<Instruction> InstructionsOf(const Program& p) {
  std::vector<Instruction> out;
  for (const Statement& st : p.statements) out.push_back(st.instruction);
  return out;
}

TEST(InstructionTest, Mtc200StatementsCarryTheirInstruction) {
  const ParseResult r = Mtc(
      "N1 @100 = 1\n"
      "N2 BEQ .A\n"
      "N3 BES .A 30\n"
      ".A\n"
      "N4 MTP\n"
      "N5 MRY\n"
      "N6 SE 30\n"
      "N7 SETTING(X, Z, , 18, 48, 16, 3)\n"
      "N8 TLD(1,3,,1,11,) = TLD(1,3,,1,11,) + 0.5\n"
      "N9 JSR .B\n"
      "N10 REV .A\n"
      "N11 RET\n"
      ".B\n"
      "N12 RTS\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  EXPECT_EQ(InstructionsOf(r.program),
            (std::vector<Instruction>{I::kNone, I::kBeq, I::kBes, I::kMtp, I::kMry, I::kSe,
                                      I::kSetting, I::kTld, I::kJsr, I::kRev, I::kRet, I::kRts}));
  // The data location written to is an assignment that names its data access.
  EXPECT_EQ(r.program.statements[7].kind, Statement::Kind::kAssign);
}

TEST(InstructionTest, IsgStatementsCarryTheirInstruction) {
  const ParseResult r = Isg(
      "%main\n"
      "N10 P1 = 2\n"
      "N20 L sub\n"
      "N30 #BLOCKSEARCH LOCKED\n"
      "N40 $IF P1 == 2\n"
      "N50 $ENDIF\n"
      "M30\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  EXPECT_EQ(InstructionsOf(r.program),
            (std::vector<Instruction>{I::kNone, I::kL, I::kNone, I::kNone, I::kNone}));
}

// The built-in function of each call in an expression's code, in code order.
std::vector<Function> CalledFunctions(const Program& p, ExprId id) {
  std::vector<Function> out;
  for (size_t pc = static_cast<size_t>(id); pc < p.code.size();) {
    const uint32_t unit = p.code[pc++];
    const bool wide = (unit >> 8) == kWideImmediate;
    switch (OpOf(unit)) {
      case ExprOp::kEnd:
        return out;
      case ExprOp::kNumber:
      case ExprOp::kVariable:
        pc += wide ? 1 : 0;
        break;
      case ExprOp::kDiv:
      case ExprOp::kMod:
        pc += 2;
        break;
      case ExprOp::kAndSkip:
      case ExprOp::kOrSkip:
        pc += 1;
        break;
      case ExprOp::kCall:
      case ExprOp::kArgs:
        pc += wide ? 1 : 0;
        out.push_back(FunctionOfUnit(p.code[pc]));
        pc += 3;
        break;
      default:
        break;
    }
  }
  ADD_FAILURE() << "expression without end";
  return out;
}

TEST(InstructionTest, ExpressionCallsCarryTheirFunction) {
  const ParseResult r = Mtc(
      "N1 @100 = SIN(30) + FOO(1, 2) * G(1) - MTD(105,,1,13) + SQRT(ABS(-4))\n"
      "N2 OTD(,,4,1) = 1\n"
      "N3 PROBE(5, 1, 20, -10, , Z, -1, 100, 1, 3, 0)\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const auto& st = r.program.statements;
  ASSERT_EQ(st.size(), 3u);
  EXPECT_EQ(CalledFunctions(r.program, st[0].value),
            (std::vector<Function>{F::kSin, F::kNone, F::kG, F::kMtd, F::kAbs, F::kSqrt}));
  // A data location written to is its data function's call; an instruction's argument list
  // calls nothing.
  EXPECT_EQ(CalledFunctions(r.program, st[1].data), (std::vector<Function>{F::kOtd}));
  EXPECT_EQ(CalledFunctions(r.program, st[2].value), (std::vector<Function>{F::kNone}));
  // The function sits beside the argument count, which reads as before.
  EXPECT_EQ(r.program.ExprText(st[0].value),
            "(((SIN(30) + (FOO(1, 2) * G(1))) - MTD(105, , 1, 13)) + SQRT(ABS(-4)))");
}

TEST(InstructionTest, UnknownNamesKeepTheirErrorsAndPlaces) {
  // An unknown word is refused by the parser, at the word.
  EXPECT_EQ(Errors(Mtc("N1 G01 X1\nN2 FOO\n")), "t.mtc:2:4: error: unknown word 'FOO'\n");
  // An unknown function is an error where the program evaluates it, at its name.
  auto run = [](const ParseResult& r) {
    EXPECT_TRUE(r.ok()) << Errors(r);
    Interpreter in({&r.program}, {});
    PreparedBlock b;
    while (in.Next(b)) {
    }
    return in.error() ? Format(*in.error(), r.program.files) : std::string();
  };
  EXPECT_EQ(run(Mtc("N1 @1 = 2\nN2 @2 = 1 + FOO(@1)\nN3 RET\n")),
            "t.mtc:2:13: error: function FOO is not supported by vmt (docs/conformance.md)");
  EXPECT_EQ(run(Isg("N10 P1 = 2\nN20 P2 = 1 + SINUS[P1]\nM30\n")),
            "t.isg:2:14: error: function SINUS is not supported by vmt (docs/conformance.md)");
  // A known function keeps its own argument check; G and M with other than one argument are
  // no built-in function.
  EXPECT_EQ(run(Mtc("N1 @1 = COS(1, 2)\nN2 RET\n")), "t.mtc:1:9: error: COS takes one argument");
  EXPECT_EQ(run(Mtc("N1 @1 = M(1, 2)\nN2 RET\n")),
            "t.mtc:1:9: error: function M is not supported by vmt (docs/conformance.md)");
}

}  // namespace
}  // namespace vmt::control::nc
