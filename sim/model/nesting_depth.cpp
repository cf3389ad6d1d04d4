#include "sim/model/nesting_depth.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace vmt::sim {
namespace {

int CountLines(std::string_view text, size_t from, size_t to) {
  return static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(from),
                                     text.begin() + static_cast<std::ptrdiff_t>(to), '\n'));
}

// Index just past `terminator` from `from`, or the text's end.
size_t Past(std::string_view text, size_t from, std::string_view terminator) {
  const size_t at = text.find(terminator, from);
  return at == std::string_view::npos ? text.size() : at + terminator.size();
}

// A tag's end '>' from `from`, skipping quoted attribute values; npos if there is none.
size_t TagEnd(std::string_view text, size_t from) {
  char quote = 0;
  for (size_t i = from; i < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '>') {
      return i;
    }
  }
  return std::string_view::npos;
}

bool StartsWith(std::string_view text, size_t at, std::string_view prefix) {
  return text.substr(at, prefix.size()) == prefix;
}

}  // namespace

int XmlNestingBeyond(std::string_view text, int limit) {
  int depth = 0, line = 1;
  size_t i = 0;
  while (i < text.size()) {
    const size_t lt = text.find('<', i);
    if (lt == std::string_view::npos) break;
    line += CountLines(text, i, lt);
    size_t next;
    if (StartsWith(text, lt, "<!--")) {
      next = Past(text, lt + 4, "-->");
    } else if (StartsWith(text, lt, "<![CDATA[")) {
      next = Past(text, lt + 9, "]]>");
    } else if (StartsWith(text, lt, "<?")) {
      next = Past(text, lt + 2, "?>");
    } else if (StartsWith(text, lt, "<!")) {
      // A declaration; a DOCTYPE's internal subset ends with "]>".
      const size_t bracket = text.find('[', lt), end = text.find('>', lt);
      next = bracket < end ? Past(text, bracket, "]>") : Past(text, lt, ">");
    } else {
      const size_t end = TagEnd(text, lt + 1);
      next = end == std::string_view::npos ? text.size() : end + 1;
      if (StartsWith(text, lt, "</")) {
        depth = std::max(0, depth - 1);
      } else if (end == std::string_view::npos || text[end - 1] != '/') {
        if (++depth > limit) return line;
      }
    }
    line += CountLines(text, lt, next);
    i = next;
  }
  return 0;
}

int YamlNestingBeyond(std::string_view text, int limit) {
  std::vector<size_t> block;  // indentation columns of the open block collections
  int flow = 0;               // open '[' and '{'
  char quote = 0;             // open quoted scalar, which may run over lines
  long block_scalar = -1;     // while >= 0: lines indented deeper are a block scalar's text
  int line = 0;
  for (size_t start = 0; start < text.size();) {
    size_t stop = text.find('\n', start);
    if (stop == std::string_view::npos) stop = text.size();
    const std::string_view l = text.substr(start, stop - start);
    start = stop + 1;
    ++line;
    size_t pos = l.find_first_not_of(' ');
    if (quote == 0) {
      if (pos == std::string_view::npos || l[pos] == '#' || l[pos] == '\r') continue;
      if (block_scalar >= 0 && static_cast<long>(pos) > block_scalar) continue;
      block_scalar = -1;
      if (flow == 0) {
        while (!block.empty() && block.back() > pos) block.pop_back();
        if (block.empty() || block.back() < pos) block.push_back(pos);
        // "- - x": each entry indicator opens a collection on the same line.
        while ((StartsWith(l, pos, "- ") || (l.size() == pos + 1 && l[pos] == '-') ||
                StartsWith(l, pos, "? "))) {
          block.push_back(pos + 2);
          pos = l.find_first_not_of(' ', pos + 1);
          if (pos == std::string_view::npos) break;
        }
        if (static_cast<int>(block.size()) > limit) return line;
        if (pos == std::string_view::npos) continue;
      }
    } else {
      pos = 0;
    }
    const size_t indent = l.find_first_not_of(' ');
    size_t content_end = l.size();
    for (size_t j = pos; j < l.size(); ++j) {
      const char c = l[j];
      const char prev = j == 0 ? ' ' : l[j - 1];
      if (quote) {
        if (quote == '"' && c == '\\') {
          ++j;
        } else if (c == quote) {
          if (quote == '\'' && j + 1 < l.size() && l[j + 1] == '\'')
            ++j;
          else
            quote = 0;
        }
        continue;
      }
      if (c == '#' && (prev == ' ' || prev == '\t')) {
        content_end = j;
        break;
      }
      // A quote opens a scalar only where a token starts: after "a:" it may be plain text, and
      // taking it for a quote could hide the nesting behind it.
      if ((c == '"' || c == '\'') &&
          (j == pos || std::string_view(" \t[{,").find(prev) != std::string_view::npos)) {
        quote = c;
      } else if (c == '[' || c == '{') {
        if (static_cast<int>(block.size()) + ++flow > limit) return line;
      } else if (c == ']' || c == '}') {
        flow = std::max(0, flow - 1);
      }
    }
    // "key: |" or "- >-": the lines below, indented deeper, are text.
    if (quote == 0 && flow == 0) {
      std::string_view content = l.substr(0, content_end);
      while (!content.empty() && (content.back() == ' ' || content.back() == '\r'))
        content.remove_suffix(1);
      while (!content.empty() && (content.back() == '+' || content.back() == '-' ||
                                  (content.back() >= '0' && content.back() <= '9')))
        content.remove_suffix(1);
      if (!content.empty() && (content.back() == '|' || content.back() == '>') &&
          (content.size() == 1 || content[content.size() - 2] == ' '))
        block_scalar = static_cast<long>(indent);
    }
  }
  return 0;
}

}  // namespace vmt::sim
