#pragma once
// The cases of a study: every subroutine x interruption point x retract x mode, each with a
// stable id (subroutine/interruption/retract/mode) so that a rerun skips what is done and shards
// merge by id. A group is the cases of one subroutine at one interruption point: they share
// the program's run up to there.

#include <string>
#include <vector>

#include "sim/study/reference_run.hpp"
#include "sim/study/study_plan.hpp"

namespace vmt::sim::study {

/// Where the program is interrupted (feed hold), on the NC cycle grid.
struct Interruption {
  std::string label;  ///< "N0030@250" (per mille of the block) or "t3.500" (every T ms)
  double t_s = 0;
  std::string block;  ///< the block current at t_s in the reference run
  int per_mille = -1;
};

std::vector<Interruption> Interruptions(const StudyPlan& plan, const Reference& ref);

struct StudyCase {
  std::string id;
  size_t subroutine = 0, interruption = 0, retract = 0;
  ReposMode mode = ReposMode::kRepositioning;
  size_t group = 0;  ///< subroutine * interruptions + interruption
};

/// In the order subroutine, interruption, retract, mode.
std::vector<StudyCase> EnumerateCases(const StudyPlan& plan,
                                      const std::vector<Interruption>& interruptions);

/// Shard `k` of `n` (1-based): the groups g with g % n == k - 1, so a group's run-up is shared.
bool InShard(const StudyCase& c, int k, int n);

}  // namespace vmt::sim::study
