// What both dialect front ends read the same way: the block start and an address' value.

#include "control/nc/front_end.hpp"

namespace vmt::control::nc {

void ReadBlockStart(LineScanner& s, Block& block) {
  if (s.Accept('/')) {
    block.skippable = true;
    s.SkipSpace();
  }
  if ((s.Peek() == 'N' || s.Peek() == 'n') && LineScanner::IsDigit(s.Peek(1))) {
    s.Advance();
    long n = 0;
    s.Integer(n);
    block.number = static_cast<int32_t>(n);
    s.SkipSpace();
  }
}

// True if an operator follows: "X-3*2" is an expression, "X-3 Z5" two numbers.
bool MoreExpression(LineScanner s) {
  s.SkipSpace();
  const char c = s.Peek();
  return c == '+' || c == '-' || c == '*' || c == '/' || c == '^';
}

bool ParseWordValue(LineScanner& s, ExpressionParser& expr, const std::string& address,
                    SourcePos address_pos, Word& word) {
  s.SkipSpace();
  if (s.Peek() == '=' && s.Peek(1) != '=') {
    s.Advance();
    return (word.value = expr.Parse(s)) != kNoExpr;
  }
  if (s.Number(word.number)) return true;
  const char c = s.Peek();
  if (c == '-' || c == '+' || c == '@' || c == expr.open()) {
    // A signed number stays a number; anything else is computed.
    if ((c == '-' || c == '+') && (LineScanner::IsDigit(s.Peek(1)) || s.Peek(1) == '.')) {
      LineScanner probe = s;
      probe.Advance();
      double v = 0;
      probe.SkipSpace();
      if (probe.Number(v) && !MoreExpression(probe)) {
        s = probe;
        word.number = c == '-' ? -v : v;
        return true;
      }
    }
    return (word.value = expr.Parse(s)) != kNoExpr;
  }
  expr.Error(address_pos, "address " + address + " needs a value");
  return false;
}

}  // namespace vmt::control::nc
