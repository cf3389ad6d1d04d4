#pragma once
// A straight move checked clear proves more than itself: every pair it measured stays at least
// its smallest clearance apart all the way. A nearby straight move (the next check ahead of a
// jog, from a little further on to a little further on) is as clear if no point of any part
// strays from where the checked move had it by as much as that clearance. Where only slides
// differ between the two moves, how far a point strays is at most the sum of the slides'
// differences: the proof costs a pass over the joints instead of distance queries.
//
// A part a rotation moves (a motor's rotor turning with the spindle) strays by as much as it
// is wide: its pairs are left to a query (PairScope). The spindle's angle moves nothing while
// the chuck is checked as the solid it sweeps: what turns with it is then bodies of revolution
// about its axis.

#include <optional>
#include <vector>

#include "sim/collision/collision_world.hpp"

namespace vmt::sim {

/// A straight move found clear, in joint positions (SI, one per model joint).
struct ClearMove {
  std::vector<double> q_from, q_to;
  double clearance_m = 0;  ///< its smallest clearance, as the check reported it
};

/// How a straight move strays from a checked one, the two taken at the same fraction of their
/// way.
struct Stray {
  double slides_m = 0;       ///< the farthest a point of a part not `turned` strays, at most
  std::vector<char> turned;  ///< per part: a rotation moves it from where the check had it
  bool any_turned = false;
};

/// How the straight move `q_from`..`q_to` strays from `checked`; nothing when the slides alone
/// move a pair against each other that `checked` held still (it never measured it).
/// `turning_joint` (-1: none) turns only bodies of revolution about its own axis. `world` as
/// last posed.
std::optional<Stray> StrayFrom(const CollisionWorld& world, const ClearMove& checked,
                               const std::vector<double>& q_from, const std::vector<double>& q_to,
                               int turning_joint);

}  // namespace vmt::sim
