#pragma once
// Character-level reading of one NC block (one line), shared by both dialect front ends. It
// never reads past the line and never throws: malformed input ends in a diagnostic.

#include <cctype>
#include <string>
#include <string_view>

#include "control/nc/source_pos.hpp"

namespace vmt::control::nc {

class LineScanner {
 public:
  LineScanner(std::string_view line, SourcePos start) : line_(line), start_(start) {}

  void SkipSpace() {
    while (i_ < line_.size() && (line_[i_] == ' ' || line_[i_] == '\t' || line_[i_] == '\r')) ++i_;
  }
  bool AtEnd() const { return i_ >= line_.size(); }
  char Peek(size_t ahead = 0) const { return i_ + ahead < line_.size() ? line_[i_ + ahead] : '\0'; }
  bool Accept(char c) {
    if (Peek() != c) return false;
    ++i_;
    return true;
  }
  void Advance(size_t n = 1) { i_ = std::min(line_.size(), i_ + n); }
  // ASCII, as the C locale the project runs in: the locale-aware <cctype> calls were a tenth of
  // the decode time.
  static bool IsLetter(char c) {
    return static_cast<unsigned char>((c | 0x20) - 'a') < 26 || c == '_';
  }
  static bool IsDigit(char c) { return c >= '0' && c <= '9'; }
  static char ToUpper(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 32) : c; }

  /// A run of letters (and '_'), upper-cased.
  std::string Letters() {
    std::string s;
    while (IsLetter(Peek())) s.push_back(ToUpper(line_[i_++]));
    return s;
  }
  /// A name: a letter, then letters, digits, '_' and '.', upper-cased (labels, ISG names).
  std::string Name() {
    std::string s;
    while (IsLetter(Peek()) || IsDigit(Peek()) || Peek() == '.') s.push_back(ToUpper(line_[i_++]));
    return s;
  }
  /// Unsigned decimal number: digits [. digits] or . digits. False (nothing read) otherwise.
  bool Number(double& value, std::string* text = nullptr) {
    const size_t begin = i_;
    size_t j = i_;
    while (j < line_.size() && IsDigit(line_[j])) ++j;
    bool digits = j > begin;
    if (j < line_.size() && line_[j] == '.') {
      size_t k = j + 1;
      while (k < line_.size() && IsDigit(line_[k])) ++k;
      if (k > j + 1 || digits) {
        digits = digits || k > j + 1;
        j = k;
      }
    }
    if (!digits) return false;
    // Hand-rolled: the decode benchmark reads millions of these; no locale, no allocation.
    double v = 0, scale = 0;
    for (size_t k = begin; k < j; ++k) {
      if (line_[k] == '.') {
        scale = 1;
        continue;
      }
      v = v * 10 + (line_[k] - '0');
      if (scale != 0) scale *= 10;
    }
    value = scale != 0 ? v / scale : v;
    if (text) *text = std::string(line_.substr(begin, j - begin));
    i_ = j;
    return true;
  }
  /// Digits only (N numbers, variable numbers).
  bool Integer(long& value) {
    if (!IsDigit(Peek())) return false;
    long v = 0;
    while (IsDigit(Peek()) && v < 1000000000) v = v * 10 + (line_[i_++] - '0');
    while (IsDigit(Peek())) ++i_;  // absurdly long: clamp, the checker reports the range
    value = v;
    return true;
  }

  SourcePos Pos() const {
    SourcePos p = start_;
    p.column += static_cast<uint32_t>(i_);
    p.offset += static_cast<uint32_t>(i_);
    return p;
  }
  size_t index() const { return i_; }

 private:
  std::string_view line_;
  SourcePos start_;
  size_t i_ = 0;
};

}  // namespace vmt::control::nc
