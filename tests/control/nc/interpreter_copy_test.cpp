// The interpreter is a value: a copy runs on as the original does, with variables of its own,
// and the events and data access handed to Next() reach whoever hands them in.

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "control/nc/interpreter.hpp"
#include "control/nc/parser.hpp"

namespace vmt::control::nc {
namespace {

const char* const kLoop =
    "N10 @1 = 0\n"
    ".LOOP\n"
    "N20 @1 = @1 + 1\n"
    "N30 @2 = TLD(1,2,,1,11,) + @1\n"
    "N40 G01 X@2 F1000\n"
    "N50 @3 = @1 - 4\n"
    "N60 BLT .LOOP\n"
    "N70 BES .SET 7\n"
    "N80 G01 Z1\n"
    ".SET\n"
    "N90 G01 Z2\n"
    "N100 RET\n";

/// TLD reads `wear`; event 7 is `event`.
struct Host {
  double wear = 0;
  bool event = false;
  std::function<bool(int)> Events() {
    return [this](int n) { return n == 7 && event; };
  }
  DataAccess Data() {
    return {[this](Instruction, const std::vector<InstructionArg>&, double& v) {
              v = wear;
              return std::string();
            },
            {}};
  }
};

/// The X and Z targets of every block `in` hands out until the end, through `host`.
std::vector<double> RunOn(Interpreter& in, Host& host) {
  std::vector<double> targets;
  PreparedBlock b;
  while (in.Next(b, host.Events(), host.Data())) {
    targets.push_back(b.target[0]);
    targets.push_back(b.target[1]);
    if (b.end) break;
  }
  EXPECT_FALSE(in.error()) << in.error()->message;
  return targets;
}

TEST(InterpreterCopyTest, ACopyRunsOnWithItsOwnVariablesAndHost) {
  const ParseResult parsed = ParseProgram(kLoop, "p.mtc", Dialect::kMtc200);
  ASSERT_TRUE(parsed.ok());
  Interpreter original({&parsed.program}, InterpreterConfig{});
  Host host;
  PreparedBlock b;
  // Into the loop: the variables are cached by then.
  ASSERT_TRUE(original.Next(b, host.Events(), host.Data()));
  ASSERT_TRUE(original.Next(b, host.Events(), host.Data()));
  ASSERT_DOUBLE_EQ(original.Variable("@1"), 2);

  Interpreter copy = original;
  Host other{.wear = 10, .event = true};
  // The copy writes its own variables: @1 counts on from 2 in both, apart.
  copy.SetVariable("@1", 0);
  const std::vector<double> copied = RunOn(copy, other);
  EXPECT_DOUBLE_EQ(original.Variable("@1"), 2);
  const std::vector<double> rest = RunOn(original, host);
  EXPECT_DOUBLE_EQ(original.Variable("@1"), 4);
  EXPECT_DOUBLE_EQ(copy.Variable("@1"), 4);

  // The original: @1 = 3, 4 with wear 0, then N80 (event 7 clear) and N90.
  EXPECT_EQ(rest, (std::vector<double>{3, 0, 4, 0, 4, 1, 4, 2, 4, 2}));
  // The copy from @1 = 0: four more passes with wear 10, then the event skips N80.
  EXPECT_EQ(copied, (std::vector<double>{11, 0, 12, 0, 13, 0, 14, 0, 14, 2, 14, 2}));

  // Copy-assigned over another interpreter, it goes on where the original stands.
  Interpreter assigned({&parsed.program}, InterpreterConfig{});
  assigned = original;
  EXPECT_DOUBLE_EQ(assigned.Variable("@1"), 4);
  EXPECT_TRUE(assigned.ended());
}

}  // namespace
}  // namespace vmt::control::nc
