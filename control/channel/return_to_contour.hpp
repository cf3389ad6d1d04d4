#pragma once
// The return to the contour after block search (block search 4.2, 4.2.2, 8) as functions of
// where the axes stand, where machining goes on and the axes' parameters: the automatic
// return's first leg, the straight move a leg is, and the manual return's check against the
// allowed deviation with the offset the program then runs with. The channel asks PathGuard
// about a leg, runs it and keeps the offset (channel_return_to_contour.cpp).

#include <cstdint>
#include <vector>

#include "control/channel/block_motion.hpp"
#include "control/channel/channel_config.hpp"

namespace vmt::control::channel {

/// Where the automatic return goes first.
struct ReturnLeg {
  std::vector<double> to;
  /// #CAX TRACK: only C turns, to its tangent at the continue position; the other axes
  /// return in a second leg.
  bool c_alignment = false;
};

/// The first leg from `commanded` to `restart` (the continue position): under #CAX TRACK
/// (`cax_track`) with C away from its position there, C alone first (4.2.2); otherwise every
/// axis at once.
ReturnLeg FirstReturnLeg(const std::vector<double>& commanded, const std::vector<double>& restart,
                         const std::vector<ChannelAxis>& axes, bool cax_track);

/// One straight move at the rapid limits with every axis ending together (4.2).
struct StraightReturn {
  /// From `from` to `to`, its length in axis space; moves false: the axes stand there.
  BlockMotion motion;
  /// The path's rate and acceleration (per unit of the motion's u, 1/s and 1/s^2): the
  /// smallest of each moving axis' rapid rate and acceleration over its distance.
  double rate = 0, accel = 0;
};
StraightReturn PlanStraightReturn(const std::vector<double>& from, const std::vector<double>& to,
                                  const std::vector<ChannelAxis>& axes);

/// The manual return (4.2, 8): the operator brought the axes near the continue position.
struct ManualReturn {
  double deviation_mm = 0;  ///< the main axes' (X, Y, Z) distance from it
  double allowed_mm = 0;    ///< mc_cmd_bs_deviation_max_w in mm
  bool within = false;      ///< the program may go on from where the axes stand
  /// Per axis, where it stands less where it should: the program goes on shifted by it.
  std::vector<double> offset;
};
/// `deviation_max`: mc_cmd_bs_deviation_max_w, 0.1 um.
ManualReturn CheckManualReturn(const std::vector<double>& commanded,
                               const std::vector<double>& restart,
                               const std::vector<ChannelAxis>& axes, int64_t deviation_max);

}  // namespace vmt::control::channel
