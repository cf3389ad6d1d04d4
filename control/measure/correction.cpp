#include "control/measure/correction.hpp"

#include <cmath>

#include "control/measure/nc_number.hpp"

namespace vmt::control::measure {
namespace {

// Limits are met "at" the limit: a dimensional difference computed as 0.1 + 1e-17 from values
// written 0.1 is not beyond a limit written 0.1. 1 nm is far below any measuring resolution.
constexpr double kAtLimit_mm = 1e-6;

bool Beyond(double amount, double limit) { return amount > std::abs(limit) + kAtLimit_mm; }

}  // namespace

std::string CheckCorrectionParameters(const CorrectionInstruction& in) {
  const double values[] = {in.upper_allowance,  in.lower_allowance,    in.upper_limit,
                           in.correction_limit, in.empirical_value,    in.strategy,
                           in.factor,           in.partial_correction, in.lower_limit};
  const char letters[] = "BCDEFGHIJ";
  for (int k = 0; k < 9; ++k)
    if (!std::isfinite(values[k]))
      return std::string("parameter ") + letters[k] + " is not a number";
  if (in.lower_allowance > in.upper_allowance)
    return "lower allowance " + NcNumber(in.lower_allowance) + " above upper allowance " +
           NcNumber(in.upper_allowance);
  if (in.strategy != 0 && in.strategy != 1)
    return "correction strategy " + NcNumber(in.strategy) +
           " is not 0 (averaging) or 1 (percentage correction)";
  // 2.1: weighting factor 0.00001 - 10, percentage correction factor 0.00001 - 100.
  const double most = in.strategy == 0 ? 10 : 100;
  if (in.factor < 0.00001 || in.factor > most)
    return std::string(in.strategy == 0 ? "weighting factor " : "percentage correction factor ") +
           NcNumber(in.factor) + " outside 0.00001.." + NcNumber(most);
  return "";
}

Correction CalculateCorrection(const CorrectionInstruction& in, const MeasuredValue& comparison,
                               double old_average) {
  Correction c;
  // 4.6 Tolerance center, Tolerance limit, Dimensional difference.
  c.tolerance_centre = comparison.command + (in.upper_allowance + in.lower_allowance) / 2;
  c.tolerance_limit = (in.upper_allowance - in.lower_allowance) / 2;
  const double d = comparison.actual + in.empirical_value - c.tolerance_centre;
  const double amount = std::abs(d);
  c.dimensional_difference = d;
  c.average_value = old_average;

  // 4.6 Upper limit, Correction limit, dimensional accuracy 3: no correction, Q9999.
  if (Beyond(amount, in.upper_limit) || Beyond(amount, in.correction_limit)) {
    c.accuracy = DimensionalAccuracy::kNotCorrectable;
    c.message = Beyond(amount, in.upper_limit) ? kIllegallyHighDimensionalDeviation : kCheckTool;
    return c;
  }
  // 4.6 Tolerance limit, dimensional accuracy 1 / 2: correctable, Q9998.
  if (amount > c.tolerance_limit + kAtLimit_mm) {
    c.accuracy = d > 0 ? DimensionalAccuracy::kOversize : DimensionalAccuracy::kUndersize;
    c.message = d > 0 ? kOversize : kUndersize;
  }

  // 4.6 Partial correction limit: beyond it, the full dimensional difference.
  if (Beyond(amount, in.partial_correction)) {
    c.range = CorrectionRange::kFull;
    c.correction_value = d;
    if (in.strategy == 0) c.average_value = 0;
    return c;
  }
  if (in.strategy == 0) {
    // Figure 4-13; 4.6 Lower limit: the difference is fed to the averaging, and a correction
    // value below the lower limit is kept as the old average value, not corrected.
    const double k = old_average - (old_average - d) / in.factor;
    if (std::abs(k) < std::abs(in.lower_limit) - kAtLimit_mm) {
      c.range = CorrectionRange::kBelowLowerLimit;
      c.average_value = k;
      return c;
    }
    c.range = CorrectionRange::kPartial;
    c.correction_value = k;
    c.average_value = 0;
    return c;
  }
  // Figure 4-14; below the lower limit no correction value is calculated (2.1 example).
  if (amount < std::abs(in.lower_limit) - kAtLimit_mm) {
    c.range = CorrectionRange::kBelowLowerLimit;
    return c;
  }
  c.range = CorrectionRange::kPartial;
  c.correction_value = d * in.factor / 100;
  return c;
}

CorrectionRun RunCorrection(MeasuringPages& pages, int process, const CorrectionInstruction& in) {
  CorrectionRun run;
  const std::string call = "CORRECTION(" + NcNumber(in.compare_number) + "," +
                           NcNumber(in.upper_allowance) + "," + NcNumber(in.lower_allowance) + "," +
                           NcNumber(in.upper_limit) + "," + NcNumber(in.correction_limit) + "," +
                           NcNumber(in.empirical_value) + "," + NcNumber(in.strategy) + "," +
                           NcNumber(in.factor) + "," + NcNumber(in.partial_correction) + "," +
                           NcNumber(in.lower_limit) + "): ";
  const std::optional<int> a = WholeNumber(in.compare_number);
  ErgebnisPage* entry = a ? pages.Result(process, *a) : nullptr;
  if (!entry) {
    run.error = call + "compare number " + NcNumber(in.compare_number) +
                " outside ERGEBNISPAGE's 1.." + std::to_string(pages.config.results) +
                " of process " + std::to_string(process);
    return run;
  }
  if (entry->measuring_axis == 0) {
    run.error = call + "compare " + std::to_string(*a) + " has not been run (COMPARE first)";
    return run;
  }
  if (std::string why = CheckCorrectionParameters(in); !why.empty()) {
    run.error = call + why;
    return run;
  }
  run.correction = CalculateCorrection(in, entry->comparison_value, entry->average_value);
  entry->dimensional_accuracy = static_cast<int8_t>(run.correction.accuracy);
  entry->average_value = run.correction.average_value;
  entry->correction_value = run.correction.correction_value;
  entry->correction_strategy = in.strategy == 1;
  return run;
}

}  // namespace vmt::control::measure
