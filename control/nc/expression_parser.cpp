#include "control/nc/expression_parser.hpp"

namespace vmt::control::nc {
namespace {

constexpr int kMaxDepth = 64;  // nesting beyond this is an error, never a stack overflow
using Op = Expr::Op;

// Binary operator at the scanner, for the precedence level; consumes it when found.
bool MatchOperator(LineScanner& s, int level, Op& op) {
  s.SkipSpace();
  const char c = s.Peek(), d = s.Peek(1);
  auto word = [&](const char* w, Op o) {
    size_t n = 0;
    while (w[n]) {
      if (std::toupper(static_cast<unsigned char>(s.Peek(n))) != w[n]) return false;
      ++n;
    }
    if (LineScanner::IsLetter(s.Peek(n)) || LineScanner::IsDigit(s.Peek(n))) return false;
    s.Advance(n);
    op = o;
    return true;
  };
  switch (level) {
    case 0:
      return word("OR", Op::kOr) || word("XOR", Op::kXor);
    case 1:
      return word("AND", Op::kAnd);
    case 2:
      if (c == '=' && d == '=') return s.Advance(2), op = Op::kEq, true;
      if (c == '!' && d == '=') return s.Advance(2), op = Op::kNe, true;
      if (c == '<' && d == '>') return s.Advance(2), op = Op::kNe, true;
      if (c == '<' && d == '=') return s.Advance(2), op = Op::kLe, true;
      if (c == '>' && d == '=') return s.Advance(2), op = Op::kGe, true;
      if (c == '<') return s.Advance(), op = Op::kLt, true;
      if (c == '>') return s.Advance(), op = Op::kGt, true;
      return false;
    case 3:
      if (c == '+') return s.Advance(), op = Op::kAdd, true;
      if (c == '-') return s.Advance(), op = Op::kSub, true;
      return false;
    case 4:
      if (c == '*' && d != '*') return s.Advance(), op = Op::kMul, true;
      if (c == '/') return s.Advance(), op = Op::kDiv, true;
      return word("MOD", Op::kMod);
    default:
      return false;
  }
}

}  // namespace

ExprId ExpressionParser::Parse(LineScanner& s) {
  depth_ = 0;
  return Binary(s, 0);
}

ExprId ExpressionParser::Binary(LineScanner& s, int level) {
  if (level > 4) return Unary(s);
  ExprId lhs = Binary(s, level + 1);
  if (lhs == kNoExpr) return kNoExpr;
  Op op;
  for (;;) {
    const SourcePos pos = s.Pos();
    if (!MatchOperator(s, level, op)) return lhs;
    const ExprId rhs = Binary(s, level + 1);
    if (rhs == kNoExpr) return kNoExpr;
    Expr e;
    e.op = op;
    e.lhs = lhs;
    e.rhs = rhs;
    e.offset = pos.offset;
    lhs = Add(e);
  }
}

ExprId ExpressionParser::Unary(LineScanner& s) {
  s.SkipSpace();
  const SourcePos pos = s.Pos();
  if (++depth_ > kMaxDepth) {
    Error(pos, "expression nested too deeply");
    return kNoExpr;
  }
  Expr e;
  e.offset = pos.offset;
  if (s.Accept('-')) {
    e.op = Op::kNeg;
  } else if (s.Accept('+')) {
    --depth_;
    return Unary(s);
  } else if ((s.Peek() == 'N' || s.Peek() == 'n') && (s.Peek(1) == 'O' || s.Peek(1) == 'o') &&
             (s.Peek(2) == 'T' || s.Peek(2) == 't') && !LineScanner::IsLetter(s.Peek(3))) {
    s.Advance(3);
    e.op = Op::kNot;
  } else {
    ExprId base = Primary(s);
    // Power binds tighter than unary minus, and to the right.
    s.SkipSpace();
    if (base != kNoExpr && (s.Peek() == '^' || (s.Peek() == '*' && s.Peek(1) == '*'))) {
      const SourcePos op_pos = s.Pos();
      s.Advance(s.Peek() == '^' ? 1 : 2);
      const ExprId exponent = Unary(s);
      if (exponent == kNoExpr) return kNoExpr;
      Expr p;
      p.op = Op::kPow;
      p.lhs = base;
      p.rhs = exponent;
      p.offset = op_pos.offset;
      base = Add(p);
    }
    --depth_;
    return base;
  }
  e.lhs = Unary(s);
  --depth_;
  if (e.lhs == kNoExpr) return kNoExpr;
  return Add(e);
}

ExprId ExpressionParser::Primary(LineScanner& s) {
  s.SkipSpace();
  Expr e;
  const SourcePos pos = s.Pos();
  e.offset = pos.offset;
  double number = 0;
  if (s.Number(number)) {
    e.number = number;
    return Add(e);
  }
  if (s.Accept(open_)) {
    const ExprId inner = Binary(s, 0);
    if (inner == kNoExpr) return kNoExpr;
    s.SkipSpace();
    if (!s.Accept(close_)) {
      Error(s.Pos(), std::string("expected '") + close_ + "'");
      return kNoExpr;
    }
    return inner;
  }
  if (p_.dialect == Dialect::kMtc200 && s.Accept('@')) {
    long n = 0;
    if (!s.Integer(n)) {
      Error(s.Pos(), "expected a variable number after '@'");
      return kNoExpr;
    }
    e.op = Op::kVariable;
    e.name = p_.symbols.Intern("@" + std::to_string(n));
    return Add(e);
  }
  if (LineScanner::IsLetter(s.Peek())) {
    std::string name = p_.dialect == Dialect::kIsg ? s.Name() : s.Letters();
    // ISG parameters P1, P25: a P followed by digits is a variable, not a call.
    if (p_.dialect == Dialect::kIsg && name.size() > 1 && name[0] == 'P' &&
        name.find_first_not_of("0123456789", 1) == std::string::npos) {
      e.op = Op::kVariable;
      e.name = p_.symbols.Intern(name);
      return Add(e);
    }
    if (p_.dialect == Dialect::kIsg && name.rfind("V.", 0) == 0) {
      e.op = Op::kVariable;
      e.name = p_.symbols.Intern(name);
      return Add(e);
    }
    s.SkipSpace();
    if (s.Accept(open_)) {
      e.op = Op::kCall;
      e.name = p_.symbols.Intern(name);
      if (!Arguments(s, pos, e.lhs)) return kNoExpr;
      return Add(e);
    }
    // A bare name stands for itself (axis names as measuring-instruction arguments).
    e.op = Op::kVariable;
    e.name = p_.symbols.Intern(name);
    return Add(e);
  }
  if (s.AtEnd())
    Error(s.Pos(), "expected a value, found the end of the block");
  else
    Error(s.Pos(), std::string("expected a value, found '") + s.Peek() + "'");
  return kNoExpr;
}

bool ExpressionParser::Arguments(LineScanner& s, SourcePos open_pos, ExprId& first) {
  first = kNoExpr;
  ExprId last = kNoExpr;
  s.SkipSpace();
  if (s.Accept(close_)) return true;
  for (;;) {
    s.SkipSpace();
    ExprId arg = kNoExpr;
    if (s.Peek() != ',' && s.Peek() != close_) {
      arg = Binary(s, 0);
      if (arg == kNoExpr) return false;
    } else {
      Expr empty;  // an omitted argument: a number flagged by name 0 and op kVariable
      empty.op = Op::kVariable;
      empty.offset = s.Pos().offset;
      arg = Add(empty);
    }
    if (first == kNoExpr)
      first = arg;
    else
      p_.exprs[last].next = arg;
    last = arg;
    s.SkipSpace();
    if (s.Accept(',')) continue;
    if (s.Accept(close_)) return true;
    Error(s.Pos(), std::string("expected ',' or '") + close_ +
                       "' in the argument list opened at column " +
                       std::to_string(open_pos.column));
    return false;
  }
}

}  // namespace vmt::control::nc
