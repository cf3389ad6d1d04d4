#pragma once
// Joints tied by gears and engaged clutches: q_motor = ratio * (q_load - offset).
// Used by the kinematic backend (which has no constraint solver) and for initial states.

#include <vector>

#include "sim/model/machine_model.hpp"

namespace vmt::sim {

struct CouplingEdge {
  int motor_joint, load_joint;
  double ratio;
  double offset;  ///< load side, rad
};

/// Sets every joint that is not yet `known` but coupled to a known one, transitively.
void PropagateCouplings(const std::vector<CouplingEdge>& edges, std::vector<double>& q,
                        std::vector<bool>& known);

}  // namespace vmt::sim
