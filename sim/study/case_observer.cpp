#include "sim/study/case_observer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace vmt::sim::study {
namespace {

std::string Fixed(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f", v);
  return buf;
}

double Micro(double v) { return std::round(v * 1000) / 1000 + 0.0; }

}  // namespace

double PastContact(const nlohmann::ordered_json& position, const nlohmann::ordered_json& target) {
  if (!position.is_object() || !target.is_object()) return 0;
  double sum = 0;
  for (const auto& [axis, to] : target.items())
    if (to.is_number() && position.contains(axis) && position[axis].is_number()) {
      const double d = to.get<double>() - position[axis].get<double>();
      sum += d * d;
    }
  return std::sqrt(sum);
}

void CaseObserver::OnEvent(const nlohmann::ordered_json& e) {
  const std::string kind = e.value("event", "");
  const double t = e.value("t", 0.0);
  if (kind == "signal" && SignalRead(e.value("name", ""))) {
    error_number_ = static_cast<int>(e.value("value", 0.0));  // the message's number (507)
    return;
  }
  if (done_) return;  // only the message number may still come (the gateway's next cycle)
  size_t step = 0;
  if (kind == "step") {
    // "timeline[12] ...": the step's index
    const std::string text = e.value("text", "");
    if (text.starts_with("timeline[")) step = std::strtoul(text.c_str() + 9, nullptr, 10);
    steps_seen_ = std::max(steps_seen_, step + 1);
    if (manual_end_ && step == manual_end_ && repos_phase_) End(t);
  }
  if (kind == "step" && step == phase_step_ && !repos_phase_) {
    repos_phase_ = true;
    t_start_ = t;
  } else if (kind == "repos") {
    last_repos_ = e;
    if (e.contains("axes")) {
      const auto& axes = e["axes"];
      if (axes.contains("X")) x_ = axes["X"].value("command", x_);
      if (axes.contains("Z")) z_ = axes["Z"].value("command", z_);
      have_command_ = true;
    }
    if (repos_phase_ && e.value("subroutine", false)) subroutine_seen_ = true;
    if (repos_phase_ && subroutine_seen_ && !e.value("subroutine", false)) End(t);
  } else if (kind == "path_guard") {
    const bool clear = e.value("clear", true);
    if (!repos_phase_) {
      if (!clear && retract_contact_.is_null()) retract_contact_ = e["parts"];
      return;
    }
    if (clear) {
      const double c = e.value("min_clearance", std::numeric_limits<double>::infinity());
      if (c < min_clearance_) min_clearance_ = c;
      if (!contact_) AddMove(e);
    } else if (!contact_) {
      contact_ = true;
      parts_ = e["parts"];
      point_ = e["point"];
      position_ = e["position"];
      move_ = e.value("move", "");
      target_ = e.contains("to") ? e["to"] : nlohmann::ordered_json();
      // Where the move would have touched, on the drawing's axes.
      // The refused move never started: the path travelled ends where it would have begun.
      AddMove(e, false);
      travelled_ = path_.size();
      if (position_.is_object()) {
        const double x = path_.empty() ? x_ : path_.back().first;
        const double z = path_.empty() ? z_ : path_.back().second;
        const double cx = position_.contains("X") ? position_["X"].get<double>() : x;
        const double cz = position_.contains("Z") ? position_["Z"].get<double>() : z;
        path_.emplace_back(cx, cz);
      }
    }
  } else if (kind == "nc") {
    const std::string state = e.value("state", "");
    if (state == "error") {
      error_ = e.value("error", "NC error");
      End(t);
    } else if (state == "ended") {
      End(t);
    }
  }
}

void CaseObserver::AddMove(const nlohmann::ordered_json& e, bool whole) {
  // A drive the record leaves out does not move: it stays where the path stands.
  const auto at = [&](const char* key, double& x, double& z) {
    if (!e.contains(key) || !e[key].is_object()) return false;
    x = e[key].value("X", x);
    z = e[key].value("Z", z);
    return true;
  };
  double x = path_.empty() ? x_ : path_.back().first;
  double z = path_.empty() ? z_ : path_.back().second;
  if (!at("from", x, z)) return;
  if (path_.empty() || std::abs(path_.back().first - x) > 5e-4 ||
      std::abs(path_.back().second - z) > 5e-4)
    path_.emplace_back(x, z);
  if (!whole || !at("to", x, z)) return;
  if (std::abs(path_.back().first - x) > 5e-4 || std::abs(path_.back().second - z) > 5e-4)
    path_.emplace_back(x, z);
}

