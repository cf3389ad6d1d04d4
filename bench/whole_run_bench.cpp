// The whole run against its backend: each showcase scene runs to its end as `vmt run` runs it
// (NC, PLC, PathGuard, the trace in memory and its digest), without pictures or files, and the
// scene's backend runs alone on the same machine model with every axis moving
// (bench::LatheMotion, as backend_bench). Counters: real_time_factor (simulated s per wall s)
// of the whole run, backend_real_time_factor of the backend alone, measured in the same
// process, and share_of_backend, their ratio: what the control, PathGuard and the bookkeeping
// leave of the backend's speed.
// Run: build/bench/whole_run_bench --benchmark_format=json

#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <string>

#include "bench/lathe_motion.hpp"
#include "sim/runner/make_backend.hpp"
#include "sim/runner/runner.hpp"

namespace {

using namespace vmt;
using Clock = std::chrono::steady_clock;

// The backend alone for half a second of wall time at least, once per scene.
double BackendRealTimeFactor(const sim::Scene& scene) {
  const std::unique_ptr<sim::MachineBackend> backend =
      sim::MakeBackend(scene.backend, *scene.model, bench::LatheMotion::Start());
  bench::LatheMotion motion(*scene.model);
  int64_t tick = 0;
  for (; tick < 400; ++tick) motion.Step(*backend, tick);  // warm caches and pools
  const Clock::time_point t0 = Clock::now();
  double wall = 0;
  int64_t steps = 0;
  while (wall < 0.5) {
    for (int i = 0; i < 4000; ++i, ++tick, ++steps) motion.Step(*backend, tick);
    wall = std::chrono::duration<double>(Clock::now() - t0).count();
  }
  return steps * sim::kDriveTickS / wall;
}

void BM_WholeRun(benchmark::State& state, const std::string& file) {
  const sim::Scene scene = sim::LoadScene(std::string(VMT_SOURCE_DIR) + "/scenes/" + file);
  sim::RunOptions options;
  options.snapshots = false;
  double simulated = 0, wall = 0;
  for (auto _ : state) {
    const Clock::time_point t0 = Clock::now();
    const sim::RunResult r = sim::RunScene(scene, options);
    wall += std::chrono::duration<double>(Clock::now() - t0).count();
    simulated += r.simulated_s;
    benchmark::DoNotOptimize(r.trace_digest);
  }
  const double run = wall > 0 ? simulated / wall : 0;
  const double backend = BackendRealTimeFactor(scene);
  state.counters["real_time_factor"] = run;
  state.counters["backend_real_time_factor"] = backend;
  state.counters["share_of_backend"] = backend > 0 ? run / backend : 0;
  state.SetLabel(sim::ToString(scene.backend));
}

// The showcase scenes: two kinematic (NC + PLC + PathGuard + probing), two physics.
BENCHMARK_CAPTURE(BM_WholeRun, repos_automatic, std::string("repos-automatic.yaml"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_WholeRun, measure_shaft, std::string("measure-shaft.yaml"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_WholeRun, turning, std::string("turning.yaml"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);
BENCHMARK_CAPTURE(BM_WholeRun, c_axis_switching, std::string("c-axis-switching.yaml"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);

}  // namespace
