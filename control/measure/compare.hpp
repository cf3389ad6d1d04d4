#pragma once
// COMPARE(A, B, C, D) (mtc200-fast-measurement.md 2.1, 2.2, 4.6 Actual values, 5.3): one or two
// test points of POINTPAGE compared by a comparison strategy into ERGEBNISPAGE entry A.

#include <cstdint>
#include <optional>
#include <string>

#include "control/measure/measuring_pages.hpp"

namespace vmt::control::measure {

/// COMPARE parameter B (2.1).
enum class ComparisonStrategy : int8_t {
  kPoint = 0,            ///< one point: its position
  kStair = 1,            ///< two points: the height of a stair (radius values in X)
  kGroove = 2,           ///< two points: the width of a groove
  kDiameter2Points = 3,  ///< two points on opposite sides: a diameter
  kDiameter1Point = 4,   ///< one point on the diameter axis X of a lathe: twice its radius
};

/// COMPARE(A, B, C, D) as the NC program gives it: reals (expressions); omitted = nullopt.
struct CompareInstruction {
  double compare_number = 0;      ///< A: entry LV2 of ERGEBNISPAGE, 1..LV2 (20, at most 50)
  double strategy = 0;            ///< B: ComparisonStrategy 0..4
  std::optional<double> point_1;  ///< C: test point 1, LV2 of POINTPAGE
  std::optional<double> point_2;  ///< D: test point 2 (strategies 1..3; ignored by 0 and 4)
};

/// ERGEBNISPAGE elements 1..10 but the strategy: the measured values used and the comparison
/// value (command = the nominal dimension, actual = the actual dimension, deviation).
struct Comparison {
  MeasuredValue measured_value_1;
  MeasuredValue measured_value_2;  ///< zeros for the one-point strategies
  MeasuredValue comparison_value;
};

/// The comparison of points `p1` and `p2` (p2 unused by kPoint and kDiameter1Point). The
/// two-point strategies give the distance between the two surfaces, oriented so that the
/// command value is >= 0; deviation = actual - command throughout.
Comparison CompareValues(ComparisonStrategy strategy, const MeasuredValue& p1,
                         const MeasuredValue& p2);

/// Runs COMPARE in `process`: reads the test points, writes elements 1..10 of ERGEBNISPAGE entry
/// A (and the points' measuring axis); elements 11..14, CORRECTION's, are kept (12 is the running
/// average over the workpieces). Returns "" or the reason the instruction cannot run (a program
/// error): A, B, C or D outside their ranges, a point not measured yet, points of different
/// measuring axes (2.1 note), strategy 4 on a point not measured along X.
std::string Compare(MeasuringPages& pages, int process, const CompareInstruction& instruction);

}  // namespace vmt::control::measure
