#include "sim/study/case_runner.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "control/nc/parser.hpp"
#include "sim/model/yaml_reader.hpp"
#include "sim/runner/runner.hpp"
#include "sim/scene/scene_steps.hpp"

namespace vmt::sim::study {
namespace {

// The operator's steps are written as a scene would write them and read by the scene's own
// step reader: a case's timeline means what the same lines in a scene file mean.
TimelineStep Step(const Scene& scene, const std::string& yaml, size_t index) {
  const YamlNode n(YAML::Load(yaml), "study case", "timeline[" + std::to_string(index) + "]");
  return ReadStep(*scene.model, n, index, scene.nc, false);
}

std::string Fixed(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f", v);
  return buf;
}

double Micro(double v) { return std::round(v * 1000) / 1000 + 0.0; }

// What a case's events say: the REPOS phase starts with the final start in AUTO; the case ends
// at the REPOS subroutine's RTS (the REPOS screen's subroutine flag falls) or an NC error.
class CaseObserver {
 public:
  /// `start_index`: the final start's step. The phase is marked one step before it, at the
  /// switch to AUTO: a step's event comes after the channel's events of its tick.
  /// `marker`: the step whose start ends the retract (0: none watched).
  explicit CaseObserver(size_t start_index, size_t marker = 0)
      : start_prefix_("timeline[" + std::to_string(start_index - 1) + "]"),
        marker_prefix_(marker ? "timeline[" + std::to_string(marker) + "]" : "") {}

