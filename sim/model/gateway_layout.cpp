#include "sim/model/gateway_layout.hpp"

#include <algorithm>

namespace vmt::sim {

control::gateway::GatewayLayout GatewayLayoutOf(const MachineModel& m) {
  control::gateway::GatewayLayout layout;
  layout.processes = {m.nc.process.number};
  int highest = 0;
  for (const control::axes::AxisParameters& a : m.nc.axes) {
    layout.axes.push_back({a.number, a.name, false, a.rotary});
    highest = std::max(highest, a.number);
  }
  if (m.nc.spindle_drive >= 0)
    layout.axes.push_back({highest + 1, m.drives[m.nc.spindle_drive].info.name, true, false});
  for (const control::IoInfo& io : m.io)
    layout.io.push_back({io.name, io.is_output,
                         io.is_output ? "valve (machine output)"
                         : io.key     ? "machine key (operator input)"
                                      : "sensor (machine input)"});
  return layout;
}

}  // namespace vmt::sim
