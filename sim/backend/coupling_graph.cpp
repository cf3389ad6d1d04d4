#include "sim/backend/coupling_graph.hpp"

namespace vmt::sim {

void PropagateCouplings(const std::vector<CouplingEdge>& edges, std::vector<double>& q,
                        std::vector<bool>& known) {
  for (bool changed = true; changed;) {
    changed = false;
    for (const CouplingEdge& e : edges) {
      if (known[e.motor_joint] && !known[e.load_joint]) {
        q[e.load_joint] = q[e.motor_joint] / e.ratio + e.offset;
        known[e.load_joint] = true;
        changed = true;
      } else if (known[e.load_joint] && !known[e.motor_joint]) {
        q[e.motor_joint] = e.ratio * (q[e.load_joint] - e.offset);
        known[e.motor_joint] = true;
        changed = true;
      }
    }
  }
}

}  // namespace vmt::sim
