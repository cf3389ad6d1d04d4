#include "sim/runner/run_story.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

namespace vmt::sim {
namespace {

using Json = nlohmann::json;

std::string Seconds(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f s", t);
  return buf;
}

std::string Millimetres(double mm) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f mm", mm);
  return buf;
}

double T(const Json& e) { return e.value("t", 0.0); }

std::string Join(const std::vector<std::string>& items, const std::string& sep) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? sep : "") + items[i];
  return out;
}

/// The keys pressed and signals written by the timeline or the operator, each once, in order.
struct OperatorActions {
  std::vector<std::string> keys;
  void Note(const Json& e) {
    std::string key;
    if (e["event"] == "step") {
      const std::string text = e.value("text", "");
      const size_t at = text.find(": press ");
      if (at != std::string::npos) key = text.substr(at + 8);
    } else if (e["event"] == "operator" && e.contains("signal") &&
               e.value("value", Json()) == true) {
      key = e["signal"].get<std::string>();
    }
    if (!key.empty() && std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
};

/// The NC program's course: when it ran, how often it held, how it ended.
struct ProgramCourse {
  double started = -1, ended = -1, error_t = -1;
  int holds = 0;
  std::string error;
  void Note(const Json& e) {
    if (e["event"] != "nc" || e.contains("channel")) return;
    const std::string state = e.value("state", "");
    if (state == "running" && started < 0) started = T(e);
    if (state == "hold") ++holds;
    if (state == "ended") ended = T(e);
    if (state == "error" && error_t < 0) {
      error_t = T(e);
      error = e.value("error", "");
    }
  }
  void Tell(std::vector<std::string>& lines) const {
    if (started < 0 && error_t < 0) return;
    std::string s = "NC program: started at " + Seconds(std::max(started, 0.0));
    if (holds > 0) s += ", held " + std::to_string(holds) + (holds == 1 ? " time" : " times");
    if (ended >= 0) s += ", ended at " + Seconds(ended);
    if (error_t >= 0)
      s += ", stopped in error at " + Seconds(error_t) + (error.empty() ? "" : ": " + error);
    if (ended < 0 && error_t < 0) s += ", still running when the run ended";
    lines.push_back(s);
  }
};

/// Repositioning: how often the REPOS subroutine ran, and the functions called.
struct Repositioning {
  bool in_subroutine = false;
  double from = 0;
  std::vector<std::string> runs;
  void Note(const Json& e) {
    if (e["event"] != "repos") return;
    const bool sub = e.value("subroutine", false);
    if (sub && !in_subroutine) from = T(e);
    if (!sub && in_subroutine) runs.push_back(Seconds(from) + " to " + Seconds(T(e)));
    in_subroutine = sub;
  }
  void Tell(std::vector<std::string>& lines) const {
    if (runs.empty() && !in_subroutine) return;
    std::string s = "repositioning: the REPOS subroutine ran " + Join(runs, ", ");
    if (in_subroutine)
      s += std::string(runs.empty() ? "" : ", ") + "from " + Seconds(from) + " (unfinished)";
    lines.push_back(s);
  }
};

/// PathGuard: moves checked, refused (with the parts that met), the tightest clearance.
struct Guard {
  int checked = 0, refused = 0;
  double min_clearance = -1;
  std::string closest;
  std::vector<std::string> refusals;
  void Note(const Json& e) {
    if (e["event"] != "path_guard") return;
    ++checked;
    if (!e.value("clear", true)) {
      ++refused;
      std::string parts;
      if (e.contains("parts") && e["parts"].is_array())
        parts = Join(e["parts"].get<std::vector<std::string>>(), " and ");
      if (refusals.size() < 3)
        refusals.push_back(e.value("move", "move") + " at " + Seconds(T(e)) +
                           (parts.empty() ? "" : " (" + parts + ")"));
      return;
    }
    if (e.contains("min_clearance") && e["min_clearance"].is_number()) {
      const double c = e["min_clearance"].get<double>();
      if (min_clearance < 0 || c < min_clearance) {
        min_clearance = c;
        closest = e.contains("closest") && e["closest"].is_array()
                      ? Join(e["closest"].get<std::vector<std::string>>(), " and ")
                      : "";
      }
    }
  }
  void Tell(std::vector<std::string>& lines) const {
    if (checked == 0) return;
    std::string s =
        "PathGuard: checked " + std::to_string(checked) + (checked == 1 ? " move" : " moves");
    if (refused == 0) {
      s += ", all clear";
    } else {
      s += ", refused " + std::to_string(refused) + ": " + Join(refusals, "; ");
      if (refused > static_cast<int>(refusals.size())) s += "; ...";
    }
    if (min_clearance >= 0)
      s += "; closest approach " + Millimetres(min_clearance) +
           (closest.empty() ? "" : " (" + closest + ")");
    lines.push_back(s);
  }
};

/// Messages the NC or the PLC raised, each number once.
struct Messages {
  std::vector<std::string> seen;
  std::set<std::string> keys;
  void Note(const Json& e) {
    if (e["event"] != "message" || e.value("state", "") == "cleared") return;
    const std::string key = e.value("source", "") + " " + e.value("number", Json(0)).dump();
    if (!keys.insert(key).second) return;
    seen.push_back(e.value("source", "") + " " + e.value("number", Json(0)).dump() + " at " +
                   Seconds(T(e)) + (e.contains("text") ? " \"" + e.value("text", "") + "\"" : ""));
  }
  void Tell(std::vector<std::string>& lines) const {
    if (!seen.empty()) lines.push_back("messages: " + Join(seen, "; "));
  }
};

/// Drive trips: a drive that stopped on overload, overspeed or a missing parameter set.
struct DriveTrips {
  std::vector<std::string> trips;
  void Note(const Json& e) {
    if (e["event"] != "drive") return;
    std::vector<std::string> why;
    for (const char* cause : {"overload", "overspeed", "parameter_set_error"})
      if (e.value(cause, false)) why.push_back(cause);
    if (!why.empty())
      trips.push_back(e.value("name", "?") + " " + Join(why, "+") + " at " + Seconds(T(e)));
  }
  void Tell(std::vector<std::string>& lines) const {
    if (!trips.empty()) lines.push_back("drive trips: " + Join(trips, "; "));
  }
};

}  // namespace

std::vector<std::string> RunStory(std::istream& events_jsonl) {
  OperatorActions actions;
  ProgramCourse course;
  Repositioning repos;
  Guard guard;
  Messages messages;
  DriveTrips trips;
  std::string line;
  while (std::getline(events_jsonl, line)) {
    const Json e = Json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (!e.is_object() || !e.contains("event") || !e["event"].is_string()) continue;
    actions.Note(e);
    course.Note(e);
    repos.Note(e);
    guard.Note(e);
    messages.Note(e);
    trips.Note(e);
  }
  std::vector<std::string> lines;
  course.Tell(lines);
  if (!actions.keys.empty()) lines.push_back("keys pressed: " + Join(actions.keys, ", "));
  repos.Tell(lines);
  guard.Tell(lines);
  messages.Tell(lines);
  trips.Tell(lines);
  return lines;
}

}  // namespace vmt::sim
