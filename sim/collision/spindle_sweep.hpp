#pragma once
// While the spindle turns, the parts that turn with it (flange, chuck body, jaws) are wherever
// the move finds them: a check against the angle they stand at now would let a path between two
// jaws pass. PathGuard then checks against what each sweeps, the solid of revolution that bounds
// it (radius of its farthest corner, filled to the axis: conservative, and the workpiece it
// holds is its own link's anyway), and sets the part itself aside.

#include <string>
#include <vector>

#include "sim/collision/collision_world.hpp"
#include "sim/collision/straight_move_check.hpp"

namespace vmt::sim {

struct SpindleSweep {
  int joint = -1;                   ///< the spindle's joint (the link's parent joint)
  std::vector<int> parts;           ///< the world's machine parts on the link
  std::vector<CylinderPart> swept;  ///< one per part, in the same order, named as it is
};

/// The sweep of the machine parts on `link`; empty (joint -1) if the model lacks the link or it
/// has no revolute parent joint.
SpindleSweep SweepOf(const CollisionWorld& world, const std::string& link);

/// A spindle about to start at joint positions `q`, in a world that holds the sweep of its
/// chuck from part `first_swept` on (PathGuard's while the spindle turns): the swept solids
/// against every part that does not turn with `joint`. The workpiece is a body of revolution
/// already: what touches it at rest (a cut ends on its surface, the tailstock's centre sits in
/// it) touches it as it turns, so vmt takes the start to add only what the chuck sweeps beyond
/// its standing parts. The first contact found (u 0), else the smallest clearance.
StraightMoveCheck CheckSpindleStart(CollisionWorld& world, const std::vector<double>& q,
                                    int joint, int first_swept);

}  // namespace vmt::sim
