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

CaseSpace::CaseSpace(const StudyPlan& plan, const std::vector<Interruption>& interruptions)
    : plan_(plan), interruptions_(interruptions) {
  for (size_t i = 0; i < interruptions.size(); ++i)
    interruption_of_.emplace(interruptions[i].label, i);  // the first of equal labels
}

StudyCase CaseSpace::At(size_t k) const {
  StudyCase c;
  c.index = k;
  const size_t modes = plan_.modes.size(), retracts = plan_.retracts.size();
  const size_t m = k % modes;
  c.mode = plan_.modes[m];
  c.retract = k / modes % retracts;
  c.group = k / modes / retracts;
  c.interruption = c.group % interruptions_.size();
  c.subroutine = c.group / interruptions_.size();
  c.id = plan_.subroutines[c.subroutine].name + "/" + interruptions_[c.interruption].label + "/" +
         plan_.retracts[c.retract].name + "/" + ToString(c.mode);
  return c;
}

std::optional<size_t> CaseSpace::IndexOf(const std::string& id) const {
  // Names may hold '/' themselves ("nc/99.mtc"): each known subroutine, retract and mode is
  // tried at the ends, and what stands between them must be an interruption's label.
  for (size_t s = 0; s < plan_.subroutines.size(); ++s) {
    const std::string& sub = plan_.subroutines[s].name;
    if (id.size() <= sub.size() || id.compare(0, sub.size(), sub) != 0 || id[sub.size()] != '/')
      continue;
    for (size_t r = 0; r < plan_.retracts.size(); ++r)
      for (size_t m = 0; m < plan_.modes.size(); ++m) {
        const std::string tail = "/" + plan_.retracts[r].name + "/" + ToString(plan_.modes[m]);
        if (id.size() < sub.size() + 1 + tail.size() ||
            id.compare(id.size() - tail.size(), tail.size(), tail) != 0)
          continue;
        const auto i = interruption_of_.find(
            id.substr(sub.size() + 1, id.size() - tail.size() - sub.size() - 1));
        if (i != interruption_of_.end()) return Index(s, i->second, r, m);
      }
  }
  return std::nullopt;
}

std::vector<StudyCase> EnumerateCases(const StudyPlan& plan,
                                      const std::vector<Interruption>& interruptions) {
  const CaseSpace space(plan, interruptions);
  std::vector<StudyCase> cases;
  cases.reserve(space.size());
  for (size_t k = 0; k < space.size(); ++k) cases.push_back(space.At(k));
  return cases;
}

bool InShard(size_t group, int k, int n) {
  return n <= 1 || static_cast<int>(group % static_cast<size_t>(n)) == k - 1;
}

}  // namespace vmt::sim::study
