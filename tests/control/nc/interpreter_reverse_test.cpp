// Reverse vectors in the convert phase (REPOS manual 4.1, fast measurement 4.4): REV .LABEL
// makes its label the reverse vector valid from its block on; a reverse runs from that label,
// and the end of that part (its RTS or RET, its file's end, or reaching `.HOME`) goes on at
// `.HOME`.

#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "control/nc/interpreter.hpp"
#include "control/nc/parser.hpp"

namespace vmt::control::nc {
namespace {

struct Reversal {
  explicit Reversal(const std::vector<std::string>& texts) {
    for (size_t i = 0; i < texts.size(); ++i) {
      parsed.push_back(ParseProgram(texts[i], i == 0 ? "p.mtc" : "99.mtc", Dialect::kMtc200));
      EXPECT_TRUE(parsed.back().ok())
          << Format(parsed.back().errors[0], parsed.back().program.files);
    }
    std::vector<const Program*> programs;
    for (const ParseResult& r : parsed) programs.push_back(&r.program);
    interpreter = std::make_unique<Interpreter>(programs, InterpreterConfig{});
  }
  /// The next block with an effect; its N number (-1 at the program end or after an error).
  int Next() {
    if (!interpreter->Next(block)) return -1;
    return block.end && block.block < 0 ? -1 : Number(block);
  }
  int Number(const PreparedBlock& b) const {
    return parsed[b.program].program.blocks[static_cast<size_t>(b.block)].number;
  }
  /// The N numbers of the blocks up to the end.
  std::vector<int> Rest() {
    std::vector<int> numbers;
    for (int i = 0; i < 50; ++i) {
      if (!interpreter->Next(block)) break;
      numbers.push_back(Number(block));
      if (block.end) break;
    }
    return numbers;
  }
  /// The block of `label` in program `program`.
  int32_t LabelBlock(size_t program, const std::string& label) const {
    const Program& p = parsed[program].program;
    return p.labels.at(p.symbols.Find(label));
  }

