// Real-time factor of the machine backends on the whole lathe with every axis moving and the
// spindles at speed. Counter real_time_factor = simulated seconds per wall second.
// Run: build/bench/backend_bench --benchmark_format=json

#include <benchmark/benchmark.h>

#include "bench/lathe_motion.hpp"
#include "sim/kinematic/kinematic_backend.hpp"
#include "sim/physics/physics_backend.hpp"

namespace {

using namespace vmt;

const sim::MachineModel& Lathe() {
  static const sim::MachineModel model =
      sim::LoadMachineModel(std::string(VMT_SOURCE_DIR) + "/models/lathe-c1/machine.yaml");
  return model;
}

// One simulated second per iteration of bench::LatheMotion.
template <typename Backend>
void BM_Backend(benchmark::State& state) {
  const sim::MachineModel& m = Lathe();
  Backend backend(m, bench::LatheMotion::Start());
  bench::LatheMotion motion(m);
  int64_t tick = 0, steps = 0;
  for (auto _ : state) {
    for (int i = 0; i < 4000; ++i, ++tick) motion.Step(backend, tick);
    steps += 4000;
    benchmark::DoNotOptimize(backend.Read().feedback[0].position);
  }
  state.counters["real_time_factor"] =
      benchmark::Counter(steps * sim::kDriveTickS, benchmark::Counter::kIsRate);
  state.counters["us_per_step"] =
      benchmark::Counter(steps, benchmark::Counter::kIsRate | benchmark::Counter::kInvert,
                         benchmark::Counter::kIs1000);
}

BENCHMARK(BM_Backend<sim::PhysicsBackend>)
    ->Name("physics_lathe_all_axes")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Backend<sim::KinematicBackend>)
    ->Name("kinematic_lathe_all_axes")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
