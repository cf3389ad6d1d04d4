// Real-time factor of the machine backends on the whole lathe with every axis moving and the
// spindles at speed. Counter real_time_factor = simulated seconds per wall second.
// Run: build/bench/backend_bench --benchmark_format=json

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "sim/kinematic/kinematic_backend.hpp"
#include "sim/physics/physics_backend.hpp"

namespace {

using namespace vmt;

const sim::MachineModel& Lathe() {
  static const sim::MachineModel model =
      sim::LoadMachineModel(std::string(VMT_SOURCE_DIR) + "/models/lathe-c1/machine.yaml");
  return model;
}

// One simulated second per iteration: X, Z, W, T and C (clutch open, so C turns its motor
// alone) follow sine commands, S1 runs at 3000 rpm, S2 at 4000 rpm.
template <typename Backend>
void BM_Backend(benchmark::State& state) {
  const sim::MachineModel& m = Lathe();
  sim::InitialState init;
  init.drive_positions = {{"Z", 300}, {"X", 100}, {"W", 300}};
  Backend backend(m, init);
  control::MasterTelegram mdt;
  mdt.setpoints.resize(m.drives.size());
  mdt.outputs.assign(m.io.size(), 0);
  struct Axis {
    const char* name;
    double centre, amplitude, hz;
  };
  const Axis axes[] = {{"Z", 300, 100, 1.0},
                       {"X", 100, 40, 1.5},
                       {"W", 300, 50, 0.5},
                       {"T", 0, 90, 1.0},
                       {"C", 0, 45, 2.0}};
  mdt.setpoints[m.DriveIndex("S1")] = {control::DriveMode::kVelocity, 3000 * 6, 0};
  mdt.setpoints[m.DriveIndex("S2")] = {control::DriveMode::kVelocity, 4000 * 6, 0};
  // Commands precomputed for two seconds (every sine repeats within them), so the benchmark
  // times the backend, not sin().
  constexpr int kTicks = 8000;
  std::vector<std::array<double, 5>> table(kTicks);
  int index[5];
  for (int k = 0; k < 5; ++k) index[k] = m.DriveIndex(axes[k].name);
  for (int i = 0; i < kTicks; ++i)
    for (int k = 0; k < 5; ++k)
      table[i][k] =
          axes[k].centre +
          axes[k].amplitude * std::sin(2 * std::numbers::pi * axes[k].hz * i * sim::kDriveTickS);
  int64_t tick = 0, steps = 0;
  for (auto _ : state) {
    for (int i = 0; i < 4000; ++i, ++tick) {
      const auto& row = table[tick % kTicks];
      for (int k = 0; k < 5; ++k)
        mdt.setpoints[index[k]] = {control::DriveMode::kPosition, row[k], 0};
      backend.Write(mdt);
      backend.Step();
    }
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
