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
  if (m.nc.spindle_drive >= 0) {
    const int number = m.nc.spindle_number > 0 ? m.nc.spindle_number : highest + 1;
    // A spindle with rotary axis capability (C-axis manual 2) is one axis with two
    // designations: its rotary axis' entry becomes spindle-capable.
    auto same = std::find_if(layout.axes.begin(), layout.axes.end(),
                             [&](const auto& a) { return a.number == number; });
    if (same != layout.axes.end())
      same->spindle_capable = true;
    else
      layout.axes.push_back({number, m.drives[m.nc.spindle_drive].info.name, true, false});
  }
  for (const control::IoInfo& io : m.io) {
    std::string meaning = io.is_output    ? "valve (machine output)"
                          : io.selector() ? "selector (operator input), positions"
                          : io.key        ? "machine key (operator input)"
                                          : "sensor (machine input)";
    for (size_t k = 0; k < io.positions.size(); ++k)
      meaning += (k ? "/" : " ") + std::to_string(io.positions[k]);
    layout.io.push_back({io.name, io.is_output, meaning, io.selector(), io.initial, io.key});
  }
  return layout;
}

}  // namespace vmt::sim
