#include "sim/cli/golden.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "common/output_file.hpp"
#include "render/image.hpp"
#include "render/image_compare.hpp"
#include "sim/cli/golden_report.hpp"
#include "sim/cli/option_checks.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {
namespace {

namespace fs = std::filesystem;

struct GoldenOptions {
  std::vector<std::string> scenes;
  std::string golden_dir;
  std::string out_dir = "out";
  std::string fail_dir;  ///< empty: <out_dir>/golden-failures
  std::string backend;
  std::string junit, json;
  bool update = false;
  bool create_missing = false;
  bool no_run = false;
};

/// A picture the run wrote, from its `snapshot` event.
struct Shot {
  std::string file;
  double t = 0;
  std::string on;  ///< event snapshots: the event's name
  std::string camera;
};

std::vector<Shot> ShotsOf(const std::string& events_path) {
  std::vector<Shot> shots;
  std::ifstream in(events_path);
  for (std::string line; std::getline(in, line);) {
    if (line.find("\"snapshot\"") == std::string::npos) continue;
    const auto e = nlohmann::json::parse(line, nullptr, false);
    if (e.is_discarded() || e.value("event", "") != "snapshot" || !e.contains("file")) continue;
    shots.push_back({e["file"].get<std::string>(), e.value("t", 0.0), e.value("on", ""),
                     e.value("camera", "")});
  }
  return shots;
}

// The scene's entry that took `shot`: an event snapshot by its event and camera, a time one
// by its file. Null when the scene changed since an earlier run wrote it.
const SnapshotSpec* SpecOf(const Scene& scene, const Shot& shot) {
  for (const SnapshotSpec& s : scene.snapshots) {
    if (shot.on.empty() ? s.on == SnapshotEvent::kNone && s.file == shot.file
                        : ToString(s.on) == shot.on && s.camera == shot.camera)
      return &s;
  }
  return nullptr;
}

render::CompareOptions CompareOptionsOf(const SnapshotSpec* spec) {
  render::CompareOptions o;
  if (!spec) return o;
  o.channel_tolerance = spec->tolerance_levels.value_or(render::kGoldenChannelTolerance);
  o.allowed_fraction = spec->allowed_fraction.value_or(render::kGoldenAllowedFraction);
  for (const SnapshotMaskRect& r : spec->mask) o.mask.push_back({r.x, r.y, r.width, r.height});
  return o;
}

void CopyPicture(const std::string& from, const std::string& to) {
  fs::create_directories(fs::path(to).parent_path());
  common::CopyFileAtomically(from, to);
}

// Compares one picture with its baseline; a failure leaves the three pictures and the page in
// fail_dir/<picture name without .png>/.
void Compare(GoldenPicture& p, const render::CompareOptions& o, const std::string& fail_dir,
             const std::string& run_dir) {
  render::Image golden, actual;
  try {
    golden = render::ReadPng(p.golden);
    actual = render::ReadPng(p.actual);
  } catch (const std::exception& e) {
    p.status = GoldenStatus::kFailed;
    p.detail = e.what();
    return;
  }
  const render::CompareResult r = render::CompareImages(golden, actual, o);
  p.detail = render::DescribeComparison(golden, actual, r, o);
  p.compared = !r.size_mismatch;
  p.differing_pixels = r.differing_pixels, p.compared_pixels = r.compared_pixels;
  p.masked_pixels = r.masked_pixels, p.max_channel_delta = r.max_channel_delta;
  p.differing_fraction = r.differing_fraction;
  if (r.equal) return;
  p.status = GoldenStatus::kFailed;
  const std::string where = fail_dir + "/" + fs::path(p.file).stem().string();
  fs::create_directories(where);
  common::CopyFileAtomically(p.actual, where + "/actual.png");
  common::CopyFileAtomically(p.golden, where + "/golden.png");
  if (!r.size_mismatch) render::WritePng(where + "/diff.png", r.diff);
  WriteFailurePage(where, p, run_dir);
  p.page = where + "/index.html";
}

// The pages an earlier check left for this scene would mislead; only what Compare writes goes,
// so a --fail-dir given by mistake loses nothing else.
void RemoveFailurePages(const std::string& fail_dir) {
  if (!fs::is_directory(fail_dir)) return;
  std::error_code ignored;
  for (const auto& entry : fs::directory_iterator(fail_dir)) {
    if (!entry.is_directory() || !fs::exists(entry.path() / "index.html")) continue;
    for (const char* file : {"index.html", "actual.png", "golden.png", "diff.png"})
      fs::remove(entry.path() / file, ignored);
    fs::remove(entry.path(), ignored);  // only if empty
  }
  fs::remove(fail_dir, ignored);
}

void Print(const GoldenScene& s, const GoldenPicture& p) {
  const std::string name = s.name + "/" + p.file;
  switch (p.status) {
    case GoldenStatus::kPassed:
      std::printf("ok   %s: %s\n", name.c_str(), p.detail.c_str());
      return;
    case GoldenStatus::kCreated:
      std::printf("new  %s: baseline written: %s\n", name.c_str(), p.golden.c_str());
      return;
    case GoldenStatus::kUpdated:
      std::printf("upd  %s: baseline written: %s\n", name.c_str(), p.golden.c_str());
      return;
    case GoldenStatus::kRemoved:
      std::printf("del  %s: no snapshot writes it any more, baseline removed\n", name.c_str());
      return;
    default:
      break;
  }
  std::printf("FAIL %s: %s\n", name.c_str(), p.detail.c_str());
  if (p.status != GoldenStatus::kFailed) return;
  std::printf("     golden: %s\n     actual: %s\n", p.golden.c_str(), p.actual.c_str());
  if (p.page.empty()) return;
  const std::string dir = fs::path(p.page).parent_path().string();
  if (fs::exists(dir + "/diff.png")) std::printf("     diff:   %s/diff.png\n", dir.c_str());
  std::printf("     page:   %s (golden, actual and difference side by side)\n", p.page.c_str());
  std::printf("     replay: %s, then open http://127.0.0.1:8080/?t=%g\n",
              ReplayCommand(s.out_dir).c_str(), p.t);
}

GoldenScene GoldenOfScene(const std::string& scene_path, const GoldenOptions& o) {
  GoldenScene g;
  g.name = fs::path(scene_path).stem().string();
  g.out_dir = o.out_dir + "/" + g.name;
  const Scene scene = LoadScene(scene_path);
  const std::string baselines = o.golden_dir + "/" + g.name;
  const std::string fail_dir =
      (o.fail_dir.empty() ? o.out_dir + "/golden-failures" : o.fail_dir) + "/" + g.name;
  if (!o.update) RemoveFailurePages(fail_dir);

  if (!o.no_run) {
    RunOptions run;
    if (o.backend == "physics") run.backend = BackendKind::kPhysics;
    if (o.backend == "kinematic") run.backend = BackendKind::kKinematic;
    run.out_dir = g.out_dir;
    fs::create_directories(g.out_dir);
    const RunResult r = RunScene(scene, run);
    if (!r.write_errors.empty()) throw std::runtime_error(r.write_errors.front());
    g.ran = true;
    g.run_failures = r.failures;
    for (const std::string& f : r.failures) std::printf("FAIL %s: %s\n", g.name.c_str(), f.c_str());
  }
  const std::string events = g.out_dir + "/events.jsonl";
  if (!fs::exists(events)) {
    g.run_failures.push_back(events + " is missing: the scene did not run");
    std::printf("FAIL %s: %s\n", g.name.c_str(), g.run_failures.back().c_str());
    return g;
  }
  const std::vector<Shot> shots = ShotsOf(events);
  if (shots.empty()) {
    g.run_failures.push_back(
        "the run wrote no snapshot: add snapshots: to the scene "
        "(docs/scene-format.md)");
    std::printf("FAIL %s: %s\n", g.name.c_str(), g.run_failures.back().c_str());
  }
  if (o.update && !g.run_failures.empty()) {
    std::printf("FAIL %s: the run failed, its baselines are left as they are\n", g.name.c_str());
    return g;
  }

  std::set<std::string> written;
  for (const Shot& shot : shots) {
    written.insert(shot.file);
    GoldenPicture p;
    p.file = shot.file, p.t = shot.t;
    p.golden = baselines + "/" + shot.file;
    p.actual = g.out_dir + "/" + shot.file;
    const render::CompareOptions options = CompareOptionsOf(SpecOf(scene, shot));
    p.tolerance_levels = options.channel_tolerance;
    p.allowed_fraction = options.allowed_fraction;
    const bool exists = fs::exists(p.golden);
    if (o.update || (!exists && o.create_missing)) {
      CopyPicture(p.actual, p.golden);
      p.status = exists ? GoldenStatus::kUpdated : GoldenStatus::kCreated;
    } else if (!exists) {
      p.status = GoldenStatus::kMissing;
      p.detail = "no golden " + p.golden +
                 " (a new snapshot? vmt golden update, or vmt golden check --create-missing)";
    } else {
      Compare(p, options, fail_dir, g.out_dir);
    }
    Print(g, p);
    g.pictures.push_back(std::move(p));
  }
  // Baselines no snapshot wrote: a renamed or dropped snapshot shows instead of passing.
  if (fs::is_directory(baselines)) {
    std::vector<std::string> stale;
    for (const auto& entry : fs::directory_iterator(baselines)) {
      const std::string file = entry.path().filename().string();
      if (entry.path().extension() == ".png" && !written.count(file)) stale.push_back(file);
    }
    std::sort(stale.begin(), stale.end());
    for (const std::string& file : stale) {
      GoldenPicture p;
      p.file = file;
      p.golden = baselines + "/" + file;
      if (o.update) {
        fs::remove(p.golden);
        p.status = GoldenStatus::kRemoved;
      } else {
        p.status = GoldenStatus::kStale;
        p.detail =
            "golden not written by the scene (snapshot renamed or dropped? vmt golden "
            "update removes it)";
      }
      Print(g, p);
      g.pictures.push_back(std::move(p));
    }
  }
  std::error_code ignored;
  fs::remove(fail_dir, ignored);  // only if empty: nothing failed
  int failed = 0;
  for (const GoldenPicture& p : g.pictures) failed += IsFailure(p.status) ? 1 : 0;
  std::printf(
      "golden: %s: %zu pictures, %d failed (tolerance %d levels, allowed fraction %g "
      "unless a snapshot says otherwise)\n",
      g.name.c_str(), shots.size(), failed, render::kGoldenChannelTolerance,
      render::kGoldenAllowedFraction);
  return g;
}

int Golden(const GoldenOptions& o) {
  // Scenes are told apart by their file names: two of one name would share folders.
  std::set<std::string> names;
  for (const std::string& scene : o.scenes) {
    if (!names.insert(fs::path(scene).stem().string()).second) {
      std::fprintf(stderr,
                   "vmt: error: %s: a second scene named '%s' (runs and baselines go to "
                   "folders named after the scene file)\n",
                   scene.c_str(), fs::path(scene).stem().string().c_str());
      return 2;
    }
  }
  std::vector<GoldenScene> results;
  bool bad_input = false;
  for (const std::string& scene : o.scenes) {
    // A scene that does not load is bad input (exit 2) but no reason to leave the others
    // unchecked or CI without its report: it is a failed run in the results.
    try {
      results.push_back(GoldenOfScene(scene, o));
    } catch (const std::exception& e) {
      std::fflush(stdout);
      std::fprintf(stderr, "vmt: error: %s\n", e.what());
      bad_input = true;
      GoldenScene g;
      g.name = fs::path(scene).stem().string();
      g.out_dir = o.out_dir + "/" + g.name;
      g.run_failures.push_back(e.what());
      results.push_back(std::move(g));
    }
    std::fflush(stdout);
  }
  if (!o.junit.empty()) WriteJUnit(o.junit, results);
  if (!o.json.empty()) WriteJson(o.json, results);
  const auto failed =
      std::count_if(results.begin(), results.end(), [](const GoldenScene& s) { return !s.ok(); });
  if (results.size() > 1)
    std::printf("golden: %zu scenes, %zu failed\n", results.size(), size_t(failed));
  return bad_input ? 2 : failed ? 1 : 0;
}

CLI::App* AddGoldenSubcommand(CLI::App& golden, const char* name, const char* help,
                              GoldenOptions& o) {
  CLI::App* sub = golden.add_subcommand(name, help);
  sub->add_option("scenes", o.scenes, "Scene files (YAML)")->required();
  sub->add_option("--golden", o.golden_dir,
                  "Baselines folder: DIR/<scene>/<picture>.png, <scene> the scene file's name "
                  "without .yaml")
      ->required();
  sub->add_option("--out", o.out_dir, "Runs go to OUT/<scene> (as vmt run --out)")
      ->check(kOutputFolder)
      ->capture_default_str();
  sub->add_flag("--no-run", o.no_run,
                "Take OUT/<scene> as an earlier vmt run left it instead of running the scene");
  sub->add_option("--backend", o.backend, "physics or kinematic (default: the scene's)")
      ->check(CLI::IsMember({"physics", "kinematic"}));
  sub->add_option("--junit", o.junit, "Write the results as JUnit XML here")->check(kOutputFile);
  sub->add_option("--json", o.json, "Write the results as JSON here")->check(kOutputFile);
  return sub;
}

}  // namespace

