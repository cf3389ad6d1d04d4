#include "control/nc/expression_parser.hpp"

#include <algorithm>
#include <bit>
#include <charconv>

namespace vmt::control::nc {
namespace {

constexpr int kMaxDepth = 64;  // nesting beyond this is an error, never a stack overflow
using Op = ExprOp;

// `w` (upper case) at the scanner as a whole word: OR, XOR, AND, MOD.
bool WordAt(const LineScanner& s, const char* w) {
  size_t n = 0;
  for (; w[n]; ++n)
    if (LineScanner::ToUpper(s.Peek(n)) != w[n]) return false;
  return !LineScanner::IsLetter(s.Peek(n)) && !LineScanner::IsDigit(s.Peek(n));
}

// The binary operator at the scanner (after spaces): its precedence level 0 (OR XOR) .. 4
// (* / MOD), or -1 if none. Looked at once per operand instead of once per level.
int OperatorAt(const LineScanner& s, Op& op, size_t& length) {
  const char c = s.Peek(), d = s.Peek(1);
  length = 1;
  switch (c) {
    case '=':
      if (d != '=') return -1;
      return length = 2, op = Op::kEq, 2;
    case '!':
      if (d != '=') return -1;
      return length = 2, op = Op::kNe, 2;
    case '<':
      if (d == '>') return length = 2, op = Op::kNe, 2;
      if (d == '=') return length = 2, op = Op::kLe, 2;
      return op = Op::kLt, 2;
    case '>':
      if (d == '=') return length = 2, op = Op::kGe, 2;
      return op = Op::kGt, 2;
    case '+':
      return op = Op::kAdd, 3;
    case '-':
      return op = Op::kSub, 3;
    case '*':
      if (d == '*') return -1;  // power, read by Unary
      return op = Op::kMul, 4;
    case '/':
      return op = Op::kDiv, 4;
    case 'O':
    case 'o':
      if (!WordAt(s, "OR")) return -1;
      return length = 2, op = Op::kOr, 0;
    case 'X':
    case 'x':
      if (!WordAt(s, "XOR")) return -1;
      return length = 3, op = Op::kXor, 0;
    case 'A':
    case 'a':
      if (!WordAt(s, "AND")) return -1;
      return length = 3, op = Op::kAnd, 1;
    case 'M':
    case 'm':
      if (!WordAt(s, "MOD")) return -1;
      return length = 3, op = Op::kMod, 4;
    default:
      return -1;
  }
}

bool IsParameter(const std::string& name) {
  return name.size() > 1 && name[0] == 'P' &&
         name.find_first_not_of("0123456789", 1) == std::string::npos;
}

}  // namespace

ExprId ExpressionParser::Parse(LineScanner& s) {
  depth_ = 0;
  sites_.clear();
  const auto start = static_cast<uint32_t>(p_.code.size());
  Sub top;
  if (!Binary(s, 0, top)) {
    p_.code.resize(start);  // the half-read expression is of no use
    return kNoExpr;
  }
  Finish(top);
  return static_cast<ExprId>(start);
}

bool ExpressionParser::Arguments(LineScanner& s, SourcePos open_pos, uint32_t name, ExprId& list) {
  depth_ = 0;
  sites_.clear();
  list = kNoExpr;
  const auto start = static_cast<uint32_t>(p_.code.size());
  Sub args;
  uint32_t count = 0;
  if (!ArgumentsOf(s, open_pos, Op::kArgs, name, Function::kNone, open_pos.offset, args, count)) {
    p_.code.resize(start);
    return false;
  }
  if (count == 0) {  // "()": no list, as before
    p_.code.resize(start);
    return true;
  }
  Finish(args);
  list = static_cast<ExprId>(start);
  return true;
}

ExprId ExpressionParser::CallOf(uint32_t name, ExprId list, uint32_t offset) {
  std::vector<uint32_t>& code = p_.code;
  if (list == kNoExpr) {
    const auto start = static_cast<ExprId>(code.size());
    EmitImmediate(Op::kCall, name);
    code.insert(code.end(),
                {CountUnit(0, FunctionOf(p_.symbols.Name(name))), offset, 0u, ExprUnit(Op::kEnd)});
    p_.max_stack = std::max(p_.max_stack, 1u);
    return start;
  }
  // The list was the last expression read: its kArgs becomes a kCall in place.
  uint32_t& unit = code[last_args_];
  unit = (unit & ~0xFFu) | static_cast<uint32_t>(Op::kCall);
  const uint32_t count_at = last_args_ + ((unit >> 8) == kWideImmediate ? 2 : 1);
  code[count_at] = CountUnit(CountOf(code[count_at]), FunctionOf(p_.symbols.Name(name)));
  code[count_at + 1] = offset;
  return list;
}

void ExpressionParser::EmitImmediate(Op op, uint32_t immediate) {
  if (immediate < kWideImmediate) {
    p_.code.push_back(ExprUnit(op, immediate));
  } else {
    p_.code.push_back(ExprUnit(op, kWideImmediate));
    p_.code.push_back(immediate);
  }
}

void ExpressionParser::Constant(double value, Sub& out) {
  out.start = static_cast<uint32_t>(p_.code.size());
  out.peak = 1;
  out.constant = true;
  out.value = value;
  out.first_site = out.last_site = -1;
  // Small integers (G codes, counts, most NC numbers) fit the unit; -0 does not.
  if (value >= -(1 << 23) && value < (1 << 23) && value == static_cast<int32_t>(value) &&
      !(value == 0 && std::signbit(value))) {
    p_.code.push_back(ExprUnit(Op::kInt, static_cast<uint32_t>(static_cast<int32_t>(value))));
    return;
  }
  const auto bits = std::bit_cast<uint64_t>(value);
  CachedNumber& cached = numbers_[(bits * 0x9E3779B97F4A7C15ull) >> 56];
  if (cached.index == 0 || cached.bits != bits) {
    p_.numbers.push_back(value);
    cached = {bits, static_cast<uint32_t>(p_.numbers.size())};
  }
  EmitImmediate(Op::kNumber, cached.index - 1);
}

int32_t ExpressionParser::AddSite() {
  sites_.push_back({static_cast<uint32_t>(p_.code.size() - 1), -1});
  return static_cast<int32_t>(sites_.size() - 1);
}

namespace {

// Appends the failure sites b_first..b_last to a_first..a_last.
template <typename Sites>
void Append(Sites& sites, int32_t& a_first, int32_t& a_last, int32_t b_first, int32_t b_last) {
  if (b_first < 0) return;
  if (a_first < 0)
    a_first = b_first;
  else
    sites[a_last].next = b_first;
  a_last = b_last;
}

}  // namespace

void ExpressionParser::Combine(Op op, uint32_t offset, Sub& lhs, const Sub& rhs) {
  std::vector<uint32_t>& code = p_.code;
  if (lhs.constant && rhs.constant && !((op == Op::kDiv || op == Op::kMod) && rhs.value == 0)) {
    const double value = ApplyBinary(op, lhs.value, rhs.value);
    code.resize(lhs.start);
    Constant(value, lhs);
    return;
  }
  lhs.constant = false;
  lhs.peak = std::max(lhs.peak, rhs.peak + 1);
  switch (op) {
    case Op::kAnd:
    case Op::kOr:
      code[rhs.start - 1] = static_cast<uint32_t>(code.size() - rhs.start + 1);
      code.push_back(ExprUnit(op));
      Append(sites_, lhs.first_site, lhs.last_site, rhs.first_site, rhs.last_site);
      return;
    case Op::kDiv:
    case Op::kMod: {
      // Tree order: the divisor, the division itself, then the dividend.
      code.insert(code.end(), {ExprUnit(op), offset, 0u});
      int32_t first = rhs.first_site, last = rhs.last_site;
      const int32_t self = AddSite();
      Append(sites_, first, last, self, self);
      Append(sites_, first, last, lhs.first_site, lhs.last_site);
      lhs.first_site = first;
      lhs.last_site = last;
      return;
    }
    case Op::kPow: {
      code.push_back(ExprUnit(op));
      int32_t first = rhs.first_site, last = rhs.last_site;
      Append(sites_, first, last, lhs.first_site, lhs.last_site);
      lhs.first_site = first;
      lhs.last_site = last;
      return;
    }
    default:
      code.push_back(ExprUnit(op));
      Append(sites_, lhs.first_site, lhs.last_site, rhs.first_site, rhs.last_site);
      return;
  }
}

void ExpressionParser::Finish(const Sub& top) {
  uint32_t rank = 0;
  for (int32_t i = top.first_site; i >= 0; i = sites_[i].next)
    p_.code[sites_[i].rank_unit] = rank++;
  p_.code.push_back(ExprUnit(Op::kEnd));
  p_.max_stack = std::max(p_.max_stack, top.peak);
}

bool ExpressionParser::Binary(LineScanner& s, int min_level, Sub& out) {
  if (!Unary(s, out)) return false;
  for (;;) {
    s.SkipSpace();
    const uint32_t offset = s.Pos().offset;
    Op op = Op::kEnd;
    size_t length;
    const int level = OperatorAt(s, op, length);
    if (level < min_level) return true;
    s.Advance(length);
    if (op == Op::kAnd || op == Op::kOr) {
      p_.code.push_back(ExprUnit(op == Op::kAnd ? Op::kAndSkip : Op::kOrSkip));
      p_.code.push_back(0);  // units to skip: known after the rhs
    }
    Sub rhs;
    if (!Binary(s, level + 1, rhs)) return false;
    Combine(op, offset, out, rhs);
  }
}

bool ExpressionParser::Unary(LineScanner& s, Sub& out) {
  s.SkipSpace();
  const SourcePos pos = s.Pos();
  if (++depth_ > kMaxDepth) {
    Error(pos, "expression nested too deeply");
    return false;
  }
  // A unary plus changes nothing and is no nesting: skipped in a loop, not by recursion.
  while (s.Accept('+')) s.SkipSpace();
  Op op = Op::kEnd;
  if (s.Accept('-')) {
    op = Op::kNeg;
  } else if (LineScanner::ToUpper(s.Peek()) == 'N' && LineScanner::ToUpper(s.Peek(1)) == 'O' &&
             LineScanner::ToUpper(s.Peek(2)) == 'T' && !LineScanner::IsLetter(s.Peek(3))) {
    s.Advance(3);
    op = Op::kNot;
  } else {
    if (!Primary(s, out)) return false;
    // Power binds tighter than unary minus, and to the right.
    s.SkipSpace();
    if (s.Peek() == '^' || (s.Peek() == '*' && s.Peek(1) == '*')) {
      s.Advance(s.Peek() == '^' ? 1 : 2);
      Sub exponent;
      if (!Unary(s, exponent)) return false;
      Combine(Op::kPow, 0, out, exponent);
    }
    --depth_;
    return true;
  }
  if (!Unary(s, out)) return false;
  --depth_;
  if (out.constant) {
    const double value = op == Op::kNeg ? -out.value : (out.value == 0 ? 1 : 0);
    p_.code.resize(out.start);
    Constant(value, out);
  } else {
    p_.code.push_back(ExprUnit(op));
  }
  return true;
}

bool ExpressionParser::Primary(LineScanner& s, Sub& out) {
  s.SkipSpace();
  const SourcePos pos = s.Pos();
  out = Sub{};
  out.start = static_cast<uint32_t>(p_.code.size());
  out.peak = 1;
  double number = 0;
  if (s.Number(number)) {
    Constant(number, out);
    return true;
  }
  if (s.Accept(open_)) {
    if (!Binary(s, 0, out)) return false;
    s.SkipSpace();
    if (!s.Accept(close_)) {
      Error(s.Pos(), std::string("expected '") + close_ + "'");
      return false;
    }
    return true;
  }
  if (p_.dialect == Dialect::kMtc200 && s.Accept('@')) {
    long n = 0;
    if (!s.Integer(n)) {
      Error(s.Pos(), "expected a variable number after '@'");
      return false;
    }
    EmitImmediate(Op::kVariable, Intern("@" + std::to_string(n)));
    return true;
  }
  if (LineScanner::IsLetter(s.Peek())) {
    const std::string name = p_.dialect == Dialect::kIsg ? s.Name() : s.Letters();
    // ISG parameters P1, P25 and V. variables are variables, not calls.
    if (p_.dialect == Dialect::kIsg && (IsParameter(name) || name.starts_with("V."))) {
      EmitImmediate(Op::kVariable, Intern(name));
      return true;
    }
    s.SkipSpace();
    if (s.Accept(open_)) {
      uint32_t count;
      return ArgumentsOf(s, pos, Op::kCall, Intern(name), FunctionOf(name), pos.offset, out,
                         count);
    }
    // A bare name stands for itself (axis names as measuring-instruction arguments).
    EmitImmediate(Op::kVariable, Intern(name));
    return true;
  }
  if (s.AtEnd())
    Error(s.Pos(), "expected a value, found the end of the block");
  else
    Error(s.Pos(), std::string("expected a value, found '") + s.Peek() + "'");
  return false;
}

bool ExpressionParser::ArgumentsOf(LineScanner& s, SourcePos open_pos, Op op, uint32_t name,
                                   Function function, uint32_t offset, Sub& out,
                                   uint32_t& count) {
  out = Sub{};
  out.start = static_cast<uint32_t>(p_.code.size());
  out.peak = 1;
  count = 0;
  s.SkipSpace();
  if (!s.Accept(close_)) {
    for (;;) {
      s.SkipSpace();
      Sub arg;
      if (s.Peek() != ',' && s.Peek() != close_) {
        if (!Binary(s, 0, arg)) return false;
      } else {
        p_.code.push_back(ExprUnit(Op::kOmitted));
        arg.peak = 1;
      }
      out.peak = std::max(out.peak, count + arg.peak);
      Append(sites_, out.first_site, out.last_site, arg.first_site, arg.last_site);
      if (++count == kMaxArguments) {
        Error(s.Pos(), "more than " + std::to_string(kMaxArguments - 1) + " arguments");
        return false;
      }
      s.SkipSpace();
      if (s.Accept(',')) continue;
      if (s.Accept(close_)) break;
      Error(s.Pos(), std::string("expected ',' or '") + close_ +
                         "' in the argument list opened at column " +
                         std::to_string(open_pos.column));
      return false;
    }
  }
  last_args_ = static_cast<uint32_t>(p_.code.size());
  EmitImmediate(op, name);
  p_.code.insert(p_.code.end(), {CountUnit(count, function), offset, 0u});
  const int32_t self = AddSite();
  Append(sites_, out.first_site, out.last_site, self, self);
  return true;
}

std::string Program::ExprText(ExprId id) const {
  std::vector<std::string> stack;
  auto pop = [&] {
    std::string top = std::move(stack.back());
    stack.pop_back();
    return top;
  };
  auto binary = [&](const char* op) {
    std::string r = pop(), l = pop();
    stack.push_back("(" + l + " " + op + " " + r + ")");
  };
  for (size_t pc = static_cast<size_t>(id);;) {
    const uint32_t unit = code[pc++];
    uint32_t immediate = unit >> 8;
    if (immediate == kWideImmediate && (OpOf(unit) == Op::kNumber || OpOf(unit) == Op::kVariable ||
                                        OpOf(unit) == Op::kCall || OpOf(unit) == Op::kArgs))
      immediate = code[pc++];
    switch (OpOf(unit)) {
      case Op::kEnd:
        return stack.empty() ? std::string() : stack.back();
      case Op::kInt:
        stack.push_back(std::to_string(static_cast<int32_t>(unit) >> 8));
        break;
      case Op::kNumber: {
        char text[32];
        const auto end = std::to_chars(text, text + sizeof text, numbers[immediate]).ptr;
        stack.emplace_back(text, end);
        break;
      }
      case Op::kVariable:
        stack.push_back(symbols.Name(immediate));
        break;
      case Op::kOmitted:
        stack.emplace_back();
        break;
      case Op::kNeg:
        stack.back() = "-" + stack.back();
        break;
      case Op::kNot:
        stack.back() = "NOT " + stack.back();
        break;
      case Op::kAdd:
        binary("+");
        break;
      case Op::kSub:
        binary("-");
        break;
      case Op::kMul:
        binary("*");
        break;
      case Op::kPow:
        binary("^");
        break;
      case Op::kEq:
        binary("==");
        break;
      case Op::kNe:
        binary("<>");
        break;
      case Op::kLt:
        binary("<");
        break;
      case Op::kLe:
        binary("<=");
        break;
      case Op::kGt:
        binary(">");
        break;
      case Op::kGe:
        binary(">=");
        break;
      case Op::kXor:
        binary("XOR");
        break;
      case Op::kDiv:
        binary("/");
        pc += 2;
        break;
      case Op::kMod:
        binary("MOD");
        pc += 2;
        break;
      case Op::kAndSkip:
      case Op::kOrSkip:
        ++pc;  // both operands are shown
        break;
      case Op::kAnd:
        binary("AND");
        break;
      case Op::kOr:
        binary("OR");
        break;
      case Op::kCall:
      case Op::kArgs: {
        const uint32_t count = CountOf(code[pc]);
        pc += 3;
        std::string args;
        for (size_t i = stack.size() - count; i < stack.size(); ++i)
          args += (i + count == stack.size() ? "" : ", ") + stack[i];
        stack.resize(stack.size() - count);
        stack.push_back(symbols.Name(immediate) + "(" + args + ")");
        break;
      }
    }
  }
}

}  // namespace vmt::control::nc
