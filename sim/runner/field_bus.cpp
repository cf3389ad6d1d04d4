#include "sim/runner/field_bus.hpp"

namespace vmt::sim {

void FieldBus::ConnectAll(const MachineModel& m, const control::gateway::SignalImage& image) {
  connected_ = true;
  for (size_t i = 0; i < m.io.size(); ++i) {
    const int id = image.Find(m.io[i].name);
    if (id < 0 || m.io[i].key) continue;  // keys are the operator's, not the machine's
    (m.io[i].is_output ? outputs_ : inputs_).emplace_back(static_cast<int>(i), id);
  }
}

}  // namespace vmt::sim