std::vector<std::pair<CLI::App*, std::function<int()>>> AddGoldenCommands(CLI::App& app) {
  CLI::App* golden = app.add_subcommand(
      "golden",
      "Image regression: compare a scene's snapshots with baseline pictures, or write them");
  golden->require_subcommand(1);
  auto check = std::make_shared<GoldenOptions>();
  auto update = std::make_shared<GoldenOptions>();
  update->update = true;
  CLI::App* check_app = AddGoldenSubcommand(
      *golden, "check",
      "Run the scenes and compare every snapshot with its baseline (exit 0 all match, 1 a "
      "picture differs, a baseline is missing or left over, or a run failed; 2 bad input)",
      *check);
  check_app->add_flag("--create-missing", check->create_missing,
                      "Write a missing baseline from the run instead of failing");
  check_app
      ->add_option("--fail-dir", check->fail_dir,
                   "Failing pictures leave DIR/<scene>/<picture>/{actual,golden,diff}.png "
                   "and index.html (default: OUT/golden-failures)")
      ->check(kOutputFolder);
  CLI::App* update_app = AddGoldenSubcommand(
      *golden, "update",
      "Run the scenes and write their snapshots as the baselines (a baseline no snapshot "
      "writes any more is removed; a scene that fails its expectations writes none)",
      *update);
  return {{check_app, [check] { return Golden(*check); }},
          {update_app, [update] { return Golden(*update); }}};
}

}  // namespace vmt::sim
