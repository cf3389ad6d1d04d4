#include "control/measure/correction_target.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

namespace vmt::control::measure {
namespace {

using ::testing::HasSubstr;
using Kind = CorrectionTarget::Kind;

ErgebnisPage Entry(char axis, double correction_value) {
  ErgebnisPage e;
  e.measuring_axis = axis;
  e.correction_value = correction_value;
  return e;
}

// 5.6: TLD(1,3,,1,11,) = TLD(1,3,,1,11,) + MTD(105,,1,13) corrects the Z face with wear L1
// of T3, and TLD(...,12,) the X diameter with wear L2.
TEST(CorrectionTarget, ToolWearAsTheSummaryProgram) {
  EXPECT_EQ(WearElement('Z'), 11);
  EXPECT_EQ(WearElement('X'), 12);
  EXPECT_EQ(WearElement('Y'), 13);
  EXPECT_FALSE(WearElement('C'));
  EXPECT_FALSE(WearElement(0));

  const CorrectionTarget t3{Kind::kToolWear, 3, 1, 0};
  // Z: old wear 0.01 + correction 0.0045 = 0.0145 into element 11 of T3 D1
  CorrectionWrite w = CorrectionFor(t3, Entry('Z', 0.0045), 0.01);
  ASSERT_EQ(w.error, "");
  EXPECT_EQ(w.kind, Kind::kToolWear);
  EXPECT_EQ(w.tool, 3);
  EXPECT_EQ(w.edge, 1);
  EXPECT_EQ(w.tld_element, 11);
  EXPECT_EQ(w.axis, 'Z');
  EXPECT_DOUBLE_EQ(w.value, 0.0145);
  // X: old wear -0.02 + 0.041 = 0.021 into element 12
  w = CorrectionFor(t3, Entry('X', 0.041), -0.02);
  ASSERT_EQ(w.error, "");
  EXPECT_EQ(w.tld_element, 12);
  EXPECT_DOUBLE_EQ(w.value, 0.021);
  // No correction (accuracy 3, or below the lower limit): the register stays as it was.
  EXPECT_DOUBLE_EQ(CorrectionFor(t3, Entry('X', 0), -0.02).value, -0.02);
}

// 2.1: OTD(,,4,1) = OTD(,,4,1) + MTD(105,,1,13), the X entry of the shift by G54.
TEST(CorrectionTarget, ZeroOffsetAsTheManual) {
  EXPECT_EQ(OtdTable(54), 4);
  EXPECT_EQ(OtdTable(59), 9);
  EXPECT_FALSE(OtdTable(53));
  EXPECT_FALSE(OtdTable(60));
  const CorrectionTarget g54{Kind::kZeroOffset, 0, 1, 54};
  // old shift 150 + correction -0.03 = 149.97
  const CorrectionWrite w = CorrectionFor(g54, Entry('X', -0.03), 150);
  ASSERT_EQ(w.error, "");
  EXPECT_EQ(w.kind, Kind::kZeroOffset);
  EXPECT_EQ(w.zero_offset_g, 54);
  EXPECT_EQ(w.otd_table, 4);
  EXPECT_EQ(w.axis, 'X');
  EXPECT_DOUBLE_EQ(w.value, 149.97);
  // A zero offset can take any axis.
  EXPECT_EQ(CorrectionFor({Kind::kZeroOffset, 0, 1, 57}, Entry('C', 1), 0).error, "");
}

TEST(CorrectionTarget, Errors) {
  const CorrectionTarget t3{Kind::kToolWear, 3, 1, 0};
  EXPECT_THAT(CorrectionFor(t3, Entry(0, 0.01), 0).error, HasSubstr("the result has no COMPARE"));
  EXPECT_THAT(CorrectionFor(t3, Entry('C', 0.01), 0).error, HasSubstr("no wear register along C"));
  EXPECT_THAT(CorrectionFor({Kind::kToolWear, 0, 1, 0}, Entry('X', 0.01), 0).error,
              HasSubstr("tool wear correction without a T number"));
  EXPECT_THAT(CorrectionFor({Kind::kZeroOffset, 0, 1, 53}, Entry('X', 0.01), 0).error,
              HasSubstr("zero offset G53 is not G54..G59"));
  EXPECT_THAT(CorrectionFor(t3, Entry('X', 0.01), std::numeric_limits<double>::infinity()).error,
              HasSubstr("old value is not a number"));
}

}  // namespace
}  // namespace vmt::control::measure
