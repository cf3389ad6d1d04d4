#include "sim/study/case_runner.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <stdexcept>
#include <unordered_map>

#include "common/json_text.hpp"
#include "common/mapped_file.hpp"
#include "control/nc/parser.hpp"
#include "sim/model/yaml_reader.hpp"
#include "sim/runner/runner.hpp"
#include "sim/scene/scene_steps.hpp"
#include "sim/study/case_files.hpp"
#include "sim/study/die_with_parent.hpp"

namespace vmt::sim::study {
namespace {

// The steps read so far for one machine, signal table, program list and axis list (the
// pointers held, so that their addresses name them while kept). Every case appends the same few
// lines (its retract's jogs and waits, the call, AUTO, start); read once in the worker (WarmSteps),
// a forked case only copies them, where reading them anew would also write across heap pages the
// case must then copy. A step's index only names it in its text.
struct ReadSteps {
  std::shared_ptr<const MachineModel> model;
  std::shared_ptr<const std::vector<control::gateway::Signal>> signals;
  std::vector<std::shared_ptr<const control::nc::ParseResult>> programs;
  std::vector<int> axis_drives;
  std::unordered_map<std::string, TimelineStep> by_line;  ///< read as timeline[0]
};

std::string StepName(size_t index) { return "timeline[" + std::to_string(index) + "]"; }

// The operator's steps are written as a scene would write them and read by the scene's own
// step reader: a case's timeline means what the same lines in a scene file mean.
TimelineStep Step(const Scene& scene, const std::string& yaml, size_t index) {
  static ReadSteps read;
  if (read.model != scene.model || read.signals != scene.nc.signals ||
      read.programs != scene.nc.programs || read.axis_drives != scene.nc.axis_drives)
    read = {scene.model, scene.nc.signals, scene.nc.programs, scene.nc.axis_drives, {}};
  auto it = read.by_line.find(yaml);
  if (it == read.by_line.end()) {
    const YamlNode n(YAML::Load(yaml), "study case", StepName(index));
    TimelineStep step = ReadStep(*scene.model, n, index, scene.nc, false);
    // A line at its own time (the feed hold, the switch to manual) serves one interruption
    // point: kept, it would grow the worker with every point it runs.
    if (yaml.starts_with("{at: ")) return step;
    TimelineStep first = step;
    first.text.replace(0, StepName(index).size(), StepName(0));
    read.by_line.emplace(yaml, std::move(first));
    return step;
  }
  TimelineStep step = it->second;
  step.text.replace(0, StepName(0).size(), StepName(index));
  return step;
}

std::string Fixed(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f", v);
  return buf;
}

// The latest simulated time a case may take: the retract's jogs (each waits at most 10 s for
// the NC's jog per direction it watches, 1 s for standstill), the REPOS phase its timeout.
double CaseLimit(const StudyPlan& plan, const Interruption& in, const RetractPattern& r) {
  double jogs_s = 0;
  for (const RetractJog& j : r.jogs) jogs_s += j.to ? 21.5 : 11.5;
  return in.t_s + plan.hold_s + jogs_s + 1 + plan.timeout_s;
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
  o.signal_events = CaseObserver::SignalRead;
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
  CaseObserver none;
  CaseResult r = none.Result(plan, interruptions, c, 0);
  r["verdict"] = "error";
  r["error"] = "the case's process died (wait status " + std::to_string(status) + ")";
  return r;
}

// A case whose run failed in the study's own process (run-ups kept in memory).
CaseResult FailedResult(const StudyPlan& plan, const std::vector<Interruption>& interruptions,
                        const StudyCase& c, const std::string& what) {
  CaseObserver none;
  CaseResult r = none.Result(plan, interruptions, c, 0);
  r["verdict"] = "error";
  r["error"] = "the case failed: " + what;
  return r;
}

}  // namespace

Scene SubroutineScene(const Scene& base, const Subroutine& subroutine) {
  return SubroutineScene(base, subroutine.file);
}

Scene SubroutineScene(const Scene& base, const std::string& subroutine_file) {
  Scene scene = base;
  if (!subroutine_file.empty()) {
    std::string why;
    const std::optional<common::MappedFile> text = common::MappedFile::Read(subroutine_file, &why);
    if (!text) throw std::runtime_error("cannot open NC program " + subroutine_file + ": " + why);
    namespace cnc = control::nc;
    auto parsed = std::make_shared<cnc::ParseResult>(
        cnc::ParseProgram(*text, subroutine_file, cnc::DetectDialect(*text, subroutine_file)));
    if (!parsed->ok())
      throw std::runtime_error(cnc::Format(parsed->errors[0], parsed->program.files));
    scene.nc.programs.push_back(parsed);
  }
  scene.expectations.clear();
  scene.snapshots.clear();
  // No trace rows between the first and the last: a case reads events only, and a row is
  // formatted (and hashed) even when nothing is written.
  scene.trace_period_s = 1e6;
  scene.timeline.clear();
  scene.timeline.push_back(Step(scene, "{nc: start}", 0));
  return scene;
}

namespace {
std::string HoldLine(double t_s) { return "{at: " + Fixed(t_s) + ", nc: stop}"; }
}  // namespace

TimelineStep HoldStep(const Scene& scene, double t_s, size_t index) {
  return Step(scene, HoldLine(t_s), index);
}

namespace {

// Until the NC's jog in `direction` (POS | NEG) is done (AxxS.MVPOS / MVNEG, its
// interpolation), then the drive: the drive's standstill window alone ends the wait before the
// increment's last tenths.
void WaitLines(const Scene& scene, const std::string& axis, const char* direction,
               std::vector<std::string>& lines, bool standstill = true) {
  int number = 0;
  for (const auto& a : scene.nc.data.axes)
    if (a.name == axis) number = a.number;
  char moving[16];
  std::snprintf(moving, sizeof moving, "A%02dS.MV%s", number, direction);
  lines.push_back(std::string("{wait_until: {signal: ") + moving + ", value: false, timeout: 10}}");
  if (standstill)
    lines.push_back("{wait_until: {axis: " + axis + ", standstill: true, timeout: 1}}");
}

// One incremental jog of `mm` (signed) on `axis`, and the waits until it is over.
void JogLines(const Scene& scene, const std::string& axis, double mm,
              std::vector<std::string>& lines) {
  // An increment once started is completed: a tap of the key moves exactly |mm|.
  lines.push_back("{nc: {jog_increment: " + Fixed(std::abs(mm)) + "}}");
  lines.push_back("{jog: {axis: " + axis + ", direction: " + (mm > 0 ? "'+'" : "'-'") +
                  ", hold: 0.05}}");
  WaitLines(scene, axis, mm > 0 ? "POS" : "NEG", lines);
}

// A jog to the drive position `to` ({jog: {axis, to}}: the increment is the distance from
// where the axis stands, so the direction is known only then: both directions' waits).
void JogToLines(const Scene& scene, const std::string& axis, double to,
                std::vector<std::string>& lines) {
  lines.push_back("{jog: {axis: " + axis + ", to: " + Fixed(to) + ", hold: 0.05}}");
  WaitLines(scene, axis, "POS", lines, false);
  WaitLines(scene, axis, "NEG", lines);
}

// The retract: manual mode, the jogs, and a short wait whose start marks that the retract is
// over (its step event), so that the modes can fork from there.
std::vector<std::string> RetractLines(const Scene& scene, const StudyPlan& plan,
                                      const Interruption& in, const RetractPattern& retract) {
  std::vector<std::string> lines;
  lines.push_back("{at: " + Fixed(in.t_s + plan.hold_s) + ", nc: {mode: manual}}");
  for (const RetractJog& j : retract.jogs) {
    if (j.to)
      JogToLines(scene, j.axis, *j.to, lines);
    else
      JogLines(scene, j.axis, j.mm, lines);
  }
  lines.push_back("{wait: 0.01}");
  return lines;
}

std::string CallLine(const Scene& scene, ReposMode mode) {
  char process[8];
  std::snprintf(process, sizeof process, "P%02dC", scene.nc.data.process.number);
  return std::string("{signal: {name: ") + process +
         (mode == ReposMode::kRepositioning ? ".REPOS" : ".RESTA") + ", value: true}}";
}

// REPOS or RESTA, AUTO, start: the last line is the start.
std::vector<std::string> ModeLines(const Scene& scene, ReposMode mode) {
  return {CallLine(scene, mode), "{wait: 0.1}", "{nc: {mode: automatic}}", "{nc: start}"};
}

// Manual mode (2.2, 3): the call in manual mode, then a wait long enough for the REPOS screen
// to show the targets; the operator's keys are chosen from it, after the last of these starts.
std::vector<std::string> ManualCallLines(const Scene& scene, ReposMode mode) {
  return {CallLine(scene, mode), "{wait: 0.1}", "{wait: 0.01}"};
}

// What the operator does with the REPOS screen `repos` in front of him: the spindle's key if
// it has the adjust symbol (3.3: M3 restores M03, M4 M04, M5 M05, M19 M19), then every axis of
// the order that has it, jogged toward its target by an increment beyond it -- the NC stops
// the axis at the target (3.2) -- and a last short wait, the case's end.
std::vector<std::string> ManualReturnLines(const Scene& scene, const Subroutine& order,
                                           const nlohmann::ordered_json& repos) {
  std::vector<std::string> lines;
  const nlohmann::ordered_json spindle = repos.value("spindle", nlohmann::ordered_json());
  if (spindle.is_object() && spindle.value("adjust", false)) {
    const int m = spindle.value("command_m", 5);
    char key[24];
    // The spindle's Axx as the gateway numbers it (sim/model/gateway_layout.cpp).
    int highest = 0;
    for (const auto& a : scene.model->nc.axes) highest = std::max(highest, a.number);
    const int number =
        scene.model->nc.spindle_number > 0 ? scene.model->nc.spindle_number : highest + 1;
    std::snprintf(key, sizeof key, "A%02dC.M%d", number, m);
    lines.push_back(std::string("{signal: {name: ") + key + ", value: true}}");
    lines.push_back("{wait: 0.5}");  // the spindle runs up before the tool comes back
  }
  const nlohmann::ordered_json axes = repos.value("axes", nlohmann::ordered_json::object());
  for (const std::string& axis : order.manual_order) {
    if (!axes.contains(axis) || !axes[axis].value("adjust", false)) continue;
    const double to_go = axes[axis].value("to_go", 0.0);
    if (to_go == 0) continue;
    const double beyond = std::ceil(std::abs(to_go)) + 1;
    JogLines(scene, axis, to_go > 0 ? beyond : -beyond, lines);
  }
  lines.push_back("{wait: 0.01}");
  return lines;
}
// `written`, when given, collects the lines: a saved case's timeline (case.yaml).
void Append(Scene& scene, const std::vector<std::string>& lines,
            std::vector<std::string>* written = nullptr) {
  for (const std::string& l : lines) {
    scene.timeline.push_back(Step(scene, l, scene.timeline.size()));
    if (written) written->push_back(l);
  }
}

// The way back of a case whose retract is appended (and perhaps run): the REPOS subroutine
// (the call, AUTO, start) or the operator's manual return; runs the case to its end. The same
// steps on the same ticks whether the case was forked or runs from the start.
void RunReturn(Scene& scene, SceneRun& run, CaseObserver& obs, const StudyPlan& plan,
               const Subroutine& way, ReposMode mode, double limit,
               std::vector<std::string>* written = nullptr) {
  if (!way.manual()) {
    const std::vector<std::string> lines = ModeLines(scene, mode);
    obs.SetPhaseStep(scene.timeline.size() + lines.size() - 2);  // the switch to AUTO
    Append(scene, lines, written);
    RunCase(run, obs, plan, limit);
    return;
  }
  obs.SetPhaseStep(scene.timeline.size());  // the call
  Append(scene, ManualCallLines(scene, mode), written);
  const size_t shown = scene.timeline.size() - 1;
  while (!run.done() && !obs.done() && !obs.step_seen(shown) && run.time_s() < limit) run.Step();
  if (!obs.done() && obs.step_seen(shown)) {
    Append(scene, ManualReturnLines(scene, way, obs.last_repos()), written);
    obs.SetManualEnd(scene.timeline.size() - 1);
  }
  RunCase(run, obs, plan, limit);
}

// Reads the lines every case of `way` appends (its retracts but for their start, the calls,
// AUTO, start), so that the forked cases find them read (Step).
void WarmSteps(const Scene& scene, const StudyPlan& plan, const Interruption& any,
               const Subroutine& way) {
  std::vector<std::string> lines;
  for (const RetractPattern& r : plan.retracts)
    for (const std::string& l : RetractLines(scene, plan, any, r)) lines.push_back(l);
  for (const ReposMode mode : plan.modes)
    for (const std::string& l :
         way.manual() ? ManualCallLines(scene, mode) : ModeLines(scene, mode))
      lines.push_back(l);
  for (const std::string& l : lines) (void)Step(scene, l, 0);
}

// Runs `work` in a forked child that writes result lines to the fd it gets; the lines, and in
// *status how the child ended.
std::vector<std::string> InChild(const std::function<void(int)>& work, int* status) {
  int fds[2];
  if (::pipe(fds) != 0) ::_exit(3);
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0) ::_exit(4);
  if (child == 0) {
    DieWithParent(parent);
    ::close(fds[0]);
    // A copy of the study process must never unwind into the study's own code.
    try {
      work(fds[1]);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "vmt study: a case failed: %s\n", e.what());
      std::fflush(stderr);
      ::_exit(5);
    }
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

// At the interruption, held: the retract the cases share, then each case's way back, a result
// line each to `emit` in the cases' order. Forked (`in_memory` false; in a child): every mode but
// the last runs in a grandchild of its own, the last runs on here (a crash in it is reported by
// the caller, as for a grandchild). In memory: each mode goes back to the end of the retract.
void RunRetractCases(Scene& scene, SceneRun& run, CaseObserver*& observer, const StudyPlan& plan,
                     const std::vector<Interruption>& interruptions, const Interruption& in,
                     size_t sub, std::span<const StudyCase> cases, const CaseWatch* watch,
                     bool in_memory, const std::function<void(const std::string&)>& emit) {
  const RetractPattern& retract = plan.retracts[cases.front().retract];
  Append(scene, RetractLines(scene, plan, in, retract));
  const size_t marker = scene.timeline.size() - 1;
  CaseObserver obs(CaseObserver::kNoStep, marker);
  observer = &obs;
  const double limit = CaseLimit(plan, in, retract);
  try {
    while (!run.done() && !obs.done() && !obs.marker_seen() && run.time_s() < limit) run.Step();
    for (int w = 0; w < 8 && obs.error_pending() && !run.done(); ++w) run.Step();
  } catch (const std::exception& e) {
    if (!in_memory) throw;  // the child's end tells
    for (const StudyCase& c : cases)
      emit(CaseJsonLine(FailedResult(plan, interruptions, c, e.what())));
    return;
  }
  // The case's result, seen by the watch, as its line.
  const auto result_line = [&](const StudyCase& c) {
    const CaseResult r = obs.Result(plan, interruptions, c, run.time_s());
    if (watch && watch->after) watch->after(run, c, r);
    return CaseJsonLine(r);
  };
  const auto way_back = [&](const StudyCase& c) {
    if (watch && watch->at_end) obs.SetOnEnd([&] { watch->at_end(run, c); });
    RunReturn(scene, run, obs, plan, plan.subroutines[sub], c.mode, limit);
    return result_line(c);
  };
  std::shared_ptr<const SavedRun> retracted;
  const size_t retract_steps = scene.timeline.size();
  const CaseObserver at_retracted = obs;
  if (in_memory && obs.marker_seen() && cases.size() > 1) retracted = run.Save();
  for (size_t m = 0; m < cases.size(); ++m) {
    const StudyCase& c = cases[m];
    if (!obs.marker_seen()) {  // the retract ended the case (a refused jog)
      emit(result_line(c));
      continue;
    }
    if (in_memory) {
      if (m > 0) {
        run.Restore(*retracted);
        scene.timeline.resize(retract_steps);
        obs = at_retracted;
      }
      std::string line;
      try {
        line = way_back(c);
      } catch (const std::exception& e) {  // the next mode goes back to the retract's end
        line = CaseJsonLine(FailedResult(plan, interruptions, c, e.what()));
      }
      emit(line);
      continue;
    }
    if (m + 1 == cases.size()) {
      emit(way_back(c));
      continue;
    }
    int mode_status = 0;
    const std::vector<std::string> one =
        InChild([&](int mode_fd) { WriteAll(mode_fd, way_back(c)); }, &mode_status);
    const bool ok = WIFEXITED(mode_status) && WEXITSTATUS(mode_status) == 0 && one.size() == 1;
    emit(ok ? one[0] + "\n" : CaseJsonLine(DiedResult(plan, interruptions, c, mode_status)));
  }
}

// Hands each result line read from `fd` to `sink` as it arrives, until the writer closes.
void ForwardResults(int fd, const std::function<void(const CaseResult&)>& sink) {
  std::string pending;
  char buf[4096];
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;) {
    pending.append(buf, static_cast<size_t>(n));
    for (size_t eol; (eol = pending.find('\n')) != std::string::npos;) {
      const CaseResult r = nlohmann::ordered_json::parse(pending.substr(0, eol), nullptr, false);
      pending.erase(0, eol + 1);
      if (!r.is_discarded()) sink(r);
    }
  }
}

// What the groups of one subroutine share: its scene (the run reads its timeline by reference;
// a group appends its steps and takes them back, or appends them in its own process), the run,
// and where the run's events go.
struct SubroutineRun {
  Scene& scene;
  SceneRun& run;
  CaseObserver*& observer;
  const StudyPlan& plan;
  const std::vector<Interruption>& interruptions;
  size_t sub;
  const CaseWatch* watch;
};

// A group's run stops a little before the step's time, so that the appended step runs on the
// same tick as in a run from the start (a step waits for its `at:`).
constexpr double kAhead = 0.002;

// The cases of one retract share it: `retract_cases` gets each retract's cases of `mine`.
void EachRetract(const std::vector<StudyCase>& mine,
                 const std::function<void(std::span<const StudyCase>)>& retract_cases) {
  for (size_t k = 0; k < mine.size();) {
    size_t end = k;
    while (end < mine.size() && mine[end].retract == mine[k].retract) ++end;
    retract_cases(std::span<const StudyCase>(mine.data() + k, end - k));
    k = end;
  }
}

// One interruption's cases in this process: the run is saved where it stands (a little before
// the interruption) and after the feed hold; each retract goes back to the held feed, and at the
// end the run goes back to where it stood, for the next interruption.
void RunGroupInMemory(const SubroutineRun& s, const Interruption& in,
                      const std::vector<StudyCase>& mine,
                      const std::function<void(const CaseResult&)>& sink) {
  const size_t run_up_steps = s.scene.timeline.size();
  const std::shared_ptr<const SavedRun> run_up = s.run.Save();
  s.scene.timeline.push_back(HoldStep(s.scene, in.t_s, s.scene.timeline.size()));
  while (!s.run.done() && s.run.time_s() < in.t_s + s.plan.hold_s - kAhead) s.run.Step();
  const size_t held_steps = s.scene.timeline.size();
  const std::shared_ptr<const SavedRun> held = s.run.Save();
  bool first = true;
  EachRetract(mine, [&](std::span<const StudyCase> cases) {
    if (!first) {
      s.run.Restore(*held);
      s.scene.timeline.resize(held_steps);
    }
    first = false;
    RunRetractCases(s.scene, s.run, s.observer, s.plan, s.interruptions, in, s.sub, cases, s.watch,
                    true,
                    [&](const std::string& line) { sink(nlohmann::ordered_json::parse(line)); });
  });
  s.observer = nullptr;
  s.run.Restore(*run_up);
  s.scene.timeline.resize(run_up_steps);
}

// One interruption's cases forked: a child holds the feed, a child of it per retract runs the
// retract, a grandchild per mode (RunRetractCases). The results come back a line each through a
// pipe, so that `sink` runs here; the run here stays where it stands.
void RunGroupForked(const SubroutineRun& s, const Interruption& in,
                    const std::vector<StudyCase>& mine,
                    const std::function<void(const CaseResult&)>& sink) {
  int lines[2];
  if (::pipe(lines) != 0) throw std::runtime_error("pipe failed");
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  const pid_t group = ::fork();
  if (group < 0) throw std::runtime_error("fork failed");
  if (group == 0) {
    DieWithParent(parent);
    ::close(lines[0]);
    s.scene.timeline.push_back(HoldStep(s.scene, in.t_s, s.scene.timeline.size()));
    while (!s.run.done() && s.run.time_s() < in.t_s + s.plan.hold_s - kAhead) s.run.Step();
    EachRetract(mine, [&](std::span<const StudyCase> cases) {
      int status = 0;
      const std::vector<std::string> got = InChild(
          [&](int fd) {
            RunRetractCases(s.scene, s.run, s.observer, s.plan, s.interruptions, in, s.sub, cases,
                            s.watch, false, [fd](const std::string& line) { WriteAll(fd, line); });
          },
          &status);
      for (size_t m = 0; m < cases.size(); ++m) {
        const StudyCase& c = cases[m];
        CaseResult r = m < got.size() ? nlohmann::ordered_json::parse(got[m], nullptr, false)
                                      : nlohmann::ordered_json();
        if (r.is_discarded() || !r.is_object() || r.value("case", "") != c.id)
          r = DiedResult(s.plan, s.interruptions, c, status);
        WriteAll(lines[1], CaseJsonLine(r));
      }
    });
    ::_exit(0);
  }
  ::close(lines[1]);
  ForwardResults(lines[0], sink);
  ::close(lines[0]);
  int status = 0;
  ::waitpid(group, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("a study process at " + in.label + " died (wait status " +
                             std::to_string(status) + ")");
}

}  // namespace

void RunSubroutineCases(const Scene& base, const StudyPlan& plan,
                        const std::vector<Interruption>& interruptions, size_t sub,
                        const std::function<bool(const StudyCase&)>& chosen, RunUpSharing sharing,
                        const std::function<void(const CaseResult&)>& sink,
                        const CaseWatch* watch) {
  // Made group by group, so that a worker holds one group's cases, not its share's.
  const CaseSpace space(plan, interruptions);
  const auto group_at = [&](size_t i) {
    std::vector<StudyCase> group;
    for (size_t r = 0; r < plan.retracts.size(); ++r)
      for (size_t m = 0; m < plan.modes.size(); ++m)
        if (StudyCase c = space.At(space.Index(sub, i, r, m)); chosen(c))
          group.push_back(std::move(c));
    return group;
  };
  std::vector<size_t> order(interruptions.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return interruptions[a].t_s < interruptions[b].t_s; });
  if (std::none_of(order.begin(), order.end(), [&](size_t i) { return !group_at(i).empty(); }))
    return;
  if (sharing == RunUpSharing::kNone) {
    for (const size_t i : order)
      for (const StudyCase& c : group_at(i))
        sink(RunCaseFromStart(base, plan, interruptions, c, watch));
    return;
  }
  Scene scene = SubroutineScene(base, plan.subroutines[sub]);
  CaseObserver* observer = nullptr;
  SceneRun run(scene, CaseOptions(&observer));
  WarmSteps(scene, plan, interruptions[order.front()], plan.subroutines[sub]);
  const SubroutineRun s{scene, run, observer, plan, interruptions, sub, watch};
  for (const size_t i : order) {
    const std::vector<StudyCase> mine = group_at(i);
    if (mine.empty()) continue;
    const Interruption& in = interruptions[i];
    while (!run.done() && run.time_s() < in.t_s - kAhead) run.Step();
    if (sharing == RunUpSharing::kMemory)
      RunGroupInMemory(s, in, mine, sink);
    else
      RunGroupForked(s, in, mine, sink);
  }
}

