#include "sim/collision/straight_move_check.hpp"

#include <algorithm>
#include <cmath>

namespace vmt::sim {
namespace {

/// The joints from the root down to `link` (model joint indices, root first).
std::vector<int> Chain(const MachineModel& m, int link) {
  std::vector<int> chain;
  for (int j = m.links[link].parent_joint; j >= 0;
       j = m.links[m.joints[j].parent_link].parent_joint)
    chain.push_back(j);
  std::reverse(chain.begin(), chain.end());
  return chain;
}

/// MotionBound for the joints of `chain` from index `first` on (those below the pair's common
/// ancestor: the ones above it move both parts alike). World poses of the start are posed.
double ChainBound(const CollisionWorld& world, int part, const std::vector<int>& chain,
                  size_t first, const std::vector<double>& dq) {
  const MachineModel& m = world.model();
  const CollisionPart& p = world.part(part);
  const Eigen::Vector3d c = world.X_WorldLink(p.link) * p.X_LinkPart * p.centre;
  double bound = 0;
  for (size_t k = first; k < chain.size(); ++k) {
    const Joint& jk = m.joints[chain[k]];
    const double step = std::abs(dq[chain[k]]);
    if (step == 0 || jk.type == JointType::kFixed) continue;
    if (jk.type == JointType::kPrismatic) {
      bound += step;
      continue;
    }
    // The farthest a point of the part gets from this joint's axis: from its origin now, plus
    // what the joints below can add (a slide moves it out, a rotation swings it across).
    const Eigen::Vector3d o = (world.X_WorldLink(jk.parent_link) * jk.X_ParentJoint).translation();
    double r = (c - o).norm() + p.radius;
    for (size_t i = k + 1; i < chain.size(); ++i) {
      const Joint& ji = m.joints[chain[i]];
      const double s = std::abs(dq[chain[i]]);
      if (s == 0 || ji.type == JointType::kFixed) continue;
      if (ji.type == JointType::kPrismatic) {
        r += s;
      } else {
        const Eigen::Vector3d oi =
            (world.X_WorldLink(ji.parent_link) * ji.X_ParentJoint).translation();
        r += 2 * ((c - oi).norm() + p.radius);
      }
    }
    bound += step * r;
  }
  return bound;
}

size_t CommonDepth(const std::vector<int>& a, const std::vector<int>& b) {
  size_t n = 0;
  while (n < a.size() && n < b.size() && a[n] == b[n]) ++n;
  return n;
}

std::vector<double> Lerp(const std::vector<double>& a, const std::vector<double>& b, double u) {
  std::vector<double> q(a.size());
  for (size_t i = 0; i < a.size(); ++i) q[i] = a[i] + (b[i] - a[i]) * u;
  return q;
}

struct Pair {
  int a, b;
  double bound;  ///< how fast the pair can approach, m per unit of u
};

/// The pairs that move relative to each other on the move, with the bound of their approach
/// speed. `world` is posed at the start.
std::vector<Pair> MovingPairs(const CollisionWorld& world, const std::vector<double>& dq,
                              int& resting) {
  const MachineModel& m = world.model();
  std::vector<std::vector<int>> chains(m.links.size());
  size_t depth = 0;
  for (size_t l = 0; l < m.links.size(); ++l) {
    chains[l] = Chain(m, static_cast<int>(l));
    depth = std::max(depth, chains[l].size());
  }
  // A part's bound depends only on where its chain parts from the other part's: worked out
  // once per part and depth, not once per pair.
  std::vector<double> bounds(static_cast<size_t>(world.size()) * (depth + 1), -1);
  auto bound_of = [&](int part, size_t common) {
    double& bound = bounds[static_cast<size_t>(part) * (depth + 1) + common];
    if (bound < 0) bound = ChainBound(world, part, chains[world.part(part).link], common, dq);
    return bound;
  };
  std::vector<Pair> pairs;
  for (int a = 0; a < world.size(); ++a)
    for (int b = a + 1; b < world.size(); ++b) {
      if (world.MayTouch(a, b)) continue;
      // A measuring sphere resting on the part as the move starts (the measurement just
      // latched: the escape, or the next approach after a PROBE without escape) may leave it.
      if (world.Measures(a, b) && world.Collide(a, b)) {
        ++resting;
        continue;
      }
      const size_t common = CommonDepth(chains[world.part(a).link], chains[world.part(b).link]);
      const double bound = bound_of(a, common) + bound_of(b, common);
      if (bound > 0) pairs.push_back({a, b, bound});
    }
  return pairs;
}

/// Where only slides move, every part keeps its rotation and its bounding box slides in a
/// straight line with u: the box spanning its start and end boxes holds it all the way. Empty
/// when a rotation moves. Leaves `world` posed at the start.
std::vector<Eigen::AlignedBox3d> SlidingBoxes(CollisionWorld& world,
                                              const std::vector<double>& q_from,
                                              const std::vector<double>& q_to,
                                              const std::vector<double>& dq) {
  const MachineModel& m = world.model();
  bool sliding = true;
  for (size_t j = 0; j < dq.size() && j < m.joints.size(); ++j)
    sliding = sliding && (dq[j] == 0 || m.joints[j].type == JointType::kPrismatic ||
                          m.joints[j].type == JointType::kFixed);
  std::vector<Eigen::AlignedBox3d> boxes;
  if (sliding) {
    world.Pose(q_to);
    for (int i = 0; i < world.size(); ++i) boxes.push_back(world.Box(i));
  }
  world.Pose(q_from);
  for (size_t i = 0; i < boxes.size(); ++i) boxes[i].extend(world.Box(static_cast<int>(i)));
  return boxes;
}

}  // namespace

double MotionBound(const CollisionWorld& world, int part, const std::vector<double>& q_from,
                   const std::vector<double>& q_to) {
  std::vector<double> dq(q_from.size());
  for (size_t i = 0; i < dq.size(); ++i) dq[i] = q_to[i] - q_from[i];
  return ChainBound(world, part, Chain(world.model(), world.part(part).link), 0, dq);
}

StraightMoveCheck CheckStraightMove(CollisionWorld& world, const std::vector<double>& q_from,
                                    const std::vector<double>& q_to,
                                    const StraightMoveOptions& options, const PairScope* scope) {
  StraightMoveCheck out;
  std::vector<double> dq(q_from.size());
  for (size_t i = 0; i < dq.size(); ++i) dq[i] = q_to[i] - q_from[i];
  const std::vector<Eigen::AlignedBox3d> swept = SlidingBoxes(world, q_from, q_to, dq);
  std::vector<Pair> pairs = MovingPairs(world, dq, out.pairs_resting);
  if (scope) {
    const std::vector<char>& in = *scope->parts;
    std::erase_if(pairs, [&in](const Pair& p) { return !in[p.a] && !in[p.b]; });
    out.min_clearance_m = scope->clearance_m;
  }

  auto tolerance = [&](double clearance) {
    return std::max(options.clearance_absolute_m, options.clearance_relative * clearance);
  };
  auto note_clearance = [&](const Pair& p, double d, double u) {
    if (d < out.min_clearance_m)
      out.min_clearance_m = d, out.closest_a = p.a, out.closest_b = p.b, out.closest_u = u;
  };
  // Bounding boxes give a lower bound of the clearance for next to nothing: exact distances
  // only where the boxes come close to a contact or to the running minimum. Nearest pairs
  // first, so that the minimum is small early and the far pairs drop out on their boxes.
  std::vector<std::pair<Pair, double>> start;
  for (const Pair& p : pairs) start.push_back({p, world.BoxDistance(p.a, p.b)});
  std::sort(start.begin(), start.end(), [](const auto& x, const auto& y) {
    return x.second - x.first.bound < y.second - y.first.bound;
  });

  // The contact is found to the resolution of the fastest pair's travel, not of its own pair's:
  // the first contact of a slow pair (a turret tool swinging past its slide) must not come out
  // later on the path than the resolution says of the machine's fastest point.
  double fastest = 0;
  for (const Pair& p : pairs) fastest = std::max(fastest, p.bound);
  const double du_resolution = fastest > 0 ? options.resolution_m / fastest : 1;

  double u_end = 1;  // nothing after the first contact found so far matters
  for (const auto& [p, box0] : start) {
    if (box0 - p.bound * u_end > out.min_clearance_m) continue;  // never closer than the minimum
    // Boxes that stay apart all the way by more than any clearance the pair could still note,
    // or step to a contact check at: the pair would make no query and change nothing. (The
    // margin covers rounding in the boxes, far below it.)
    const double tol = std::abs(tolerance(out.min_clearance_m));
    if (!swept.empty() && swept[p.a].exteriorDistance(swept[p.b]) >
                              out.min_clearance_m + 2 * tol + std::abs(options.resolution_m) + 1e-9)
      continue;
    ++out.pairs_checked;
    double u = 0;
    bool contact = false;
    while (u < u_end) {
      if (u > 0) world.PosePair(Lerp(q_from, q_to, u), p.a, p.b);
      // A lower bound of the clearance here: the boxes' while they are far, else the exact one.
      double d = world.BoxDistance(p.a, p.b);
      if (d <= out.min_clearance_m + tolerance(out.min_clearance_m)) {
        d = world.Distance(p.a, p.b);
        note_clearance(p, d, u);
        // FCL's distance and collision may disagree within rounding: a distance of 0 without
        // a collision steps on by the resolution, checking for the contact (below).
        if (d <= 0 && world.Collide(p.a, p.b)) {
          contact = true;
          break;
        }
      }
      // Step so that neither a contact nor a clearance below the running minimum (less its
      // tolerance) can lie within the step.
      const double gap = std::min(d, d - out.min_clearance_m + tolerance(out.min_clearance_m));
      const double u_next = std::min(u_end, u + std::max(gap, options.resolution_m) / p.bound);
      if (gap < options.resolution_m) {
        world.PosePair(Lerp(q_from, q_to, u_next), p.a, p.b);
        if (world.Collide(p.a, p.b)) {
          // Bisect: u clear, u_next touching.
          double lo = u, hi = u_next;
          while (hi - lo > du_resolution) {
            const double mid = (lo + hi) / 2;
            world.PosePair(Lerp(q_from, q_to, mid), p.a, p.b);
            (world.Collide(p.a, p.b) ? hi : lo) = mid;
          }
          u = hi;
          contact = true;
          break;
        }
      }
      if (u_next >= u_end) break;
      u = u_next;
    }
    if (contact && u <= u_end) {
      u_end = u;
      out.clear = false;
      out.part_a = p.a, out.part_b = p.b, out.u = u;
    }
    world.PosePair(q_from, p.a, p.b);
  }
  if (!out.clear) {
    out.q = Lerp(q_from, q_to, out.u);
    world.Pose(out.q);
    world.Collide(out.part_a, out.part_b, &out.point);
    out.min_clearance_m = 0;
    out.closest_a = out.part_a, out.closest_b = out.part_b, out.closest_u = out.u;
  } else {
    world.Pose(q_to);
  }
  return out;
}

}  // namespace vmt::sim
