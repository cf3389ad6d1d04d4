#pragma once
// Where machining goes on after block search (block search 4.1). The search first looks for the
// block boundary of the continue position; inside that block the covered distance (a per mille
// of the block's path) places it, or, with a distance from program start, the search goes on
// block by block until the path from program start reaches that distance. Under G41/G42 the per
// mille lies on the block's own piece of the tip path, never on the corner the compensation
// inserted before it. The search never goes back into blocks it has passed.

#include <algorithm>
#include <string>

#include "control/channel/block_motion.hpp"
#include "control/channel/block_search.hpp"
#include "control/channel/block_search_run.hpp"

namespace vmt::control::channel {

/// What the search does with one simulated block.
struct ContinueStep {
  bool found = false;  ///< the continue position lies in this block
  double u = 0;        ///< where in the block's motion (0 its start, 1 its end), when found
  /// The distance from program start lies before the continue block: machining goes on at
  /// the block's start instead (DistancePassedWarning says so).
  bool distance_passed = false;
};

/// The warning of a step whose distance from program start lay before the continue block
/// (`passed` mm then).
std::string DistancePassedWarning(const BlockSearchParameters& started, double passed);

/// Decides for the block the search simulates now, its `motion` (`length` mm of it count for
/// the distance from program start, `passed` mm before it), whether the continue position lies
/// in it. `boundary`: this block matched the continue block. `s.inserted_piece` says whether the
/// block is a corner G41/G42 inserted; the decision keeps its progress in `s` (found,
/// by_distance, await_own_piece). Nothing to decide before the boundary (!s.Deciding()).
// Inline: the search decides once per block, a hot loop (block_search_bench).
inline ContinueStep DecideContinue(BlockSearchRun& s, const BlockSearchParameters& started,
                            const BlockMotion& motion, double length, double passed,
                            bool boundary) {
  const auto found = [](double u) { return ContinueStep{true, u, false}; };
  // 4.1.1 / 10: the covered distance splits a motion block; a block without motion is not.
  const double permille = motion.moves ? started.covered_distance / 1000 : 0;
  const double wanted = started.distance_prog_start * 1e-4;
  if (s.await_own_piece && !s.inserted_piece) {
    // The continue block's own piece after the corner the compensation inserted before it.
    s.await_own_piece = false;
    return found(permille);
  }
  if (boundary) {
    s.found = true;
    if (wanted <= 0 && s.inserted_piece) {
      // The per mille measures the block's own piece of the tip path, not the corner arc
      // before it: the same point whatever the nose radius (4.1.1, note to figure 10).
      s.await_own_piece = true;
    } else if (wanted <= 0) {
      return found(permille);
    } else if (wanted < passed - 1e-9) {
      // 4.1.2, figure 18: never back into blocks the search has passed.
      return {true, 0, true};
    } else {
      s.by_distance = true;
    }
  }
  if (s.by_distance && motion.moves && length > 0 && wanted <= passed + length + 1e-9)
    return found(std::clamp((wanted - passed) / length, 0.0, 1.0));
  return {};
}

}  // namespace vmt::control::channel
