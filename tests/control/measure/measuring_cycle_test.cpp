// The measuring instructions one by one (fast-measurement manual 2.1, 4.1, 4.3, 4.4): SETTING,
// SAVE / RESTORE, MOVE, where each may stand, their parameter ranges and the errors of 4.1.

#include "control/measure/measuring_cycle.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "measuring_cycle_support.hpp"

namespace vmt::control::measure {
namespace {

using namespace testing;  // vmt::control::measure::testing
using ::testing::HasSubstr;
using ::testing::StartsWith;

TEST(MeasuringInstruction, TheSevenNames) {
  for (const char* name : {"SETTING", "SAVE", "MOVE", "PROBE", "COMPARE", "CORRECTION", "RESTORE"})
    EXPECT_TRUE(IsMeasuringInstruction(name)) << name;
  EXPECT_FALSE(IsMeasuringInstruction("MTD"));
  EXPECT_FALSE(IsMeasuringInstruction("probe"));
}

// 2.1 SETTING, 3.1 BASISMESSPAGE 6..10, 6.1 Q9992.
TEST_F(Lathe, SettingWritesTheBasePageAndIssuesQ9992) {
  const MeasuringPlan plan = Plan("SETTING(X,Z,,18,48,16,25)");
  ASSERT_EQ(plan.error, "");
  ASSERT_EQ(plan.steps.size(), 1u);
  EXPECT_EQ(plan.steps[0].kind, Kind::kAux);
  EXPECT_EQ(plan.steps[0].q, 9992);
  ASSERT_TRUE(plan.setting);
  EXPECT_EQ(plan.setting->axis[0], 'X');
  EXPECT_EQ(plan.setting->axis[1], 'Z');
  EXPECT_EQ(plan.setting->axis[2], 0);
  EXPECT_EQ(plan.setting->plane, nc::Plane::kZX);
  EXPECT_EQ(plan.setting->tool_length, nc::ToolLength::kAdd);
  EXPECT_TRUE(plan.setting->diameter);
  EXPECT_EQ(plan.setting->stylus, 1);  // T number 25 is stylus 1
  const BasisMessPage& b = pages.basis[0];
  EXPECT_TRUE(b.PIN_DDS);
  EXPECT_TRUE(b.Pushbutton_contact);
  EXPECT_TRUE(b.measuring_axis_1);
  EXPECT_TRUE(b.measuring_axis_2);
  EXPECT_FALSE(b.measuring_axis_3);
}

TEST_F(Lathe, SettingStylusNumberOneToFour) {
  pages.stylus[2].pin5 = false;
  const MeasuringPlan plan = Plan("SETTING(X,Z,,18,48,16,3)");
  ASSERT_EQ(plan.error, "");
  EXPECT_EQ(plan.setting->stylus, 3);
  EXPECT_FALSE(pages.basis[0].PIN_DDS);
  EXPECT_THAT(Plan("SETTING(X,Z,,18,48,16,7)").error,
              HasSubstr("G (stylus number) 7 is neither 1..4 nor the T number"));
}

// 4.1: the errors the manual names, with the call as written and the section.
TEST_F(Lathe, SettingG49IsAnError) {
  const std::string e = Plan("SETTING(X,Z,,18,49,16,25)").error;
  EXPECT_THAT(e, StartsWith("SETTING(X,Z,,18,49,16,25): "));
  EXPECT_THAT(e, HasSubstr("G49"));
  EXPECT_THAT(e, HasSubstr("4.1 Tool Path and Length Correction"));
}

TEST_F(Lathe, SettingFreePlaneIsAnError) {
  EXPECT_THAT(Plan("SETTING(X,Z,,29,48,16,25)").error,
              HasSubstr("free plane selection G20 (G29) cannot be used (4.1 Plane Selection)"));
  EXPECT_THAT(Plan("SETTING(X,Z,,20,48,16,25)").error, HasSubstr("G20 (G20)"));
  EXPECT_THAT(Plan("SETTING(X,Z,,21,48,16,25)").error, HasSubstr("21 is not 17, 18, 19"));
}

TEST_F(Lathe, SettingG16OutsideTurningIsAnError) {
  context.turning = false;
  EXPECT_THAT(Plan("SETTING(X,Y,Z,17,48,16,1)").error,
              HasSubstr("G16 is only possible in turning (4.1 Diameter and Radius Programming)"));
  EXPECT_EQ(Plan("SETTING(X,Y,Z,17,48,15,1)").error, "");
}

TEST_F(Lathe, SettingG48WithoutToolListIsAnError) {
  context.tool_list = false;
  EXPECT_THAT(Plan("SETTING(X,Z,,18,48,16,25)").error, HasSubstr("G48 requires a tools list"));
  EXPECT_EQ(Plan("SETTING(X,Z,,18,47,16,25)").error, "");
}

TEST_F(Lathe, SettingSecondaryAndOtherAxesAreErrors) {
  EXPECT_THAT(Plan("SETTING(U,Z,,18,48,16,25)").error,
              HasSubstr("A (axis 1) U: secondary axes are not permitted"));
  EXPECT_THAT(Plan("SETTING(X,C,,18,48,16,25)").error,
              HasSubstr("B (axis 2) C is not one of the linear main axes X, Y, Z"));
  EXPECT_THAT(Plan("SETTING(X,X,,18,48,16,25)").error, HasSubstr("axis X given twice"));
  EXPECT_THAT(Plan("SETTING(,,,18,48,16,25)").error, HasSubstr("no measuring axis"));
  EXPECT_THAT(Plan("SETTING(X,Z,,18,48,17,25)").error, HasSubstr("17 is not 15, 16"));
}

// Whatever a program writes, planning answers with a plan or an error that quotes the call.
TEST_F(Lathe, OddArgumentsGiveErrorsNotCrashes) {
  Setting();
  const std::vector<InstructionArg> odd = {
      {InstructionArg::Kind::kOmitted, 0, ""},
      {InstructionArg::Kind::kName, 0, "Q"},
      {InstructionArg::Kind::kValue, std::numeric_limits<double>::quiet_NaN(), ""},
      {InstructionArg::Kind::kValue, std::numeric_limits<double>::infinity(), ""},
      {InstructionArg::Kind::kValue, -1e300, ""},
      {InstructionArg::Kind::kValue, 2.5, ""}};
  const std::vector<std::string> good = {
      "SETTING(X,Z,,18,48,16,25)", "SAVE(1,1,1)",
      "MOVE(50,20,,1,0)",          "PROBE(1,1,64,35,,X,-2,100,1,3,0)",
      "COMPARE(1,0,1,)",           "CORRECTION(1,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005,0.002)"};
  int errors = 0;
  for (const std::string& text : good) {
    const InstructionCall base = Call(text);
    for (size_t i = 0; i < base.args.size(); ++i)
      for (const InstructionArg& a : odd) {
        InstructionCall call = base;
        call.args[i] = a;
        MeasuringContext c = context;
        const MeasuringPlan plan = PlanInstruction(call, c, pages, reverse);
        if (!plan.error.empty()) {
          ++errors;
          EXPECT_THAT(plan.error, StartsWith(std::string(nc::InstructionName(call.instruction)) + "(")) << text << " arg " << i;
          EXPECT_TRUE(plan.steps.empty()) << plan.error;
        }
      }
  }
  EXPECT_GT(errors, 150);
}

// A latch value that is not a number is no contact.
TEST_F(Lathe, ContactThatIsNotANumberIsNotFound) {
  Setting();
  const MeasuringPlan plan = Plan("PROBE(,0,30,55,,X,-2,100,1,1,0)");
  EXPECT_EQ(FinishProbe(Call("PROBE(,0,30,55,,X,-2,100,1,1,0)"), plan, context, pages,
                        std::numeric_limits<double>::quiet_NaN()),
            &kTestPointNotFound);
  EXPECT_EQ(pages.calibration[0][0].measuring_direction[1], 0);
}

// 2.1 "Position in the NC program": every instruction after SETTING, RESTORE after SAVE.
TEST_F(Lathe, InstructionsBeforeSettingAreErrors) {
  for (const char* text :
       {"SAVE(1,1,1)", "MOVE(50,20,,1,0)", "PROBE(1,1,64,35,,X,-2,100,1,3,0)", "COMPARE(1,0,3,)",
        "RESTORE()", "CORRECTION(1,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005,0.002)"}) {
    const std::string e = Plan(text).error;
    EXPECT_THAT(e, StartsWith(std::string(text) + ": ")) << text;
    EXPECT_THAT(e, HasSubstr("no SETTING before this instruction (2.1 SETTING)")) << text;
  }
}

TEST_F(Lathe, RestoreBeforeSaveIsAnError) {
  Setting();
  EXPECT_THAT(Plan("RESTORE()").error, HasSubstr("no SAVE before RESTORE (2.1 RESTORE)"));
}

// 4.1: G40 before MOVE and PROBE.
TEST_F(Lathe, CutterCompensationBeforeMoveOrProbeIsAnError) {
  Setting();
  context.compensation = nc::Compensation::kLeft;
  EXPECT_THAT(Plan("MOVE(50,20,,1,0)").error, HasSubstr("G41 is active; program G40"));
  context.compensation = nc::Compensation::kRight;
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,X,-2,100,1,3,0)").error,
              HasSubstr("G42 is active; program G40"));
}

