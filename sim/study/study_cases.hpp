#pragma once
// The cases of a study: every subroutine x interruption point x retract x mode, each with a
// stable id (subroutine/interruption/retract/mode) so that a rerun skips what is done and shards
// merge by id. A group is the cases of one subroutine at one interruption point: they share
// the program's run up to there.

#include <optional>
#include <string>
#include <unordered_map>
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
  size_t index = 0;  ///< in the order subroutine, interruption, retract, mode
};

/// Every case of a plan, made from its index when asked for: a study of any size holds the
/// plan's names and the interruption points, not its cases (a set of them is a bit per case).
/// Keeps references: `plan` and `interruptions` outlive it.
class CaseSpace {
 public:
  CaseSpace(const StudyPlan& plan, const std::vector<Interruption>& interruptions);

  size_t size() const { return plan_.subroutines.size() * groups_per_subroutine(); }
  size_t groups() const { return plan_.subroutines.size() * interruptions_.size(); }
  /// Case `k`, 0 <= k < size().
  StudyCase At(size_t k) const;
  /// Case (subroutine, interruption, retract, mode position in the plan's modes).
  size_t Index(size_t subroutine, size_t interruption, size_t retract, size_t mode) const {
    return ((subroutine * interruptions_.size() + interruption) * plan_.retracts.size() + retract) *
               plan_.modes.size() +
           mode;
  }
  size_t cases_per_group() const { return plan_.retracts.size() * plan_.modes.size(); }
  /// The index of the case with this id; nullopt for an id that is none of the plan's.
  std::optional<size_t> IndexOf(const std::string& id) const;

 private:
  size_t groups_per_subroutine() const { return interruptions_.size() * cases_per_group(); }

  const StudyPlan& plan_;
  const std::vector<Interruption>& interruptions_;
  std::unordered_map<std::string, size_t> interruption_of_;  ///< label -> index
};

/// Every case, in index order (tests and small studies; a study itself goes by CaseSpace).
std::vector<StudyCase> EnumerateCases(const StudyPlan& plan,
                                      const std::vector<Interruption>& interruptions);

/// Shard `k` of `n` (1-based): the groups g with g % n == k - 1, so a group's run-up is shared.
bool InShard(size_t group, int k, int n);

}  // namespace vmt::sim::study
