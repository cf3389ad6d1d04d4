#include "control/measure/correction.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "control/measure/compare.hpp"

namespace vmt::control::measure {
namespace {

using ::testing::HasSubstr;

constexpr double kTol = 1e-12;

// A comparison value: nominal dimension (command) and actual dimension.
MeasuredValue Dimension(double nominal, double actual) {
  return {nominal, actual, actual - nominal};
}

// 5.6 C1: CORRECTION(1,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005,0.002) -- averaging.
constexpr CorrectionInstruction kSummaryC1 = {1,     0.01, -0.01, 0.12,  0.1,
                                              0.001, 0,    1.1,   0.005, 0.002};
// 5.4: CORRECTION(1,0.1,-0.1,0.2,0.14,0.005,1,85,0.06,0.02) -- percentage correction 85 %.
constexpr CorrectionInstruction kExample54 = {1, 0.1, -0.1, 0.2, 0.14, 0.005, 1, 85, 0.06, 0.02};
// 2.1: CORRECTION(1,0.1,-0.1,0.24,0.18,0.004,0,1.5,0.07,0.01) -- averaging, weighting 1.5.
constexpr CorrectionInstruction kExample21 = {1, 0.1, -0.1, 0.24, 0.18, 0.004, 0, 1.5, 0.07, 0.01};

void ExpectCorrection(const Correction& c, DimensionalAccuracy accuracy, CorrectionRange range,
                      double correction, double average) {
  EXPECT_EQ(c.accuracy, accuracy);
  EXPECT_EQ(c.range, range);
  EXPECT_NEAR(c.correction_value, correction, kTol);
  EXPECT_NEAR(c.average_value, average, kTol);
}

// 4.6: tolerance centre = nominal + (A_o + A_u) / 2, dimensional difference = actual +
// empirical value - tolerance centre; the tolerance limit is symmetric about the centre.
TEST(Correction, ToleranceCentreAndDimensionalDifference) {
  CorrectionInstruction in = kSummaryC1;
  in.upper_allowance = 0.05;
  in.lower_allowance = -0.01;
  in.empirical_value = -0.002;
  const Correction c = CalculateCorrection(in, Dimension(10, 10.045), 0);
  // centre 10 + (0.05 - 0.01) / 2 = 10.02; limit (0.05 + 0.01) / 2 = 0.03
  EXPECT_NEAR(c.tolerance_centre, 10.02, kTol);
  EXPECT_NEAR(c.tolerance_limit, 0.03, kTol);
  // d = 10.045 - 0.002 - 10.02 = 0.023
  EXPECT_NEAR(c.dimensional_difference, 0.023, kTol);
}

// Dimensional accuracy 0/1/2 against max dimension = nominal + A_o, min = nominal + A_u
// (4.6), with an asymmetric tolerance field 9.99..10.05.
TEST(Correction, DimensionalAccuracyAgainstTheToleranceField) {
  CorrectionInstruction in = kSummaryC1;
  in.upper_allowance = 0.05;
  in.lower_allowance = -0.01;
  in.empirical_value = 0;
  in.upper_limit = 1;
  in.correction_limit = 1;
  // actual 10.045 (inside): d = 10.045 - 10.02 = 0.025 <= 0.03 -> 0, no message
  Correction c = CalculateCorrection(in, Dimension(10, 10.045), 0);
  EXPECT_EQ(c.accuracy, DimensionalAccuracy::kInTolerance);
  EXPECT_FALSE(c.message);
  // actual 10.055 (above 10.05): d = 0.035 > 0.03 -> 1 OVERSIZE, Q9998
  c = CalculateCorrection(in, Dimension(10, 10.055), 0);
  EXPECT_EQ(c.accuracy, DimensionalAccuracy::kOversize);
  ASSERT_TRUE(c.message);
  EXPECT_STREQ(c.message->text, "OVERSIZE");
  EXPECT_EQ(c.message->q_function, 9998);
  // actual 9.985 (below 9.99): d = -0.035 -> 2 UNDERSIZE, Q9998
  c = CalculateCorrection(in, Dimension(10, 9.985), 0);
  EXPECT_EQ(c.accuracy, DimensionalAccuracy::kUndersize);
  ASSERT_TRUE(c.message);
  EXPECT_STREQ(c.message->text, "UNDERSIZE");
  EXPECT_EQ(c.message->q_function, 9998);
  // The empirical value counts: actual 10.055 with F = -0.01: d = 0.025 -> inside
  in.empirical_value = -0.01;
  EXPECT_EQ(CalculateCorrection(in, Dimension(10, 10.055), 0).accuracy,
            DimensionalAccuracy::kInTolerance);
}

// 5.6 C1 (averaging, W 1.1), on the face P3 at Z0, one branch each.
TEST(Correction, AveragingBranches) {
  const CorrectionInstruction& in = kSummaryC1;
  // Partial: actual 0.0034 -> d = 0.0034 + 0.001 - 0 = 0.0044 <= I 0.005;
  // K = 0 - (0 - 0.0044) / 1.1 = 0.004 >= J 0.002 -> correction 0.004, average reset to 0
  ExpectCorrection(CalculateCorrection(in, Dimension(0, 0.0034), 0),
                   DimensionalAccuracy::kInTolerance, CorrectionRange::kPartial, 0.004, 0);
  // Full: actual 0.019 -> d = 0.02 > I 0.005 -> correction 0.02; 0.02 > tolerance 0.01 -> 1
  Correction c = CalculateCorrection(in, Dimension(0, 0.019), 0.0015);
  ExpectCorrection(c, DimensionalAccuracy::kOversize, CorrectionRange::kFull, 0.02, 0);
  EXPECT_NEAR(c.dimensional_difference, 0.02, kTol);
  // Full, undersize: actual -0.021 -> d = -0.02 -> correction -0.02, accuracy 2
  c = CalculateCorrection(in, Dimension(0, -0.021), 0);
  ExpectCorrection(c, DimensionalAccuracy::kUndersize, CorrectionRange::kFull, -0.02, 0);
  EXPECT_STREQ(c.message->text, "UNDERSIZE");
  // Below the lower limit: actual 0 -> d = 0.001; K = 0 - (0 - 0.001) / 1.1 = 0.000909...
  // < J 0.002 -> no correction; K kept as the average value (4.6 Lower limit note)
  ExpectCorrection(CalculateCorrection(in, Dimension(0, 0), 0), DimensionalAccuracy::kInTolerance,
                   CorrectionRange::kBelowLowerLimit, 0, 0.001 / 1.1);
  // The next workpiece: actual 0.002 -> d = 0.003; MW_alt = 1/1100;
  // K = MW_alt - (MW_alt - 0.003) / 1.1 = 1/12100 + 0.003/1.1 = 0.0028099173553719...
  // >= J 0.002 -> the accumulated average is corrected and the average reset
  ExpectCorrection(CalculateCorrection(in, Dimension(0, 0.002), 0.001 / 1.1),
                   DimensionalAccuracy::kInTolerance, CorrectionRange::kPartial,
                   1.0 / 12100 + 0.003 / 1.1, 0);
}

// 4.6: a weighting factor of 0.8 corresponds to about a percentage correction of 125 %.
TEST(Correction, WeightingFactorAndPercentageCorrespond) {
  CorrectionInstruction averaging = kExample21;
  averaging.factor = 0.8;
  averaging.empirical_value = 0;
  CorrectionInstruction percentage = averaging;
  percentage.strategy = 1;
  percentage.factor = 125;
  // d = 0.04: averaging K = 0 - (0 - 0.04) / 0.8 = 0.05; percentage 0.04 x 125 / 100 = 0.05
  EXPECT_NEAR(CalculateCorrection(averaging, Dimension(20, 20.04), 0).correction_value, 0.05, kTol);
  EXPECT_NEAR(CalculateCorrection(percentage, Dimension(20, 20.04), 0).correction_value, 0.05,
              kTol);
}

// 2.1 example (averaging, W 1.5): "a partial correction if the dimension difference is less
// than 0.07 mm; no correction value if less than 0.01 mm".
TEST(Correction, ManualExample21) {
  const CorrectionInstruction& in = kExample21;
  // actual 20.026 -> d = 20.026 + 0.004 - 20 = 0.03 < 0.07; K = 0.03 / 1.5 = 0.02 >= 0.01
  ExpectCorrection(CalculateCorrection(in, Dimension(20, 20.026), 0),
                   DimensionalAccuracy::kInTolerance, CorrectionRange::kPartial, 0.02, 0);
  // actual 20.086 -> d = 0.09 > 0.07 -> full correction 0.09 (inside the tolerance 0.1)
  ExpectCorrection(CalculateCorrection(in, Dimension(20, 20.086), 0),
                   DimensionalAccuracy::kInTolerance, CorrectionRange::kFull, 0.09, 0);
  // actual 20.001 -> d = 0.005; K = 0.005 / 1.5 = 0.00333 < 0.01 -> kept as average
  ExpectCorrection(CalculateCorrection(in, Dimension(20, 20.001), 0),
                   DimensionalAccuracy::kInTolerance, CorrectionRange::kBelowLowerLimit, 0,
                   0.005 / 1.5);
  // actual 20.196 -> d = 0.2 > E 0.18, <= D 0.24 -> CHECK TOOL
  const Correction c = CalculateCorrection(in, Dimension(20, 20.196), 0.003);
  ExpectCorrection(c, DimensionalAccuracy::kNotCorrectable, CorrectionRange::kRefused, 0, 0.003);
  EXPECT_STREQ(c.message->text, "CHECK TOOL");
}

// 5.4 (percentage correction, 85 %) on a groove of nominal width 5: every branch.
TEST(Correction, PercentageBranchesManualExample54) {
  const CorrectionInstruction& in = kExample54;
  // actual 5.035 -> d = 5.035 + 0.005 - 5 = 0.04, J 0.02 <= 0.04 <= I 0.06 -> 0.04 x 0.85 = 0.034
  ExpectCorrection(CalculateCorrection(in, Dimension(5, 5.035), 0.001),
                   DimensionalAccuracy::kInTolerance, CorrectionRange::kPartial, 0.034, 0.001);
  // actual 5.01 -> d = 0.015 < J 0.02 -> no correction value; the average is not touched
  ExpectCorrection(CalculateCorrection(in, Dimension(5, 5.01), 0.001),
                   DimensionalAccuracy::kInTolerance, CorrectionRange::kBelowLowerLimit, 0, 0.001);
  // actual 4.915 -> d = -0.08, > I 0.06 -> full -0.08; |d| <= tolerance 0.1 -> accuracy 0
  ExpectCorrection(CalculateCorrection(in, Dimension(5, 4.915), 0),
                   DimensionalAccuracy::kInTolerance, CorrectionRange::kFull, -0.08, 0);
  // actual 4.875 -> d = -0.12: beyond the tolerance 0.1, within E 0.14 -> UNDERSIZE, full -0.12
  Correction c = CalculateCorrection(in, Dimension(5, 4.875), 0);
  ExpectCorrection(c, DimensionalAccuracy::kUndersize, CorrectionRange::kFull, -0.12, 0);
  EXPECT_STREQ(c.message->text, "UNDERSIZE");
  // actual 5.135 -> d = 0.14 at E: not beyond it -> OVERSIZE, full 0.14
  c = CalculateCorrection(in, Dimension(5, 5.135), 0);
  ExpectCorrection(c, DimensionalAccuracy::kOversize, CorrectionRange::kFull, 0.14, 0);
  EXPECT_STREQ(c.message->text, "OVERSIZE");
  // actual 5.145 -> d = 0.15 > E 0.14, <= D 0.2 -> accuracy 3, CHECK TOOL, Q9999
  c = CalculateCorrection(in, Dimension(5, 5.145), 0);
  ExpectCorrection(c, DimensionalAccuracy::kNotCorrectable, CorrectionRange::kRefused, 0, 0);
  EXPECT_STREQ(c.message->text, "CHECK TOOL");
  EXPECT_EQ(c.message->q_function, 9999);
  // actual 5.25 -> d = 0.255 > D 0.2 -> accuracy 3, ILLEGALLY HIGH DIMENSIONAL DEVIATION, Q9999
  c = CalculateCorrection(in, Dimension(5, 5.25), 0);
  ExpectCorrection(c, DimensionalAccuracy::kNotCorrectable, CorrectionRange::kRefused, 0, 0);
  EXPECT_STREQ(c.message->text, "ILLEGALLY HIGH DIMENSIONAL DEVIATION");
  EXPECT_EQ(c.message->q_function, 9999);
  // Undersize beyond D: actual 4.7 -> d = -0.295 -> ILLEGALLY HIGH as well (amounts, 6.1)
  c = CalculateCorrection(in, Dimension(5, 4.7), 0);
  EXPECT_EQ(c.accuracy, DimensionalAccuracy::kNotCorrectable);
  EXPECT_STREQ(c.message->text, "ILLEGALLY HIGH DIMENSIONAL DEVIATION");
}

// The manual's summary program (5.6) end to end on the pages: three COMPAREs, three
// CORRECTIONs with its parameters, the results read by MTD as its TLD lines and BEQ do.
TEST(Correction, ManualSummaryProgram) {
  MeasuringPages pages;
  auto probe = [&](int n, char axis, double command, double actual) {
    *pages.Point(0, n) = {{command, actual, actual - command}, axis};
  };
  probe(1, 'Z', -100, -100.01);  // PROBE(1,1,180,-100,,Z,...)
  probe(2, 'X', 62.5, 62.52);    // PROBE(2,1,125,-10,,X,...): diameter 125, radius 62.5
  probe(3, 'Z', 0, 0.004);       // PROBE(3,1,115,0,,Z,...)
  ASSERT_EQ(Compare(pages, 0, {1, 0, 3, {}}), "");
  ASSERT_EQ(Compare(pages, 0, {2, 4, 2, {}}), "");
  ASSERT_EQ(Compare(pages, 0, {3, 1, 1, 3}), "");

  // C1: Point 0 / 0.004; d = 0.004 + 0.001 - 0 = 0.005, at the partial correction limit 0.005
  // (not beyond it: averaging), K = 0.005 / 1.1 = 0.0045454... >= 0.002 -> correction K
  CorrectionRun r = RunCorrection(pages, 0, kSummaryC1);
  ASSERT_EQ(r.error, "");
  ExpectCorrection(r.correction, DimensionalAccuracy::kInTolerance, CorrectionRange::kPartial,
                   0.005 / 1.1, 0);
  // C2: CORRECTION(2,0.02,-0.02,0.35,0.28,0.001,0,1.8,0.01,0.007) on the diameter 125 / 125.04:
  // d = 125.04 + 0.001 - 125 = 0.041 > tolerance 0.02 -> OVERSIZE; > I 0.01 -> full 0.041
  r = RunCorrection(pages, 0, {2, 0.02, -0.02, 0.35, 0.28, 0.001, 0, 1.8, 0.01, 0.007});
  ASSERT_EQ(r.error, "");
  ExpectCorrection(r.correction, DimensionalAccuracy::kOversize, CorrectionRange::kFull, 0.041, 0);
  EXPECT_STREQ(r.correction.message->text, "OVERSIZE");
  // C3: the stair 100 / 100.014 with C1's parameters: d = 0.014 + 0.001 = 0.015 > 0.01 ->
  // OVERSIZE, > I 0.005 -> full 0.015
  CorrectionInstruction c3 = kSummaryC1;
  c3.compare_number = 3;
  r = RunCorrection(pages, 0, c3);
  ASSERT_EQ(r.error, "");
  ExpectCorrection(r.correction, DimensionalAccuracy::kOversize, CorrectionRange::kFull, 0.015, 0);

  // TLD(1,3,,1,11,) = TLD(1,3,,1,11,) + MTD(105,,1,13), and MTD(105,,2,13).
  EXPECT_NEAR(ReadMtd(pages, {105, {}, 1, 13}, 0).value, 0.005 / 1.1, kTol);
  EXPECT_NEAR(ReadMtd(pages, {105, {}, 2, 13}, 0).value, 0.041, kTol);
  // @100 = MTD(105,,3,11) - 0 BEQ .FEHLER: the stair's dimensional accuracy is 1, not 0.
  EXPECT_EQ(ReadMtd(pages, {105, {}, 3, 11}, 0).value, 1);
  EXPECT_EQ(ReadMtd(pages, {105, {}, 1, 11}, 0).value, 0);
  EXPECT_EQ(ReadMtd(pages, {105, {}, 1, 14}, 0).value, 0);  // averaging
}

// RunCorrection writes elements 11..14; accuracy 3 leaves no correction value and keeps the
// average value.
TEST(Correction, RunWritesTheResultPage) {
  MeasuringPages pages;
  *pages.Point(0, 4) = {{5, 5.035, 0.035}, 'Z'};
  ASSERT_EQ(Compare(pages, 0, {1, 0, 4, {}}), "");
  ASSERT_EQ(RunCorrection(pages, 0, kExample54).error, "");  // d = 0.04 -> 0.034 (as above)
  const ErgebnisPage& e = *pages.Result(0, 1);
  EXPECT_EQ(e.dimensional_accuracy, 0);
  EXPECT_NEAR(e.correction_value, 0.034, kTol);
  EXPECT_TRUE(e.correction_strategy);  // 1: percentage correction
  EXPECT_EQ(e.average_value, 0);       // percentage correction does not average

  // The next workpiece is far too large: 5.3 -> d = 0.305 > D 0.2
  pages.Point(0, 4)->value = {5, 5.3, 0.3};
  pages.Result(0, 1)->average_value = 0.004;
  ASSERT_EQ(Compare(pages, 0, {1, 0, 4, {}}), "");
  const CorrectionRun r = RunCorrection(pages, 0, kExample54);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(e.dimensional_accuracy, 3);
  EXPECT_EQ(e.correction_value, 0);  // the previous 0.034 must not be applied again
  EXPECT_EQ(e.average_value, 0.004);
  EXPECT_STREQ(r.correction.message->text, "ILLEGALLY HIGH DIMENSIONAL DEVIATION");

  // Averaging keeps its average in element 12 for the next workpiece.
  pages.Point(0, 4)->value = {5, 5.0, 0};
  pages.Result(0, 1)->average_value = 0;
  ASSERT_EQ(Compare(pages, 0, {1, 0, 4, {}}), "");
  ASSERT_EQ(RunCorrection(pages, 0, kExample21).error, "");
  // d = 5 + 0.004 - 5 = 0.004; K = 0.004 / 1.5 = 0.002667 < J 0.01 -> element 12 = K, 13 = 0
  EXPECT_NEAR(ReadMtd(pages, {105, {}, 1, 12}, 0).value, 0.004 / 1.5, kTol);
  EXPECT_EQ(ReadMtd(pages, {105, {}, 1, 13}, 0).value, 0);
  EXPECT_EQ(ReadMtd(pages, {105, {}, 1, 14}, 0).value, 0);
}

TEST(Correction, ParameterErrors) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    CorrectionInstruction in;
    const char* error;
  };
  CorrectionInstruction base = kExample54;
  auto with = [&](auto change) {
    CorrectionInstruction in = base;
    change(in);
    return in;
  };
  const std::vector<Case> cases = {
      {with([](auto& in) { in.lower_allowance = 0.2; }),
       "lower allowance 0.2 above upper allowance 0.1"},
      {with([](auto& in) { in.strategy = 2; }),
       "correction strategy 2 is not 0 (averaging) or 1 (percentage correction)"},
      {with([](auto& in) { in.factor = 100.5; }),
       "percentage correction factor 100.5 outside 0.00001..100"},
      {with([](auto& in) { in.factor = 0; }), "percentage correction factor 0 outside"},
      {with([](auto& in) { in.strategy = 0, in.factor = 11; }),
       "weighting factor 11 outside 0.00001..10"},
      {with([](auto& in) { in.strategy = 0, in.factor = -1; }), "weighting factor -1 outside"},
      {with([](auto& in) { in.empirical_value = nan; }), "parameter F is not a number"},
      {with([](auto& in) { in.lower_limit = nan; }), "parameter J is not a number"},
  };
  for (const Case& c : cases) EXPECT_THAT(CheckCorrectionParameters(c.in), HasSubstr(c.error));
  // The ranges' ends are allowed (2.1: 0.00001 - 10, 0.00001 - 100).
  EXPECT_EQ(CheckCorrectionParameters(with([](auto& in) { in.factor = 100; })), "");
  EXPECT_EQ(CheckCorrectionParameters(with([](auto& in) { in.factor = 0.00001; })), "");
  EXPECT_EQ(CheckCorrectionParameters(with([](auto& in) { in.strategy = 0, in.factor = 10; })), "");

