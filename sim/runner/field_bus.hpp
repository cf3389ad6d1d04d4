#pragma once
// The field bus between the machine's I/O points and the signal image, where a PLC runs: the
// machine's sensors go into their signals at the end of each PLC cycle (so that the next scan
// sees them), the PLC's valve signals go out to the machine's outputs every tick. The operator's
// keys are no points of the bus: they stay the panel's.

#include <utility>
#include <vector>

#include "control/drive_bus.hpp"
#include "control/gateway/signal_image.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

class FieldBus {
 public:
  /// Connects every I/O point of `m` that has a signal in `image`, keys left out.
  void ConnectAll(const MachineModel& m, const control::gateway::SignalImage& image);
  /// Connects the bus without points; Add* add them one at a time.
  void Connect() { connected_ = true; }
  void AddInput(int io, int signal) { inputs_.emplace_back(io, signal); }
  void AddOutput(int io, int signal) { outputs_.emplace_back(io, signal); }
  bool connected() const { return connected_; }

  /// The sensors of `at` into their signals.
  void ReadInputs(const control::AmplifierTelegram& at,
                  control::gateway::SignalImage& image) const {
    for (const auto& [io, id] : inputs_) image.SetBool(id, at.inputs[io] != 0);
  }
  /// The valve signals out to the machine's outputs.
  void WriteOutputs(const control::gateway::SignalImage& image,
                    control::MasterTelegram& mdt) const {
    for (const auto& [io, id] : outputs_) mdt.outputs[io] = image.Bool(id) ? 1 : 0;
  }

 private:
  bool connected_ = false;
  std::vector<std::pair<int, int>> inputs_, outputs_;  ///< I/O point, signal id
};

}  // namespace vmt::sim
