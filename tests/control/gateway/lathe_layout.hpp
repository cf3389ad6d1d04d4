#pragma once
// The gateway layout of the lathe of models/lathe-c1 (c-axis manual 4.4): one process, X and Z,
// main spindle S1 (spindle-capable), C servo engaged by clutch K, the clutch valves and switches.

#include "control/gateway/signal_table.hpp"

namespace vmt::control::gateway::testing {

inline GatewayLayout LatheLayout() {
  GatewayLayout layout;
  layout.processes = {0};
  layout.axes = {{1, "X", false, false},
                 {2, "Z", false, false},
                 {3, "S1", true, false},
                 {4, "C", false, true}};
  layout.io = {{"QROTMODE", true, "Valve: engage clutch K (rotary axis mode)"},
               {"QSPMODE", true, "Valve: release clutch K (spindle mode)"},
               {"IROTMODE", false, "Switch: clutch K engaged"},
               {"ISPMODE", false, "Switch: clutch K released"}};
  return layout;
}

}  // namespace vmt::control::gateway::testing
