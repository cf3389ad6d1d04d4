// The ISG dialect (TwinCAT CNC): %name program headers, N10 block numbers, ';' and ( ) comments,
// P-parameters and V. variables with [ ] expressions, $IF/$ELSEIF/$ELSE/$ENDIF, $FOR/$ENDFOR,
// $WHILE/$ENDWHILE, L name subprogram calls, #-commands (#DISTANCE PROG START, #BLOCKSEARCH,
// #CAX TRACK, #VECTOR OFFSET, #CALL AX, #PUT AX, ...), and address words.

#include <array>
#include <string>

#include "control/nc/front_end.hpp"

namespace vmt::control::nc {
namespace {

constexpr std::array kAddresses = {"A", "B", "C", "D", "E", "F", "G", "H", "I", "J", "K",
                                   "M", "Q", "R", "S", "T", "U", "V", "W", "X", "Y", "Z"};

// kAddresses by letter: a word's address is looked up once per word.
constexpr std::array<bool, 26> kIsAddress = [] {
  std::array<bool, 26> is{};
  for (const char* a : kAddresses) is[a[0] - 'A'] = true;
  return is;
}();

// Skips spaces and ( ... ) comments; false (after an error) for an unclosed comment.
bool SkipSpaceAndComments(LineScanner& s, ExpressionParser& expr) {
  for (;;) {
    s.SkipSpace();
    if (s.Peek() != '(') return true;
    const SourcePos open = s.Pos();
    while (!s.AtEnd() && s.Peek() != ')') s.Advance();
    if (!s.Accept(')')) {
      expr.Error(open, "comment '(' is not closed on this line");
      return false;
    }
  }
}

// "#DISTANCE   PROG START ON ; x" -> "DISTANCE PROG START ON": upper case, single spaces.
std::string HashCommandText(LineScanner& s) {
  std::string text;
  bool space = false;
  while (!s.AtEnd() && s.Peek() != ';') {
    const char c = s.Peek();
    s.Advance();
    if (c == ' ' || c == '\t' || c == '\r') {
      space = !text.empty();
      continue;
    }
    if (space) text.push_back(' ');
    space = false;
    text.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  }
  return text;
}

}  // namespace

bool ParseIsgLine(std::string_view line, SourcePos start, ExpressionParser& expr, Block& block) {
  LineScanner s(line, start);
  Program& p = expr.program();
  if (!SkipSpaceAndComments(s, expr)) return true;
  if (s.AtEnd() || s.Peek() == ';') return false;
  block.pos = s.Pos();
  if (s.Accept('%')) {  // program header: %name
    s.SkipSpace();
    // Program names may hold '-' and '.': %block-search-cax-track, %t_sv_number.nc.
    std::string name;
    while (!s.AtEnd() && s.Peek() != ' ' && s.Peek() != '\t' && s.Peek() != ';' &&
           s.Peek() != '\r') {
      name.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(s.Peek()))));
      s.Advance();
    }
    if (name.empty())
      expr.Error(s.Pos(), "expected a program name after '%'");
    else if (p.name.empty() || p.blocks.empty())
      p.name = name;
    block.label = p.symbols.Intern(name);
    return true;
  }
  ReadBlockStart(s, block);

  for (;;) {
    if (!SkipSpaceAndComments(s, expr)) return true;
    if (s.AtEnd() || s.Peek() == ';') return true;
    const SourcePos pos = s.Pos();
    Statement st;
    st.pos = pos;

    if (s.Accept('#')) {
      st.kind = Statement::Kind::kHashCommand;
      std::string text = HashCommandText(s);
      if (text.empty()) return expr.Error(pos, "empty #-command"), true;
      st.text = static_cast<uint32_t>(p.texts.size());
      p.texts.push_back(std::move(text));
      p.statements.push_back(st);
      return true;
    }
    if (s.Accept('$')) {
      const std::string kw = s.Letters();
      using K = Statement::Kind;
      if (kw == "IF" || kw == "ELSEIF" || kw == "WHILE") {
        st.kind = kw == "IF" ? K::kIf : kw == "ELSEIF" ? K::kElseIf : K::kWhile;
        if ((st.value = expr.Parse(s)) == kNoExpr) return true;
      } else if (kw == "ELSE" || kw == "ENDIF" || kw == "ENDFOR" || kw == "ENDWHILE") {
        st.kind = kw == "ELSE"     ? K::kElse
                  : kw == "ENDIF"  ? K::kEndIf
                  : kw == "ENDFOR" ? K::kEndFor
                                   : K::kEndWhile;
      } else if (kw == "FOR") {  // $FOR P1 = start, limit, step
        st.kind = K::kFor;
        s.SkipSpace();
        const SourcePos var_pos = s.Pos();
        const std::string var = s.Name();
        if (var.empty()) return expr.Error(var_pos, "expected a loop variable after $FOR"), true;
        st.name = p.symbols.Intern(var);
        s.SkipSpace();
        if (!s.Accept('='))
          return expr.Error(s.Pos(), "expected '=' after the $FOR variable"), true;
        if ((st.value = expr.Parse(s)) == kNoExpr) return true;
        s.SkipSpace();
        if (!s.Accept(',')) return expr.Error(s.Pos(), "expected ', limit' in $FOR"), true;
        if ((st.limit = expr.Parse(s)) == kNoExpr) return true;
        s.SkipSpace();
        if (s.Accept(',') && (st.step = expr.Parse(s)) == kNoExpr) return true;
      } else {
        expr.Error(pos, "unknown control statement '$" + kw + "'");
        return true;
      }
      p.statements.push_back(st);
      continue;
    }
    if (!LineScanner::IsLetter(s.Peek())) {
      expr.Error(pos, std::string("unexpected '") + s.Peek() + "'");
      return true;
    }
    // Look at the whole name first: P1 = ..., V.L.X = ..., L name, or address letters.
    LineScanner probe = s;
    const std::string name = probe.Name();
    const bool parameter = name.size() > 1 && name[0] == 'P' &&
                           name.find_first_not_of("0123456789", 1) == std::string::npos;
    if (parameter || name.rfind("V.", 0) == 0) {
      s = probe;
      s.SkipSpace();
      if (!s.Accept('=')) return expr.Error(s.Pos(), "expected '=' after " + name), true;
      st.kind = Statement::Kind::kAssign;
      st.name = p.symbols.Intern(name);
      if ((st.value = expr.Parse(s)) == kNoExpr) return true;
      p.statements.push_back(st);
      continue;
    }
    if (name == "L" && (probe.Peek() == ' ' || probe.Peek() == '\t')) {
      s = probe;
      s.SkipSpace();
      const SourcePos target_pos = s.Pos();
      const std::string target = s.Name();
      if (target.empty()) return expr.Error(target_pos, "expected a subprogram name after L"), true;
      st.kind = Statement::Kind::kCall;
      st.name = p.symbols.Intern("L");
      st.target = p.symbols.Intern(target);
      p.statements.push_back(st);
      continue;
    }
    const char upper = LineScanner::ToUpper(s.Peek());
    if (upper < 'A' || upper > 'Z' || !kIsAddress[upper - 'A']) {
      expr.Error(pos, "unknown word '" + name + "'");
      return true;
    }
    const std::string letter(1, upper);
    s.Advance();
    Word w;
    w.offset = pos.offset;
    w.address = p.symbols.Intern(letter);
    if (!ParseWordValue(s, expr, letter, pos, w)) return true;
    p.words.push_back(w);
  }
}

}  // namespace vmt::control::nc
