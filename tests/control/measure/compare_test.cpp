#include "control/measure/compare.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

namespace vmt::control::measure {
namespace {

using ::testing::HasSubstr;

constexpr double kTol = 1e-12;

// What PROBE leaves in POINTPAGE (radius values, 4.6 Actual values).
void Probe(MeasuringPages& pages, int n, char axis, double command, double actual) {
  PointPage& p = *pages.Point(0, n);
  p.value = {command, actual, actual - command};
  p.measuring_axis = axis;
}

void ExpectValue(const MeasuredValue& v, double command, double actual, double deviation) {
  EXPECT_NEAR(v.command, command, kTol);
  EXPECT_NEAR(v.actual, actual, kTol);
  EXPECT_NEAR(v.deviation, deviation, kTol);
}

// The manual's summary program (5.6): P1 a face at Z-100, P2 the diameter 125 (X, G16: radius
// 62.5 in the point page), P3 the face at Z0; then COMPARE(1,0,3,), (2,4,2,), (3,1,1,3).
class CompareSummary : public ::testing::Test {
 protected:
  void SetUp() override {
    Probe(pages, 1, 'Z', -100, -100.01);
    Probe(pages, 2, 'X', 62.5, 62.52);
    Probe(pages, 3, 'Z', 0, 0.004);
  }
  MeasuringPages pages;
};

// Strategy 0, Point: the point itself.
TEST_F(CompareSummary, Compare1PointOnP3) {
  ASSERT_EQ(Compare(pages, 0, {1, 0, 3, {}}), "");
  const ErgebnisPage& r = *pages.Result(0, 1);
  EXPECT_EQ(r.comparison_strategy, 0);
  ExpectValue(r.measured_value_1, 0, 0.004, 0.004);
  ExpectValue(r.measured_value_2, 0, 0, 0);
  ExpectValue(r.comparison_value, 0, 0.004, 0.004);  // = P3
  EXPECT_EQ(r.measuring_axis, 'Z');
}

// Strategy 4, Diameter with one point: 2 x radius (4.6: the Diam strategy's exception).
TEST_F(CompareSummary, Compare2DiameterOnP2) {
  ASSERT_EQ(Compare(pages, 0, {2, 4, 2, {}}), "");
  const ErgebnisPage& r = *pages.Result(0, 2);
  EXPECT_EQ(r.comparison_strategy, 4);
  ExpectValue(r.measured_value_1, 62.5, 62.52, 0.02);
  // command 2 x 62.5 = 125 (the programmed diameter), actual 2 x 62.52 = 125.04,
  // deviation 125.04 - 125 = 0.04
  ExpectValue(r.comparison_value, 125, 125.04, 0.04);
  EXPECT_EQ(r.measuring_axis, 'X');
}

// Strategy 1, Stair between P1 (Z-100) and P3 (Z0).
TEST_F(CompareSummary, Compare3StairP1P3) {
  ASSERT_EQ(Compare(pages, 0, {3, 1, 1, 3}), "");
  const ErgebnisPage& r = *pages.Result(0, 3);
  EXPECT_EQ(r.comparison_strategy, 1);
  ExpectValue(r.measured_value_1, -100, -100.01, -0.01);
  ExpectValue(r.measured_value_2, 0, 0.004, 0.004);
  // command 0 - (-100) = 100; actual 0.004 - (-100.01) = 100.014; deviation 0.014
  ExpectValue(r.comparison_value, 100, 100.014, 0.014);
  // The points the other way round: the same stair, the height positive.
  ASSERT_EQ(Compare(pages, 0, {4, 1, 3, 1}), "");
  // sign -1 since -100 < 0: command -(-100 - 0) = 100, actual -(-100.01 - 0.004) = 100.014
  ExpectValue(pages.Result(0, 4)->comparison_value, 100, 100.014, 0.014);
}

// Strategy 2, Groove (5.3 COMPARE(1,2,1,2)): walls at Z-20 and Z-25.
TEST(Compare, GrooveWidth) {
  MeasuringPages pages;
  Probe(pages, 1, 'Z', -20, -20.01);
  Probe(pages, 2, 'Z', -25, -25.02);
  ASSERT_EQ(Compare(pages, 0, {1, 2, 1, 2}), "");
  const ErgebnisPage& r = *pages.Result(0, 1);
  EXPECT_EQ(r.comparison_strategy, 2);
  // sign -1 since -25 < -20: command -(-25 - -20) = 5, actual -(-25.02 - -20.01) = 5.01,
  // deviation 0.01: the groove is 10 um wider than drawn
  ExpectValue(r.comparison_value, 5, 5.01, 0.01);
  ExpectValue(r.measured_value_1, -20, -20.01, -0.01);
  ExpectValue(r.measured_value_2, -25, -25.02, -0.02);
}

// Strategy 3, Diameter with two points: the lathe example 2 (5.2) has P2 at X160 and P9 at
// X-160 (G16 diameters: radii 80 and -80).
TEST(Compare, DiameterFromTwoPoints) {
  MeasuringPages pages;
  Probe(pages, 2, 'X', 80, 80.01);
  Probe(pages, 9, 'X', -80, -80.02);
  ASSERT_EQ(Compare(pages, 0, {5, 3, 2, 9}), "");
  const ErgebnisPage& r = *pages.Result(0, 5);
  EXPECT_EQ(r.comparison_strategy, 3);
  // sign -1 since -80 < 80: command -(-80 - 80) = 160, actual -(-80.02 - 80.01) = 160.03,
  // deviation 0.03
  ExpectValue(r.comparison_value, 160, 160.03, 0.03);
}

// Strategy 4 on the negative side of the turning axis: the diameter is still positive.
TEST(Compare, DiameterFromOnePointBelowTheAxis) {
  MeasuringPages pages;
  Probe(pages, 6, 'X', -40, -39.99);
  ASSERT_EQ(Compare(pages, 0, {7, 4, 6, {}}), "");  // 2.1 example 2: COMPARE(7,4,6,)
  // command -2 x -40 = 80, actual -2 x -39.99 = 79.98, deviation -0.02 (undersize)
  ExpectValue(pages.Result(0, 7)->comparison_value, 80, 79.98, -0.02);
}

// 2.1 example 1: COMPARE(10,1,2,8), a stair between points 2 and 8 written to entry 10.
TEST(Compare, ManualExampleStairIntoEntry10) {
  MeasuringPages pages;
  Probe(pages, 2, 'Z', -10, -10.003);
  Probe(pages, 8, 'Z', -35, -34.998);
  ASSERT_EQ(Compare(pages, 0, {10, 1, 2, 8}), "");
  // sign -1: command -(-35 - -10) = 25, actual -(-34.998 - -10.003) = 24.995, deviation -0.005
  ExpectValue(pages.Result(0, 10)->comparison_value, 25, 24.995, -0.005);
  EXPECT_EQ(ReadMtd(pages, {105, {}, 10, 7}, 0).value, 1);
  EXPECT_NEAR(ReadMtd(pages, {105, {}, 10, 10}, 0).value, -0.005, kTol);
}

// COMPARE writes elements 1..10 and keeps CORRECTION's 11..14 (12: the running average).
TEST(Compare, KeepsTheCorrectionElements) {
  MeasuringPages pages;
  Probe(pages, 1, 'Z', 0, 0.01);
  ErgebnisPage& r = *pages.Result(0, 1);
  r.dimensional_accuracy = 1;
  r.average_value = 0.0031;
  r.correction_value = 0.02;
  r.correction_strategy = true;
  ASSERT_EQ(Compare(pages, 0, {1, 0, 1, 99}), "");  // D is not used by strategy 0
  EXPECT_EQ(r.dimensional_accuracy, 1);
  EXPECT_EQ(r.average_value, 0.0031);
  EXPECT_EQ(r.correction_value, 0.02);
  EXPECT_TRUE(r.correction_strategy);
  ExpectValue(r.comparison_value, 0, 0.01, 0.01);
}

TEST(Compare, Errors) {
  MeasuringPagesConfig config;
  config.results = 50;
  config.points = 50;
  MeasuringPages pages(config);
  Probe(pages, 1, 'Z', -100, -100);
  Probe(pages, 2, 'X', 60, 60);
  Probe(pages, 3, 'Z', 0, 0);
  Probe(pages, 50, 'Z', 10, 10);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    CompareInstruction in;
    const char* error;
  };
  const std::vector<Case> cases = {
      {{51, 0, 1, {}}, "COMPARE(51,0,1,): compare number 51 outside ERGEBNISPAGE's 1..50"},
      {{0, 0, 1, {}}, "compare number 0 outside"},
      {{1.5, 0, 1, {}}, "compare number 1.5 outside"},
      {{nan, 0, 1, {}}, "compare number nan outside"},
      {{1, 5, 1, {}}, "comparison strategy 5 is not 0..4"},
      {{1, -1, 1, {}}, "comparison strategy -1 is not 0..4"},
      {{1, 0.5, 1, {}}, "comparison strategy 0.5 is not 0..4"},
      {{1, 0, {}, {}}, "strategy 0 needs test point C"},
      {{1, 1, 1, {}}, "COMPARE(1,1,1,): strategy 1 needs test point D"},
      {{1, 2, 1, {}}, "strategy 2 needs test point D"},
      {{1, 3, 1, {}}, "strategy 3 needs test point D"},
      {{1, 0, 51, {}}, "test point 51 outside POINTPAGE's 1..50"},
      {{1, 1, 1, 0}, "test point 0 outside"},
      {{1, 0, 4, {}}, "test point 4 has not been measured"},
      {{1, 1, 1, 4}, "test point 4 has not been measured"},
      {{1, 1, 1, 1}, "test points C and D are the same point"},
      {{1, 1, 1, 2}, "test points of different measuring axes (Z, X)"},  // 2.1 note
      {{1, 3, 2, 3}, "test points of different measuring axes (X, Z)"},
      {{1, 4, 3, {}}, "strategy 4 needs a test point measured along X, not Z"},
  };
  for (const Case& c : cases) {
    EXPECT_THAT(Compare(pages, 0, c.in), HasSubstr(c.error));
    EXPECT_EQ(pages.Result(0, 1)->measuring_axis, 0) << c.error;  // nothing written
  }
  // Process 1 does not exist.
  EXPECT_THAT(Compare(pages, 1, {1, 0, 1, {}}), HasSubstr("outside ERGEBNISPAGE's 1..50 of "
                                                          "process 1"));
  // The 50th entry and point are there.
  EXPECT_EQ(Compare(pages, 0, {50, 1, 50, 3}), "");
  EXPECT_NEAR(pages.Result(0, 50)->comparison_value.command, 10, kTol);  // |0 - 10|
}

// With the default installation (LV2 = 20), compare 21 and point 21 are refused.
TEST(Compare, DefaultInstallationHasTwenty) {
  MeasuringPages pages;
  Probe(pages, 20, 'X', 5, 5);
  EXPECT_EQ(Compare(pages, 0, {20, 4, 20, {}}), "");
  EXPECT_THAT(Compare(pages, 0, {21, 4, 20, {}}),
              HasSubstr("compare number 21 outside ERGEBNISPAGE's 1..20"));
  EXPECT_THAT(Compare(pages, 0, {1, 4, 21, {}}),
              HasSubstr("test point 21 outside POINTPAGE's 1..20"));
}

}  // namespace
}  // namespace vmt::control::measure
