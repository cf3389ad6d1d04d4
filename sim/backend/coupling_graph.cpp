#include "sim/backend/coupling_graph.hpp"

namespace vmt::sim {

std::vector<int> PropagateCouplings(const std::vector<CouplingEdge>& edges,
                                    std::vector<double>& q, std::vector<bool>& known) {
  std::vector<int> set;
  for (bool changed = true; changed;) {
    changed = false;
    for (const CouplingEdge& e : edges) {
      if (known[e.motor_joint] && !known[e.load_joint]) {
        q[e.load_joint] = q[e.motor_joint] / e.ratio + e.offset;
        known[e.load_joint] = true;
        set.push_back(e.load_joint);
        changed = true;
      } else if (known[e.load_joint] && !known[e.motor_joint]) {
        q[e.motor_joint] = e.ratio * (q[e.load_joint] - e.offset);
        known[e.motor_joint] = true;
        set.push_back(e.motor_joint);
        changed = true;
      }
    }
  }
  return set;
}

}  // namespace vmt::sim
