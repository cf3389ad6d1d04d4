#pragma once
// Arithmetic and logical expressions of both dialects, into the program's expression arena.
// MTC200 groups with ( ) and calls G(2), M(5), TLD(1,2); ISG groups and calls with [ ]
// (its ( ) are comments). Precedence, lowest first: OR XOR, AND, comparisons, + -, * / MOD,
// ^ (right-associative), unary - + NOT.

#include <vector>

#include "control/nc/line_scanner.hpp"
#include "control/nc/program.hpp"

namespace vmt::control::nc {

class ExpressionParser {
 public:
  ExpressionParser(Program& program, std::vector<Diagnostic>& errors)
      : p_(program),
        errors_(errors),
        open_(program.dialect == Dialect::kIsg ? '[' : '('),
        close_(program.dialect == Dialect::kIsg ? ']' : ')') {}

  /// An expression, or kNoExpr after reporting an error at the scanner's position.
  ExprId Parse(LineScanner& s);
  /// A comma-separated list up to the closing bracket (already past the opening one); omitted
  /// arguments (SETTING (X, Z, , 18, ...)) become a nameless kVariable. `first` is the first of
  /// the chain (kNoExpr for "()"). False after reporting an error.
  bool Arguments(LineScanner& s, SourcePos open_pos, ExprId& first);

  ExprId Add(const Expr& e) {
    p_.exprs.push_back(e);
    return static_cast<ExprId>(p_.exprs.size() - 1);
  }
  void Error(SourcePos pos, std::string message) { errors_.push_back({pos, std::move(message)}); }
  char open() const { return open_; }
  char close() const { return close_; }

 private:
  ExprId Binary(LineScanner& s, int level);
  ExprId Unary(LineScanner& s);
  ExprId Primary(LineScanner& s);

  Program& p_;
  std::vector<Diagnostic>& errors_;
  char open_, close_;
  int depth_ = 0;
};

}  // namespace vmt::control::nc
