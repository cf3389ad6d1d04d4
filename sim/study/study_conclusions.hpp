#pragma once
// What a study's results say, for the machine builder: each case's class (clear, crash, graze,
// error, retract refused), the cases ordered by severity, and per mode the sentences that
// conclude the report -- which subroutine (or manual order) is clear in all cases, and for the
// others which two parts meet, how often and how badly, and where in the program the
// interruptions lay. Generated from the results alone (plain data in, text out).

#include <memory>
#include <string>
#include <vector>

#include "sim/study/case_runner.hpp"
#include "sim/study/reference_run.hpp"

namespace vmt::sim::study {

/// r[key], null when r lacks it (cases.jsonl is a file anyone can edit).
const nlohmann::ordered_json& Field(const CaseResult& r, const char* key);

/// clear | crash | graze | error | retract_refused. A collision is a graze when its first
/// contact lies within kGrazeMm of the refused move's end, else a crash. Results written
/// before the classes existed count every collision as a crash, and an error after a retract
/// PathGuard refused as retract_refused.
std::string ClassOf(const CaseResult& r);

/// Case counts by class.
struct ClassCount {
  size_t cases = 0, clear = 0, crash = 0, graze = 0, error = 0, retract_refused = 0;
  void Add(const CaseResult& r);
  /// The cases the subroutine is judged by: all but the retracts PathGuard refused.
  size_t judged() const { return cases - retract_refused; }
};

/// Crashes first (deepest past the first contact first), then grazes (likewise), then errors,
/// then clear cases (smallest clearance first), then refused retracts; ties by case id.
bool MoreSevere(const CaseResult& a, const CaseResult& b);

/// The axis positions (machine coordinates) at the first contact, e.g. "X28.000 Z159.999";
/// empty without a contact.
std::string ContactAxes(const CaseResult& r);

/// The conclusion of one mode: the subroutines clear in all cases, then a sentence per
/// subroutine (or manual order).
struct ModeConclusion {
  std::string mode;
  std::string headline;
  std::vector<std::string> sentences;
};

/// The conclusions over cases given one at a time (in id order), keeping counts and the names
/// of blocks, retracts and parts, not the cases: a study of any size in bounded memory.
class ConclusionTally {
 public:
  /// `reference` (may be null) must outlive the tally.
  explicit ConclusionTally(const Reference* reference);
  ~ConclusionTally();
  ConclusionTally(const ConclusionTally&) = delete;
  ConclusionTally& operator=(const ConclusionTally&) = delete;
  void Add(const CaseResult& r);
  /// As Conclusions() of the cases added.
  std::vector<ModeConclusion> Conclusions() const;

 private:
  struct State;
  const Reference* reference_;
  std::unique_ptr<State> state_;
};

/// Per mode (in order of first appearance), from `cases`; `reference` (may be null) names the
/// interrupted blocks' program lines and orders them as the program runs.
std::vector<ModeConclusion> Conclusions(const std::vector<CaseResult>& cases,
                                        const Reference* reference);

}  // namespace vmt::sim::study