TEST_F(Lathe, MeasuringAxisMustBeXYZOfTheSetting) {
  Setting();
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,Y,-2,100,1,3,0)").error,
              HasSubstr("measuring axis Y is not an axis of the SETTING (4.1"));
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,W,-2,100,1,3,0)").error,
              HasSubstr("F (measuring axis) W: secondary axes are not permitted"));
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,C,-2,100,1,3,0)").error,
              HasSubstr("C is not one of the linear main axes"));
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,5,-2,100,1,3,0)").error,
              HasSubstr("F (measuring axis) 5 is not an axis designation"));
}

TEST_F(Lathe, ParameterRanges) {
  Setting();
  EXPECT_THAT(Plan("PROBE(21,1,64,35,,X,-2,100,1,3,0)").error,
              HasSubstr("A (point number) 21 is not 1..20 (2.1 PROBE)"));
  EXPECT_THAT(Plan("PROBE(,1,64,35,,X,-2,100,1,3,0)").error,
              HasSubstr("A (point number) is missing (2.1 PROBE)"));
  EXPECT_THAT(Plan("PROBE(1.5,1,64,35,,X,-2,100,1,3,0)").error,
              HasSubstr("A (point number) 1.5 is not 1..20"));
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,X,-2,F,1,3,0)").error,
              HasSubstr("H (measuring feed) F is not a number"));
  EXPECT_THAT(Plan("PROBE(1,2,64,35,,X,-2,100,1,3,0)").error,
              HasSubstr("B (calibration/measurement) 2 is not 0..1"));
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,X,0,100,1,3,0)").error, HasSubstr("G (measuring path) 0"));
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,X,-2,0,1,3,0)").error, HasSubstr("H (measuring feed)"));
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,X,-2,100,6,3,0)").error,
              HasSubstr("I (measuring sphere number) 6 is not 1..5"));
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,X,-2,100,1,5,0)").error,
              HasSubstr("J (approach variant) 5 is not 1..4"));
  EXPECT_THAT(Plan("PROBE(1,1,64,35,,X,-2,100,1,3,11)").error,
              HasSubstr("K (reverse variant) 11 is not 0..10"));
  EXPECT_THAT(Plan("PROBE(1,1,64,35,7,X,-2,100,1,3,0)").error,
              HasSubstr("measuring position of axis 3 given, but SETTING has no axis 3"));
  EXPECT_THAT(Plan("PROBE(1,1,64,,,X,-2,100,1,3,0)").error,
              HasSubstr("measuring position of axis 2 (Z) is missing"));
  EXPECT_THAT(Plan("PROBE(1,1,200000,35,,X,-2,100,1,3,0)").error,
              HasSubstr("C (measuring position of axis 1) 200000 is not -100000..100000"));
  EXPECT_THAT(Plan("MOVE(50,20,,0,0)").error, HasSubstr("D (measuring sphere number) 0"));
  EXPECT_THAT(Plan("MOVE(50,20,3,1,0)").error, HasSubstr("SETTING has no axis 3"));
  EXPECT_THAT(Plan("MOVE(50,20,,1,0,1)").error, HasSubstr("more than 5 arguments"));
  EXPECT_THAT(Plan("SAVE(2,0,0)").error, HasSubstr("A (variables 100 - 112) 2 is not 0..1"));
  EXPECT_THAT(Plan("RESTORE(1)").error, HasSubstr("more than 0 arguments"));
}

