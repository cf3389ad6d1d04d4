#include "sim/study/case_snapshots.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "common/json_text.hpp"
#include "common/output_file.hpp"
#include "render/image.hpp"
#include "render/offscreen_renderer.hpp"
#include "sim/runner/scene_renderer.hpp"
#include "sim/study/case_files.hpp"
#include "sim/study/contact_picture.hpp"
#include "sim/study/die_with_parent.hpp"
#include "sim/study/study_conclusions.hpp"

namespace vmt::sim::study {
namespace {

std::string Str(const CaseResult& r, const char* key) {
  return r.contains(key) && r[key].is_string() ? r[key].get<std::string>() : "";
}

// The look of the pictures: the scene's own first snapshot's camera and size.
SnapshotSpec Look(const Scene& scene) {
  SnapshotSpec look;
  look.width = 320, look.height = 240;
  if (!scene.snapshots.empty()) {
    look.camera = scene.snapshots[0].camera;
    look.width = scene.snapshots[0].width, look.height = scene.snapshots[0].height;
  } else if (!scene.cameras.empty()) {
    look.camera = scene.cameras[0].name;
  }
  return look;
}

}  // namespace

void WriteSnapshotIndex(const std::string& dir, const std::map<std::string, std::string>& index) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [id, file] : index) j[id] = file;
  common::WriteFileAtomically(dir + "/snapshots.json",
                              j.dump(1, ' ', false, common::kReplaceBadUtf8) + "\n");
}

void WorstCasePicker::Add(const CaseResult& r) {
  Picked& p = by_sub_[Str(r, "subroutine")];
  const std::string v = Str(r, "verdict");
  if (v == "collision" && collisions_ > 0) {
    const auto at =
        std::upper_bound(p.worst.begin(), p.worst.end(), r,
                         [](const CaseResult& a, const CaseResult& b) { return MoreSevere(a, b); });
    if (at - p.worst.begin() < collisions_) {
      p.worst.insert(at, r);
      if (p.worst.size() > static_cast<size_t>(collisions_)) p.worst.pop_back();
    }
  }
  if (v == "clear" && r["min_clearance_mm"].is_number() &&
      (!p.tightest ||
       r["min_clearance_mm"].get<double>() < (*p.tightest)["min_clearance_mm"].get<double>()))
    p.tightest = r;
}

