#include "sim/model/yaml_text_checks.hpp"

#include <cstdio>
#include <map>
#include <set>
#include <utility>

#include "sim/model/model_error.hpp"

namespace vmt::sim {

namespace {

std::string Place(const std::string& file, const YAML::Mark& mark) {
  if (mark.line < 0) return file;
  return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

// Length of the UTF-8 sequence at text[i], or 0 when it is not one (overlong forms, surrogates
// and code points past U+10FFFF included).
size_t Utf8Length(const std::string& text, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  size_t n = 0;
  unsigned int lo = 0x80, hi = 0xBF;
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

class KeyChecker {
 public:
  explicit KeyChecker(const std::string& file) : file_(file) {}

  void Walk(const YAML::Node& node, const std::string& path) {
    if (!node.IsMap() && !node.IsSequence()) return;
    // An alias repeats its anchor's node: walk each collection once (a mark names it), so
    // nested aliases cannot make the walk exponential.
    const YAML::Mark mark = node.Mark();
    if (!seen_.insert({mark.line, mark.column}).second) return;
    if (node.IsSequence()) {
      size_t i = 0;
      for (const YAML::Node& item : node) Walk(item, path + "[" + std::to_string(i++) + "]");
      return;
    }
    std::map<std::string, YAML::Mark> keys;
    for (const auto& kv : node) {
      const YAML::Node& key = kv.first;
      const std::string where = path.empty() ? "(top level)" : path;
      if (!key.IsScalar() || key.IsNull()) {
        const char* what = key.IsMap() ? "a map" : key.IsSequence() ? "a list" : "null";
        throw ModelError(Place(file_, key.Mark()), where,
                         std::string("a key must be a name, not ") + what);
      }
      const std::string name = key.Scalar();
      const std::string child = path.empty() ? name : path + "." + name;
      const auto [it, fresh] = keys.emplace(name, key.Mark());
      if (!fresh)
        throw ModelError(Place(file_, key.Mark()), child,
                         "duplicate key '" + name + "' (first given at line " +
                             std::to_string(it->second.line + 1) + ":" +
                             std::to_string(it->second.column + 1) + ")");
      Walk(kv.second, child);
    }
  }

 private:
  const std::string& file_;
  std::set<std::pair<int, int>> seen_;
};

}  // namespace

void CheckUtf8Text(const std::string& file, const std::string& text) {
  int line = 1, column = 1;
  for (size_t i = 0; i < text.size();) {
    const size_t n = Utf8Length(text, i);
    if (n == 0) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(text[i]));
      throw ModelError(file + ":" + std::to_string(line) + ":" + std::to_string(column), "",
                       std::string("not UTF-8 text (byte ") + hex + "); save the file as UTF-8");
    }
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
    i += n;
  }
}

void CheckMapKeys(const std::string& file, const YAML::Node& root) {
  KeyChecker(file).Walk(root, "");
}

std::string YamlSyntaxError(const std::string& file, const YAML::Exception& e) {
  // yaml-cpp's terse texts, as the reason a user can act on.
  static const std::map<std::string, std::string> kReasons = {
      {"bad file", "the file cannot be read as YAML (nested too deeply?)"},
      {"illegal map value", "a ':' where no map value can start (a missing space or quote?)"},
      {"end of map not found", "a map is not closed"},
      {"end of map flow not found", "a '{' is not closed by '}'"},
      {"end of sequence not found", "a list is not closed"},
      {"end of sequence flow not found", "a '[' is not closed by ']'"},
      {"illegal flow end", "a ']' or '}' without its opening bracket"},
      {"illegal block entry", "a '- ' list entry where a list cannot start"},
      {"unknown token", "text YAML does not know here"},
      {"illegal EOF in scalar", "a quoted text is not closed"},
  };
  const auto it = kReasons.find(e.msg);
  const std::string reason = it == kReasons.end() ? e.msg : it->second + " (" + e.msg + ")";
  return Place(file, e.mark) + ": YAML syntax error: " + reason;
}

}  // namespace vmt::sim
