#pragma once
// Jogging the fictive axes X1/Y1 of G31 for one NC cycle (REPOS manual 5.2): the point of the face
// plane moves along X1 or Y1 by a key held, one increment per press or the handwheel's counts,
// braking in time at the edge of the zone each may move in. X1/Y1's jog state is plain data
// (FictiveJog); the channel gives the rest as a narrow context and turns the point into X and C
// (channel_fictive_jog.cpp), so each rule can be tested without a channel.
#include <cmath>
#include <optional>

#include "control/channel/jog_state.hpp"
#include "control/nc/coordinate_transformation.hpp"

namespace vmt::control::channel {

/// What X1/Y1's jog needs of the channel in a cycle.
struct FictiveJogContext {
  JogMode mode = JogMode::kContinuous;
  double increment = 0;        ///< one key press' distance; 0: the keys jog continuously
  double speed = 0;            ///< mm/s of the keys and increments
  double handwheel_speed = 0;  ///< mm/s of the handwheel
  double acceleration = 0;     ///< X's: the fictive axes brake and start with it
  bool enabled = true;         ///< the process' and X's and C's enabling: keys start nothing
  /// Per fictive axis, where it may go (REPOS manual 3.2 while a REPOS function is called;
  /// unlimited otherwise).
  double low[2] = {-HUGE_VAL, -HUGE_VAL};
  double high[2] = {HUGE_VAL, HUGE_VAL};
};

/// Advances X1's and Y1's jogs by one cycle `dt` from the point `at`: the point they moved to,
/// or nothing when neither moved.
std::optional<nc::FictivePoint> FictiveJogCycle(FictiveJog (&jogs)[2], nc::FictivePoint at,
                                                const FictiveJogContext& context, double dt);

/// Where X1/Y1 could come to rest from `next`, the point of this cycle, for PathGuard: a key's
/// jog after braking at `acceleration` and one more check `interval` at its velocity; the
/// handwheel at its target (it brakes to be there), as for the real axes.
nc::FictivePoint FictiveJogStop(const FictiveJog (&jogs)[2], JogMode mode, nc::FictivePoint next,
                                double acceleration, double interval);

/// The handwheel's counts start afresh from where a fictive axis at `at` comes to rest: the end
/// of its increment under way or where its jog stops braking; a fictive axis at rest gets no
/// target (it has one only while counts are to go).
void RestartFictiveHandwheel(FictiveJog (&jogs)[2], JogMode mode, nc::FictivePoint at,
                             double acceleration);

}  // namespace vmt::control::channel
