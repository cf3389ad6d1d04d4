#include "control/measure/compare.hpp"

#include "control/measure/nc_number.hpp"

namespace vmt::control::measure {
namespace {

bool OnePoint(ComparisonStrategy s) {
  return s == ComparisonStrategy::kPoint || s == ComparisonStrategy::kDiameter1Point;
}

MeasuredValue Oriented(double sign, double command, double actual) {
  const double c = sign * command, a = sign * actual;
  return {c, a, a - c};
}

}  // namespace

Comparison CompareValues(ComparisonStrategy strategy, const MeasuredValue& p1,
                         const MeasuredValue& p2) {
  Comparison c;
  c.measured_value_1 = p1;
  switch (strategy) {
    case ComparisonStrategy::kPoint:
      c.comparison_value = p1;
      break;
    case ComparisonStrategy::kDiameter1Point: {
      // 4.6 Actual values: the point page holds radius values; the Diam strategy is the
      // exception that gives a diameter, twice the distance from the turning axis.
      const double sign = p1.command < 0 ? -1 : 1;
      c.comparison_value = Oriented(2 * sign, p1.command, p1.actual);
      break;
    }
    case ComparisonStrategy::kStair:
    case ComparisonStrategy::kGroove:
    case ComparisonStrategy::kDiameter2Points: {
      // The distance between the two surfaces along the common measuring axis: the stair's
      // height, the groove's width, the diameter between opposite sides. Its sign is the one
      // that makes the nominal distance positive, so a positive deviation is always "larger".
      c.measured_value_2 = p2;
      const double sign = p2.command < p1.command ? -1 : 1;
      c.comparison_value = Oriented(sign, p2.command - p1.command, p2.actual - p1.actual);
      break;
    }
  }
  return c;
}

std::string Compare(MeasuringPages& pages, int process, const CompareInstruction& in) {
  const std::string call = "COMPARE(" + NcNumber(in.compare_number) + "," + NcNumber(in.strategy) +
                           "," + NcArgument(in.point_1) + "," + NcArgument(in.point_2) + "): ";
  const MeasuringPagesConfig& config = pages.config;

  const std::optional<int> a = WholeNumber(in.compare_number);
  ErgebnisPage* entry = a ? pages.Result(process, *a) : nullptr;
  if (!entry)
    return call + "compare number " + NcNumber(in.compare_number) + " outside ERGEBNISPAGE's 1.." +
           std::to_string(config.results) + " of process " + std::to_string(process);

  const std::optional<int> b = WholeNumber(in.strategy);
  if (!b || *b < 0 || *b > 4)
    return call + "comparison strategy " + NcNumber(in.strategy) + " is not 0..4";
  const auto strategy = static_cast<ComparisonStrategy>(*b);

  // The points: C always, D for the two-point strategies; each measured already.
  const int wanted = OnePoint(strategy) ? 1 : 2;
  const PointPage* point[2] = {nullptr, nullptr};
  for (int k = 0; k < wanted; ++k) {
    const char* letter = k == 0 ? "C" : "D";
    const std::optional<double>& given = k == 0 ? in.point_1 : in.point_2;
    if (!given) return call + "strategy " + std::to_string(*b) + " needs test point " + letter;
    const std::optional<int> n = WholeNumber(*given);
    point[k] = n ? pages.Point(process, *n) : nullptr;
    if (!point[k])
      return call + "test point " + NcNumber(*given) + " outside POINTPAGE's 1.." +
             std::to_string(config.points);
    if (point[k]->measuring_axis == 0)
      return call + "test point " + NcNumber(*given) + " has not been measured";
  }
  if (wanted == 2) {
    if (point[0] == point[1]) return call + "test points C and D are the same point";
    // 2.1 note: comparison is only possible for points that have the same measuring axis.
    if (point[0]->measuring_axis != point[1]->measuring_axis)
      return call + "test points of different measuring axes (" +
             std::string(1, point[0]->measuring_axis) + ", " +
             std::string(1, point[1]->measuring_axis) + ")";
  }
  // 2.1 note: strategy 4 is the diameter of a lathe measured at one point along X.
  if (strategy == ComparisonStrategy::kDiameter1Point && point[0]->measuring_axis != 'X')
    return call + "strategy 4 needs a test point measured along X, not " +
           std::string(1, point[0]->measuring_axis);

  const Comparison c =
      CompareValues(strategy, point[0]->value, point[1] ? point[1]->value : MeasuredValue{});
  entry->measured_value_1 = c.measured_value_1;
  entry->measured_value_2 = c.measured_value_2;
  entry->comparison_strategy = static_cast<int8_t>(strategy);
  entry->comparison_value = c.comparison_value;
  entry->measuring_axis = point[0]->measuring_axis;
  return "";
}

}  // namespace vmt::control::measure
