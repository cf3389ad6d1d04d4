#include "sim/backend/stylus.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include "common/demand.hpp"

namespace vmt::sim {
namespace {

// A tick in which a crossing may lie is sampled at this many steps; the first step whose ends
// differ holds the crossing, which bisection then solves. Two crossings within one step (a
// graze shorter than a sixteenth of a tick) are missed, as a sampled input misses them.
constexpr int kSteps = 16;
// Bisection stops when the spheres move less than this within the bracket: 0.01 nm.
constexpr double kSolvedM = 1e-11;
// What the bounding cylinder's test leaves beyond the rounding of the exact distances (a few
// ulps of a machine's size).
constexpr double kFarMarginM = 1e-9;

struct Deepest {
  double depth_m = -1e300;  ///< largest (sphere radius - signed distance); < 0: clear
  int sphere = -1;
};

Deepest DeepestAt(const ProbeStylus& stylus, const RevolvedPart& part,
                  const std::vector<Eigen::Vector3d>& before,
                  const std::vector<Eigen::Vector3d>& after, double u) {
  Deepest d;
  for (size_t i = 0; i < stylus.spheres.size(); ++i) {
    const Eigen::Vector3d c = before[i] + u * (after[i] - before[i]);
    const double depth = stylus.spheres[i].radius_m - SignedDistance(part, c).distance_m;
    if (depth > d.depth_m) d = {depth, static_cast<int>(i)};
  }
  return d;
}

bool Level(const ProbeStylus& stylus, bool tripped, bool ready) {
  return ready && (tripped != stylus.normally_closed);
}

/// The depth (sphere radius - distance) a sphere must stay below, with the travel in the tick
/// added, for the tick to be a quiet one.
double FarDepth(const ProbeStylus& stylus, const StylusState& state) {
  double lowest = std::min(0.0, stylus.pre_travel_m);
  if (!state.damaged) lowest = std::min(lowest, stylus.over_travel_m);
  return lowest - kFarMarginM;
}

}  // namespace

double FarRoom(const ProbeStylus& stylus, const RevolvedPart& part, const StylusState& state,
               const std::vector<Eigen::Vector3d>& centres) {
  const double far_depth = FarDepth(stylus, state);
  double room = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < stylus.spheres.size(); ++i)
    room = std::min(
        room, far_depth - (stylus.spheres[i].radius_m - DistanceLowerBound(part, centres[i])));
  return room;
}

StylusTick QuietTick(const ProbeStylus& stylus, StylusState& state, bool ready) {
  StylusTick tick;
  tick.io_input = stylus.contact_input;
  const bool level = Level(stylus, false, ready);
  tick.changed = level != state.level;
  tick.level = level;  // a level that changes here changes at the tick's start (ready)
  state = {false, level, state.damaged, 0.0};
  return tick;
}

std::vector<Eigen::Vector3d> SphereCentres(const ProbeStylus& stylus,
                                           const Eigen::Isometry3d& X_PartLink) {
  std::vector<Eigen::Vector3d> centres;
  for (const MeasuringSphere& s : stylus.spheres) centres.push_back(X_PartLink * s.centre_m);
  return centres;
}

double SphereDeflection(const ProbeStylus& stylus, const RevolvedPart& part, int index,
                        const Eigen::Vector3d& centre_m) {
  return std::max(0.0, stylus.spheres[index].radius_m - SignedDistance(part, centre_m).distance_m);
}

