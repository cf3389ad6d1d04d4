#pragma once
// Arithmetic and logical expressions of both dialects, into the program's expression code
// (postfix, see ExprOp). MTC200 groups with ( ) and calls G(2), M(5), TLD(1,2); ISG groups and
// calls with [ ] (its ( ) are comments). Precedence, lowest first: OR XOR, AND, comparisons,
// + -, * / MOD, ^ (right-associative), unary - + NOT. Operators on constants are folded, except
// / and MOD by 0: that stays a fault at run time, at its place.
//
// One parser serves a whole program: it keeps a cache of the constants and symbols it has
// seen, which the million-block decode benchmark looks up a few million times.

#include <array>
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
  /// A comma-separated list up to the closing bracket (already past the opening one) as a kArgs
  /// expression of `name`; omitted arguments (SETTING (X, Z, , 18, ...)) are kOmitted. `list`
  /// is kNoExpr for "()". False after reporting an error.
  bool Arguments(LineScanner& s, SourcePos open_pos, uint32_t name, ExprId& list);
  /// The call name(args) of an argument list just read by Arguments (kNoExpr: no arguments):
  /// a data location written to, TLD(1,3,,1,12,) = ...
  ExprId CallOf(uint32_t name, ExprId list, uint32_t offset);

  void Error(SourcePos pos, std::string message) { errors_.push_back({pos, std::move(message)}); }
  char open() const { return open_; }
  char close() const { return close_; }
  Program& program() { return p_; }
  std::vector<Diagnostic>& errors() { return errors_; }

 private:
  // What a parsed sub-expression left at the end of the code.
  struct Sub {
    uint32_t start = 0;                       ///< its first unit
    uint32_t peak = 0;                        ///< stack depth it needs above its base
    int32_t first_site = -1, last_site = -1;  ///< its failure sites in tree order (sites_)
    bool constant = false;
    double value = 0;  ///< if constant
  };
  // A place that can fail at run time: the rank unit in the code, and the next site.
  struct Site {
    uint32_t rank_unit;
    int32_t next;
  };

  bool Binary(LineScanner& s, int min_level, Sub& out);
  bool Unary(LineScanner& s, Sub& out);
  bool Primary(LineScanner& s, Sub& out);
  // The arguments of a call or an instruction, then its kCall | kArgs units.
  bool ArgumentsOf(LineScanner& s, SourcePos open_pos, ExprOp op, uint32_t name,
                   Function function, uint32_t offset, Sub& out, uint32_t& count);
  void Constant(double value, Sub& out);
  void Combine(ExprOp op, uint32_t offset, Sub& lhs, const Sub& rhs);
  void EmitImmediate(ExprOp op, uint32_t immediate);
  int32_t AddSite();
  void Finish(const Sub& top);  ///< ranks the failure sites, ends the code
  uint32_t Intern(std::string_view name) { return p_.symbols.Intern(name); }

  Program& p_;
  std::vector<Diagnostic>& errors_;
  char open_, close_;
  int depth_ = 0;
  uint32_t last_args_ = 0;   ///< the kArgs | kCall unit of the last argument list
  std::vector<Site> sites_;  ///< of the expression being parsed
  struct CachedNumber {
    uint64_t bits = 0;
    uint32_t index = 0;  ///< into Program::numbers, + 1; 0 = empty
  };
  std::array<CachedNumber, 256> numbers_{};  ///< recent constants: a program repeats its own
};

}  // namespace vmt::control::nc