std::vector<std::string> WorstCasePicker::Ids() const {
  std::vector<std::string> ids;
  for (const CaseResult& r : Results()) ids.push_back(Str(r, "case"));
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<CaseResult> WorstCasePicker::Results() const {
  std::vector<CaseResult> out;
  for (const auto& [sub, p] : by_sub_) {
    out.insert(out.end(), p.worst.begin(), p.worst.end());
    if (p.tightest && collisions_ > 0) out.push_back(*p.tightest);
  }
  return out;
}

std::vector<std::string> WorstCaseIds(const std::vector<CaseResult>& results, int collisions) {
  WorstCasePicker picker(collisions);
  for (const CaseResult& r : results) picker.Add(r);
  return picker.Ids();
}

std::string SnapshotFileOf(const std::string& case_id) {
  return "snapshots/" + FileNameOf(case_id) + ".png";
}

namespace {

// The picture of a clear case at its end: the machine at that tick as the scene's own snapshot
// draws it, the workpiece as turned (as the picture an `at:` of that time would show).
render::Image EndImage(const Scene& scene, const SceneRun& run, const SnapshotSpec& look) {
  const NamedCamera* camera = scene.Camera(look.camera);
  if (!camera) throw std::runtime_error("the scene has no camera " + look.camera);
  SceneRenderer renderer(*scene.model, scene.workpiece);
  if (run.stock_cuts() == 0)
    return renderer.Render(run.joint_positions(), *camera, look.width, look.height);
  const TurnedProfile turned{run.stock_cuts(), run.TurnedStockCylinders()};
  return renderer.Render(run.joint_positions(), *camera, look.width, look.height, &turned);
}

// Pictures the cases of subroutine `sub` in `wanted` (by index) whose file is not in `dir` yet.
// They run as the study ran them (RunSubroutineCases: one run-up, forked at each interruption
// point), each picture taken in its case's process: a collision at its first contact
// (contact_picture.hpp), a clear case at the tick it ended.
void PictureSubroutine(const Scene& base, const StudyPlan& plan,
                       const std::vector<Interruption>& interruptions, size_t sub,
                       const std::map<size_t, const CaseResult*>& wanted, const std::string& dir,
                       const std::function<bool()>& stop) {
  const SnapshotSpec look = Look(base);
  const auto file_of = [&](const StudyCase& c) {
    return dir + "/" + SnapshotFileOf(Str(*wanted.at(c.index), "case"));
  };
  const auto collision = [&](const StudyCase& c) {
    return Str(*wanted.at(c.index), "verdict") == "collision";
  };
  const auto chosen = [&](const StudyCase& c) {
    return wanted.count(c.index) && !std::filesystem::exists(file_of(c)) && !(stop && stop());
  };
  CaseWatch watch;
  watch.at_end = [&](const SceneRun& run, const StudyCase& c) {
    if (!collision(c)) render::WritePng(file_of(c), EndImage(base, run, look));
  };
  // PathGuard refused the move before it started, so the machine stands where it would have
  // begun until the case ends; the picture poses it at the contact from there.
  watch.after = [&](const SceneRun& run, const StudyCase& c, const CaseResult&) {
    if (!collision(c)) return;
    const ContactStage stage{run.joint_positions(), run.TurnedStockCylinders()};
    render::WritePng(file_of(c), ContactImage(base, stage, *wanted.at(c.index), look));
  };
  // In memory: a process that has rendered must not fork a renderer (render::RendererStarted).
  RunSubroutineCases(
      base, plan, interruptions, sub, chosen, RunUpSharing::kMemory, [](const CaseResult&) {},
      &watch);
}

}  // namespace

std::map<std::string, std::string> SnapshotCases(const Scene& base, const StudyPlan& plan,
                                                 const std::vector<Interruption>& interruptions,
                                                 const std::vector<CaseResult>& results,
                                                 const std::vector<std::string>& ids,
                                                 const std::string& dir,
                                                 const std::function<bool()>& stop, int jobs) {
  std::map<std::string, std::string> index;
  if (ids.empty()) return index;
  const CaseSpace space(plan, interruptions);
  std::filesystem::create_directories(dir + "/snapshots");
  // Per subroutine, the cases to picture (by index) and their results.
  std::vector<std::map<size_t, const CaseResult*>> wanted(plan.subroutines.size());
  for (const std::string& id : ids) {
    const std::optional<size_t> k = space.IndexOf(id);
    const auto r = std::find_if(results.begin(), results.end(),
                                [&](const CaseResult& k) { return Str(k, "case") == id; });
    if (k && r != results.end()) wanted[space.At(*k).subroutine][*k] = &*r;
  }
  std::vector<size_t> subs;
  for (size_t s = 0; s < wanted.size(); ++s)
    if (!wanted[s].empty()) subs.push_back(s);
  // With jobs > 1, that many processes take the subroutines side by side, each every jobs-th.
  // This process then takes only what a process left out (it failed or was ended).
  if (jobs > 1 && subs.size() > 1 && !render::RendererStarted()) {
    std::vector<pid_t> helpers;
    std::fflush(nullptr);
    const pid_t parent = ::getpid();
    for (int w = 0; w < jobs && static_cast<size_t>(w) < subs.size(); ++w) {
      const pid_t pid = ::fork();
      if (pid < 0) break;
      if (pid > 0) {
        helpers.push_back(pid);
        continue;
      }
      DieWithParent(parent);
      int code = 0;
      try {
        for (size_t i = static_cast<size_t>(w); i < subs.size() && !(stop && stop()); i += jobs)
          PictureSubroutine(base, plan, interruptions, subs[i], wanted[subs[i]], dir, stop);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "vmt study: a picture failed: %s\n", e.what());
        code = 1;
      }
      std::fflush(nullptr);
      ::_exit(code);
    }
    for (const pid_t pid : helpers) {
      int status = 0;
      ::waitpid(pid, &status, 0);
    }
  }
  for (const size_t s : subs) {
    if (stop && stop()) break;
    PictureSubroutine(base, plan, interruptions, s, wanted[s], dir, stop);
  }
  for (const std::string& id : ids)
    if (std::filesystem::exists(dir + "/" + SnapshotFileOf(id))) index[id] = SnapshotFileOf(id);
  WriteSnapshotIndex(dir, index);
  return index;
}

std::map<std::string, std::string> ReadSnapshotIndex(const std::string& dir) {
  std::map<std::string, std::string> index;
  std::ifstream in(dir + "/snapshots.json", std::ios::binary);
  if (!in) return index;
  const nlohmann::ordered_json j = nlohmann::ordered_json::parse(in, nullptr, false);
  if (!j.is_object()) return index;
  for (const auto& [id, file] : j.items())
    if (file.is_string()) index[id] = file.get<std::string>();
  return index;
}

}  // namespace vmt::sim::study