  // Through RunCorrection: the instruction named, the page untouched.
  MeasuringPages pages;
  *pages.Point(0, 1) = {{0, 0.01, 0.01}, 'X'};
  ASSERT_EQ(Compare(pages, 0, {1, 4, 1, {}}), "");
  CorrectionRun r = RunCorrection(pages, 0, cases[1].in);
  EXPECT_THAT(r.error, HasSubstr("CORRECTION(1,0.1,-0.1,0.2,0.14,0.005,2,85,0.06,0.02): "
                                 "correction strategy 2"));
  EXPECT_EQ(pages.Result(0, 1)->correction_value, 0);
  EXPECT_FALSE(pages.Result(0, 1)->correction_strategy);
  r = RunCorrection(pages, 0, with([](auto& in) { in.compare_number = 21; }));
  EXPECT_THAT(r.error, HasSubstr("compare number 21 outside ERGEBNISPAGE's 1..20"));
  r = RunCorrection(pages, 0, with([](auto& in) { in.compare_number = nan; }));
  EXPECT_THAT(r.error, HasSubstr("compare number nan outside"));
  r = RunCorrection(pages, 0, with([](auto& in) { in.compare_number = 2; }));
  EXPECT_THAT(r.error, HasSubstr("compare 2 has not been run (COMPARE first)"));
}

}  // namespace
}  // namespace vmt::control::measure
