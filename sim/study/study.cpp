#include "sim/study/study.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <thread>

#include "common/output_file.hpp"
#include "sim/study/case_files.hpp"
#include "sim/study/case_merge.hpp"
#include "sim/study/case_replay.hpp"
#include "sim/study/case_snapshots.hpp"
#include "sim/study/die_with_parent.hpp"
#include "sim/study/scratch_folder.hpp"
#include "sim/study/study_conclusions.hpp"
#include "sim/study/study_report.hpp"
#include "sim/study/study_source.hpp"

namespace vmt::sim::study {
namespace {

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// The reference run is the scene's alone: a rerun (or another shard) in the folder reuses it.
Reference LoadOrRunReference(const Scene& scene, const std::string& dir,
                             const std::function<bool()>& stop) {
  const std::string file = dir + "/reference.json";
  if (std::filesystem::exists(file)) {
    try {
      return ReferenceFromJson(ReadText(file));
    } catch (const std::exception&) {  // torn: run it again
    }
  }
  const Reference ref = [&] {
    const ScratchFolder work(dir + "/.reference-" + std::to_string(::getpid()));
    return RunReference(scene, work.path(), stop);
  }();
  common::WriteFileAtomically(file, ReferenceJson(ref));
  return ref;
}

size_t CountLines(const std::string& path) {
  const std::string text = ReadText(path);
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

void Bar(size_t done, size_t total, double wall_s) {
  const int width = 40;
  const int filled = total ? static_cast<int>(width * done / total) : width;
  const double rate = wall_s > 0 ? done / wall_s * 60 : 0;
  std::fprintf(stderr, "\r[%s%s] %zu/%zu cases, %.0f/min ", std::string(filled, '#').c_str(),
               std::string(width - filled, '.').c_str(), done, total, rate);
  std::fflush(stderr);
}

std::string Tally(const std::map<std::string, ClassCount>& by) {
  std::string s;
  for (const auto& [sub, c] : by)
    s += sub + ": " + std::to_string(c.cases) + " cases, " + std::to_string(c.clear) + " clear, " +
         std::to_string(c.crash + c.graze) + " collisions (" + std::to_string(c.crash) +
         " crashes, " + std::to_string(c.graze) + " grazes), " + std::to_string(c.error) +
         " errors, " + std::to_string(c.retract_refused) + " retract refused\n";
  return s;
}

// The CPU time of this process and its waited-for children (forked workers and cases).
double CpuSeconds() {
  double seconds = 0;
  for (const int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
    rusage u{};
    ::getrusage(who, &u);
    seconds += static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
               static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
  }
  return seconds;
}

// SIGINT and SIGTERM held back while it lives: a worker writes a case's lines whole, and a
// worker forked now takes the default action on them before one can reach it.
class StopSignalsHeld {
 public:
  StopSignalsHeld() {
    sigset_t stops;
    sigemptyset(&stops);
    sigaddset(&stops, SIGINT);
    sigaddset(&stops, SIGTERM);
    ::sigprocmask(SIG_BLOCK, &stops, &before_);
  }
  StopSignalsHeld(const StopSignalsHeld&) = delete;
  StopSignalsHeld& operator=(const StopSignalsHeld&) = delete;
  ~StopSignalsHeld() { ::sigprocmask(SIG_SETMASK, &before_, nullptr); }

 private:
  sigset_t before_{};
};

struct WorkersEnd {
  bool failed = false;  ///< a worker failed (not one ended because the study stopped)
  std::string stopped;  ///< the stop's reason when the workers were ended for it
};

// A worker: its share of `todo` (whole groups), each result appended to the case files. It
// ends on SIGINT or SIGTERM at once (the default action), between two writes.
[[noreturn]] void Worker(const StudyOptions& o, int w, const Scene& scene, const StudyPlan& plan,
                         const std::vector<Interruption>& interruptions,
                         const std::vector<bool>& todo, const std::vector<int>& worker_of) {
  int code = 0;
  try {
    CaseFiles files(o.out_dir);
    const auto mine = [&](const StudyCase& c) { return todo[c.index] && worker_of[c.group] == w; };
    for (size_t s = 0; s < plan.subroutines.size(); ++s)
      RunSubroutineCases(scene, plan, interruptions, s, mine, o.run_ups, [&](const CaseResult& r) {
        const StopSignalsHeld whole_lines;
        files.Write(r);
      });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vmt study: worker %d: %s\n", w, e.what());
    code = 1;
  }
  std::fflush(nullptr);
  ::_exit(code);
}

// The cases of `todo` in this process, in order, each result appended to the case files. The
// stop is asked after each case (a case is short); stopped, the cases written so far stay.
WorkersEnd RunHere(const StudyOptions& o, const Scene& scene, const StudyPlan& plan,
                   const std::vector<Interruption>& interruptions, const std::vector<bool>& todo,
                   size_t todo_count, std::chrono::steady_clock::time_point wall0) {
  struct Stopped {};  // not a std::exception: a case's error handling lets it through
  WorkersEnd end;
  const auto stop = [&] { return o.stop ? o.stop() : std::string(); };
  size_t written = 0;
  try {
    CaseFiles files(o.out_dir);
    const auto mine = [&](const StudyCase& c) { return static_cast<bool>(todo[c.index]); };
    for (size_t s = 0; s < plan.subroutines.size() && (end.stopped = stop()).empty(); ++s)
      RunSubroutineCases(scene, plan, interruptions, s, mine, o.run_ups, [&](const CaseResult& r) {
        files.Write(r);
        ++written;
        if (o.progress)
          Bar(written, todo_count,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count());
        if (!(end.stopped = stop()).empty()) throw Stopped{};
      });
  } catch (const Stopped&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vmt study: %s\n", e.what());
    end.failed = true;
  }
  if (o.progress) std::fprintf(stderr, "\n");
  return end;
}

// Forks the workers and waits for them. Asked to stop (o.stop), it forks no more and ends them
// (SIGTERM; SIGKILL to one that is still there after kEndWait) before it returns; the cases of
// their processes (which die with them) go unfinished.
WorkersEnd RunWorkers(const StudyOptions& o, const Scene& scene, const StudyPlan& plan,
                      const std::vector<Interruption>& interruptions, const CaseSpace& space,
                      const std::vector<bool>& todo, size_t todo_count, size_t lines_before,
                      std::chrono::steady_clock::time_point wall0) {
  constexpr std::chrono::seconds kEndWait{5};
  const auto stop = [&] { return o.stop ? o.stop() : std::string(); };
  // Workers take whole groups (one interruption point of one subroutine) in turn, of the
  // groups with a case to run.
  std::vector<int> worker_of(space.groups(), -1);
  int next = 0;
  for (size_t k = 0; k < space.size(); ++k) {
    const size_t group = k / space.cases_per_group();
    if (todo[k] && worker_of[group] < 0) {
      worker_of[group] = next;
      next = (next + 1) % o.jobs;
    }
  }
  std::vector<pid_t> workers;
  std::fflush(nullptr);
  const pid_t study_pid = ::getpid();
  {
    const StopSignalsHeld forking;
    for (int w = 0; w < o.jobs && todo_count > 0 && stop().empty(); ++w) {
      const pid_t pid = ::fork();
      if (pid < 0) throw std::runtime_error("fork failed");
      if (pid > 0) {
        workers.push_back(pid);
        continue;
      }
      DieWithParent(study_pid);
      std::signal(SIGINT, SIG_DFL);
      std::signal(SIGTERM, SIG_DFL);
      sigset_t stops;
      sigemptyset(&stops);
      sigaddset(&stops, SIGINT);
      sigaddset(&stops, SIGTERM);
      ::sigprocmask(SIG_UNBLOCK, &stops, nullptr);
      Worker(o, w, scene, plan, interruptions, todo, worker_of);
    }
  }
  WorkersEnd end;
  std::chrono::steady_clock::time_point ended_at{};
  bool killed = false;
  for (size_t alive = workers.size(); alive > 0;) {
    if (end.stopped.empty() && !(end.stopped = stop()).empty()) {
      for (const pid_t pid : workers)
        if (pid > 0) ::kill(pid, SIGTERM);
      ended_at = std::chrono::steady_clock::now();
    } else if (!end.stopped.empty() && !killed &&
               std::chrono::steady_clock::now() - ended_at > kEndWait) {
      for (const pid_t pid : workers)
        if (pid > 0) ::kill(pid, SIGKILL);
      killed = true;
    }
    for (pid_t& pid : workers) {
      if (pid <= 0) continue;
      int status = 0;
      if (::waitpid(pid, &status, WNOHANG) == pid) {
        const bool ended_by_us = !end.stopped.empty() && WIFSIGNALED(status);
        end.failed =
            end.failed || (!ended_by_us && (!WIFEXITED(status) || WEXITSTATUS(status) != 0));
        pid = 0;
        --alive;
      }
    }
    if (o.progress) {
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      Bar(CountLines(o.out_dir + "/cases.jsonl") - lines_before, todo_count, wall);
    }
    if (alive > 0) std::this_thread::sleep_for(std::chrono::milliseconds(o.progress ? 200 : 20));
  }
  if (o.progress) std::fprintf(stderr, "\n");
  if (end.stopped.empty()) end.stopped = stop();
  return end;
}

}  // namespace

StudySummary RunStudy(const StudyOptions& o) {
  const auto wall0 = std::chrono::steady_clock::now();
  if (o.shards < 1 || o.shard < 1 || o.shard > o.shards || o.shards > kMaxShards)
    throw std::runtime_error("--shard K/N needs 1 <= K <= N <= " + std::to_string(kMaxShards));
  if (o.jobs < 1 || o.jobs > 256) throw std::runtime_error("--jobs needs 1..256");
  const Scene scene = LoadScene(o.scene);
  StudyPlan plan = LoadStudyPlan(o.scene, scene);
  if (o.every_ms) {
    if (!(*o.every_ms >= kMinEveryMs && *o.every_ms <= kMaxEveryMs))
      throw std::runtime_error("--every-ms needs 1..1e7 ms");
    plan.every_ms = *o.every_ms;
    plan.per_mille.clear();
  }
  if (o.per_mille) {
    if (o.per_mille->empty() || o.per_mille->size() > kMaxPerMillePoints)
      throw std::runtime_error("--per-mille needs 1.." + std::to_string(kMaxPerMillePoints) +
                               " points");
    for (const int p : *o.per_mille)
      if (p < 0 || p > 1000) throw std::runtime_error("--per-mille points are 0..1000");
    plan.per_mille = *o.per_mille;
    plan.every_ms = 0;
  }
  std::filesystem::create_directories(o.out_dir);
  RemoveDeadScratch(o.out_dir);
  StudySource source = SourceOf(o.scene, plan);
  source.shard = o.shard;
  source.shards = o.shards;
  source.max_cases = o.max_cases;
  WriteStudySource(o.out_dir, source);
  const auto stop_asked = [&] { return o.stop && !o.stop().empty(); };
  StudySummary summary;
  std::optional<Reference> ref;
  try {
    ref = LoadOrRunReference(scene, o.out_dir, stop_asked);
  } catch (const ReferenceStopped&) {
    summary.stopped = o.stop();
    std::set<std::string> ids;
    ForEachCase(o.out_dir + "/cases.jsonl",
                [&](const CaseResult& r) { ids.insert(r["case"].get<std::string>()); });
    summary.finished = ids.size();
    return summary;
  }
  const std::vector<Interruption> interruptions = Interruptions(plan, *ref);
  const CaseSpace space(plan, interruptions);
  const std::vector<bool> share = ShareOf(space, source);

  // What the folder holds already (whole lines only) is kept and skipped. A bit per case: the
  // study's memory does not grow with its cases.
  const std::string jsonl = o.out_dir + "/cases.jsonl";
  std::vector<bool> todo = share;
  MergeCaseFiles({jsonl}, o.out_dir, TornLine::kLeftOut, [&](const CaseResult& r) {
    if (const std::optional<size_t> k = space.IndexOf(r["case"].get<std::string>()))
      todo[*k] = false;
  });
  const size_t share_count = static_cast<size_t>(std::count(share.begin(), share.end(), true));
  const size_t todo_count = static_cast<size_t>(std::count(todo.begin(), todo.end(), true));

  summary.cases = share_count;
  summary.skipped = share_count - todo_count;
  summary.run = todo_count;
  const double cpu0 = CpuSeconds();
  // One job with run-ups in memory or from the start needs no process of its own: the study
  // runs where POSIX fork does not exist or costs more than it gives.
  const WorkersEnd workers =
      o.jobs == 1 && o.run_ups != RunUpSharing::kFork
          ? RunHere(o, scene, plan, interruptions, todo, todo_count, wall0)
          : RunWorkers(o, scene, plan, interruptions, space, todo, todo_count, CountLines(jsonl),
                       wall0);
  summary.cases_cpu_s = CpuSeconds() - cpu0;
  // The files in case id order, whatever the workers' interleaving: the same study gives the
  // same bytes.
  // Merged as they stream by: the tally and the worst cases keep bounded state.
  std::vector<bool> finished(space.size(), false);
  std::map<std::string, ClassCount> tally;
  WorstCasePicker worst(o.snapshots);
  MergeCaseFiles({jsonl}, o.out_dir, TornLine::kLeftOut, [&](const CaseResult& r) {
    if (const std::optional<size_t> k = space.IndexOf(r["case"].get<std::string>()))
      finished[*k] = true;
    tally[r.value("subroutine", "")].Add(r);
    worst.Add(r);
  });
  summary.finished = 0;
  for (size_t k = 0; k < space.size(); ++k) summary.finished += share[k] && finished[k];
  summary.stopped = workers.stopped;
  if (!summary.stopped.empty()) {
    summary.run = summary.finished > summary.skipped ? summary.finished - summary.skipped : 0;
    return summary;
  }
  if (!workers.failed && o.snapshots > 0) {
    const auto shots0 = std::chrono::steady_clock::now();
    summary.snapshots = SnapshotCases(scene, plan, interruptions, worst.Results(), worst.Ids(),
                                      o.out_dir, stop_asked, o.jobs)
                            .size();
    summary.snapshots_wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - shots0).count();
    if (stop_asked()) {
      summary.stopped = o.stop();
      return summary;
    }
  }
  WriteReport(o.out_dir, "REPOS study: " + scene.name);
  if (workers.failed)
    throw std::runtime_error("a study worker failed; the finished cases are kept");
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  summary.cases_per_minute = summary.wall_s > 0 ? summary.run / summary.wall_s * 60 : 0;
  summary.text = Tally(tally);
  return summary;
}

size_t MergeStudies(const std::vector<std::string>& dirs, const std::string& out_dir) {
  std::vector<std::string> inputs;
  std::string reference;
  for (const std::string& d : dirs) {
    if (!std::filesystem::exists(d + "/cases.jsonl"))
      throw std::runtime_error(d + ": no cases.jsonl (not a study folder)");
    inputs.push_back(d + "/cases.jsonl");
    if (reference.empty() && std::filesystem::exists(d + "/reference.json"))
      reference = ReadText(d + "/reference.json");
  }
  // Each shard's file is in case id order: a k-way merge, a case per shard in memory.
  const size_t merged = MergeCaseFiles(inputs, out_dir, TornLine::kError);
  // The shards' pictures (each shard pictured its own worst cases).
  std::map<std::string, std::string> shots;
  for (const std::string& d : dirs)
    for (const auto& [id, file] : ReadSnapshotIndex(d)) {
      if (shots.count(id) || !std::filesystem::exists(d + "/" + file)) continue;
      const std::filesystem::path to = std::filesystem::path(out_dir) / file;
      std::filesystem::create_directories(to.parent_path());
      if (std::filesystem::absolute(d + "/" + file) != std::filesystem::absolute(to))
        common::CopyFileAtomically(d + "/" + file, to.string());
      shots[id] = file;
    }
  if (!shots.empty()) WriteSnapshotIndex(out_dir, shots);
  if (!reference.empty()) common::WriteFileAtomically(out_dir + "/reference.json", reference);
  // The shards ran one study: the first's record of its scene serves them all, as the whole.
  for (const std::string& d : dirs)
    if (std::optional<StudySource> source = ReadStudySource(d)) {
      source->shard = source->shards = 1;
      source->max_cases.reset();
      WriteStudySource(out_dir, *source);
      break;
    }
  WriteReport(out_dir, "REPOS study (merged)");
  return merged;
}

}  // namespace vmt::sim::study
