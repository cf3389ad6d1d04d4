#include "control/measure/measuring_cycle.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cstdlib>
#include <limits>

namespace vmt::control::measure {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using Kind = MeasuringStep::Kind;
using Point = std::array<double, 3>;

constexpr double kTol = 1e-9;

// A call as the program writes it: "PROBE(1,1,64,35,,X,-2,100,1,3,0)". An empty place is an
// omitted argument, a letter a name, anything else a number.
InstructionCall Call(const std::string& text) {
  InstructionCall call;
  const size_t open = text.find('(');
  call.name = text.substr(0, open);
  const std::string inside = text.substr(open + 1, text.rfind(')') - open - 1);
  if (inside.empty()) return call;
  size_t from = 0;
  while (true) {
    const size_t comma = inside.find(',', from);
    const std::string word = inside.substr(from, comma == std::string::npos ? comma : comma - from);
    InstructionArg arg;
    if (word.empty()) {
      arg.kind = InstructionArg::Kind::kOmitted;
    } else if (std::isalpha(static_cast<unsigned char>(word[0]))) {
      arg.kind = InstructionArg::Kind::kName;
      arg.name = word;
    } else {
      arg.kind = InstructionArg::Kind::kValue;
      arg.value = std::strtod(word.c_str(), nullptr);
    }
    call.args.push_back(arg);
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  return call;
}

void ExpectPoint(const Point& p, double x, double z) {
  EXPECT_NEAR(p[0], x, kTol);
  EXPECT_NEAR(p[1], z, kTol);
  EXPECT_NEAR(p[2], 0, kTol);
}

void ExpectPoint(const ReversePoint& p, double x, double z, int sphere) {
  ExpectPoint(p.centre, x, z);
  EXPECT_EQ(p.sphere, sphere);
}

void ExpectEvent(const MeasuringStep& s, int event, bool value) {
  EXPECT_EQ(s.kind, Kind::kEvent);
  EXPECT_EQ(s.event, event);
  EXPECT_EQ(s.value, value);
}

void ExpectWaitE29Reset(const MeasuringStep& s) {
  EXPECT_EQ(s.kind, Kind::kWaitEvent);
  EXPECT_EQ(s.event, 29);
  EXPECT_FALSE(s.value);
}

void ExpectRapid(const MeasuringStep& s, uint8_t axes, double x, double z, int sphere = 1) {
  EXPECT_EQ(s.kind, Kind::kRapid);
  EXPECT_EQ(s.axes, axes);
  EXPECT_EQ(s.sphere, sphere);
  for (int n = 0; n < 3; ++n)
    if (axes & (1u << n)) {
      EXPECT_NEAR(s.target[n], n == 0 ? x : z, kTol) << "axis " << n;
    }
}

void ExpectMeasure(const MeasuringStep& s, uint8_t axis, double x, double z, double feed,
                   int sphere = 1) {
  EXPECT_EQ(s.kind, Kind::kMeasure);
  EXPECT_EQ(s.axes, axis);
  EXPECT_EQ(s.sphere, sphere);
  EXPECT_NEAR(s.feed, feed, kTol);
  EXPECT_NEAR(s.target[0], x, kTol);
  EXPECT_NEAR(s.target[1], z, kTol);
}

constexpr uint8_t kX = 1, kZ = 2, kXZ = 3;

// A lathe with axes X and Z. The stylus of the manual's programs has T number 25 (they write
// SETTING(...,25)); its spheres 1, 2, 4 have radii 2.5, 3 and 1.5 mm. The channel is simulated:
// rapids move the sphere centre, the measuring move stops at `contact` if one is given.
class Lathe : public ::testing::Test {
 protected:
  void SetUp() override {
    TastwerkzeugPage& t = pages.stylus[0];
    t.tool_number = 25;
    t.sphere_radius = {2.5, 3, 0, 1.5, 0};
    t.pin5 = true;
    t.normally_closed = true;
    context.position = {60, 100, 0};  // X diameter 120, Z 100
  }

  MeasuringPlan Plan(const std::string& text) {
    MeasuringPlan plan = PlanInstruction(Call(text), context, pages, reverse);
    if (plan.setting) context.setting = plan.setting;
    return plan;
  }

  // Plans and runs a MOVE / PROBE; a PROBE's measuring move stops at `contact`.
  MeasuringPlan Run(const std::string& text, std::optional<double> contact = std::nullopt,
                    const MeasuringMessage** message = nullptr) {
    MeasuringPlan plan = Plan(text);
    EXPECT_EQ(plan.error, "") << text;
    for (const MeasuringStep& s : plan.steps) {
      if (s.kind == Kind::kRapid) {
        for (int n = 0; n < 3; ++n)
          if (s.axes & (1u << n)) context.position[n] = s.target[n];
      } else if (s.kind == Kind::kMeasure) {
        const int a = plan.measuring_axis;
        context.position[a] = contact ? *contact : s.target[a];
      }
    }
    if (plan.measuring_axis >= 0) {
      const MeasuringMessage* m = FinishProbe(Call(text), plan, context, pages, contact);
      if (message) *message = m;
    }
    return plan;
  }

  void Setting() { ASSERT_EQ(Plan("SETTING(X,Z,,18,48,16,25)").error, ""); }

  MeasuringPages pages;
  MeasuringContext context;
  ReverseVectors reverse;
};

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
  EXPECT_EQ(plan.setting->plane, 18);
  EXPECT_EQ(plan.setting->tool_length, 48);
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
      "SETTING(X,Z,,18,48,16,25)", "SAVE(1,1,1)", "MOVE(50,20,,1,0)",
      "PROBE(1,1,64,35,,X,-2,100,1,3,0)", "COMPARE(1,0,1,)",
      "CORRECTION(1,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005,0.002)"};
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
          EXPECT_THAT(plan.error, StartsWith(call.name + "(")) << text << " arg " << i;
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
  for (const char* text : {"SAVE(1,1,1)", "MOVE(50,20,,1,0)", "PROBE(1,1,64,35,,X,-2,100,1,3,0)",
                           "COMPARE(1,0,3,)", "RESTORE()",
                           "CORRECTION(1,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005,0.002)"}) {
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
  context.compensation = 41;
  EXPECT_THAT(Plan("MOVE(50,20,,1,0)").error, HasSubstr("G41 is active; program G40"));
  context.compensation = 42;
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
  ExpectRapid(g16.steps[1], kXZ, 18.5, 55);   // 15 + 1 + 2.5
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
  Run("PROBE(2,1,80,-35,,X,-2,100,2,4,0)", 40);     // 52
  Run("PROBE(3,1,95,-23,,X,-2,100,2,4,0)", 47.5);   // 53
  Run("MOVE(100,30,,1,0)");                         // 54
  Run("MOVE(24,30,,4,0)");                          // 55
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
  Run("MOVE(,12,,4,5)");                            // 57
  Run("PROBE(5,1,40,-12,,X,2,100,4,3,5)", 18.5);    // 58: setup X 17.5 at Z-12
  Run("PROBE(6,1,30,-23,,X,2,100,4,4,5)", 13.5);    // 59: X to 12.5, then Z to -23
  Run("MOVE(24,30,,4,5)");                          // 60
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
  const MeasuringPlan c2 =
      Plan("CORRECTION(2,0.02,-0.02,0.35,0.28,0.001,0,1.8,0.01,0.007)");
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
  EXPECT_THAT(Plan("COMPARE(1,1,1,2)").error,
              HasSubstr("COMPARE(1,1,1,2): test points of different measuring axes (Z, X) (2.1 COMPARE)"));
  EXPECT_THAT(Plan("COMPARE(30,0,1,)").error, HasSubstr("compare number 30 outside"));
  EXPECT_THAT(Plan("CORRECTION(1,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005)").error,
              HasSubstr("J (lower limit) is missing (2.1 CORRECTION)"));
  EXPECT_THAT(Plan("CORRECTION(9,0.01,-0.01,0.12,0.1,0.001,0,1.1,0.005,0.002)").error,
              HasSubstr("compare 9 has not been run"));
}

}  // namespace
}  // namespace vmt::control::measure
