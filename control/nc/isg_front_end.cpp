// The ISG dialect (TwinCAT CNC): %name program headers, N10 block numbers, ';' and ( ) comments,
// P-parameters and V. variables with [ ] expressions, $IF/$ELSEIF/$ELSE/$ENDIF, $FOR/$ENDFOR,
// $WHILE/$ENDWHILE, L name subprogram calls, #-commands (#DISTANCE PROG START, #BLOCKSEARCH,
// #CAX TRACK, #VECTOR OFFSET, #CALL AX, #PUT AX, ...), and address words.

#include <algorithm>
#include <array>
#include <string>
#include <vector>

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
// `source` gets the scanner index of each character of the text and, last, of its end: a wrong
// word is reported where it stands in the line, not where it stands in the text.
std::string HashCommandText(LineScanner& s, std::vector<size_t>& source) {
  std::string text;
  bool space = false;
  size_t end = s.index();
  while (!s.AtEnd() && s.Peek() != ';') {
    const char c = s.Peek();
    const size_t at = s.index();
    s.Advance();
    if (c == ' ' || c == '\t' || c == '\r') {
      space = !text.empty();
      continue;
    }
    if (space) text.push_back(' '), source.push_back(at);
    space = false;
    text.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
    source.push_back(at);
    end = at + 1;
  }
  source.push_back(end);
  return text;
}

// The words of a #-command text and where each starts in it.
struct TextWord {
  std::string_view word;
  size_t at;
};
std::vector<TextWord> SplitWords(std::string_view text) {
  std::vector<TextWord> words;
  for (size_t i = 0; i < text.size();) {
    const size_t end = std::min(text.find(' ', i), text.size());
    words.push_back({text.substr(i, end - i), i});
    i = end + 1;
  }
  return words;
}

}  // namespace

SearchCommand ReadSearchCommand(std::string_view text) {
  using Kind = SearchCommand::Kind;
  // Most #-commands are others: they are let go before anything is allocated for them.
  if (!text.starts_with("BLOCKSEARCH") && !text.starts_with("DISTANCE PROG START")) return {};
  const std::vector<TextWord> words = SplitWords(text);
  size_t first = 0;  // the word after the command's name
  std::string command;
  if (!words.empty() && words[0].word == "BLOCKSEARCH") {
    first = 1, command = "BLOCKSEARCH";
  } else if (words.size() >= 3 && words[0].word == "DISTANCE" && words[1].word == "PROG" &&
             words[2].word == "START") {
    first = 3, command = "DISTANCE PROG START";
  } else {
    return {};
  }
  const char* choices = first == 1 ? "LOCKED or RELEASED" : "ON, OFF or CLEAR";
  SearchCommand c;
  auto invalid = [&](size_t word, std::string message) {
    c.kind = Kind::kInvalid;
    c.at = word < words.size() ? words[word].at : text.size();
    c.message = std::move(message);
    return c;
  };
  if (first >= words.size())
    return invalid(first, "expected " + std::string(choices) + " after #" + command);
  const std::string_view k = words[first].word;
  if (first == 1 && k == "LOCKED") {
    c.kind = Kind::kLock;
  } else if (first == 1 && k == "RELEASED") {
    c.kind = Kind::kRelease;
  } else if (first == 3 && (k == "ON" || k == "OFF" || k == "CLEAR")) {
    c.kind = Kind::kDistance;
    c.distance = k == "ON"    ? DistanceCommand::kOn
                 : k == "OFF" ? DistanceCommand::kOff
                              : DistanceCommand::kClear;
  } else {
    return invalid(
        first, "unknown #" + command + " keyword '" + std::string(k) + "': expected " + choices);
  }
  if (first + 1 < words.size())
    return invalid(first + 1, "unexpected '" + std::string(words[first + 1].word) + "' after #" +
                                  command + " " + std::string(k));
  return c;
}

namespace {

/// A #-command after its '#' (at index `hash` of the line): its text, typed, as a statement of
/// the block; a block search command with a bad value is an error at that value. Always true:
/// the rest of the line belongs to the command.
bool ParseHashCommand(LineScanner& s, size_t hash, ExpressionParser& expr, Statement st) {
  Program& p = expr.program();
  st.kind = Statement::Kind::kHashCommand;
  std::vector<size_t> source;
  std::string text = HashCommandText(s, source);
  if (text.empty()) return expr.Error(st.pos, "empty #-command"), true;
  if (const SearchCommand c = ReadSearchCommand(text); c.kind == SearchCommand::Kind::kInvalid) {
    SourcePos at = st.pos;
    const auto shift = static_cast<uint32_t>(source[c.at] - hash);
    at.column += shift;
    at.offset += shift;
    return expr.Error(at, c.message), true;
  }
  st.hash = HashCommandOf(text);
  st.text = static_cast<uint32_t>(p.texts.size());
  p.texts.push_back(std::move(text));
  p.statements.push_back(st);
  return true;
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

    const size_t hash = s.index();
    if (s.Accept('#')) return ParseHashCommand(s, hash, expr, st);
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
      st.instruction = Instruction::kL;
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