  std::deque<ParseResult> parsed;  ///< stable addresses: the interpreter keeps the programs'
  std::unique_ptr<Interpreter> interpreter;
  PreparedBlock block;
};

const char* kProgram =
    "N1 G01 X10 F100\n"
    "N2 REV .BACK\n"
    "N3 G01 X20\n"
    "N4 G01 X30\n"
    "N5 RET\n"
    ".BACK\n"
    "N10 G01 Z5\n"
    "N11 RTS\n"
    ".HOME\n"
    "N20 G00 X0\n"
    "N21 RET\n";

TEST(InterpreterReverse, TheLabelIsValidFromItsBlockOn) {
  Reversal r({kProgram});
  ASSERT_EQ(r.Next(), 1);
  EXPECT_FALSE(r.block.reverse.valid());
  ASSERT_EQ(r.Next(), 3);
  EXPECT_EQ(r.block.reverse.program, 0);
  EXPECT_EQ(r.block.reverse.block, r.LabelBlock(0, "BACK"));
  ASSERT_EQ(r.Next(), 4);
  EXPECT_EQ(r.block.reverse.block, r.LabelBlock(0, "BACK"));
}

TEST(InterpreterReverse, TheLabelsPartRunsThenHome) {
  Reversal r({kProgram});
  r.Next(), r.Next();  // N3
  ASSERT_TRUE(r.interpreter->Reverse(r.block.reverse));
  EXPECT_EQ(r.Rest(), (std::vector<int>{10, 20, 21}));
  EXPECT_TRUE(r.block.end);
  EXPECT_FALSE(r.interpreter->error().has_value());
}

TEST(InterpreterReverse, WithoutAValidLabelHomeAtOnce) {
  Reversal r({kProgram});
  r.Next();  // N1, before the REV
  ASSERT_TRUE(r.interpreter->Reverse(r.block.reverse));
  EXPECT_EQ(r.Rest(), (std::vector<int>{20, 21}));
}

TEST(InterpreterReverse, ASecondReverseDuringTheReverseProgramGoesHome) {
  Reversal r({kProgram});
  r.Next(), r.Next();
  ASSERT_TRUE(r.interpreter->Reverse(r.block.reverse));
  ASSERT_EQ(r.Next(), 10);
  EXPECT_FALSE(r.block.reverse.valid());
  ASSERT_TRUE(r.interpreter->Reverse(r.block.reverse));
  EXPECT_EQ(r.Rest(), (std::vector<int>{20, 21}));
}

// RET at the top of the part, the part running into `.HOME`, the part calling a subroutine
// whose RTS returns into it, and the part ending with its file: `.HOME` runs once, to its end.
TEST(InterpreterReverse, EveryEndOfThePartGoesOnAtHomeOnce) {
  const std::string head = "N1 REV .BACK\nN2 G01 X20 F100\nN3 RET\n.BACK\nN10 G01 Z5\n";
  const std::string home = ".HOME\nN20 G00 X0\nN21 RET\n";
  for (const auto& [text, expected] : std::vector<std::pair<std::string, std::vector<int>>>{
           {head + "N11 RET\n" + home, {10, 20, 21}},
           {head + home, {10, 20, 21}},
           {head + "N11 JSR .SUB\nN12 G01 Z6 RTS\n.SUB\nN30 G01 Z7 RTS\n" + home,
            {10, 30, 12, 20, 21}},
           {"N1 REV .BACK\nN2 G01 X20 F100\nN3 RET\n" + home + ".BACK\nN10 G01 Z5\n",
            {10, 20, 21}}}) {
    SCOPED_TRACE(text);
    Reversal r({text});
    int n = 0;
    while ((n = r.Next()) != 2 && n != -1) {
    }
    ASSERT_EQ(n, 2);
    ASSERT_TRUE(r.interpreter->Reverse(r.block.reverse));
    EXPECT_EQ(r.Rest(), expected);
    EXPECT_TRUE(r.block.end);
  }
}

// A REV in a subroutine stays valid after its RTS: the reverse vector follows the flow.
TEST(InterpreterReverse, AReverseVectorOfACalledSubroutineStaysValid) {
  Reversal r({"N1 JSR .SUB\nN2 G01 X20 F100\nN3 RET\n.SUB\nN10 REV .BACK\nN11 G01 X5 F100 RTS\n"
         ".BACK\nN12 G01 Z5 RTS\n.HOME\nN20 G00 X0\nN21 RET\n"});
  ASSERT_EQ(r.Next(), 11);
  ASSERT_EQ(r.Next(), 2);
  EXPECT_EQ(r.block.reverse.block, r.LabelBlock(0, "BACK"));
  ASSERT_TRUE(r.interpreter->Reverse(r.block.reverse));
  EXPECT_EQ(r.Rest(), (std::vector<int>{12, 20, 21}));
}

// REPOS manual 4.1: the REPOS subroutine in program 99 programs its own reverse vector; the
// reverse runs program 99's part, then the main program's `.HOME`.
TEST(InterpreterReverse, TheRepoSubroutinesLabelInProgram99) {
  Reversal r({"N1 G01 X20 F100\nN2 RET\n.HOME\nN20 G00 X0\nN21 RET\n",
         ".REPOS\nN10 REV .RBACK\nN11 G77 Z0 F1000\nN12 RTS\n.RBACK\nN13 G01 Z9 F1000 RTS\n"});
  ASSERT_EQ(r.interpreter->FindSubroutine("REPOS"), 1);
  ASSERT_TRUE(r.interpreter->RunSubroutine(1, "REPOS"));
  ASSERT_EQ(r.Next(), 11);
  EXPECT_EQ(r.block.reverse.program, 1);
  EXPECT_EQ(r.block.reverse.block, r.LabelBlock(1, "RBACK"));
  ASSERT_TRUE(r.interpreter->Reverse(r.block.reverse));
  EXPECT_EQ(r.Rest(), (std::vector<int>{13, 20, 21}));
}

TEST(InterpreterReverse, WithoutHomeNothingChanges) {
  Reversal r({"N1 REV .BACK\nN2 G01 X20 F100\nN3 G01 X30\nN4 RET\n.BACK\nN10 G01 Z5 RTS\n"});
  ASSERT_EQ(r.Next(), 2);
  EXPECT_FALSE(r.interpreter->Reverse(r.block.reverse));
  EXPECT_EQ(r.Next(), 3);
}

}  // namespace
}  // namespace vmt::control::nc