// 4.4: a calibration PROBE not in a linear path sequence; a MOVE that opens one gives all axes.
TEST_F(Lathe, PlacementInLinearPathSequences) {
  Setting();
  EXPECT_THAT(Plan("PROBE(,0,30,55,,X,-2,100,1,1,3)").error,
              HasSubstr("a calibration PROBE may not be in a linear path sequence (K 3) (4.4)"));
  EXPECT_THAT(Plan("MOVE(,12,,4,6)").error,
              HasSubstr("first MOVE of linear path sequence 6 must give the position of every "
                        "SETTING axis; X is missing (4.4)"));
  Run("MOVE(24,30,,4,6)");
  EXPECT_EQ(Plan("MOVE(,12,,4,6)").error, "");  // not the first any more
}

// 2.1 SAVE / RESTORE: only what SAVE selected comes back; the axes do not move.
TEST_F(Lathe, SaveAndRestore) {
  Setting();
  for (int k = 0; k < 13; ++k) context.variables[k] = 100 + k;
  context.feed = 2000;
  context.position = {50, 80, 0};
  MeasuringPlan save = Plan("SAVE(1,1,1)");
  ASSERT_EQ(save.error, "");
  EXPECT_TRUE(save.steps.empty());
  const ZwischenspeicherPage& b = pages.buffer[0];
  EXPECT_EQ(b.variable[12], 112);
  EXPECT_EQ(b.axis_position[0], 100);  // as the program writes X under G16: a diameter
  EXPECT_EQ(b.axis_position[1], 80);
  EXPECT_EQ(b.F_value, 2000);
  context.variables.fill(0);
  context.feed = 1;
  InstructionCall one_omitted = Call("RESTORE()");
  one_omitted.args.resize(1);  // however the parser hands over the empty parentheses
  EXPECT_EQ(PlanInstruction(one_omitted, context, pages, reverse).error, "");
  const MeasuringPlan restore = Plan("RESTORE()");
  ASSERT_EQ(restore.error, "");
  EXPECT_TRUE(restore.steps.empty());
  ASSERT_TRUE(restore.restore_variables);
  EXPECT_EQ((*restore.restore_variables)[0], 100);
  EXPECT_EQ((*restore.restore_variables)[12], 112);
  ASSERT_TRUE(restore.restore_feed);
  EXPECT_EQ(*restore.restore_feed, 2000);

  ASSERT_EQ(Plan("SAVE(1,0,0)").error, "");
  const MeasuringPlan only_variables = Plan("RESTORE()");
  EXPECT_TRUE(only_variables.restore_variables);
  EXPECT_FALSE(only_variables.restore_feed);
}

// 2.1 MOVE, 4.3: G00 of the given axes to the sphere centre, no sphere radius; SE 29 first.
TEST_F(Lathe, MoveOfTheManual) {
  Setting();
  context.g_groups = {0, 18, 90, 94, 40, 48, 16};
  const MeasuringPlan plan = Run("MOVE(50,20,,1,0)");
  ASSERT_EQ(plan.steps.size(), 2u);
  ExpectEvent(plan.steps[0], 29, true);
  ExpectRapid(plan.steps[1], kXZ, 25, 20);  // X50 is a diameter: the centre at radius 25
  EXPECT_EQ(pages.buffer[0].g_group, context.g_groups);  // 2.1: saved at the beginning
  EXPECT_EQ(plan.reverse_variant, 0);
  const MeasuringPlan z_only = Run("MOVE(,44,,2,0)");
  ExpectRapid(z_only.steps[1], kZ, 0, 44, 2);
}

}  // namespace
}  // namespace vmt::control::measure
