// The manual's summary cycle (5.6): three points, three comparisons, three corrections, and
// the messages of 4.6 / 6.1 for each verdict.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "control/measure/measuring_cycle.hpp"
#include "measuring_cycle_support.hpp"

namespace vmt::control::measure {
namespace {

using namespace testing;  // vmt::control::measure::testing
using ::testing::HasSubstr;
using ::testing::StartsWith;

// 5.6: three points, three comparisons, three corrections; the messages of 4.6 / 6.1.
class Summary : public Lathe {
 protected:
  void Measure(double p3_actual) {
    Setting();
    ASSERT_EQ(Plan("SAVE(1,1,1)").error, "");
    context.position = {120, 50, 0};
    // P1 face Z-100 two-dimensionally: setup Z -96.5 at X90.
    const MeasuringPlan p1 = Run("PROBE(1,1,180,-100,,Z,-1,100,1,3,0)", -97.51);
    ExpectRapid(p1.steps[1], kXZ, 90, -96.5);
    ExpectMeasure(p1.steps[4], kZ, 90, -98.5, 100);
    // P2 diameter 125 (radius 62.5): setup X 66 at Z-10.
    const MeasuringPlan p2 = Run("PROBE(2,1,125,-10,,X,-2,100,1,3,0)", 65.01);
    ExpectRapid(p2.steps[1], kXZ, 66, -10);
    ExpectMeasure(p2.steps[4], kX, 64, -10, 100);
    // P3 face Z0 by the positioning logic: Z to 3.5 first, then X to 57.5.
    const MeasuringPlan p3 = Run("PROBE(3,1,115,0,,Z,-1,100,1,4,0)", p3_actual + 2.5);
    ExpectRapid(p3.steps[1], kZ, 66, 3.5);
    ExpectRapid(p3.steps[2], kX, 57.5, 3.5);
    ExpectMeasure(p3.steps[5], kZ, 57.5, 1.5, 100);
    EXPECT_NEAR(pages.Point(0, 1)->value.actual, -100.01, kTol);
    EXPECT_NEAR(pages.Point(0, 2)->value.actual, 62.51, kTol);
    EXPECT_NEAR(pages.Point(0, 3)->value.actual, p3_actual, kTol);
    ASSERT_EQ(Plan("COMPARE(1,0,3,)").error, "");
    ASSERT_EQ(Plan("COMPARE(2,4,2,)").error, "");
    ASSERT_EQ(Plan("COMPARE(3,1,1,3)").error, "");
  }
  const MeasuringMessage* Correct1() {
    const MeasuringPlan plan = Plan("CORRECTION(1,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005,0.002)");
    EXPECT_EQ(plan.error, "");
    EXPECT_TRUE(plan.steps.empty());
    return plan.message;
  }
};

TEST_F(Summary, InTolerance) {
  Measure(0.004);  // d = 0.004 + 0.001 = 0.005 <= tolerance limit 0.01
  EXPECT_EQ(Correct1(), nullptr);
  EXPECT_EQ(pages.Result(0, 1)->dimensional_accuracy, 0);
  // C2: diameter 125.02 against 125 (d 0.021 > 0.02 limit: OVERSIZE); C3: stair.
  const MeasuringPlan c2 = Plan("CORRECTION(2,0.02,-0.02,0.35,0.28,0.001,0,1.8,0.01,0.007)");
  ASSERT_EQ(c2.error, "");
  EXPECT_NEAR(pages.Result(0, 2)->comparison_value.actual, 125.02, kTol);
  EXPECT_EQ(c2.message, &kOversize);
  ASSERT_EQ(Plan("CORRECTION(3,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005,0.002)").error, "");
  EXPECT_NEAR(pages.Result(0, 3)->comparison_value.command, 100, kTol);
}

TEST_F(Summary, Oversize) {
  Measure(0.05);  // d = 0.051: beyond the tolerance limit, below the correction limit 0.1
  const MeasuringMessage* m = Correct1();
  EXPECT_EQ(m, &kOversize);
  EXPECT_EQ(m->q_function, 9998);
  EXPECT_EQ(pages.Result(0, 1)->dimensional_accuracy, 1);
}

TEST_F(Summary, Undersize) {
  Measure(-0.05);  // d = -0.049
  EXPECT_EQ(Correct1(), &kUndersize);
  EXPECT_EQ(pages.Result(0, 1)->dimensional_accuracy, 2);
}

TEST_F(Summary, CheckTool) {
  Measure(0.11);  // d = 0.111: above the correction limit 0.1, below the upper limit 0.12
  const MeasuringMessage* m = Correct1();
  EXPECT_EQ(m, &kCheckTool);
  EXPECT_EQ(m->q_function, 9999);
  EXPECT_EQ(pages.Result(0, 1)->dimensional_accuracy, 3);
}

TEST_F(Summary, IllegallyHighDimensionalDeviation) {
  Measure(0.2);
  EXPECT_EQ(Correct1(), &kIllegallyHighDimensionalDeviation);
}

TEST_F(Summary, CompareAndCorrectionErrorsNameTheCall) {
  Measure(0.004);
  EXPECT_THAT(
      Plan("COMPARE(1,1,1,2)").error,
      HasSubstr("COMPARE(1,1,1,2): test points of different measuring axes (Z, X) (2.1 COMPARE)"));
  EXPECT_THAT(Plan("COMPARE(30,0,1,)").error, HasSubstr("compare number 30 outside"));
  EXPECT_THAT(Plan("CORRECTION(1,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005)").error,
              HasSubstr("J (lower limit) is missing (2.1 CORRECTION)"));
  EXPECT_THAT(Plan("CORRECTION(9,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005,0.002)").error,
              HasSubstr("compare 9 has not been run"));
}

}  // namespace
}  // namespace vmt::control::measure
