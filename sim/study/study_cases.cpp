#include "sim/study/study_cases.hpp"

#include <cmath>
#include <cstdio>
#include <map>

namespace vmt::sim::study {
namespace {

// The NC cycle (1 ms) grid: a feed hold acts at a cycle, and the label stays short.
double OnCycle(double t) { return std::round(t * 1000) / 1000; }

std::string BlockAt(const Reference& ref, double t) {
  for (const BlockSpan& b : ref.blocks)
    if (t >= b.start_s - 1e-9 && t <= b.end_s + 1e-9) return b.label;
  return "";
}

}  // namespace

std::vector<Interruption> Interruptions(const StudyPlan& plan, const Reference& ref) {
  std::vector<Interruption> out;
  if (plan.every_ms > 0) {
    for (int k = 1;; ++k) {
      const double t = OnCycle(ref.start_s + k * plan.every_ms / 1000);
      if (t >= ref.end_s) break;
      char label[32];
      std::snprintf(label, sizeof label, "t%.3f", t);
      out.push_back({label, t, BlockAt(ref, t), -1});
    }
    return out;
  }
  std::map<std::string, int> seen;  // a block label met again (a loop) gets #2, #3, ...
  for (const BlockSpan& b : ref.blocks) {
    if (!b.motion) continue;
    const int n = ++seen[b.label];
    const std::string name = n == 1 ? b.label : b.label + "#" + std::to_string(n);
    for (const int p : plan.per_mille) {
      const double t = OnCycle(b.start_s + (b.end_s - b.start_s) * p / 1000.0);
      out.push_back({name + "@" + std::to_string(p), t, b.label, p});
    }
  }
  return out;
}

std::vector<StudyCase> EnumerateCases(const StudyPlan& plan,
                                      const std::vector<Interruption>& interruptions) {
  std::vector<StudyCase> cases;
  for (size_t s = 0; s < plan.subroutines.size(); ++s)
    for (size_t i = 0; i < interruptions.size(); ++i)
      for (size_t r = 0; r < plan.retracts.size(); ++r)
        for (const ReposMode m : plan.modes) {
          StudyCase c;
          c.subroutine = s, c.interruption = i, c.retract = r, c.mode = m;
          c.group = s * interruptions.size() + i;
          c.id = plan.subroutines[s].name + "/" + interruptions[i].label + "/" +
                 plan.retracts[r].name + "/" + ToString(m);
          cases.push_back(c);
        }
  return cases;
}

bool InShard(const StudyCase& c, int k, int n) {
  return n <= 1 || static_cast<int>(c.group % static_cast<size_t>(n)) == k - 1;
}

}  // namespace vmt::sim::study
