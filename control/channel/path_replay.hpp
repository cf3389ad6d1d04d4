#pragma once
// Backward and forward travel along the recorded path (block search 4.3): where on the path
// memory the axes stand, the interruption point, and the leg in work.

#include <cstddef>
#include <vector>

#include "control/channel/block_motion.hpp"
#include "control/channel/path_profile.hpp"

namespace vmt::control::channel {

struct PathReplay {
  bool backward_requested = false;  ///< SetBackward
  bool away = false;                ///< off the interruption point, on the path behind it
  std::vector<double> home;         ///< the interruption point
  size_t index = 0;                 ///< the path memory's step the axes stand on
  double u = 1;                     ///< where on it (its own parameter)
  double home_u = 1;                ///< the interruption point on the last step
  int direction = 0;                ///< a leg in work: -1 back, +1 forward; 0 standing
  bool stopping = false;            ///< feed hold: the leg brakes to rest on the path
  double leg_from = 0, leg_to = 0;  ///< the leg on the step (u)
  BlockMotion leg;
  PathProfile profile;
};

}  // namespace vmt::control::channel
