#include "control/channel/continue_position.hpp"

#include "control/channel/block_search_support.hpp"

namespace vmt::control::channel {

std::string DistancePassedWarning(const BlockSearchParameters& started, double passed) {
  return "the distance from program start " + Mm(started.distance_prog_start * 1e-4) +
         " mm lies before the block of the continue position (" + Mm(passed) +
         " mm): machining continues at its start";
}

}  // namespace vmt::control::channel
