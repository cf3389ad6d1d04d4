#include "sim/study/case_snapshots.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/json_text.hpp"
#include "common/output_file.hpp"
#include "render/image.hpp"
#include "render/offscreen_renderer.hpp"
#include "sim/study/case_files.hpp"
#include "sim/study/contact_picture.hpp"
#include "sim/study/die_with_parent.hpp"
#include "sim/study/scratch_folder.hpp"
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
  const SnapshotSpec look = Look(base);
  // The picture of case `id` into its file unless it is there: the file, "" if none was taken.
  const auto take = [&](const std::string& id) -> std::string {
    const std::optional<size_t> k = space.IndexOf(id);
    const auto r = std::find_if(results.begin(), results.end(),
                                [&](const CaseResult& k) { return Str(k, "case") == id; });
    if (!k || r == results.end()) return "";
    const StudyCase c = space.At(*k);
    const std::string file = SnapshotFileOf(id);
    if (std::filesystem::exists(dir + "/" + file)) return file;
    const ScratchFolder scratch(dir + "/.snapshot-" + std::to_string(::getpid()));
    const std::string& work = scratch.path();
    SnapshotSpec shot = look;
    if (Str(*r, "verdict") == "collision") {
      // At the first contact: PathGuard refused the move before it started, so the machine
      // stands where it would have begun until the case ends; posed at the contact from there.
      ContactStage stage;
      RunCaseFromStart(base, plan, interruptions, c, {}, "", nullptr, [&](const SceneRun& run) {
        stage.joints = run.joint_positions();
        stage.stock = run.TurnedStockCylinders();
      });
      render::WritePng(dir + "/" + file, ContactImage(base, stage, *r, look));
      return file;
    }
    // The clear case at its end: first learn when that is, then picture it.
    double t_end = 0;
    RunCaseFromStart(base, plan, interruptions, c, {}, "", &t_end);
    shot.at_s = t_end;
    shot.file = "end.png";
    RunCaseFromStart(base, plan, interruptions, c, {shot}, work);
    for (const auto& entry : std::filesystem::directory_iterator(work))
      if (entry.path().extension() == ".png") {
        std::filesystem::rename(entry.path(), dir + "/" + file);
        return file;
      }
    return "";
  };
  // With jobs > 1, that many processes take the pictures side by side, each every jobs-th
  // (each case's run is the longest part of a picture). This process then finds them there
  // and takes only those a process left out (it failed or was ended). A process that has
  // rendered already takes them alone (RendererStarted).
  if (jobs > 1 && ids.size() > 1 && !render::RendererStarted()) {
    std::vector<pid_t> helpers;
    std::fflush(nullptr);
    const pid_t parent = ::getpid();
    for (int w = 0; w < jobs && static_cast<size_t>(w) < ids.size(); ++w) {
      const pid_t pid = ::fork();
      if (pid < 0) break;
      if (pid > 0) {
        helpers.push_back(pid);
        continue;
      }
      DieWithParent(parent);
      int code = 0;
      try {
        for (size_t i = static_cast<size_t>(w); i < ids.size() && !(stop && stop()); i += jobs)
          (void)take(ids[i]);
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
  for (const std::string& id : ids) {
    if (stop && stop()) break;
    if (const std::string file = take(id); !file.empty()) index[id] = file;
  }
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