StylusTick StepStylus(const ProbeStylus& stylus, const RevolvedPart& part, StylusState& state,
                      const std::vector<Eigen::Vector3d>& before,
                      const std::vector<Eigen::Vector3d>& after, bool ready) {
  VMT_DEMAND(before.size() == stylus.spheres.size() && after.size() == stylus.spheres.size(),
             "StepStylus: %zu spheres, %zu centres before, %zu after", stylus.spheres.size(),
             before.size(), after.size());
  StylusTick tick;
  tick.io_input = stylus.contact_input;
  double travel_m = 0;  // the farthest any centre moves: bounds how fast the depth changes
  for (size_t i = 0; i < stylus.spheres.size(); ++i)
    travel_m = std::max(travel_m, (after[i] - before[i]).norm());

  // Far from the part (the common case) the bounding cylinder alone shows that no sphere comes
  // near any threshold in this tick: the tick is the quiet one the exact depths would give.
  const double far_depth = FarDepth(stylus, state);
  bool far = true;
  for (size_t i = 0; i < stylus.spheres.size() && far; ++i)
    for (const Eigen::Vector3d* c : {&before[i], &after[i]})
      far = far && stylus.spheres[i].radius_m - DistanceLowerBound(part, *c) + travel_m < far_depth;
  if (far) return QuietTick(stylus, state, ready);

  // Depth along the tick at u = k / kSteps. The depth changes no faster than the centres
  // move, so when both ends lie far enough on one side of a threshold the tick cannot cross
  // it, and the ends are all it takes (the common case: nothing near the part).
  std::array<Deepest, kSteps + 1> at;
  at[0] = DeepestAt(stylus, part, before, after, 0);
  at[kSteps] = DeepestAt(stylus, part, before, after, 1);
  auto may_cross = [&](double threshold) {
    const double sum = at[0].depth_m + at[kSteps].depth_m;
    return !((sum - travel_m) / 2 > threshold || (sum + travel_m) / 2 < threshold);
  };
  const bool sampled = travel_m > 0 && (may_cross(stylus.pre_travel_m) ||
                                        (!state.damaged && may_cross(stylus.over_travel_m)));
  if (sampled)
    for (int k = 1; k < kSteps; ++k)
      at[k] = DeepestAt(stylus, part, before, after, static_cast<double>(k) / kSteps);
  const int last = sampled ? kSteps : 1;
  auto sample = [&](int k) { return sampled || k == 0 ? at[k] : at[kSteps]; };

  // The first instant at which depth > threshold differs from its value at u = 0, by
  // bisection in the first step where it changes; -1 when it does not change.
  auto first_crossing = [&](double threshold) {
    const bool start = sample(0).depth_m > threshold;
    for (int k = 1; k <= last; ++k) {
      if ((sample(k).depth_m > threshold) == start) continue;
      double lo = static_cast<double>(k - 1) / last, hi = static_cast<double>(k) / last;
      while ((hi - lo) * travel_m > kSolvedM) {
        const double mid = (lo + hi) / 2;
        if ((DeepestAt(stylus, part, before, after, mid).depth_m > threshold) == start)
          lo = mid;
        else
          hi = mid;
      }
      return (lo + hi) / 2;
    }
    return -1.0;
  };

  // The switch: its level from the start of the tick on, then where the geometry flips it.
  const bool tripped_start = at[0].depth_m > stylus.pre_travel_m;
  const bool tripped_end = at[kSteps].depth_m > stylus.pre_travel_m;
  const bool level_end = Level(stylus, tripped_end, ready);
  if (level_end != state.level) {
    tick.changed = true;
    tick.level = level_end;
    // A level that differs already at the tick's start (the first tick, the ready message
    // come or gone) changed at its start.
    const bool jumped = Level(stylus, tripped_start, ready) != state.level;
    tick.tick_fraction = jumped ? 0.0 : std::max(0.0, first_crossing(stylus.pre_travel_m));
  } else {
    tick.level = state.level;
  }
  state.level = level_end;
  state.tripped = tripped_end;

  tick.deflection_m = std::max(0.0, at[kSteps].depth_m);
  tick.sphere = at[kSteps].depth_m > 0 ? at[kSteps].sphere : -1;
  state.deflection_m = tick.deflection_m;

  // Over-travel: the first instant the deflection passes it damages the stylus, once.
  if (!state.damaged) {
    int k_over = -1;
    for (int k = 0; k <= last && k_over < 0; ++k)
      if (sample(k).depth_m > stylus.over_travel_m) k_over = k;
    if (k_over >= 0) {
      const double u = k_over == 0 ? 0.0 : first_crossing(stylus.over_travel_m);
      const Deepest d = DeepestAt(stylus, part, before, after, u);
      const Eigen::Vector3d c = before[d.sphere] + u * (after[d.sphere] - before[d.sphere]);
      tick.over_travel = true;
      tick.over_travel_fraction = u;
      tick.over_travel_sphere = d.sphere;
      tick.over_travel_point_m = SignedDistance(part, c).point_m;
      state.damaged = true;
    }
  }
  return tick;
}

}  // namespace vmt::sim
