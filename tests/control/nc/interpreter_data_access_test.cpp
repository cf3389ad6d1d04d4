// TLD(...) / OTD(...) / MTD(...) in running programs: the interpreter hands reads and writes with
// their arguments as written to the DataAccess the channel provides, and stops at its errors.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "control/nc/interpreter.hpp"
#include "control/nc/parser.hpp"

namespace vmt::control::nc {
namespace {

using Kind = InstructionArg::Kind;

/// A data store keyed by the address text ("TLD(1,3,_,1,11,_)", _ = omitted) that records every
/// call; addresses listed in `refuse` answer with an error.
struct FakeData {
  std::map<std::string, double> store;
  std::vector<std::string> reads, writes;
  std::map<std::string, std::string> refuse;

  static std::string Key(const std::string& name, const std::vector<InstructionArg>& args) {
    std::string k = name + "(";
    for (size_t i = 0; i < args.size(); ++i) {
      if (i) k += ",";
      k += args[i].kind == Kind::kOmitted ? "_" : std::to_string(static_cast<int>(args[i].value));
    }
    return k + ")";
  }
  DataAccess Access() {
    DataAccess d;
    d.read = [this](Instruction data, const std::vector<InstructionArg>& args,
                    double& value) -> std::string {
      const std::string k = Key(InstructionName(data), args);
      reads.push_back(k);
      if (refuse.count(k)) return refuse[k];
      value = store[k];
      return "";
    };
    d.write = [this](Instruction data, const std::vector<InstructionArg>& args,
                     double value) -> std::string {
      const std::string k = Key(InstructionName(data), args);
      writes.push_back(k);
      if (refuse.count(k)) return refuse[k];
      store[k] = value;
      return "";
    };
    return d;
  }
};

struct DataRun {
  ParseResult parsed;
  std::vector<PreparedBlock> blocks;
  std::string error;
  std::unique_ptr<Interpreter> interpreter;
};

DataRun Execute(const std::string& text, FakeData& data) {
  DataRun run;
  run.parsed = ParseProgram(text, "m.mtc", Dialect::kMtc200);
  EXPECT_TRUE(run.parsed.ok()) << Format(run.parsed.errors[0], run.parsed.program.files);
  run.interpreter = std::make_unique<Interpreter>(std::vector<const Program*>{&run.parsed.program},
                                                  InterpreterConfig{});
  run.interpreter->SetDataAccess(data.Access());
  PreparedBlock b;
  for (int guard = 0; guard < 100 && run.interpreter->Next(b); ++guard) {
    run.blocks.push_back(b);
    if (b.end) break;
  }
  if (run.interpreter->error())
    run.error = Format(*run.interpreter->error(), {run.interpreter->ErrorFile()});
  return run;
}

TEST(InterpreterDataAccessTest, ManualCorrectionLinesReadAndWriteWithOmittedArguments) {
  // Fast measurement 5.6 and 2.1: every omitted argument reaches the access as omitted.
  FakeData data;
  data.store["TLD(1,3,_,1,11,_)"] = 0.25;
  data.store["MTD(105,_,1,13)"] = 0.0125;
  data.store["OTD(_,_,4,1)"] = -3;
  const DataRun r = Execute(
      "TLD(1,3,,1,11,) = TLD(1,3,,1,11,) + MTD(105,,1,13)\n"
      "OTD(,,4,1) = OTD(,,4,1) + MTD(105,,1,13)\n"
      "RET\n",
      data);
  ASSERT_EQ(r.error, "");
  EXPECT_THAT(data.reads, ::testing::ElementsAre("TLD(1,3,_,1,11,_)", "MTD(105,_,1,13)",
                                                 "OTD(_,_,4,1)", "MTD(105,_,1,13)"));
  EXPECT_THAT(data.writes, ::testing::ElementsAre("TLD(1,3,_,1,11,_)", "OTD(_,_,4,1)"));
  EXPECT_DOUBLE_EQ(data.store["TLD(1,3,_,1,11,_)"], 0.2625);
  EXPECT_DOUBLE_EQ(data.store["OTD(_,_,4,1)"], -2.9875);
}

TEST(InterpreterDataAccessTest, ArgumentsAreEvaluatedAndBareNamesAreVariables) {
  FakeData data;
  data.store["TLD(1,7,_,2,12,_)"] = 1.5;
  const DataRun r = Execute(
      "@1 = 7\n"
      "@2 = TLD(1, @1, , 1 + 1, 12, ) * 2\n"
      "MTD(105, , @1 - 6, 13) = @2\n"
      "RET\n",
      data);
  ASSERT_EQ(r.error, "");
  EXPECT_DOUBLE_EQ(r.interpreter->Variable("@2"), 3);
  EXPECT_THAT(data.writes, ::testing::ElementsAre("MTD(105,_,1,13)"));
  EXPECT_DOUBLE_EQ(data.store["MTD(105,_,1,13)"], 3);
}

TEST(InterpreterDataAccessTest, MtdResultBranchesWithBeq) {
  // 5.6: "@100 = MTD(105,,3,11) - 0 BEQ .FEHLER" - dimensional accuracy 0 branches.
  const std::string program =
      "@100 = MTD(105,,3,11) - 0 BEQ .FEHLER\n"
      "G01 X10 F100\n"
      "RET\n"
      ".FEHLER\n"
      "G01 X20 F100\n"
      "RET\n";
  for (const double accuracy : {0.0, 2.0}) {
    FakeData data;
    data.store["MTD(105,_,3,11)"] = accuracy;
    const DataRun r = Execute(program, data);
    ASSERT_EQ(r.error, "");
    ASSERT_GE(r.blocks.size(), 1u);
    EXPECT_EQ(r.blocks[0].target[0], accuracy == 0 ? 20 : 10) << accuracy;
  }
}

TEST(InterpreterDataAccessTest, ReadErrorStopsAtTheCall) {
  FakeData data;
  data.refuse["MTD(105,_,9,13)"] = "MTD(105,,9,13): no compare 9";
  const DataRun r = Execute(
      "G01 X1 F100\n"
      "@1 = 2 + MTD(105,,9,13)\n"
      "G01 X2\n"
      "RET\n",
      data);
  EXPECT_EQ(r.error, "m.mtc:2:10: error: MTD(105,,9,13): no compare 9");
  ASSERT_EQ(r.blocks.size(), 1u);  // G01 X2 is never prepared
}

TEST(InterpreterDataAccessTest, WriteErrorStopsAtTheAssignment) {
  FakeData data;
  data.refuse["OTD(_,_,12,1)"] = "OTD(,,12,1): no table 12";
  const DataRun r = Execute(
      "G01 X1 F100\n"
      "   OTD(,,12,1) = 1\n"
      "G01 X2\n"
      "RET\n",
      data);
  EXPECT_EQ(r.error, "m.mtc:2:4: error: OTD(,,12,1): no table 12");
  ASSERT_EQ(r.blocks.size(), 1u);
}

TEST(InterpreterDataAccessTest, WithoutAnAccessDataIsAnError) {
  ParseResult parsed = ParseProgram("@1 = TLD(1,3,,1,11,)\nRET\n", "m.mtc", Dialect::kMtc200);
  ASSERT_TRUE(parsed.ok());
  Interpreter in({&parsed.program}, InterpreterConfig{});
  PreparedBlock b;
  EXPECT_FALSE(in.Next(b));
  ASSERT_TRUE(in.error());
  EXPECT_THAT(Format(*in.error(), {in.ErrorFile()}),
              ::testing::HasSubstr("m.mtc:1:6: error: TLD(...) data access is not available"));
}

}  // namespace
}  // namespace vmt::control::nc
