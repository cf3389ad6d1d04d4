#include "sim/cli/view.hpp"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "sim/runner/runner.hpp"
#include "sim/station/station_session.hpp"

namespace vmt::sim {
namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }

/// summary.json of `dir`, with what a replay needs checked.
nlohmann::json ReadSummary(const std::string& dir) {
  const std::string path = dir + "/summary.json";
  std::ifstream in(path);
  if (!in)
    throw std::invalid_argument(
        dir + ": no summary.json (give the output folder of vmt run or vmt serve)");
  nlohmann::json s = nlohmann::json::parse(in, nullptr, false);
  if (s.is_discarded() || !s.is_object()) throw std::invalid_argument(path + ": not a JSON object");
  if (!s.contains("scene_file") || !s["scene_file"].is_string())
    throw std::invalid_argument(
        path + ": no scene_file (written before vmt view existed: run the scene again)");
  if (!s.contains("simulated_time_s") || !s["simulated_time_s"].is_number())
    throw std::invalid_argument(path + ": no simulated_time_s");
  return s;
}

}  // namespace

int View(const ViewOptions& o) {
  const nlohmann::json summary = ReadSummary(o.out_dir);
  const Scene scene = LoadScene(summary["scene_file"].get<std::string>());
  RunOptions options;
  options.until_s = summary["simulated_time_s"].get<double>();
  options.snapshots = false;
  const std::string backend = summary.value("backend", "");
  if (backend == "physics") options.backend = BackendKind::kPhysics;
  if (backend == "kinematic") options.backend = BackendKind::kKinematic;
  const std::string operator_file = o.out_dir + "/operator.yaml";
  if (std::filesystem::exists(operator_file))
    options.operator_steps = ReadOperatorSteps(operator_file);
  const std::string recorded_digest = summary.value("trace_digest", "");

  station::StationSession station;
  // The events listed are the recorded ones; the replay's own only place the marks.
  std::ifstream events(o.out_dir + "/events.jsonl");
  for (std::string line; std::getline(events, line);)
    if (!line.empty()) station.Listed(line);
  options.on_event = [&station](const nlohmann::ordered_json& e) { station.Mark(e); };

  station::StationServerOptions http;
  const size_t colon = o.http.rfind(':');
  if (colon == std::string::npos || colon == 0)
    throw std::invalid_argument("--http " + o.http + ": expected HOST:PORT");
  http.host = o.http.substr(0, colon);
  try {
    http.port = std::stoi(o.http.substr(colon + 1));
  } catch (const std::exception&) {
    throw std::invalid_argument("--http " + o.http + ": the port is not a number");
  }
  http.token = o.http_token;
  http.web_dir = station::DefaultWebDir();
  http.operate_refused = "a replay is watched, not operated";
  http.seekable = true;

  auto run = std::make_unique<SceneRun>(scene, options);
  station.Open(*run, http, "replay", "");
  std::printf("vmt view: %s (%.3f s), operator station on http://%s:%d/\n", scene.name.c_str(),
              *options.until_s, http.host.c_str(), station.port());
  std::fflush(stdout);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  station::RunControl& control = station.control();
  bool compared = false;
  while (!g_stop) {
    if (control.seek) {
      const double t = std::min(*control.seek, *options.until_s);
      control.seek.reset();
      if (t < run->time_s()) {  // back: from the start again
        run = std::make_unique<SceneRun>(scene, options);
        station.ClearMarks();
      }
      while (!run->done() && run->time_s() + 1e-9 < t) run->Step();
      station.Publish(*run, run->done() ? "ended" : control.running ? "running" : "paused", true);
      continue;
    }
    if (run->done()) {
      if (!compared) {
        compared = true;
        const RunResult r = run->Finish();
        if (r.trace_digest != recorded_digest)
          std::fprintf(stderr,
                       "vmt view: the replay's trace digest %s differs from the recorded %s: "
                       "the scene, its model or vmt changed since the run\n",
                       r.trace_digest.c_str(), recorded_digest.c_str());
      }
      station.TakeInputs(*run);
      station.Publish(*run, "ended");
      station.Wait(std::chrono::milliseconds(20));
      continue;
    }
    if (!station.CycleDue(*run)) continue;
    for (int64_t k = 0; k < run->ticks_per_plc_cycle() && !run->done(); ++k) run->Step();
    station.Published(*run);
  }
  return 0;
}

}  // namespace vmt::sim