CaseResult RunCaseFromStart(const Scene& base, const StudyPlan& plan,
                            const std::vector<Interruption>& interruptions, const StudyCase& c,
                            const CaseWatch* watch) {
  Scene scene = SubroutineScene(base, plan.subroutines[c.subroutine]);
  const Interruption& in = interruptions[c.interruption];
  const RetractPattern& retract = plan.retracts[c.retract];
  scene.timeline.push_back(HoldStep(scene, in.t_s, scene.timeline.size()));
  Append(scene, RetractLines(scene, plan, in, retract));
  CaseObserver obs;
  CaseObserver* observer = &obs;
  SceneRun run(scene, CaseOptions(&observer));
  if (watch && watch->at_end) obs.SetOnEnd([&] { watch->at_end(run, c); });
  RunReturn(scene, run, obs, plan, plan.subroutines[c.subroutine], c.mode,
            CaseLimit(plan, in, retract));
  const CaseResult r = obs.Result(plan, interruptions, c, run.time_s());
  if (watch && watch->after) watch->after(run, c, r);
  return r;
}

SavedCase SaveCaseRun(const Scene& base, const StudyPlan& plan,
                      const std::vector<Interruption>& interruptions, const StudyCase& c,
                      const std::string& out_dir) {
  const Subroutine& way = plan.subroutines[c.subroutine];
  Scene scene = SubroutineScene(base, way);
  scene.trace_period_s = base.trace_period_s;  // watched, so traced as the scene is
  const Interruption& in = interruptions[c.interruption];
  const RetractPattern& retract = plan.retracts[c.retract];
  SavedCase saved;
  Append(scene, {HoldLine(in.t_s)}, &saved.timeline);
  Append(scene, RetractLines(scene, plan, in, retract), &saved.timeline);
  CaseObserver obs;
  CaseObserver* observer = &obs;
  RunOptions options = CaseOptions(&observer);
  options.out_dir = out_dir;
  SceneRun run(scene, options);
  RunReturn(scene, run, obs, plan, way, c.mode, CaseLimit(plan, in, retract), &saved.timeline);
  saved.result = obs.Result(plan, interruptions, c, run.time_s());
  saved.subroutine_file = way.file;
  saved.until_s = run.time_s();
  const RunResult r = run.Finish();
  if (!r.write_errors.empty()) throw std::runtime_error(r.write_errors.front());
  saved.trace_digest = r.trace_digest;
  return saved;
}

Scene SavedCaseScene(const Scene& base, const SavedCase& saved) {
  Scene scene = SubroutineScene(base, saved.subroutine_file);
  scene.trace_period_s = base.trace_period_s;
  Append(scene, saved.timeline);
  return scene;
}

}  // namespace vmt::sim::study
