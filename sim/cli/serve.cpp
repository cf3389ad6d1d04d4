#include "sim/cli/serve.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "control/plc/modbus_server.hpp"
#include "sim/runner/runner.hpp"

namespace vmt::sim {
namespace {

std::atomic<bool> g_stop{false};

void OnSignal(int) { g_stop = true; }

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size())))];
}

}  // namespace

int Serve(const ServeOptions& o) {
  const size_t colon = o.endpoint.rfind(':');
  if (colon == std::string::npos || colon + 1 == o.endpoint.size())
    throw std::invalid_argument("--modbus " + o.endpoint + ": expected HOST:PORT");
  control::plc::ModbusServerOptions mb;
  mb.host = o.endpoint.substr(0, colon);
  try {
    size_t used = 0;
    mb.port = std::stoi(o.endpoint.substr(colon + 1), &used);
    if (used != o.endpoint.size() - colon - 1) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw std::invalid_argument("--modbus " + o.endpoint + ": the port is not a number");
  }

  const Scene scene = LoadScene(o.scene);
  RunOptions run_options;
  run_options.external_plc = true;
  run_options.out_dir = o.out_dir;
  if (o.until_s > 0) run_options.until_s = o.until_s;
  SceneRun run(scene, run_options);
  control::gateway::SignalImage* image = run.image();
  if (!image)
    throw std::invalid_argument(o.scene + ": vmt serve needs a scene with an nc: section");
  const int64_t ticks = run.ticks_per_plc_cycle();
  const auto cycle = [&] {
    for (int64_t k = 0; k < ticks && !run.done(); ++k) run.Step();
  };
  if (o.lockstep) {
    mb.cycle_register = control::gateway::LockstepCycleRegister(image->table());
    mb.on_cycle = [&](uint32_t) { cycle(); };
  }
  control::plc::ModbusServer server(*image, mb);
  std::printf("vmt serve: %s, Modbus TCP on %s:%d, %s", scene.name.c_str(), mb.host.c_str(),
              server.port(), o.lockstep ? "lockstep" : "real time");
  if (o.lockstep)
    std::printf(" (write cycle n+1 to holding register %d to run a PLC cycle of %.1f ms)",
                *mb.cycle_register, ticks * 0.25);
  std::printf("\n");
  std::fflush(stdout);

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  std::vector<double> lateness_ms;
  if (o.lockstep) {
    while (!run.done() && !g_stop) server.Poll(100);
  } else {
    // Real time: each PLC cycle starts at its wall-clock time; between cycles the server
    // answers the PLC. Lateness = how long after its time a cycle started.
    using Clock = std::chrono::steady_clock;
    const auto period = std::chrono::microseconds(ticks * 250);
    const auto start = Clock::now();
    for (int64_t n = 0; !run.done() && !g_stop; ++n) {
      const auto due = start + n * period;
      for (auto now = Clock::now(); now < due; now = Clock::now())
        server.Poll(static_cast<int>(std::max<int64_t>(
            0, std::chrono::duration_cast<std::chrono::milliseconds>(due - now).count())));
      lateness_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - due).count());
      cycle();
      server.Poll(0);
    }
  }
  const RunResult r = run.Finish();
  const auto& st = server.stats();
  nlohmann::ordered_json serve = {{"scene", scene.name},
                                  {"mode", o.lockstep ? "lockstep" : "realtime"},
                                  {"stopped_early", !run.done()},
                                  {"simulated_time_s", run.time_s()},
                                  {"trace_digest", r.trace_digest},
                                  {"modbus",
                                   {{"requests", st.requests_served},
                                    {"exceptions", st.exceptions_sent},
                                    {"clients_accepted", st.clients_accepted},
                                    {"clients_dropped", st.clients_dropped},
                                    {"clients_refused", st.clients_refused},
                                    {"cycles", st.cycles}}}};
  if (!o.lockstep)
    serve["cycle_lateness_ms"] = {{"p50", Percentile(lateness_ms, 0.5)},
                                  {"p99", Percentile(lateness_ms, 0.99)},
                                  {"max", Percentile(lateness_ms, 1.0)}};
  if (!o.out_dir.empty()) std::ofstream(o.out_dir + "/serve.json") << serve.dump(2) << '\n';
  std::printf("%s: %.3f s simulated, trace digest %s, %llu Modbus requests, %llu exceptions\n",
              scene.name.c_str(), run.time_s(), r.trace_digest.c_str(),
              static_cast<unsigned long long>(st.requests_served),
              static_cast<unsigned long long>(st.exceptions_sent));
  if (!o.lockstep)
    std::printf("cycle lateness: p50 %.3f ms, p99 %.3f ms, max %.3f ms\n",
                Percentile(lateness_ms, 0.5), Percentile(lateness_ms, 0.99),
                Percentile(lateness_ms, 1.0));
  for (const std::string& f : r.failures) std::fprintf(stderr, "FAILED: %s\n", f.c_str());
  return r.ok() ? 0 : 1;
}

}  // namespace vmt::sim
