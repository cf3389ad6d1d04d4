#include "sim/cli/view.hpp"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "sim/runner/runner.hpp"
#include "sim/station/station_session.hpp"
#include "sim/station/study_index.hpp"
#include "sim/study/case_replay.hpp"

namespace vmt::sim {
namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }

/// What a replay runs again, and what it is compared with.
struct ReplaySource {
  Scene scene;
  RunOptions options;
  std::string recorded_digest;
  std::string events_file;
};

/// summary.json of `dir`, with what a replay needs checked.
nlohmann::json ReadSummary(const std::string& dir) {
  const std::string path = dir + "/summary.json";
  std::ifstream in(path);
  if (!in)
    throw std::invalid_argument(
        dir + ": no summary.json (give the output folder of vmt run or vmt serve, or a study's)");
  nlohmann::json s = nlohmann::json::parse(in, nullptr, false);
  if (s.is_discarded() || !s.is_object()) throw std::invalid_argument(path + ": not a JSON object");
  if (!s.contains("scene_file") || !s["scene_file"].is_string())
    throw std::invalid_argument(
        path + ": no scene_file (written before vmt view existed: run the scene again)");
  if (!s.contains("simulated_time_s") || !s["simulated_time_s"].is_number())
    throw std::invalid_argument(path + ": no simulated_time_s");
  return s;
}

ReplaySource ReadRun(const std::string& dir) {
  ReplaySource src;
  src.events_file = dir + "/events.jsonl";
  src.options.snapshots = false;
  if (std::optional<study::CaseReplay> c = study::ReadCaseReplay(dir)) {
    src.scene = std::move(c->scene);
    src.options.backend = BackendKind::kKinematic;  // as the study ran it
    src.options.until_s = c->until_s;
    src.recorded_digest = c->trace_digest;
    return src;
  }
  const nlohmann::json summary = ReadSummary(dir);
  src.scene = LoadScene(summary["scene_file"].get<std::string>());
  src.options.until_s = summary["simulated_time_s"].get<double>();
  const std::string backend = summary.value("backend", "");
  if (backend == "physics") src.options.backend = BackendKind::kPhysics;
  if (backend == "kinematic") src.options.backend = BackendKind::kKinematic;
  const std::string operator_file = dir + "/operator.yaml";
  if (std::filesystem::exists(operator_file))
    src.options.operator_steps = ReadOperatorSteps(operator_file);
  src.recorded_digest = summary.value("trace_digest", "");
  return src;
}

/// Serves the replay of `src` until `stop`; `opened` gets the station's port once it listens.
void ServeReplay(ReplaySource src, station::StationServerOptions http,
                 const std::atomic<bool>& stop, const std::function<void(int)>& opened) {
  station::StationSession station;
  // The events listed are the recorded ones; the replay's own only place the marks.
  std::ifstream events(src.events_file);
  for (std::string line; std::getline(events, line);)
    if (!line.empty()) station.Listed(line);
  RunOptions& options = src.options;
  options.on_event = [&station](const nlohmann::ordered_json& e) { station.Mark(e); };
  http.operate_refused = "a replay is watched, not operated";
  http.seekable = true;

  auto run = std::make_unique<SceneRun>(src.scene, options);
  station.Open(*run, http, "replay", "");
  opened(station.port());
  station::RunControl& control = station.control();
  bool compared = false;
  while (!stop) {
    if (control.seek) {
      const double t = std::min(*control.seek, *options.until_s);
      control.seek.reset();
      if (t < run->time_s()) {  // back: from the start again
        run = std::make_unique<SceneRun>(src.scene, options);
        station.ClearMarks();
      }
      const bool to_end = t >= *options.until_s;
      while (!run->done() && (to_end || run->time_s() + 1e-9 < t)) run->Step();
      station.Publish(*run, run->done() ? "ended" : control.running ? "running" : "paused", true);
      continue;
    }
    if (run->done()) {
      if (!compared) {
        compared = true;
        const RunResult r = run->Finish();
        if (r.trace_digest != src.recorded_digest)
          std::fprintf(stderr,
                       "vmt view: the replay's trace digest %s differs from the recorded %s: "
                       "the scene, its model or vmt changed since the run\n",
                       r.trace_digest.c_str(), src.recorded_digest.c_str());
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
}

station::StationServerOptions HttpOptions(const ViewOptions& o) {
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
  return http;
}

void WaitForSignal() {
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
}

/// The cases of a study opened so far, each a replay station on a port of its own.
class CaseStations {
 public:
  CaseStations(std::string dir, station::StationServerOptions http)
      : dir_(std::move(dir)), http_(std::move(http)) {
    http_.port = 0;
  }
  ~CaseStations() {
    stop_ = true;
    for (auto& [id, t] : threads_) t.join();
  }
  int Open(const std::string& id) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto p = ports_.find(id); p != ports_.end()) return p->second;
    std::string folder;
    try {
      folder = study::SaveCase(dir_, id);
    } catch (const study::UnknownCase& e) {
      throw std::out_of_range(e.what());
    }
    std::printf("vmt view: case %s saved in %s\n", id.c_str(), folder.c_str());
    std::fflush(stdout);
    std::promise<int> port;
    std::future<int> opened = port.get_future();
    threads_[id] = std::thread([this, src = ReadRun(folder), &port]() mutable {
      try {
        ServeReplay(std::move(src), http_, stop_, [&port](int p) { port.set_value(p); });
      } catch (const std::exception& e) {
        try {
          port.set_exception(std::current_exception());
        } catch (const std::future_error&) {  // already open: a failure later on
          std::fprintf(stderr, "vmt view: the replay stopped: %s\n", e.what());
        }
      }
    });
    try {
      ports_[id] = opened.get();  // rethrows the replay's failure to open
    } catch (...) {
      threads_[id].join();
      threads_.erase(id);
      throw;
    }
    return ports_[id];
  }

 private:
  std::string dir_;
  station::StationServerOptions http_;
  std::mutex mutex_;
  std::atomic<bool> stop_{false};
  std::map<std::string, int> ports_;
  std::map<std::string, std::thread> threads_;
};

int ViewStudy(const ViewOptions& o) {
  const station::StationServerOptions http = HttpOptions(o);
  CaseStations cases(o.out_dir, http);
  station::StudyIndexOptions index;
  index.host = http.host;
  index.port = http.port;
  index.token = http.token;
  index.study_dir = o.out_dir;
  index.open_case = [&cases](const std::string& id) { return cases.Open(id); };
  station::StudyIndexServer server(index);
  std::printf("vmt view: study %s, its report on http://%s:%d/ (each case a link to its replay)\n",
              o.out_dir.c_str(), http.host.c_str(), server.port());
  std::fflush(stdout);
  WaitForSignal();
  while (!g_stop) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  return 0;
}

}  // namespace

int View(const ViewOptions& o) {
  if (!std::filesystem::exists(o.out_dir + "/summary.json") &&
      std::filesystem::exists(o.out_dir + "/cases.jsonl"))
    return ViewStudy(o);
  ReplaySource src = ReadRun(o.out_dir);
  const std::string name = src.scene.name;
  const double until = *src.options.until_s;
  WaitForSignal();
  ServeReplay(std::move(src), HttpOptions(o), g_stop, [&](int port) {
    std::printf("vmt view: %s (%.3f s), operator station on http://%s:%d/\n", name.c_str(), until,
                HttpOptions(o).host.c_str(), port);
    std::fflush(stdout);
  });
  return 0;
}

}  // namespace vmt::sim
