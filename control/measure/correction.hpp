#pragma once
// CORRECTION(A, ..., J) (mtc200-fast-measurement.md 2.1, 2.2, 4.6 Definition of Terms, 6.1):
// the comparison value of ERGEBNISPAGE entry A judged against the tolerance, the limits and the
// correction strategy; the dimensional accuracy, the average value and the correction value are
// written back into the entry (elements 11..14), with the message and Q function to issue.
//
// With the nominal dimension N (the comparison's command value, element 8) and the actual
// dimension I (element 9):
//   tolerance centre       = N + (A_o + A_u) / 2
//   tolerance limit        = (A_o - A_u) / 2, the half width of the tolerance field about it
//   dimensional difference = I + empirical value - tolerance centre
// and with d = the dimensional difference, |d| compared with the amounts of the limits:
//   |d| > upper limit              accuracy 3, ILLEGALLY HIGH DIMENSIONAL DEVIATION (Q9999)
//   |d| > correction limit         accuracy 3, CHECK TOOL (Q9999); no correction either way
//   |d| > tolerance limit          accuracy 1 OVERSIZE (d > 0) / 2 UNDERSIZE (d < 0) (Q9998)
//   otherwise                      accuracy 0
//   |d| > partial correction       full correction: correction value = d
//   otherwise, averaging           K = MW_alt - (MW_alt - d) / weighting factor; K is the
//                                  correction value unless |K| < lower limit: then 0, and K is
//                                  kept as the average value (element 12) for the next workpiece
//   otherwise, percentage          0 if |d| < lower limit, else d * factor / 100
// After a correction the average value is 0: the correction took it out of the process.

#include <cstdint>
#include <optional>
#include <string>

#include "control/measure/measuring_messages.hpp"
#include "control/measure/measuring_pages.hpp"

namespace vmt::control::measure {

/// CORRECTION parameter G; ERGEBNISPAGE element 14.
enum class CorrectionStrategy : int8_t { kAveraging = 0, kPercentage = 1 };

/// ERGEBNISPAGE element 11 (4.6 Dimensional accuracy).
enum class DimensionalAccuracy : int8_t {
  kInTolerance = 0,     ///< inside the tolerance field A_o - A_u
  kOversize = 1,        ///< beyond the tolerance limit, d > 0, correctable (Q9998 OVERSIZE)
  kUndersize = 2,       ///< beyond the tolerance limit, d < 0, correctable (Q9998 UNDERSIZE)
  kNotCorrectable = 3,  ///< beyond the correction or upper limit (Q9999)
};

/// CORRECTION(A, B, C, D, E, F, G, H, I, J) as the NC program gives it; lengths in mm.
struct CorrectionInstruction {
  double compare_number = 0;      ///< A: ERGEBNISPAGE entry of the COMPARE, 1..LV2
  double upper_allowance = 0;     ///< B: A_o
  double lower_allowance = 0;     ///< C: A_u
  double upper_limit = 0;         ///< D
  double correction_limit = 0;    ///< E
  double empirical_value = 0;     ///< F: added to the actual dimension
  double strategy = 0;            ///< G: CorrectionStrategy 0 / 1
  double factor = 1;              ///< H: weighting factor (G 0) / percentage factor (G 1)
  double partial_correction = 0;  ///< I: partial correction limit
  double lower_limit = 0;         ///< J
};

/// Which rule gave the correction value.
enum class CorrectionRange : uint8_t {
  kRefused,          ///< accuracy 3: no correction
  kBelowLowerLimit,  ///< no correction (averaging: the average value keeps K)
  kPartial,          ///< the correction strategy's value
  kFull,             ///< the full dimensional difference
};

/// What CORRECTION found and decided.
struct Correction {
  double tolerance_centre = 0;
  double tolerance_limit = 0;
  double dimensional_difference = 0;
  DimensionalAccuracy accuracy = DimensionalAccuracy::kInTolerance;
  CorrectionRange range = CorrectionRange::kRefused;
  double correction_value = 0;  ///< element 13
  double average_value = 0;     ///< element 12 afterwards
  /// OVERSIZE / UNDERSIZE (Q9998) or ILLEGALLY HIGH DIMENSIONAL DEVIATION / CHECK TOOL (Q9999).
  std::optional<MeasuringMessage> message;
};

/// "" if the instruction's parameters (all but A) can be used, else why not: a value that is not
/// a number, A_u above A_o, G not 0 or 1, H outside 0.00001..10 (averaging) or 0.00001..100
/// (percentage) (2.1).
std::string CheckCorrectionParameters(const CorrectionInstruction& instruction);

/// The correction of a comparison value (nominal = command, actual) with the average value kept
/// from earlier workpieces. The instruction must pass CheckCorrectionParameters.
Correction CalculateCorrection(const CorrectionInstruction& instruction,
                               const MeasuredValue& comparison_value, double old_average);

/// CORRECTION run in `process`, or why it cannot run (a program error, pages unchanged).
struct CorrectionRun {
  std::string error;
  Correction correction;
};

/// Runs CORRECTION on ERGEBNISPAGE entry A of `process`: writes the dimensional accuracy (11),
/// the average value (12), the correction value (13) and the strategy (14). The entry must have
/// been written by a COMPARE.
CorrectionRun RunCorrection(MeasuringPages& pages, int process,
                            const CorrectionInstruction& instruction);

}  // namespace vmt::control::measure
