// The expression parser of both dialects: precedence and associativity as postfix code, constant
// folding (never of a division by zero), calls and argument lists, and its caches.

#include "control/nc/expression_parser.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "parse_support.hpp"

namespace vmt::control::nc {
namespace {

TEST(ExpressionTest, PrecedenceAndOperatorsAsPostfixCode) {
  const ParseResult r =
      Mtc("N1 @1=@2 OR @3 AND @4 == @5 + @6 * @7 ^ -@8\n"
          "N2 @1=@2 XOR NOT @3 <> @4 != @5 < @6 <= @7 > @8 >= @9\n"
          "N3 @1=@2 - @3 - @4 / @5 MOD @6 ** @7 ^ @8\n"
          "N4 @1=+-+@2 or @3 and @4 xor @5 mod @6\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Program& p = r.program;
  auto text = [&](size_t b) { return p.ExprText(p.Statements(p.blocks[b])[0].value); };
  EXPECT_EQ(text(0), "(@2 OR (@3 AND (@4 == (@5 + (@6 * (@7 ^ -@8))))))");
  EXPECT_EQ(text(1), "(@2 XOR ((((((NOT @3 <> @4) <> @5) < @6) <= @7) > @8) >= @9))");
  EXPECT_EQ(text(2), "((@2 - @3) - ((@4 / @5) MOD (@6 ^ (@7 ^ @8))))");
  EXPECT_EQ(text(3), "((-@2 OR (@3 AND @4)) XOR (@5 MOD @6))");
}

TEST(ExpressionTest, ConstantsAreFoldedExceptDivisionByZero) {
  const ParseResult r =
      Isg("N1 P1 = 1 + 2 * 3 - [4 - 1] ^ 2\n"
          "N2 P1 = [P2 + 2 * 3] * [1 / 4] + -[2] - NOT 0\n"
          "N3 P1 = 5 / [2 - 2] + 7 MOD 0 + 7 MOD 4\n"
          "N4 P1 = 2 ^ 0.5 + 0.1 + [1 < 2] + [1 AND 0] + [0 OR 3] + [1 XOR 1] + [2 == 2]\n"
          "N5 P1 = -0 + 8388607 + 8388608 - -8388608 - -8388609\n"
          "N6 X[-3 * 2] Y-[0] Z[0.5 * 3]\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Program& p = r.program;
  auto value = [&](size_t b) { return p.Statements(p.blocks[b])[0].value; };
  EXPECT_EQ(p.ExprText(value(0)), "-2");
  EXPECT_EQ(p.ExprText(value(1)), "((((P2 + 6) * 0.25) + -2) - 1)");
  // A division by zero stays in the code: it is a fault at run time, at its place.
  EXPECT_EQ(p.ExprText(value(2)), "(((5 / 0) + (7 MOD 0)) + 3)");
  const double folded = std::pow(2.0, 0.5) + 0.1 + 1 + 0 + 1 + 0 + 1;
  EXPECT_EQ(Eval(p, value(3)), folded);  // bit for bit what the interpreter computes
  EXPECT_EQ(Eval(p, value(4)), -0.0 + 8388607 + 8388608 + 8388608 + 8388609);
  EXPECT_EQ(p.ExprText(value(4)), "33554432");
  const auto words = p.Words(p.blocks[5]);
  EXPECT_EQ(p.ExprText(words[0].value), "-6");
  EXPECT_EQ(p.ExprText(words[1].value), "-0");
  EXPECT_TRUE(std::signbit(Eval(p, words[1].value)));
  EXPECT_EQ(Eval(p, words[2].value), 1.5);
}

TEST(ExpressionTest, CallsAndArgumentLists) {
  const ParseResult r =
      Mtc("N1 @1=SIN(30) + TLD(1, , @2 + 1, ) - G( 2 ) * FOO()\n"
          "N2 SETTING (X, Z, , 18)\n"
          "N3 SETTING (,)\n"
          "N4 TLD() = 5\n"
          "N5 MTD(1,2) = MTD(1,2) * 2\n");
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Program& p = r.program;
  EXPECT_EQ(p.ExprText(p.Statements(p.blocks[0])[0].value),
            "((SIN(30) + TLD(1, , (@2 + 1), )) - (G(2) * FOO()))");
  EXPECT_EQ(p.ExprText(p.Statements(p.blocks[1])[0].value), "SETTING(X, Z, , 18)");
  EXPECT_EQ(p.ExprText(p.Statements(p.blocks[2])[0].value), "SETTING(, )");
  const Statement& empty = p.Statements(p.blocks[3])[0];
  EXPECT_EQ(empty.kind, Statement::Kind::kAssign);
  EXPECT_EQ(p.ExprText(empty.data), "TLD()");
  EXPECT_EQ(p.ExprText(empty.value), "5");
  const Statement& data = p.Statements(p.blocks[4])[0];
  EXPECT_EQ(p.ExprText(data.data), "MTD(1, 2)");
  EXPECT_EQ(p.ExprText(data.value), "(MTD(1, 2) * 2)");
}

TEST(ExpressionTest, ManyConstantsAndNamesStayDistinct) {
  // The parser's caches of constants and names must never mix two of them up.
  std::string text = "%many\n";
  for (int i = 0; i < 3000; ++i)
    text += "P" + std::to_string(i % 700 + 1) + " = " + std::to_string(i) + ".25 + V.L.A" +
            std::to_string(i % 300) + " * " + std::to_string(i * 7 % 1000) + ".5\n";
  const ParseResult r = Isg(text);
  ASSERT_TRUE(r.ok()) << Errors(r);
  const Program& p = r.program;
  for (int i = 0; i < 3000; ++i) {
    const Statement& st = p.Statements(p.blocks[i + 1])[0];
    ASSERT_EQ(p.symbols.Name(st.name), "P" + std::to_string(i % 700 + 1));
    ASSERT_EQ(p.ExprText(st.value), "(" + std::to_string(i) + ".25 + (V.L.A" +
                                        std::to_string(i % 300) + " * " +
                                        std::to_string(i * 7 % 1000) + ".5))");
  }
}

}  // namespace
}  // namespace vmt::control::nc
