#pragma once
// What a case's events say (the runner's on_event stream): where the REPOS phase starts, the
// PathGuard checks of its moves (the first contact, the smallest clearance, and the approach
// path corner by corner from their records), the NC's error, and when the case is over -- at
// the REPOS subroutine's RTS (program-driven, 4.1) or at the end of the operator's jogs (3).

#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "sim/study/study_cases.hpp"

namespace vmt::sim::study {

/// The case's result line (cases.jsonl): id, interruption, retract, mode, verdict (collision |
/// clear | error | retract_refused), the first contact's parts, point (model frame) and axis
/// positions, its severity (past_contact_mm, contact_class graze | crash), the smallest
/// clearance of the REPOS moves, the approach path (X, Z axis positions, machine coordinates)
/// and its length, the simulated time of the REPOS phase.
using CaseResult = nlohmann::ordered_json;

/// A contact this close to the refused move's end (mm) is a graze, farther a crash.
constexpr double kGrazeMm = 0.1;

/// The distance of the axes from `position` (the first contact) to `target` (the refused
/// move's end), over the axes `target` names that `position` has: how far the move would have
/// gone on into the part.
double PastContact(const nlohmann::ordered_json& position, const nlohmann::ordered_json& target);

class CaseObserver {
 public:
  /// `phase_step`: the timeline step whose start begins the REPOS phase (program-driven: the
  /// switch to AUTO before the start, because a step's event comes after the channel's events
  /// of its tick; manual: the call of the function). `marker`: the step whose start ends the
  /// retract (0: none watched).
  static constexpr size_t kNoStep = static_cast<size_t>(-1);
  explicit CaseObserver(size_t phase_step = kNoStep, size_t marker = 0)
      : phase_step_(phase_step), marker_(marker) {}

  void SetPhaseStep(size_t step) { phase_step_ = step; }
  /// Manual mode: the case is over when this step starts (after the last jog's standstill);
  /// clear if the conditions are restored then (PxxS.CREST, 7.3).
  void SetManualEnd(size_t step) { manual_end_ = step; }
  /// Called once, inside the tick the case ends in (before the machine steps on).
  void SetOnEnd(std::function<void()> on_end) { on_end_ = std::move(on_end); }
  void OnEvent(const nlohmann::ordered_json& e);
  /// The gateway signals whose events OnEvent reads (RunOptions::signal_events): the NC's
  /// message number.
  static bool SignalRead(const std::string& name) { return name.ends_with("S.ERRNR"); }

  bool done() const { return done_; }
  bool step_seen(size_t step) const { return steps_seen_ > step; }
  bool marker_seen() const { return marker_ && step_seen(marker_); }
  bool error_pending() const { return !error_.empty() && error_number_ == 0; }
  bool repos_phase() const { return repos_phase_; }
  double t_start() const { return t_start_; }
  /// When the case ended (RTS, the last jog's end, an NC error); 0 while it runs.
  double t_end() const { return done_ ? t_end_ : 0; }
  /// The latest `repos` event (the REPOS screen: targets, distances to go, the spindle).
  const nlohmann::ordered_json& last_repos() const { return last_repos_; }

  CaseResult Result(const StudyPlan& plan, const std::vector<Interruption>& interruptions,
                    const StudyCase& c, double t_now) const;

 private:
  void End(double t);
  /// A PathGuard record of the REPOS phase onto the path: where its move starts, and (`whole`:
  /// a clear one) where it ends.
  void AddMove(const nlohmann::ordered_json& e, bool whole = true);

  size_t phase_step_, marker_;
  size_t manual_end_ = 0;  // 0: program-driven
  size_t steps_seen_ = 0;  // one past the highest timeline step started
  bool repos_phase_ = false, subroutine_seen_ = false, done_ = false, contact_ = false;
  bool have_command_ = false;
  double t_start_ = 0, t_end_ = 0, x_ = 0, z_ = 0;
  double min_clearance_ = std::numeric_limits<double>::infinity();
  nlohmann::ordered_json parts_, point_, position_, target_, retract_contact_, last_repos_;
  std::string move_;  ///< the refused move's kind (jog, G77)
  std::string error_;
  int error_number_ = 0;
  std::vector<std::pair<double, double>> path_;
  size_t travelled_ = 0;  ///< with a contact: the path's points up to the refused move's start
  std::function<void()> on_end_;
};

}  // namespace vmt::sim::study
