#pragma once
// Look-ahead over the blocks after the one in work. The blocks read ahead make a list of speed
// limits along the path (speed targets): at each junction the corner (junction deviation) and
// the feeds on both sides, and a stop at the end of the last block known. Each NC cycle the
// path profile brakes in time for every one of them, wherever it lies: a braking may span many
// short blocks, and the path goes on through a block's end with its speed and acceleration. Knowing
// more blocks only moves the final stop further away, so what was planned with fewer blocks stays
// safe when more are read.

#include <span>
#include <vector>

#include "control/channel/path_profile.hpp"

namespace vmt::control::channel {

/// Look-ahead: how far (mm) the path may be thought to round a corner when choosing its speed.
inline constexpr double kCornerDeviation = 0.01;
/// Blocks read ahead at most for the look-ahead.
inline constexpr int kLookAheadBlocks = 32;

/// One block after the block in work, in path units (mm of axis space).
struct LookAheadLeg {
  double max_speed = 0;  ///< at the programmed feed, mm/s
  double accel = 0;      ///< along the path, mm/s^2
  double jerk = 0;       ///< along the path, mm/s^3; 0: not limited
  double length = 0;     ///< mm
  double cos_turn = 1;   ///< cosine of the direction change into this block (1: tangent)
};

/// A speed limit ahead, from the start of the block in work.
struct SpeedTarget {
  double distance = 0;     ///< mm
  double corner = 0;       ///< mm/s, whatever the override
  double feed = 0;         ///< mm/s at 100 % override: the feeds on both sides
  double accel = 0;        ///< least path acceleration on the way there, mm/s^2
  double jerk = 0;         ///< least path jerk on the way there, mm/s^3; 0: not limited
  double settle_jerk = 0;  ///< path jerk of the block beyond, mm/s^3; 0: not limited
};

/// Path distance the profile needs to brake from `from` (at zero acceleration) to `to`; never
/// more for a higher `to`.
double BrakingDistance(double from, double to, double accel, double jerk, double cycle_s);

/// Highest speed through a corner whose directions have the cosine `cos_turn`: the centripetal
/// acceleration of an arc that leaves the corner kCornerDeviation away stays within `accel`.
/// Infinite for a tangent join, zero for a reversal.
double CornerSpeed(double cos_turn, double accel);

/// The targets for the block in work (`length` mm, feed `max_speed`, path `accel` and `jerk`)
/// followed by `legs`: one at each block end, the last one at rest.
void PlanTargets(double length, double max_speed, double accel, double jerk,
                 std::span<const LookAheadLeg> legs, std::vector<SpeedTarget>& out);

/// The targets as the profile of the block in work (`length` mm) takes them (PathProfile::ahead),
/// in its u. Above 100 % the override raises the feed limits, not the corners.
void ProfileTargets(std::span<const SpeedTarget> targets, double length, double override,
                    std::vector<ProfileTarget>& out);

/// The channel's look-ahead between feed moves as the block in work runs: its speed targets in
/// the profile's u (scratch, reused) and the speed and acceleration carried into the next block.
struct LookAheadState {
  std::vector<ProfileTarget> profile_targets;
  double carry_speed = 0, carry_accel = 0, carry_leftover = 0;
};

}  // namespace vmt::control::channel
