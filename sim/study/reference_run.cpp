#include "sim/study/reference_run.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "common/json_text.hpp"
#include "sim/collision/spindle_sweep.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim::study {
namespace {

std::vector<std::string> SplitCsv(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream ss(row);
  for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
  return out;
}

// The first word of each source line of the main program: the block's N number if it has one.
std::vector<std::string> FirstWords(const Scene& scene) {
  std::vector<std::string> words;
  if (scene.nc.programs.empty()) return words;
  const auto& files = scene.nc.programs[0]->program.files;
  if (files.empty()) return words;
  std::ifstream in(files[0]);
  for (std::string line; std::getline(in, line);) {
    std::stringstream ss(line);
    std::string w;
    ss >> w;
    words.push_back(w);
  }
  return words;
}

// The drive `name`'s position (mm) for joint positions `q`.
std::optional<double> DrivePosition(const MachineModel& m, const std::vector<double>& q,
                                    const std::string& name) {
  for (const DriveParams& d : m.drives)
    if (d.info.name == name) {
      if (d.load_joint >= 0) return q[d.load_joint] * kMmPerM;
      if (d.motor_joint >= 0) return q[d.motor_joint] / d.ratio * kMmPerM;
    }
  return std::nullopt;
}

// The tool tip's offset from the axes and the chuck's outline, where the program ended.
void MachineFrame(const Scene& scene, const SceneRun& run, Reference& ref) {
  const std::optional<Eigen::Vector3d> tip = run.ToolTip();
  if (!tip || !scene.model) return;
  const std::vector<double> q = run.joint_positions();
  const std::optional<double> x = DrivePosition(*scene.model, q, "X");
  const std::optional<double> z = DrivePosition(*scene.model, q, "Z");
  if (!x || !z) return;
  ref.has_tip = true;
  // To the µm: a model's tip stands at round figures, its floats do not.
  const auto micro = [](double v) { return std::round(v * 1000) / 1000 + 0.0; };
  ref.tip_x = micro(std::hypot(tip->x(), tip->y()) * kMmPerM - *x);
  ref.tip_z = micro(tip->z() * kMmPerM - *z);
  CollisionWorld world(*scene.model);
  world.Pose(q);
  const std::string link = scene.workpiece.present ? scene.workpiece.part.link : "spindle";
  const SpindleSweep sweep = SweepOf(world, link);
  for (size_t i = 0; i < sweep.swept.size() && i < sweep.parts.size(); ++i) {
    const CylinderPart& c = sweep.swept[i];
    const Eigen::Isometry3d& X = world.X_WorldLink(world.part(sweep.parts[i]).link);
    const double a = (X * Eigen::Vector3d(0, 0, c.z_m)).z() * kMmPerM - ref.tip_z;
    const double b = (X * Eigen::Vector3d(0, 0, c.z_m + c.length_m)).z() * kMmPerM - ref.tip_z;
    ref.chuck.push_back({c.name, micro(c.radius_m * kMmPerM - ref.tip_x), micro(std::min(a, b)),
                         micro(std::max(a, b))});
  }
}

}  // namespace

