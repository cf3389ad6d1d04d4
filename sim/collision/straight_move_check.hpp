#pragma once
// PathGuard's geometric core: may the machine move in a straight line from joint positions A to
// B (every joint linear in the same parameter u, as the NC's G00-like approach moves are)
// without two parts touching?
//
// FCL 0.7's continuous collision is not fit for it (it misses contacts or finds them only to
// 1/100 of the path), so the check is built from discrete queries: per pair of parts that move
// relative to each other, conservative advancement (step by clearance / the fastest a point of
// the pair can approach, which never steps over a contact), then bisection between the last
// clear and the first touching parameter to the resolution. The smallest clearance comes from
// the same steps, taken short enough near the running minimum to bound the error.

#include <Eigen/Core>
#include <vector>

#include "sim/collision/collision_world.hpp"

namespace vmt::sim {

struct StraightMoveOptions {
  /// Contact position along the path, as travel of the fastest point of any pair that moves
  /// relative to each other (not only of the pair that touches).
  double resolution_m = 1e-6;
  /// The smallest clearance is exact to max(absolute, relative x clearance) (it may be that
  /// much smaller than reported, never larger).
  double clearance_absolute_m = 10e-6;
  double clearance_relative = 0.1;
};

struct StraightMoveCheck {
  bool clear = true;
  // The first contact (clear == false):
  int part_a = -1, part_b = -1;
  double u = 1;                                     ///< path parameter of the contact, 0..1
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< where the parts touch, world, m
  std::vector<double> q;                            ///< joint positions at the contact
  // The smallest clearance on the way (up to the contact), and between which parts:
  double min_clearance_m = 1e30;
  int closest_a = -1, closest_b = -1;
  double closest_u = 0;
  int pairs_checked = 0;
  int pairs_resting = 0;  ///< left out: a measuring sphere resting on the part at the start
};

/// A check of some of the pairs only: those with a part `parts` marks (one flag per part),
/// the others known to stay `clearance_m` apart at least (clearance_proof.hpp). The smallest
/// clearance reported is then that, unless a checked pair comes nearer (closest_a -1 if none).
struct PairScope {
  const std::vector<char>* parts = nullptr;
  double clearance_m = 0;
};

/// Poses `world` along the way (it is left at the end pose or the contact).
StraightMoveCheck CheckStraightMove(CollisionWorld& world, const std::vector<double>& q_from,
                                    const std::vector<double>& q_to,
                                    const StraightMoveOptions& options = {},
                                    const PairScope* scope = nullptr);

/// The fastest any point of the part can move per unit of u on the move (m): translations plus
/// rotations times the farthest the part gets from their axis. An upper bound.
double MotionBound(const CollisionWorld& world, int part, const std::vector<double>& q_from,
                   const std::vector<double>& q_to);

}  // namespace vmt::sim
