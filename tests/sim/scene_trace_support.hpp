#pragma once
// Shared by the headstock tests: a scene run's trace.csv by column and its headstock
// changeovers from events.jsonl.

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace vmt::sim::testing {

/// trace.csv as columns by header name.
struct Trace {
  std::map<std::string, std::vector<double>> columns;
  const std::vector<double>& operator[](const std::string& name) const {
    const auto it = columns.find(name);
    if (it == columns.end()) throw std::runtime_error("no trace column " + name);
    return it->second;
  }
  size_t size() const { return columns.empty() ? 0 : columns.begin()->second.size(); }
  /// The first row at or after time `t_s` (the last row if there is none).
  size_t RowAt(double t_s) const {
    const std::vector<double>& t = (*this)["t"];
    for (size_t i = 0; i < t.size(); ++i)
      if (t[i] >= t_s) return i;
    return t.empty() ? 0 : t.size() - 1;
  }
  /// The rows while the block at source line `line` is in work.
  std::vector<size_t> RowsOfLine(int line) const {
    std::vector<size_t> rows;
    for (size_t i = 0; i < size(); ++i)
      if ((*this)["nc.line"][i] == line) rows.push_back(i);
    return rows;
  }
};

inline Trace ReadTrace(const std::string& dir) {
  std::ifstream in(dir + "/trace.csv");
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (size_t start = 0;;) {
    const size_t comma = line.find(',', start);
    names.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  Trace t;
  while (std::getline(in, line)) {
    size_t start = 0;
    for (const std::string& name : names) {
      const size_t comma = line.find(',', start);
      t.columns[name].push_back(std::stod(line.substr(start, comma - start)));
      start = comma + 1;
    }
  }
  return t;
}

/// A headstock changeover as events.jsonl records it: from the request to the new mode.
struct Changeover {
  std::string target;
  double start_s = 0, end_s = -1;
  double duration_s() const { return end_s - start_s; }
};

inline std::vector<Changeover> Changeovers(const std::string& dir) {
  std::ifstream in(dir + "/events.jsonl");
  std::vector<Changeover> result;
  for (std::string line; std::getline(in, line);) {
    const nlohmann::json e = nlohmann::json::parse(line);
    if (e["event"] != "headstock") continue;
    if (e.contains("target") && e["mode"] == "none")
      result.push_back({e["target"].get<std::string>(), e["t"].get<double>()});
    else if (e.contains("axis") && !result.empty() && result.back().end_s < 0 &&
             e["mode"] == result.back().target)
      result.back().end_s = e["t"].get<double>();
  }
  return result;
}

}  // namespace vmt::sim::testing
