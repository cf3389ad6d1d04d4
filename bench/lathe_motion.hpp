#pragma once
// The backend benchmarks' motion on lathe-c1: X, Z, W, T and C (clutch open, so C turns its
// motor alone) follow sine commands, S1 runs at 3000 rpm, S2 at 4000 rpm. The commands are
// precomputed for two seconds (every sine repeats within them), so a benchmark times the
// backend, not sin().

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "sim/backend/machine_backend.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::bench {

class LatheMotion {
 public:
  explicit LatheMotion(const sim::MachineModel& m) {
    telegram_.setpoints.resize(m.drives.size());
    telegram_.outputs.assign(m.io.size(), 0);
    const Axis axes[kAxes] = {{"Z", 300, 100, 1.0},
                              {"X", 100, 40, 1.5},
                              {"W", 300, 50, 0.5},
                              {"T", 0, 90, 1.0},
                              {"C", 0, 45, 2.0}};
    telegram_.setpoints[m.DriveIndex("S1")] = {control::DriveMode::kVelocity, 3000 * 6, 0};
    telegram_.setpoints[m.DriveIndex("S2")] = {control::DriveMode::kVelocity, 4000 * 6, 0};
    for (int k = 0; k < kAxes; ++k) index_[k] = m.DriveIndex(axes[k].name);
    table_.resize(kTicks);
    for (int i = 0; i < kTicks; ++i)
      for (int k = 0; k < kAxes; ++k)
        table_[i][k] =
            axes[k].centre +
            axes[k].amplitude * std::sin(2 * std::numbers::pi * axes[k].hz * i * sim::kDriveTickS);
  }

  /// The initial state the motion starts from (inside every axis' travel).
  static sim::InitialState Start() {
    sim::InitialState init;
    init.drive_positions = {{"Z", 300}, {"X", 100}, {"W", 300}};
    return init;
  }

  /// Writes tick `tick`'s commands and steps the backend once (a template: a concrete backend's
  /// calls need no virtual dispatch).
  template <typename Backend>
  void Step(Backend& backend, int64_t tick) {
    const auto& row = table_[tick % kTicks];
    for (int k = 0; k < kAxes; ++k)
      telegram_.setpoints[index_[k]] = {control::DriveMode::kPosition, row[k], 0};
    backend.Write(telegram_);
    backend.Step();
  }

 private:
  static constexpr int kAxes = 5, kTicks = 8000;
  struct Axis {
    const char* name;
    double centre, amplitude, hz;
  };
  control::MasterTelegram telegram_;
  int index_[kAxes] = {};
  std::vector<std::array<double, kAxes>> table_;
};

}  // namespace vmt::bench
