// The manual's measuring programs planned and run on a simulated lathe with their stated
// results: calibration (5.1), the two lathe examples (5.2) and the reverse vectors of figure 4-9.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "control/measure/measuring_cycle.hpp"
#include "measuring_cycle_support.hpp"

namespace vmt::control::measure {
namespace {

using namespace testing;  // vmt::control::measure::testing
using ::testing::HasSubstr;
using ::testing::StartsWith;

// 5.1 example 2 (lathe calibration), then the same surface measured: deviation 0. The manual
// prints PROBE(,0,30,55,,X,-2,100,1,0) with ten arguments; its text ("fed with interpolation and
// return to the start point") is approach variant 1, and a calibration is single point (4.4).
TEST_F(Lathe, CalibrationExample2ThenMeasuringTheSameSurfaceGivesDeviation0) {
  Setting();
  ASSERT_EQ(Plan("SAVE(1,1,1)").error, "");
  context.position = {50, 80, 0};
  // X30 diameter: the surface at radius 15; path -2 diameter: 1 mm; sphere 1 radius 2.5.
  // Setup X = 15 + 1 + 2.5 = 18.5, measuring path 2 mm to 16.5. The probe switches at 17.48
  // (the sphere touches at 17.5; 0.02 more travel before the latch).
  const MeasuringPlan plan = Run("PROBE(,0,30,55,,X,-2,100,1,1,0)", 17.48);
  ASSERT_EQ(plan.steps.size(), 8u);
  ExpectEvent(plan.steps[0], 29, true);
  ExpectRapid(plan.steps[1], kXZ, 18.5, 55);  // directly: both axes together
  ExpectEvent(plan.steps[2], 30, true);
  ExpectWaitE29Reset(plan.steps[3]);
  ExpectMeasure(plan.steps[4], kX, 16.5, 55, 100);
  ExpectEvent(plan.steps[5], 30, false);
  ExpectRapid(plan.steps[6], kX, 18.5, 55);
  ExpectRapid(plan.steps[7], kXZ, 50, 80);  // escape to the initial point
  EXPECT_EQ(plan.measuring_axis, 0);
  EXPECT_EQ(plan.direction, -1);
  EXPECT_NEAR(plan.command, 15, kTol);
  const EichwertePage& cal = pages.calibration[0][0];
  EXPECT_NEAR(cal.measuring_direction[1], -0.02, kTol);  // axis 1, - direction
  EXPECT_EQ(cal.measuring_direction[0], 0);
  EXPECT_EQ(cal.measuring_feed[1], 100);
  EXPECT_EQ(pages.Point(0, 1)->measuring_axis, 0);  // a calibration writes no test point
  EXPECT_TRUE(Plan("RESTORE()").restore_variables);

  Run("PROBE(1,1,30,55,,X,-2,100,1,1,0)", 17.48);
  const PointPage& p = *pages.Point(0, 1);
  EXPECT_EQ(p.measuring_axis, 'X');
  EXPECT_NEAR(p.value.command, 15, kTol);
  EXPECT_NEAR(p.value.actual, 15, kTol);
  EXPECT_NEAR(p.value.deviation, 0, kTol);
  // 0.03 mm more material: the probe switches 0.03 earlier.
  Run("PROBE(1,1,30,55,,X,-2,100,1,1,0)", 17.51);
  EXPECT_NEAR(pages.Point(0, 1)->value.deviation, 0.03, kTol);
}

// 3.1 EICHWERTEPAGE keeps the feed a direction was calibrated at: a measuring PROBE at another
// feed warns (the calibration value holds that feed's latch delay), and still measures. The
// same feed, a calibration, another direction or a direction never calibrated do not warn.
TEST_F(Lathe, MeasuringAtAnotherFeedThanTheCalibrationsWarns) {
  Setting();
  context.position = {50, 80, 0};
  EXPECT_EQ(Run("PROBE(1,1,30,55,,X,-2,300,1,1,0)", 17.48).warning, "");  // not calibrated
  EXPECT_EQ(Run("PROBE(,0,30,55,,X,-2,100,1,1,0)", 17.48).warning, "");
  EXPECT_EQ(Run("PROBE(1,1,30,55,,X,-2,100,1,1,0)", 17.48).warning, "");
  const MeasuringPlan other = Run("PROBE(2,1,30,55,,X,-2,250,1,1,0)", 17.48);
  EXPECT_THAT(other.warning, HasSubstr("F250"));
  EXPECT_THAT(other.warning, HasSubstr("axis X- of sphere 1 was calibrated at F100"));
  EXPECT_NE(pages.Point(0, 2), nullptr);  // measured all the same
  EXPECT_EQ(Run("PROBE(,0,30,55,,X,-2,250,1,1,0)", 17.48).warning, "");  // a new calibration
  EXPECT_EQ(Run("PROBE(3,1,30,55,,X,-2,250,1,1,0)", 17.48).warning, "");
  EXPECT_EQ(Run("PROBE(4,1,70,-44,,Z,1,400,1,1,0)", -46.97).warning, "");  // Z+ never calibrated
}

TEST_F(Lathe, CalibrationInThePlusDirection) {
  Setting();
  // Z measured in + toward a face at Z-44, sphere 2 (radius 3): setup Z -48; the latch at
  // -46.97 (the sphere touches at -47; the stylus is 0.03 short of a perfect ball).
  Run("PROBE(,0,70,-44,,Z,1,100,2,1,0)", -46.97);
  EXPECT_NEAR(pages.calibration[0][1].measuring_direction[2], -0.03, kTol);  // axis 2 +
  Run("PROBE(3,1,70,-44,,Z,1,100,2,1,0)", -46.97);
  EXPECT_NEAR(pages.Point(0, 3)->value.actual, -44, kTol);
  EXPECT_NEAR(pages.Point(0, 3)->value.deviation, 0, kTol);
}

// 3.1 ZWISCHENSPEICHERPAGE element 1 hides the calibration points.
TEST_F(Lathe, HiddenCalibrationDoesNothing) {
  Setting();
  pages.buffer[0].calibration_off = true;
  const MeasuringPlan plan = Plan("PROBE(,0,30,55,,X,-2,100,1,1,0)");
  EXPECT_EQ(plan.error, "");
  EXPECT_TRUE(plan.steps.empty());
  EXPECT_EQ(plan.measuring_axis, -1);
  EXPECT_EQ(FinishProbe(Call("PROBE(,0,30,55,,X,-2,100,1,1,0)"), plan, context, pages, 1.0),
            nullptr);
  EXPECT_EQ(pages.calibration[0][0].measuring_direction[1], 0);
}

// 6.1: no switch on the measuring path.
TEST_F(Lathe, TestPointNotFound) {
  Setting();
  const MeasuringMessage* message = nullptr;
  Run("PROBE(1,1,64,35,,X,-2,100,1,3,0)", std::nullopt, &message);
  EXPECT_EQ(message, &kTestPointNotFound);
  EXPECT_EQ(message->q_function, 9999);
  EXPECT_EQ(pages.Point(0, 1)->measuring_axis, 0);  // nothing recorded
}

// 4.5: under G16 a measuring path along X is a diameter (2 mm program: 1 mm to the surface);
// along Z it is not halved. G15 for comparison.
TEST_F(Lathe, DiameterPathIsHalved) {
  Setting();
  const MeasuringPlan g16 = Plan("PROBE(1,1,30,55,,X,-2,100,1,3,0)");
  ExpectRapid(g16.steps[1], kXZ, 18.5, 55);        // 15 + 1 + 2.5
  ExpectMeasure(g16.steps[4], kX, 16.5, 55, 100);  // 2 x 1 mm
  const MeasuringPlan z = Plan("PROBE(2,1,30,55,,Z,-2,100,1,3,0)");
  ExpectRapid(z.steps[1], kXZ, 15, 59.5);  // 55 + 2 + 2.5
  ExpectMeasure(z.steps[4], kZ, 15, 55.5, 100);
  ASSERT_EQ(Plan("SETTING(X,Z,,18,48,15,25)").error, "");
  const MeasuringPlan g15 = Plan("PROBE(1,1,30,55,,X,-2,100,1,3,0)");
  ExpectRapid(g15.steps[1], kXZ, 34.5, 55);  // 30 + 2 + 2.5
  ExpectMeasure(g15.steps[4], kX, 30.5, 55, 100);
}

// 5.2 example 1: three diameters and three faces, P4..P6 in linear path sequence 10.
TEST_F(Lathe, MeasuringExample1) {
  Setting();
  ASSERT_EQ(Plan("SAVE(1,1,1)").error, "");
  context.position = {40, 60, 0};
  // P1 X64 (radius 32), path -2 (1 mm), sphere 2.5: setup X 35.5 at Z35, two-dimensional,
  // no escape: the stylus stays at the setup position.
  const MeasuringPlan p1 = Run("PROBE(1,1,64,35,,X,-2,100,1,3,0)", 34.5);
  ASSERT_EQ(p1.steps.size(), 7u);
  ExpectEvent(p1.steps[0], 29, true);
  ExpectRapid(p1.steps[1], kXZ, 35.5, 35);
  ExpectEvent(p1.steps[2], 30, true);
  ExpectWaitE29Reset(p1.steps[3]);
  ExpectMeasure(p1.steps[4], kX, 33.5, 35, 100);
  ExpectEvent(p1.steps[5], 30, false);
  ExpectRapid(p1.steps[6], kX, 35.5, 35);
  ExpectPoint(context.position, 35.5, 35);
  EXPECT_NEAR(pages.Point(0, 1)->value.actual, 32, kTol);  // 34.5 - 2.5

  // P2 face Z40, path -1, positioning logic: first Z (parallel to the measuring path) into the
  // plane Z 43.5 of the setup position, then X to 26 (X52).
  const MeasuringPlan p2 = Run("PROBE(2,1,52,40,,Z,-1,100,1,4,0)", 42.5);
  ASSERT_EQ(p2.steps.size(), 8u);
  ExpectEvent(p2.steps[0], 29, true);
  ExpectRapid(p2.steps[1], kZ, 35.5, 43.5);
  ExpectRapid(p2.steps[2], kX, 26, 43.5);
  ExpectEvent(p2.steps[3], 30, true);
  ExpectWaitE29Reset(p2.steps[4]);
  ExpectMeasure(p2.steps[5], kZ, 26, 41.5, 100);
  ExpectEvent(p2.steps[6], 30, false);
  ExpectRapid(p2.steps[7], kZ, 26, 43.5);
  EXPECT_NEAR(pages.Point(0, 2)->value.actual, 40, kTol);
  EXPECT_EQ(p2.measuring_axis, 1);

  // P3 X40: setup X 23.5 at Z50.
  Run("PROBE(3,1,40,50,,X,-2,100,1,3,0)", 22.5);
  ExpectPoint(context.position, 23.5, 50);
  // P4 face Z55 (sequence 10): Z to 58.5, then X to 16.
  const MeasuringPlan p4 = Run("PROBE(4,1,32,55,,Z,-1,100,1,4,10)", 57.5);
  ExpectRapid(p4.steps[1], kZ, 23.5, 58.5);
  ExpectRapid(p4.steps[2], kX, 16, 58.5);
  EXPECT_EQ(p4.reverse_variant, 10);
  // P5 bore X24 measured in +X: setup X 12 - 1 - 2.5 = 8.5; X first, then Z to 50.
  const MeasuringPlan p5 = Run("PROBE(5,1,24,50,,X,2,100,1,4,10)", 9.5);
  ExpectRapid(p5.steps[1], kX, 8.5, 58.5);
  ExpectRapid(p5.steps[2], kZ, 8.5, 50);
  ExpectMeasure(p5.steps[5], kX, 10.5, 50, 100);
  EXPECT_EQ(p5.direction, 1);
  EXPECT_NEAR(pages.Point(0, 5)->value.actual, 12, kTol);  // 9.5 + 2.5
  // P6 face Z30, two-dimensional to X6 Z33.5.
  const MeasuringPlan p6 = Run("PROBE(6,1,12,30,,Z,-1,100,1,3,10)", 32.5);
  ExpectRapid(p6.steps[1], kXZ, 6, 33.5);
  // Sequence 10 from P4's start back: P6, P5, P4's setup and plane points, P4's start.
  const std::vector<ReversePoint> back = reverse.Reversal();
  ASSERT_EQ(back.size(), 6u);
  ExpectPoint(back[0], 6, 33.5, 1);
  ExpectPoint(back[1], 8.5, 50, 1);
  ExpectPoint(back[2], 8.5, 58.5, 1);
  ExpectPoint(back[3], 16, 58.5, 1);
  ExpectPoint(back[4], 23.5, 58.5, 1);
  ExpectPoint(back[5], 23.5, 50, 1);
  EXPECT_TRUE(Plan("RESTORE()").restore_variables);
}

// 5.2 example 2: P1 three-dimensional, P2 by the positioning logic opening sequence 8; P10 with
// K 0 ends the sequence.
TEST_F(Lathe, MeasuringExample2) {
  Setting();
  ASSERT_EQ(Plan("SAVE(1,1,1)").error, "");
  context.position = {120, 50, 0};
  const MeasuringPlan p1 = Run("PROBE(1,1,180,0,,Z,-1,100,1,3,0)", 2.5);
  ExpectRapid(p1.steps[1], kXZ, 90, 3.5);
  ExpectMeasure(p1.steps[4], kZ, 90, 1.5, 100);
  EXPECT_NEAR(pages.Point(0, 1)->value.actual, 0, kTol);
  // P2 X160 in +X: setup X 80 - 3.5 = 76.5; first X into that plane, then Z to -20.
  const MeasuringPlan p2 = Run("PROBE(2,1,160,-20,,X,2,100,1,4,8)", 77.5);
  ExpectRapid(p2.steps[1], kX, 76.5, 3.5);
  ExpectRapid(p2.steps[2], kZ, 76.5, -20);
  ExpectMeasure(p2.steps[5], kX, 78.5, -20, 100);
  EXPECT_NEAR(pages.Point(0, 2)->value.actual, 80, kTol);
  const MeasuringPlan p3 = Run("PROBE(3,1,130,-100,,Z,-1,100,1,3,8)", -97.5);
  ExpectRapid(p3.steps[1], kXZ, 65, -96.5);
  EXPECT_EQ(reverse.sequence[7].size(), 4u);  // P2's start, plane point, setup; P3's setup
  // P7 X-100 (radius -50) measured in -X: setup X -50 + 3.5 = -46.5.
  const MeasuringPlan p7 = Run("PROBE(7,1,-100,-110,,X,-2,100,1,3,8)", -47.5);
  ExpectRapid(p7.steps[1], kXZ, -46.5, -110);
  EXPECT_NEAR(pages.Point(0, 7)->value.actual, -50, kTol);
  const MeasuringPlan p10 = Run("PROBE(10,1,-180,0,,Z,-1,100,1,4,0)", 2.5);
  EXPECT_EQ(p10.reverse_variant, 0);
  EXPECT_TRUE(reverse.sequence[7].empty());
  EXPECT_EQ(reverse.active, 0);
  EXPECT_TRUE(Plan("RESTORE()").restore_feed);
}

// Figure 4-9: blocks 50..55 single point, 56..60 linear path sequence 5 (the manual's
// MOVE(-,12,,4,5) of block 57 read as X omitted).
TEST_F(Lathe, ReverseVectorsOfFigure4_9) {
  pages.stylus[0].sphere_radius = {2.5, 3, 0, 1.5, 0};
  Setting();
  context.position = {60, 100, 0};
  Run("MOVE(,44,,2,0)");  // 50
  std::vector<ReversePoint> back = reverse.Reversal();
  ASSERT_EQ(back.size(), 2u);
  ExpectPoint(back[0], 60, 44, 2);
  ExpectPoint(back[1], 60, 100, 2);
  // 51: face Z-44 measured in +Z with sphere 2: Z first to -48, then X to 35.
  Run("PROBE(1,1,70,-44,,Z,1,100,2,4,0)", -47);
  back = reverse.Reversal();
  ASSERT_EQ(back.size(), 3u);  // only this instruction's movements
  ExpectPoint(back[0], 35, -48, 2);
  ExpectPoint(back[1], 60, -48, 2);
  ExpectPoint(back[2], 60, 44, 2);
  Run("PROBE(2,1,80,-35,,X,-2,100,2,4,0)", 40);    // 52
  Run("PROBE(3,1,95,-23,,X,-2,100,2,4,0)", 47.5);  // 53
  Run("MOVE(100,30,,1,0)");                        // 54
  Run("MOVE(24,30,,4,0)");                         // 55
  back = reverse.Reversal();
  ASSERT_EQ(back.size(), 2u);
  ExpectPoint(back[0], 12, 30, 4);
  ExpectPoint(back[1], 50, 30, 4);

  // 56: P4, bore X30 in +X, sphere 4 (1.5): setup X 15 - 1 - 1.5 = 12.5 at Z-3, directly.
  const MeasuringPlan p4 = Run("PROBE(4,1,30,-3,,X,2,100,4,3,5)", 13.5);
  ExpectRapid(p4.steps[1], kXZ, 12.5, -3, 4);
  EXPECT_EQ(reverse.active, 5);
  EXPECT_TRUE(reverse.single_point.empty());
  back = reverse.Reversal();
  ASSERT_EQ(back.size(), 2u);
  ExpectPoint(back[0], 12.5, -3, 4);
  ExpectPoint(back[1], 12, 30, 4);
  Run("MOVE(,12,,4,5)");                          // 57
  Run("PROBE(5,1,40,-12,,X,2,100,4,3,5)", 18.5);  // 58: setup X 17.5 at Z-12
  Run("PROBE(6,1,30,-23,,X,2,100,4,4,5)", 13.5);  // 59: X to 12.5, then Z to -23
  Run("MOVE(24,30,,4,5)");                        // 60
  back = reverse.Reversal();
  ASSERT_EQ(back.size(), 7u);
  ExpectPoint(back[0], 12, 30, 4);
  ExpectPoint(back[1], 12.5, -23, 4);
  ExpectPoint(back[2], 12.5, -12, 4);
  ExpectPoint(back[3], 17.5, -12, 4);
  ExpectPoint(back[4], 12.5, 12, 4);
  ExpectPoint(back[5], 12.5, -3, 4);
  ExpectPoint(back[6], 12, 30, 4);  // where the sequence began, outside the workpiece
  Run("MOVE(100,30,,1,0)");
  EXPECT_TRUE(reverse.sequence[4].empty());
  EXPECT_EQ(reverse.Reversal().size(), 2u);
}

}  // namespace
}  // namespace vmt::control::measure
