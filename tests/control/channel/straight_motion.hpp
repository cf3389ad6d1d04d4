#pragma once
// A straight block motion for the tests of the path memory and backward travel: from `start`
// to `end` at 100 mm/s, 1000 mm/s^2 and 20000 mm/s^3 along its path.
#include <cmath>
#include <utility>
#include <vector>

#include "control/channel/block_motion.hpp"

namespace vmt::control::channel {

inline BlockMotion StraightMotion(std::vector<double> start, std::vector<double> end) {
  BlockMotion m;
  m.start = std::move(start);
  m.end = std::move(end);
  double sq = 0;
  for (size_t a = 0; a < m.start.size(); ++a)
    sq += (m.end[a] - m.start[a]) * (m.end[a] - m.start[a]);
  m.length = std::sqrt(sq);
  m.max_rate = 100 / m.length;
  m.max_accel = 1000 / m.length;
  m.max_jerk = 20000 / m.length;
  m.moves = true;
  return m;
}

}  // namespace vmt::control::channel
