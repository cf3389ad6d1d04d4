#pragma once
// `vmt study compare DIR_A DIR_B`: two studies (two machines, two program versions, two
// subroutines' revisions) case by case. Cases match by their identity -- subroutine,
// interruption point, retract and mode -- and a matched pair changed when its class differs
// (clear, crash, graze, error, retract refused) or its clearance or depth past the first
// contact moved by more than a threshold; cases only in one study are listed apart.

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/study/case_runner.hpp"
#include "sim/study/study_conclusions.hpp"

namespace vmt::sim::study {

/// subroutine/interrupt/retract/mode of a result (its case id when a field is missing).
std::string CaseIdentity(const CaseResult& r);

struct CaseChange {
  std::string identity;
  /// What the comparison read of the case in A and in B (nullopt: missing there).
  std::optional<CaseResult> a, b;
  std::string class_a, class_b;  ///< ClassOf, empty where the case is missing
  bool class_changed = false;
  /// B minus A of min_clearance_mm (both clear-checked) and of past_contact_mm (both contacts);
  /// 0 when either lacks it.
  double clearance_delta = 0, past_contact_delta = 0;
  bool beyond = false;  ///< a delta beyond the threshold
};

/// Per subroutine and mode, the class counts of A and of B.
using CompareTallies =
    std::map<std::pair<std::string, std::string>, std::pair<ClassCount, ClassCount>>;

struct Comparison {
  std::string name_a, name_b;
  size_t cases_a = 0, cases_b = 0, matched = 0, only_a = 0, only_b = 0;
  size_t class_changes = 0, beyond = 0;
  double threshold_mm = 0.1;
  CompareTallies tallies;
  /// Every case with a change (class, a delta beyond the threshold, only in one study): class
  /// changes first (the more severe B first), then deltas (largest first), then only in A,
  /// only in B; ties by identity.
  std::vector<CaseChange> changes;
};

Comparison CompareCases(const std::vector<CaseResult>& a, const std::vector<CaseResult>& b,
                        double threshold_mm, const std::string& name_a = "A",
                        const std::string& name_b = "B");

/// The summary for stdout: counts, class changes by kind, per subroutine and mode the classes
/// in A and in B, the first changes.
std::string CompareText(const Comparison& c);

/// The same side by side as a page, every changed case a row.
std::string CompareHtml(const Comparison& c);

/// Reads both folders' cases.jsonl (std::runtime_error for a folder without one), writes the
/// page to `html_path` and returns the text summary. Files in case id order (a finished or
/// merged study's) are walked side by side, holding the changed cases only; others are read
/// whole.
std::string CompareStudies(const std::string& dir_a, const std::string& dir_b,
                           const std::string& html_path, double threshold_mm);

}  // namespace vmt::sim::study
