#pragma once
// The fast-measurement instruction tests' rig: calls written as the program writes them, the
// step checks, and a lathe (X, Z) whose channel the tests simulate.

#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

#include "control/measure/measuring_cycle.hpp"

namespace vmt::control::measure::testing {

using Kind = MeasuringStep::Kind;
using Point = std::array<double, 3>;

constexpr double kTol = 1e-9;

// A call as the program writes it: "PROBE(1,1,64,35,,X,-2,100,1,3,0)". An empty place is an
// omitted argument, a letter a name, anything else a number.
inline InstructionCall Call(const std::string& text) {
  InstructionCall call;
  const size_t open = text.find('(');
  call.instruction = nc::InstructionOf(text.substr(0, open));
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

inline void ExpectPoint(const Point& p, double x, double z) {
  EXPECT_NEAR(p[0], x, kTol);
  EXPECT_NEAR(p[1], z, kTol);
  EXPECT_NEAR(p[2], 0, kTol);
}

inline void ExpectPoint(const ReversePoint& p, double x, double z, int sphere) {
  ExpectPoint(p.centre, x, z);
  EXPECT_EQ(p.sphere, sphere);
}

inline void ExpectEvent(const MeasuringStep& s, int event, bool value) {
  EXPECT_EQ(s.kind, Kind::kEvent);
  EXPECT_EQ(s.event, event);
  EXPECT_EQ(s.value, value);
}

inline void ExpectWaitE29Reset(const MeasuringStep& s) {
  EXPECT_EQ(s.kind, Kind::kWaitEvent);
  EXPECT_EQ(s.event, 29);
  EXPECT_FALSE(s.value);
}

inline void ExpectRapid(const MeasuringStep& s, uint8_t axes, double x, double z, int sphere = 1) {
  EXPECT_EQ(s.kind, Kind::kRapid);
  EXPECT_EQ(s.axes, axes);
  EXPECT_EQ(s.sphere, sphere);
  for (int n = 0; n < 3; ++n)
    if (axes & (1u << n)) {
      EXPECT_NEAR(s.target[n], n == 0 ? x : z, kTol) << "axis " << n;
    }
}

inline void ExpectMeasure(const MeasuringStep& s, uint8_t axis, double x, double z, double feed,
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

}  // namespace vmt::control::measure::testing