  void OnEvent(const nlohmann::ordered_json& e) {
    const std::string kind = e.value("event", "");
    const double t = e.value("t", 0.0);
    if (kind == "signal" && e.value("name", "").ends_with("S.ERRNR")) {
      error_number_ = static_cast<int>(e.value("value", 0.0));  // the message's number (507)
      return;
    }
    if (done_) return;  // only the message number may still come (the gateway's next cycle)
    if (kind == "step" && !marker_prefix_.empty() &&
        e.value("text", "").starts_with(marker_prefix_))
      marker_seen_ = true;
    if (kind == "step" && e.value("text", "").starts_with(start_prefix_)) {
      repos_phase_ = true;
      t_start_ = t;
      if (have_command_) path_.emplace_back(x_, z_);
    } else if (kind == "repos") {
      if (e.contains("axes")) {
        const auto& axes = e["axes"];
        if (axes.contains("X")) x_ = axes["X"].value("command", x_);
        if (axes.contains("Z")) z_ = axes["Z"].value("command", z_);
        have_command_ = true;
        if (repos_phase_ && !contact_ &&
            (path_.empty() || path_.back() != std::make_pair(x_, z_)))
          path_.emplace_back(x_, z_);
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
      } else if (!contact_) {
        contact_ = true;
        parts_ = e["parts"];
        point_ = e["point"];
        position_ = e["position"];
        // Where the move would have touched, on the drawing's axes.
        if (position_.is_object()) {
          const double cx = position_.contains("X") ? position_["X"].get<double>() : x_;
          const double cz = position_.contains("Z") ? position_["Z"].get<double>() : z_;
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

  bool done() const { return done_; }
  bool marker_seen() const { return marker_seen_; }
  bool error_pending() const { return !error_.empty() && error_number_ == 0; }
  bool repos_phase() const { return repos_phase_; }
  double t_start() const { return t_start_; }

  CaseResult Result(const StudyPlan& plan, const std::vector<Interruption>& interruptions,
                    const StudyCase& c, double t_now) const {
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
    else if (!error_.empty() || !done_ || !subroutine_seen_)
      verdict = "error";
    r["verdict"] = verdict;
    r["parts"] = contact_ ? parts_ : nullptr;
    r["point"] = contact_ ? point_ : nullptr;
    r["contact_position"] = contact_ ? position_ : nullptr;
    r["min_clearance_mm"] = std::isfinite(min_clearance_) ? nlohmann::ordered_json(min_clearance_)
                                                          : nullptr;
    double length = 0;
    for (size_t i = 1; i < path_.size(); ++i)
      length += std::hypot(path_[i].first - path_[i - 1].first,
                           path_[i].second - path_[i - 1].second);
    if (contact_) length = 0;  // the move was checked whole and never started
    r["path_length_mm"] = Micro(length);
    const double end = done_ ? t_end_ : t_now;
    r["repos_time_s"] = repos_phase_ ? Micro(end - t_start_) : 0.0;
    std::string error = error_;
    if (error.empty() && !done_)
      error = repos_phase_ ? "timeout: no RTS of the REPOS subroutine within " +
                                 Fixed(plan.timeout_s) + " s"
                           : "timeout: the retract did not end";
    if (error.empty() && done_ && !subroutine_seen_) error = "the REPOS subroutine did not run";
    r["error_number"] = error_number_ ? nlohmann::ordered_json(error_number_) : nullptr;
    r["error"] = error.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(error);
    r["retract_contact"] = retract_contact_;
    auto& path = r["path"] = nlohmann::ordered_json::array();
    for (const auto& [x, z] : path_) path.push_back({Micro(x), Micro(z)});
    return r;
  }

 private:
  void End(double t) {
    if (done_) return;
    done_ = true;
    t_end_ = t;
  }

  std::string start_prefix_, marker_prefix_;
  bool marker_seen_ = false;
  bool repos_phase_ = false, subroutine_seen_ = false, done_ = false, contact_ = false;
  bool have_command_ = false;
  double t_start_ = 0, t_end_ = 0, x_ = 0, z_ = 0;
  double min_clearance_ = std::numeric_limits<double>::infinity();
  nlohmann::ordered_json parts_, point_, position_, retract_contact_;
  std::string error_;
  int error_number_ = 0;
  std::vector<std::pair<double, double>> path_;
};

// The latest simulated time a case may take: the retract's jogs (each waits for standstill at
// most 10 s), the REPOS phase its timeout.
double CaseLimit(const StudyPlan& plan, const Interruption& in, const RetractPattern& r) {
  return in.t_s + plan.hold_s + 11.5 * static_cast<double>(r.jogs.size()) + 1 + plan.timeout_s;
}

void RunCase(SceneRun& run, CaseObserver& obs, const StudyPlan& plan, double limit_s) {
  while (!run.done() && !obs.done() && run.time_s() < limit_s &&
         !(obs.repos_phase() && run.time_s() > obs.t_start() + plan.timeout_s))
    run.Step();
  // An NC error shows its number (PxxS.ERRNR) at the gateway's next NC cycle.
  for (int k = 0; k < 8 && obs.error_pending() && !run.done(); ++k) run.Step();
}

RunOptions CaseOptions(CaseObserver** observer) {
  RunOptions o;
  o.backend = BackendKind::kKinematic;
  o.snapshots = false;
  o.until_s = 1e6;  // the case ends on its own condition, not the scene's duration
  o.on_event = [observer](const nlohmann::ordered_json& e) {
    if (*observer) (*observer)->OnEvent(e);
  };
  return o;
}

void WriteAll(int fd, const std::string& s) {
  size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n <= 0) return;
    done += static_cast<size_t>(n);
  }
}

std::string ReadAll(int fd) {
  std::string s;
  char buf[4096];
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;) s.append(buf, static_cast<size_t>(n));
  return s;
}

CaseResult DiedResult(const StudyPlan& plan, const std::vector<Interruption>& interruptions,
                      const StudyCase& c, int status) {
  CaseObserver none(1);
  CaseResult r = none.Result(plan, interruptions, c, 0);
  r["verdict"] = "error";
  r["error"] = "the case's process died (wait status " + std::to_string(status) + ")";
  return r;
}

}  // namespace

Scene SubroutineScene(const Scene& base, const Subroutine& subroutine) {
  Scene scene = base;
  std::ifstream in(subroutine.file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open NC program " + subroutine.file);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  namespace cnc = control::nc;
  auto parsed = std::make_shared<cnc::ParseResult>(
      cnc::ParseProgram(text, subroutine.file, cnc::DetectDialect(text, subroutine.file)));
  if (!parsed->ok())
    throw std::runtime_error(cnc::Format(parsed->errors[0], parsed->program.files));
  scene.nc.programs.push_back(parsed);
  scene.expectations.clear();
  scene.snapshots.clear();
  // No trace rows between the first and the last: a case reads events only, and a row is
  // formatted (and hashed) even when nothing is written.
  scene.trace_period_s = 1e6;
  scene.timeline.clear();
  scene.timeline.push_back(Step(scene, "{nc: start}", 0));
  return scene;
}

TimelineStep HoldStep(const Scene& scene, double t_s, size_t index) {
  return Step(scene, "{at: " + Fixed(t_s) + ", nc: stop}", index);
}

namespace {

// The retract: manual mode, the jogs, and a short wait whose start marks that the retract is
// over (its step event), so that the modes can fork from there.
std::vector<std::string> RetractLines(const Scene& scene, const StudyPlan& plan,
                                      const Interruption& in, const RetractPattern& retract) {
  std::vector<std::string> lines;
  lines.push_back("{at: " + Fixed(in.t_s + plan.hold_s) + ", nc: {mode: manual}}");
  for (const RetractJog& j : retract.jogs) {
    // An increment once started is completed: a tap of the key moves exactly |mm|.
    lines.push_back("{nc: {jog_increment: " + Fixed(std::abs(j.mm)) + "}}");
    lines.push_back("{jog: {axis: " + j.axis + ", direction: " + (j.mm > 0 ? "'+'" : "'-'") +
                    ", hold: 0.05}}");
    // Until the NC's jog is done (AxxS.MVPOS / MVNEG, its interpolation), then the drive: the
    // drive's standstill window alone ends the wait before the increment's last tenths.
    int number = 0;
    for (const auto& a : scene.nc.data.axes)
      if (a.name == j.axis) number = a.number;
    char moving[16];
    std::snprintf(moving, sizeof moving, "A%02dS.MV%s", number, j.mm > 0 ? "POS" : "NEG");
    lines.push_back(std::string("{wait_until: {signal: ") + moving +
                    ", value: false, timeout: 10}}");
    lines.push_back("{wait_until: {axis: " + j.axis + ", standstill: true, timeout: 1}}");
  }
  lines.push_back("{wait: 0.01}");
  return lines;
}

// REPOS or RESTA, AUTO, start: the last line is the start.
std::vector<std::string> ModeLines(const Scene& scene, ReposMode mode) {
  char process[8];
  std::snprintf(process, sizeof process, "P%02dC", scene.nc.data.process.number);
  return {std::string("{signal: {name: ") + process +
              (mode == ReposMode::kRepositioning ? ".REPOS" : ".RESTA") + ", value: true}}",
          "{wait: 0.1}", "{nc: {mode: automatic}}", "{nc: start}"};
}

void Append(Scene& scene, const std::vector<std::string>& lines) {
  for (const std::string& l : lines)
    scene.timeline.push_back(Step(scene, l, scene.timeline.size()));
}

// Runs `work` in a forked child that writes result lines to the fd it gets; the lines, and in
// *status how the child ended.
std::vector<std::string> InChild(const std::function<void(int)>& work, int* status) {
  int fds[2];
  if (::pipe(fds) != 0) ::_exit(3);
  std::fflush(nullptr);
  const pid_t child = ::fork();
  if (child < 0) ::_exit(4);
  if (child == 0) {
    ::close(fds[0]);
    work(fds[1]);
    ::_exit(0);
  }
  ::close(fds[1]);
  const std::string text = ReadAll(fds[0]);
  ::close(fds[0]);
  ::waitpid(child, status, 0);
  std::vector<std::string> lines;
  size_t begin = 0;
  for (size_t end; (end = text.find('\n', begin)) != std::string::npos; begin = end + 1)
    lines.push_back(text.substr(begin, end - begin));
  return lines;
}

}  // namespace

std::vector<TimelineStep> OperatorSteps(const Scene& scene, const StudyPlan& plan,
                                        const Interruption& in, const RetractPattern& retract,
                                        ReposMode mode, size_t first, size_t* start_index) {
  std::vector<std::string> lines = RetractLines(scene, plan, in, retract);
  for (const std::string& l : ModeLines(scene, mode)) lines.push_back(l);
  std::vector<TimelineStep> steps;
  for (size_t k = 0; k < lines.size(); ++k) steps.push_back(Step(scene, lines[k], first + k));
  *start_index = first + lines.size() - 1;
  return steps;
}

void RunSubroutineCases(const Scene& base, const StudyPlan& plan,
                        const std::vector<Interruption>& interruptions,
                        const std::vector<StudyCase>& cases, size_t sub, bool fork,
                        const std::function<void(const CaseResult&)>& sink) {
  std::vector<const StudyCase*> mine;
  for (const StudyCase& c : cases)
    if (c.subroutine == sub) mine.push_back(&c);
  if (mine.empty()) return;
  std::stable_sort(mine.begin(), mine.end(), [&](const StudyCase* a, const StudyCase* b) {
    return interruptions[a->interruption].t_s < interruptions[b->interruption].t_s;
  });
  if (!fork) {
    for (const StudyCase* c : mine) sink(RunCaseFromStart(base, plan, interruptions, *c));
    return;
  }
  // The scene lives here; the run reads its timeline by reference, and each child appends to
  // its own copy of it.
  Scene scene = SubroutineScene(base, plan.subroutines[sub]);
  CaseObserver* observer = nullptr;
  SceneRun run(scene, CaseOptions(&observer));
  // Forks a little before the step's time, so that the appended step runs on the same tick as
  // in a run from the start (a step waits for its `at:`).
  constexpr double kAhead = 0.002;
  for (size_t first = 0; first < mine.size();) {
    const Interruption& in = interruptions[mine[first]->interruption];
    size_t last = first;
    while (last < mine.size() && mine[last]->interruption == mine[first]->interruption) ++last;
    while (!run.done() && run.time_s() < in.t_s - kAhead) run.Step();
    // The group's results come back a line each through a pipe, so that `sink` runs here.
    int lines[2];
    if (::pipe(lines) != 0) throw std::runtime_error("pipe failed");
    std::fflush(nullptr);
    const pid_t group = ::fork();
    if (group < 0) throw std::runtime_error("fork failed");
    if (group == 0) {
      ::close(lines[0]);
      scene.timeline.push_back(HoldStep(scene, in.t_s, scene.timeline.size()));
      while (!run.done() && run.time_s() < in.t_s + plan.hold_s - kAhead) run.Step();
      // The cases of one retract share it: a child per retract runs it, a grandchild per mode.
      for (size_t k = first; k < last;) {
        const RetractPattern& retract = plan.retracts[mine[k]->retract];
        size_t end = k;
        while (end < last && mine[end]->retract == mine[k]->retract) ++end;
        int status = 0;
        const std::vector<std::string> got = InChild(
            [&](int fd) {
              Append(scene, RetractLines(scene, plan, in, retract));
              const size_t marker = scene.timeline.size() - 1;
              const size_t start_index = marker + ModeLines(scene, ReposMode::kRestart).size();
              CaseObserver obs(start_index, marker);
              observer = &obs;
              const double limit = CaseLimit(plan, in, retract);
              while (!run.done() && !obs.done() && !obs.marker_seen() && run.time_s() < limit)
                run.Step();
              for (int w = 0; w < 8 && obs.error_pending() && !run.done(); ++w) run.Step();
              for (size_t m = k; m < end; ++m) {
                const StudyCase& c = *mine[m];
                if (!obs.marker_seen()) {  // the retract ended the case (a refused jog)
                  WriteAll(fd, obs.Result(plan, interruptions, c, run.time_s()).dump() + "\n");
                  continue;
                }
                int mode_status = 0;
                const std::vector<std::string> one = InChild(
                    [&](int mode_fd) {
                      Append(scene, ModeLines(scene, c.mode));
                      RunCase(run, obs, plan, limit);
                      WriteAll(mode_fd,
                               obs.Result(plan, interruptions, c, run.time_s()).dump() + "\n");
                    },
                    &mode_status);
                const bool ok = WIFEXITED(mode_status) && WEXITSTATUS(mode_status) == 0 &&
                                one.size() == 1;
                WriteAll(fd, (ok ? one[0]
                                 : DiedResult(plan, interruptions, c, mode_status).dump()) +
                                 "\n");
              }
            },
            &status);
        for (size_t m = k; m < end; ++m) {
          const StudyCase& c = *mine[m];
          CaseResult r = m - k < got.size()
                             ? nlohmann::ordered_json::parse(got[m - k], nullptr, false)
                             : nlohmann::ordered_json();
          if (r.is_discarded() || !r.is_object() || r.value("case", "") != c.id)
            r = DiedResult(plan, interruptions, c, status);
          WriteAll(lines[1], r.dump() + "\n");
        }
        k = end;
      }
      ::_exit(0);
    }
    ::close(lines[1]);
    std::string pending;
    char buf[4096];
    for (ssize_t n; (n = ::read(lines[0], buf, sizeof buf)) > 0;) {
      pending.append(buf, static_cast<size_t>(n));
      for (size_t eol; (eol = pending.find('\n')) != std::string::npos;) {
        const CaseResult r = nlohmann::ordered_json::parse(pending.substr(0, eol), nullptr, false);
        pending.erase(0, eol + 1);
        if (!r.is_discarded()) sink(r);
      }
    }
    ::close(lines[0]);
    int status = 0;
    ::waitpid(group, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
      throw std::runtime_error("a study process at " + in.label + " died (wait status " +
                               std::to_string(status) + ")");
    first = last;
  }
}

CaseResult RunCaseFromStart(const Scene& base, const StudyPlan& plan,
                            const std::vector<Interruption>& interruptions, const StudyCase& c) {
  Scene scene = SubroutineScene(base, plan.subroutines[c.subroutine]);
  const Interruption& in = interruptions[c.interruption];
  scene.timeline.push_back(HoldStep(scene, in.t_s, scene.timeline.size()));
  size_t start_index = 0;
  for (TimelineStep& s : OperatorSteps(scene, plan, in, plan.retracts[c.retract], c.mode,
                                       scene.timeline.size(), &start_index))
    scene.timeline.push_back(std::move(s));
  CaseObserver obs(start_index);
  CaseObserver* observer = &obs;
  SceneRun run(scene, CaseOptions(&observer));
  RunCase(run, obs, plan, CaseLimit(plan, in, plan.retracts[c.retract]));
  return obs.Result(plan, interruptions, c, run.time_s());
}

}  // namespace vmt::sim::study
