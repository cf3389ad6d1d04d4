// The MTC200 dialect (Bosch Rexroth): N0001 block numbers, .LABEL labels, ';' comments, @100
// variables, branches on the result of the last computation (BRA/BEQ/BNE/BGT/BLT/BGE/BLE),
// event branches BES/BEC, JSR/RTS/RET, reverse vectors REV, SE/RE events, turret commands
// MTP/MMP/MRF/MHP/MFP/MOP, MRY, data access TLD/OTD/MTD(...), fast-measurement instructions,
// and address words.

#include <array>
#include <string>
#include <unordered_map>

#include "control/nc/front_end.hpp"

namespace vmt::control::nc {
namespace {

constexpr std::array kBranches = {"BRA", "BEQ", "BNE", "BGT", "BLT", "BGE", "BLE"};
constexpr std::array kEventBranches = {"BES", "BEC"};
constexpr std::array kPlainInstructions = {"MTP", "MMP", "MRF", "MHP", "MFP", "MOP", "MRY"};
constexpr std::array kEventInstructions = {"SE", "RE"};
constexpr std::array kCallInstructions = {"TLD",  "OTD",   "MTD",     "SETTING",    "SAVE",
                                          "MOVE", "PROBE", "COMPARE", "CORRECTION", "RESTORE"};
// Address letters and multi-letter addresses of the MTC200 block.
constexpr std::array kAddresses = {"A", "B", "C", "D", "E", "F",  "G",  "H", "I",
                                   "J", "K", "M", "P", "Q", "R",  "S",  "T", "U",
                                   "V", "W", "X", "Y", "Z", "RX", "RY", "RZ"};

enum class WordClass {
  kUnknown,
  kBranch,
  kEventBranch,
  kJump,
  kReturn,
  kReverse,
  kEvent,
  kPlain,
  kCall,
  kAddress
};

// What a word is: its class and, for a mnemonic, the instruction it names.
struct Classified {
  WordClass cls = WordClass::kUnknown;
  Instruction instruction = Instruction::kNone;
};

// One hash lookup per word instead of a string compare against every mnemonic.
Classified Classify(const std::string& word) {
  static const std::unordered_map<std::string_view, Classified> table = [] {
    std::unordered_map<std::string_view, WordClass> t;
    for (const char* w : kBranches) t[w] = WordClass::kBranch;
    for (const char* w : kEventBranches) t[w] = WordClass::kEventBranch;
    for (const char* w : kPlainInstructions) t[w] = WordClass::kPlain;
    for (const char* w : kEventInstructions) t[w] = WordClass::kEvent;
    for (const char* w : kCallInstructions) t[w] = WordClass::kCall;
    for (const char* w : kAddresses) t[w] = WordClass::kAddress;
    t["JSR"] = WordClass::kJump;
    t["RTS"] = t["RET"] = WordClass::kReturn;
    // Reverse vectors (REPOS manual 4.1, fast measurement 4.4): the manuals give no syntax for
    // the ones a user programs, only the form the control writes for its own, `rev .*$...`
    // (fast measurement 4.4 CAUTION). vmt reads that as the statement REV naming a jump label,
    // and takes the same form for the user's: `REV .LABEL`, like a branch.
    t["REV"] = WordClass::kReverse;
    std::unordered_map<std::string_view, Classified> classified;
    for (const auto& [w, cls] : t)
      classified[w] = {cls, cls == WordClass::kAddress ? Instruction::kNone : InstructionOf(w)};
    return classified;
  }();
  const auto it = table.find(word);
  return it == table.end() ? Classified{} : it->second;
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

bool ParseMtc200Line(std::string_view line, SourcePos start, ExpressionParser& expr, Block& block) {
  LineScanner s(line, start);
  Program& p = expr.program();
  s.SkipSpace();
  if (s.AtEnd() || s.Peek() == ';') return false;
  block.pos = s.Pos();
  ReadBlockStart(s, block);
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
      long n = 0;
      if (!s.Integer(n)) return expr.Error(s.Pos(), "expected a variable number after '@'"), true;
      s.SkipSpace();
      if (!s.Accept('='))
        return expr.Error(s.Pos(), "expected '=' after @" + std::to_string(n)), true;
      st.kind = Statement::Kind::kAssign;
      st.name = p.symbols.Intern("@" + std::to_string(n));
      if ((st.value = expr.Parse(s)) == kNoExpr) return true;
      p.statements.push_back(st);
      continue;
    }
    if (!LineScanner::IsLetter(s.Peek())) {
      expr.Error(pos, std::string("unexpected '") + s.Peek() + "'");
      return true;
    }
    const std::string word = s.Letters();
    const auto [cls, instruction] = Classify(word);
    st.instruction = instruction;
    if (cls == WordClass::kBranch) {
      st.kind = Statement::Kind::kBranch;
      st.name = p.symbols.Intern(word);
      if ((st.target = Label(s, expr, p, word)) == 0) return true;
    } else if (cls == WordClass::kEventBranch) {
      st.kind = Statement::Kind::kEventBranch;
      st.name = p.symbols.Intern(word);
      if ((st.target = Label(s, expr, p, word)) == 0) return true;
      if ((st.value = expr.Parse(s)) == kNoExpr) return true;
    } else if (cls == WordClass::kJump) {
      st.kind = Statement::Kind::kCall;
      st.name = p.symbols.Intern(word);
      if ((st.target = Label(s, expr, p, word)) == 0) return true;
    } else if (cls == WordClass::kReverse) {
      st.kind = Statement::Kind::kReverse;
      st.name = p.symbols.Intern(word);
      if ((st.target = Label(s, expr, p, word)) == 0) return true;
    } else if (cls == WordClass::kReturn) {
      st.kind = Statement::Kind::kReturn;
      st.name = p.symbols.Intern(word);
    } else if (cls == WordClass::kEvent) {
      st.kind = Statement::Kind::kInstruction;
      st.name = p.symbols.Intern(word);
      if ((st.value = expr.Parse(s)) == kNoExpr) return true;
    } else if (cls == WordClass::kPlain || cls == WordClass::kCall) {
      st.kind = Statement::Kind::kInstruction;
      st.name = p.symbols.Intern(word);
      s.SkipSpace();
      if (s.Peek() == '(') {
        const SourcePos open = s.Pos();
        s.Advance();
        if (!expr.Arguments(s, open, st.name, st.value)) return true;
        s.SkipSpace();
        if (cls == WordClass::kCall && s.Peek() == '=' && s.Peek(1) != '=') {
          // A data location written to: TLD(1,3,,1,12,) = TLD(1,3,,1,12,) + MTD(105,,2,13).
          s.Advance();
          st.kind = Statement::Kind::kAssign;
          st.data = expr.CallOf(st.name, st.value, pos.offset);
          if ((st.value = expr.Parse(s)) == kNoExpr) return true;
        }
      } else if (cls == WordClass::kCall) {
        expr.Error(s.Pos(), "expected '(' after " + word);
        return true;
      }
    } else if (cls == WordClass::kAddress) {
      Word w;
      w.offset = pos.offset;
      std::string address = word;
      // An index (S1=0, X1=0) is digits directly followed by '='; otherwise digits are the value.
      if (LineScanner::IsDigit(s.Peek())) {
        LineScanner probe = s;
        long index = 0;
        probe.Integer(index);
        probe.SkipSpace();
        if (probe.Peek() == '=' && probe.Peek(1) != '=') {
          s.Integer(index);
          address += std::to_string(index);
        }
      }
      w.address = p.symbols.Intern(address);
      if (!ParseWordValue(s, expr, address, pos, w)) return true;
      p.words.push_back(w);
      continue;
    } else {
      expr.Error(pos, "unknown word '" + word + "'");
      return true;
    }
    p.statements.push_back(st);
  }
}

}  // namespace vmt::control::nc
