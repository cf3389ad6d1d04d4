// The MTC200 dialect (Bosch Rexroth): N0001 block numbers, .LABEL labels, ';' comments, @100
// variables, branches on the result of the last computation (BRA/BEQ/BNE/BGT/BLT/BGE/BLE),
// event branches BES/BEC, JSR/RTS/RET, SE/RE events, turret commands MTP/MMP/MRF/MHP/MFP/MOP,
// MRY, data access TLD/OTD/MTD(...), fast-measurement instructions, and address words.

#include <array>
#include <string>

#include "control/nc/front_end.hpp"

namespace vmt::control::nc {
namespace {

constexpr std::array kBranches = {"BRA", "BEQ", "BNE", "BGT", "BLT", "BGE", "BLE"};
constexpr std::array kEventBranches = {"BES", "BEC"};
constexpr std::array kPlainInstructions = {"MTP", "MMP", "MRF", "MHP", "MFP", "MOP", "MRY"};
constexpr std::array kEventInstructions = {"SE", "RE"};
constexpr std::array kCallInstructions = {"TLD",     "OTD",  "MTD",     "SETTING", "SAVE",
                                          "MOVE",    "PROBE", "COMPARE", "CORRECTION",
                                          "RESTORE"};
// Address letters and multi-letter addresses of the MTC200 block.
constexpr std::array kAddresses = {"A", "B", "C", "D", "E", "F", "G", "H", "I", "J", "K",
                                   "M", "P", "Q", "R", "S", "T", "U", "V", "W", "X", "Y",
                                   "Z", "RX", "RY", "RZ"};

template <size_t N>
bool OneOf(const std::string& word, const std::array<const char*, N>& list) {
  for (const char* w : list)
    if (word == w) return true;
  return false;
}

// ".LABEL" at the scanner; returns the interned label or 0 after an error.
uint32_t Label(LineScanner& s, ExpressionParser& expr, Program& p, const std::string& after) {
  s.SkipSpace();
  const SourcePos pos = s.Pos();
  if (!s.Accept('.') || !LineScanner::IsLetter(s.Peek())) {
    expr.Error(pos, "expected a label (.NAME) after " + after);
    return 0;
  }
  return p.symbols.Intern(s.Name());
}

}  // namespace

bool ParseMtc200Line(std::string_view line, SourcePos start, Program& p,
                     std::vector<Diagnostic>& errors, Block& block) {
  LineScanner s(line, start);
  ExpressionParser expr(p, errors);
  s.SkipSpace();
  if (s.AtEnd() || s.Peek() == ';') return false;
  block.pos = s.Pos();
  if (s.Accept('/')) {
    block.skippable = true;
    s.SkipSpace();
  }
  if ((s.Peek() == 'N' || s.Peek() == 'n') && LineScanner::IsDigit(s.Peek(1))) {
    s.Advance();
    long n;
    s.Integer(n);
    block.number = static_cast<int32_t>(n);
    s.SkipSpace();
  }
  if (s.Peek() == '.') {
    s.Advance();
    if (!LineScanner::IsLetter(s.Peek())) {
      expr.Error(s.Pos(), "expected a label name after '.'");
      return true;
    }
    block.label = p.symbols.Intern(s.Name());
  }

  for (;;) {
    s.SkipSpace();
    if (s.AtEnd() || s.Peek() == ';') return true;
    const SourcePos pos = s.Pos();
    Statement st;
    st.pos = pos;

    if (s.Accept('@')) {  // @100=expression
      long n;
      if (!s.Integer(n)) return expr.Error(s.Pos(), "expected a variable number after '@'"), true;
      s.SkipSpace();
      if (!s.Accept('=')) return expr.Error(s.Pos(), "expected '=' after @" + std::to_string(n)), true;
      st.kind = Statement::Kind::kAssign;
      st.name = p.symbols.Intern("@" + std::to_string(n));
      if ((st.value = expr.Parse(s)) == kNoExpr) return true;
      block.statements.push_back(st);
      continue;
    }
    if (!LineScanner::IsLetter(s.Peek())) {
      expr.Error(pos, std::string("unexpected '") + s.Peek() + "'");
      return true;
    }
    const std::string word = s.Letters();
    if (OneOf(word, kBranches)) {
      st.kind = Statement::Kind::kBranch;
      st.name = p.symbols.Intern(word);
      if ((st.target = Label(s, expr, p, word)) == 0) return true;
    } else if (OneOf(word, kEventBranches)) {
      st.kind = Statement::Kind::kEventBranch;
      st.name = p.symbols.Intern(word);
      if ((st.target = Label(s, expr, p, word)) == 0) return true;
      if ((st.value = expr.Parse(s)) == kNoExpr) return true;
    } else if (word == "JSR") {
      st.kind = Statement::Kind::kCall;
      st.name = p.symbols.Intern(word);
      if ((st.target = Label(s, expr, p, word)) == 0) return true;
    } else if (word == "RTS" || word == "RET") {
      st.kind = Statement::Kind::kReturn;
      st.name = p.symbols.Intern(word);
    } else if (OneOf(word, kEventInstructions)) {
      st.kind = Statement::Kind::kInstruction;
      st.name = p.symbols.Intern(word);
      if ((st.value = expr.Parse(s)) == kNoExpr) return true;
    } else if (OneOf(word, kPlainInstructions) || OneOf(word, kCallInstructions)) {
      st.kind = Statement::Kind::kInstruction;
      st.name = p.symbols.Intern(word);
      s.SkipSpace();
      if (s.Peek() == '(') {
        const SourcePos open = s.Pos();
        s.Advance();
        if (!expr.Arguments(s, open, st.value)) return true;
      } else if (OneOf(word, kCallInstructions)) {
        expr.Error(s.Pos(), "expected '(' after " + word);
        return true;
      }
    } else if (OneOf(word, kAddresses)) {
      Word w;
      w.pos = pos;
      std::string address = word;
      // An index (S1=0, X1=0) is digits directly followed by '='; otherwise digits are the value.
      if (LineScanner::IsDigit(s.Peek())) {
        LineScanner probe = s;
        long index;
        probe.Integer(index);
        probe.SkipSpace();
        if (probe.Peek() == '=' && probe.Peek(1) != '=') {
          s.Integer(index);
          address += std::to_string(index);
        }
      }
      w.address = p.symbols.Intern(address);
      if ((w.value = ParseWordValue(s, expr, address, pos)) == kNoExpr) return true;
      block.words.push_back(w);
      continue;
    } else {
      expr.Error(pos, "unknown word '" + word + "'");
      return true;
    }
    block.statements.push_back(st);
  }
}

ExprId ParseWordValue(LineScanner& s, ExpressionParser& expr, const std::string& address,
                      SourcePos address_pos) {
  s.SkipSpace();
  if (s.Peek() == '=' && s.Peek(1) != '=') {
    s.Advance();
    return expr.Parse(s);
  }
  double number;
  const SourcePos pos = s.Pos();
  if (s.Number(number)) {
    Expr e;
    e.number = number;
    e.pos = pos;
    return expr.Add(e);
  }
  const char c = s.Peek();
  if (c == '-' || c == '+' || c == '@' || c == expr.open()) {
    return expr.Parse(s);  // a signed or computed value
  }
  expr.Error(address_pos, "address " + address + " needs a value");
  return kNoExpr;
}

}  // namespace vmt::control::nc
