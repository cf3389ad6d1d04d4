#pragma once
// Checks of command-line values, so that a bad one is refused with the option and its allowed
// range (`--until: must be a finite number of seconds in 0..86400, got nan`) before any work.
// CLI11's own range check lets NaN through and prints the range as a 300-digit number.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace vmt::sim {

namespace option_checks_detail {
inline std::string Shown(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}
}  // namespace option_checks_detail

/// A finite number in [lo, hi]; `what` names its unit ("number of seconds").
inline CLI::Validator FiniteIn(double lo, double hi, const std::string& what = "number") {
  using option_checks_detail::Shown;
  const std::string range = "must be a finite " + what + " in " + Shown(lo) + ".." + Shown(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi || errno)
          return range + ", got '" + text + "'";
        return "";
      },
      "FLOAT in " + Shown(lo) + ".." + Shown(hi));
}

/// A whole number in [lo, hi].
inline CLI::Validator WholeIn(long long lo, long long hi) {
  const std::string range =
      "must be a whole number in " + std::to_string(lo) + ".." + std::to_string(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const long long v = std::strtoll(text.c_str(), &end, 10);
        if (text.empty() || *end != '\0' || errno || v < lo || v > hi)
          return range + ", got '" + text + "'";
        return "";
      },
      "INT in " + std::to_string(lo) + ".." + std::to_string(hi));
}

/// `K/N` with 1 <= K <= N <= max: one of N shards of a study.
inline CLI::Validator ShardOf(long long max) {
  const std::string range = "must be K/N with 1 <= K <= N <= " + std::to_string(max);
  return CLI::Validator(
      [max, range](std::string& text) -> std::string {
        const size_t slash = text.find('/');
        if (slash == std::string::npos) return range + ", e.g. 2/8, got '" + text + "'";
        const std::string k_text = text.substr(0, slash), n_text = text.substr(slash + 1);
        char* k_end = nullptr;
        char* n_end = nullptr;
        errno = 0;
        const long long k = std::strtoll(k_text.c_str(), &k_end, 10);
        const long long n = std::strtoll(n_text.c_str(), &n_end, 10);
        if (k_text.empty() || n_text.empty() || *k_end != '\0' || *n_end != '\0' || errno ||
            k < 1 || n < k || n > max)
          return range + ", e.g. 2/8, got '" + text + "'";
        return "";
      },
      "K/N");
}

/// Comma-separated whole numbers, each in [lo, hi], one to `count` of them.
inline CLI::Validator WholeListIn(long long lo, long long hi, size_t count) {
  const std::string range = "must be 1.." + std::to_string(count) +
                            " comma-separated whole numbers in " + std::to_string(lo) + ".." +
                            std::to_string(hi);
  return CLI::Validator(
      [lo, hi, count, range](std::string& text) -> std::string {
        size_t n = 0, begin = 0;
        for (;;) {
          const size_t comma = std::min(text.find(',', begin), text.size());
          const std::string item = text.substr(begin, comma - begin);
          char* end = nullptr;
          errno = 0;
          const long long v = std::strtoll(item.c_str(), &end, 10);
          if (item.empty() || *end != '\0' || errno || v < lo || v > hi || ++n > count)
            return range + ", e.g. 250,750, got '" + text + "'";
          if (comma == text.size()) return "";
          begin = comma + 1;
        }
      },
      "LIST");
}

/// A folder to write into: named, and not an existing file (it is made when missing).
inline const CLI::Validator kOutputFolder(
    [](std::string& path) -> std::string {
      if (path.empty()) return "needs a folder name, got ''";
      std::error_code ec;
      if (std::filesystem::exists(path, ec) && !std::filesystem::is_directory(path, ec))
        return path + ": is not a directory";
      return "";
    },
    "FOLDER");

/// A file to write: named, and not an existing folder.
inline const CLI::Validator kOutputFile(
    [](std::string& path) -> std::string {
      if (path.empty()) return "needs a file name, got ''";
      std::error_code ec;
      if (std::filesystem::is_directory(path, ec)) return path + ": is a directory, not a file";
      return "";
    },
    "FILE");

}  // namespace vmt::sim