Reference RunReference(const Scene& base, const std::string& work_dir,
                       const std::function<bool()>& stop) {
  Scene scene = base;
  scene.timeline.clear();
  scene.expectations.clear();
  scene.snapshots.clear();
  TimelineStep start{};
  start.kind = TimelineStep::Kind::kNcStart;
  start.text = "timeline[0]: nc start";
  scene.timeline.push_back(start);
  RunOptions options;
  options.backend = BackendKind::kKinematic;
  options.out_dir = work_dir;
  options.snapshots = false;
  std::string state, error;
  options.on_event = [&](const nlohmann::ordered_json& e) {
    if (e.value("event", "") != "nc") return;
    state = e.value("state", "");
    error = e.value("error", "");
  };
  Reference ref;
  {
    SceneRun run(scene, options);
    while (!run.done() && state != "ended" && state != "error") {
      if (stop && stop()) throw ReferenceStopped();
      run.Step();
    }
    MachineFrame(scene, run, ref);
    const RunResult r = run.Finish();
    if (!r.write_errors.empty()) throw std::runtime_error(r.write_errors.front());
  }
  if (state != "ended")
    throw std::runtime_error("the study's reference run of " + base.file +
                             (state == "error" ? " stopped with an NC error: " + error
                                               : " did not end within its duration"));
  std::ifstream trace(work_dir + "/trace.csv");
  std::string row;
  std::getline(trace, row);
  const std::vector<std::string> head = SplitCsv(row);
  auto column = [&](const std::string& name) {
    for (size_t i = 0; i < head.size(); ++i)
      if (head[i] == name) return static_cast<int>(i);
    throw std::runtime_error("the reference trace has no column " + name);
  };
  const int cx = column("X.pos"), cz = column("Z.pos"), cs = column("nc.state"),
            cl = column("nc.line");
  const std::vector<std::string> words = FirstWords(base);
  bool started = false;
  double last_path_t = -1;
  BlockSpan* open = nullptr;
  double open_x = 0, open_z = 0;
  while (std::getline(trace, row)) {
    const std::vector<std::string> c = SplitCsv(row);
    if (c.size() < head.size()) continue;
    const double t = std::stod(c[0]), x = std::stod(c[cx]), z = std::stod(c[cz]);
    const int st = std::lround(std::stod(c[cs])), line = std::lround(std::stod(c[cl]));
    const bool running = st == static_cast<int>(control::channel::ChannelState::kRunning);
    if (running && !started) started = true, ref.start_s = t;
    if (!started) continue;
    if (t - last_path_t >= 0.01 - 1e-9) {
      ref.path.emplace_back(x, z);
      last_path_t = t;
    }
    if (!running) {
      if (st == static_cast<int>(control::channel::ChannelState::kEnded)) {
        ref.end_s = t;
        break;
      }
      continue;
    }
    // Between two blocks the NC may run a cycle with none current (line 0): that cycle finishes
    // the block before, so an interruption there belongs to it, never to a block "L0".
    if (line == 0) {
      if (open) open->end_s = t;
      continue;
    }
    if (!open || open->line != line) {
      BlockSpan b;
      b.line = line;
      b.label = line >= 1 && line <= static_cast<int>(words.size()) && !words[line - 1].empty() &&
                        words[line - 1][0] == 'N'
                    ? words[line - 1]
                    : "L" + std::to_string(line);
      b.start_s = b.end_s = t;
      ref.blocks.push_back(b);
      open = &ref.blocks.back();
      open_x = x, open_z = z;
    }
    open->end_s = t;
    if (std::abs(x - open_x) > 1e-3 || std::abs(z - open_z) > 1e-3) open->motion = true;
  }
  if (ref.end_s <= ref.start_s)
    ref.end_s = ref.blocks.empty() ? ref.start_s : ref.blocks.back().end_s;
  return ref;
}

std::string ReferenceJson(const Reference& r) {
  nlohmann::ordered_json j;
  j["start_s"] = r.start_s;
  j["end_s"] = r.end_s;
  auto& blocks = j["blocks"] = nlohmann::ordered_json::array();
  for (const BlockSpan& b : r.blocks)
    blocks.push_back({{"line", b.line},
                      {"label", b.label},
                      {"start_s", b.start_s},
                      {"end_s", b.end_s},
                      {"motion", b.motion}});
  auto& path = j["path"] = nlohmann::ordered_json::array();
  for (const auto& [x, z] : r.path) path.push_back({x, z});
  if (r.has_tip) {
    j["tip_offset_mm"] = {{"x", r.tip_x}, {"z", r.tip_z}};
    auto& chuck = j["chuck"] = nlohmann::ordered_json::array();
    for (const ChuckOutline& c : r.chuck)
      chuck.push_back({{"name", c.name}, {"x1", c.x1}, {"z0", c.z0}, {"z1", c.z1}});
  }
  return j.dump(-1, ' ', false, common::kReplaceBadUtf8) + "\n";
}

Reference ReferenceFromJson(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  Reference r;
  r.start_s = j.at("start_s").get<double>();
  r.end_s = j.at("end_s").get<double>();
  for (const auto& b : j.at("blocks"))
    r.blocks.push_back({b.at("line").get<int>(), b.at("label").get<std::string>(),
                        b.at("start_s").get<double>(), b.at("end_s").get<double>(),
                        b.at("motion").get<bool>()});
  for (const auto& p : j.at("path"))
    r.path.emplace_back(p.at(0).get<double>(), p.at(1).get<double>());
  if (j.contains("tip_offset_mm")) {  // a folder of an older vmt has none
    r.has_tip = true;
    r.tip_x = j["tip_offset_mm"].at("x").get<double>();
    r.tip_z = j["tip_offset_mm"].at("z").get<double>();
    for (const auto& c : j.value("chuck", nlohmann::json::array()))
      r.chuck.push_back({c.at("name").get<std::string>(), c.at("x1").get<double>(),
                         c.at("z0").get<double>(), c.at("z1").get<double>()});
  }
  return r;
}

}  // namespace vmt::sim::study
