#pragma once
// What block search (block_search_simulation.cpp) and its return to the contour
// (channel_return_to_contour.cpp) share: private to control/channel/.

#include <cstdio>
#include <string>

#include "control/channel/block_motion.hpp"
#include "control/channel/path_profile.hpp"

namespace vmt::control::channel {

/// The main axes of the manual's 3D deviation and covered distance (4.1.1, 4.2).
inline bool MainAxis(const std::string& name) { return name == "X" || name == "Y" || name == "Z"; }

/// The profile of `motion` standing at u: a block taken up again from a point inside it.
inline PathProfile ProfileFrom(const BlockMotion& motion, double u) {
  PathProfile p;
  p.max_rate = motion.max_rate;
  p.max_accel = motion.max_accel;
  p.max_jerk = motion.max_jerk;
  p.u = u;
  return p;
}

/// A length in a message, to 0.1 um as the CNC objects count.
inline std::string Mm(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", v);
  return text;
}

}  // namespace vmt::control::channel