CaseResult CaseObserver::Result(const StudyPlan& plan,
                                const std::vector<Interruption>& interruptions, const StudyCase& c,
                                double t_now) const {
  const Interruption& in = interruptions[c.interruption];
  CaseResult r;
  r["case"] = c.id;
  r["subroutine"] = plan.subroutines[c.subroutine].name;
  r["interrupt"] = in.label;
  r["block"] = in.block;
  r["per_mille"] = in.per_mille >= 0 ? nlohmann::ordered_json(in.per_mille) : nullptr;
  r["t_interrupt_s"] = in.t_s;
  r["retract"] = plan.retracts[c.retract].name;
  r["mode"] = ToString(c.mode);
  std::string verdict = "clear";
  if (contact_)
    verdict = "collision";
  else if (!error_.empty() || !done_ || (!manual_end_ && !subroutine_seen_) ||
           (manual_end_ && !last_repos_.value("conditions_restored", false)))
    // PathGuard refusing the operator's own retract ends the case before any return: the
    // operator's problem, never the subroutine's.
    verdict = retract_contact_.is_null() ? "error" : "retract_refused";
  r["verdict"] = verdict;
  r["parts"] = contact_ ? parts_ : nullptr;
  r["point"] = contact_ ? point_ : nullptr;
  r["contact_position"] = contact_ ? position_ : nullptr;
  // Severity: how far the refused move would have gone on past its first contact (the axes'
  // distance from the contact to the move's end). Within kGrazeMm the parts only meet at the
  // move's end (a tool set back onto the contour it cut): a graze, apart from a crash.
  const double past = contact_ ? PastContact(position_, target_) : 0;
  r["contact_move"] = contact_ ? nlohmann::ordered_json(move_) : nullptr;
  r["contact_target"] = contact_ && target_.is_object() ? target_ : nullptr;
  r["past_contact_mm"] = contact_ ? nlohmann::ordered_json(Micro(past)) : nullptr;
  r["contact_class"] =
      contact_ ? nlohmann::ordered_json(past <= kGrazeMm + 1e-9 ? "graze" : "crash") : nullptr;
  r["min_clearance_mm"] =
      std::isfinite(min_clearance_) ? nlohmann::ordered_json(min_clearance_) : nullptr;
  double length = 0;
  for (size_t i = 1; i < (contact_ ? travelled_ : path_.size()); ++i)
    length +=
        std::hypot(path_[i].first - path_[i - 1].first, path_[i].second - path_[i - 1].second);
  r["path_length_mm"] = Micro(length);
  const double end = done_ ? t_end_ : t_now;
  r["repos_time_s"] = repos_phase_ ? Micro(end - t_start_) : 0.0;
  std::string error = error_;
  if (error.empty() && !done_)
    error = repos_phase_ ? std::string(manual_end_ ? "timeout: the jogs did not end"
                                                   : "timeout: no RTS of the REPOS subroutine") +
                               " within " + Fixed(plan.timeout_s) + " s"
                         : "timeout: the retract did not end";
  if (error.empty() && done_ && !manual_end_ && !subroutine_seen_)
    error = "the REPOS subroutine did not run";
  if (error.empty() && done_ && manual_end_ && !last_repos_.value("conditions_restored", false))
    error = "conditions not restored after the jogs (PxxS.CREST 0)";
  r["error_number"] = error_number_ ? nlohmann::ordered_json(error_number_) : nullptr;
  r["error"] = error.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(error);
  r["retract_contact"] = retract_contact_;
  auto& path = r["path"] = nlohmann::ordered_json::array();
  for (const auto& [x, z] : path_) path.push_back({Micro(x), Micro(z)});
  // No move at all: the tool stayed where the REPOS screen shows it.
  if (path_.empty() && have_command_) path.push_back({Micro(x_), Micro(z_)});
  return r;
}

void CaseObserver::End(double t) {
  if (done_) return;
  done_ = true;
  t_end_ = t;
  if (on_end_) on_end_();
}

}  // namespace vmt::sim::study
