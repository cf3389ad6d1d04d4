#pragma once
// What the NC parser tests share: parsing a text in either dialect, the errors as the user sees
// them, and the value of a constant expression read straight from the code.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "control/nc/parser.hpp"

namespace vmt::control::nc {

inline ParseResult Mtc(const std::string& text) {
  return ParseProgram(text, "t.mtc", Dialect::kMtc200);
}
inline ParseResult Isg(const std::string& text) {
  return ParseProgram(text, "t.isg", Dialect::kIsg);
}

inline std::string Errors(const ParseResult& r) {
  std::string all;
  for (const Diagnostic& d : r.errors) all += Format(d, r.program.files) + "\n";
  return all;
}

// Evaluates a constant expression (numbers and operators only) for checking the parse.
inline double Eval(const Program& p, ExprId id) {
  std::vector<double> stack;
  for (size_t pc = static_cast<size_t>(id);;) {
    const uint32_t unit = p.code.at(pc++);
    const ExprOp op = OpOf(unit);
    if (op == ExprOp::kEnd) return stack.at(0);
    if (op == ExprOp::kInt) {
      stack.push_back(static_cast<int32_t>(unit) >> 8);
    } else if (op == ExprOp::kNumber) {
      stack.push_back(p.numbers.at(unit >> 8));
    } else if (op == ExprOp::kNeg) {
      stack.back() = -stack.back();
    } else if (op >= ExprOp::kAdd && op <= ExprOp::kMod) {
      const double r = stack.back();
      stack.pop_back();
      stack.back() = ApplyBinary(op, stack.back(), r);
      if (op == ExprOp::kDiv || op == ExprOp::kMod) pc += 2;
    } else {
      ADD_FAILURE() << "not constant: " << p.ExprText(id);
      return 0;
    }
  }
}

}  // namespace vmt::control::nc
