// The fast measurement on its own, handed a narrow fake of the channel: the block in work from
// an interpreter, axes that arrive where they are commanded at once, the PLC's measuring block
// as the events' sink, and PathGuard and the errors recorded. It runs SETTING and PROBE's steps,
// stops the measuring path at the drive's latch, checks the measuring path only up to the
// nominal surface, reports its errors as values, watches the probe for collisions and simulates
// an instruction for block search.

#include "control/channel/fast_measurement.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "control/channel/block_motion.hpp"
#include "control/channel/channel_messages.hpp"
#include "control/nc/parser.hpp"

namespace vmt::control::channel {
namespace {

constexpr double kSphereRadius = 3;

ChannelConfig LatheConfig() {
  ChannelConfig c;
  axes::AxisParameters x;
  x.name = "X";
  x.drive = 0;
  x.rapid_per_s = 200;
  x.acceleration = 2000;
  x.travel_min = -10;
  x.travel_max = 300;
  axes::AxisParameters z = x;
  z.name = "Z";
  z.drive = 1;
  z.travel_max = 500;
  c.axes = {x, z};
  c.tools.edges = {{3, 1, {0, 0}, kSphereRadius, 0}};
  c.aux_handshake = true;
  return c;
}

/// The channel as the fast measurement sees it, X at 50 and Z at 5 with no offsets.
struct Rig {
  explicit Rig(const std::string& text, bool with_pages = true)
      : parsed(nc::ParseProgram(text, "p.mtc", nc::Dialect::kMtc200)) {
    pages.stylus[0].tool_number = 3;
    pages.stylus[0].sphere_radius[0] = kSphereRadius;
    if (with_pages) measuring.SetPages(&pages);
    nc::InterpreterConfig ic;
    ic.axes = {"X", "Z"};
    work.interpreter.emplace(std::vector<const nc::Program*>{&parsed.program}, ic);
    work.interpreter->SetPosition(commanded);
    // The PLC's measuring block: event 30 is acknowledged by resetting event 29 (6.2).
    events.sink = [this](int n, bool set) {
      if (n == 30 && set) events.own[29] = false;
    };
    at.feedback.resize(2);
  }

  MeasuringLink Link() {
    return {work,
            commanded,
            translation,
            state,
            events,
            aux,
            [this](uint32_t) -> const nc::Program& { return parsed.program; },
            [](const nc::ModalState&) { return std::vector<double>(2, 0.0); },
            [](const nc::ModalState&, uint32_t, int32_t) { return true; },
            [this] {
              if (const auto error = PlanBlockMotion(work.block, commanded, translation,
                                                     config.axes, 0, work.motion, 0)) {
                errors.push_back({error->text, error->number, 0, work.block.block, false});
                return false;
              }
              return true;
            },
            [this](const std::string& move, const std::vector<double>* end, bool measuring_path) {
              guarded.push_back(move);
              guard_ends.push_back(end ? *end : work.motion.end);
              EXPECT_EQ(measuring_path, move == "measuring path");
              return !guard_stops;
            },
            [this](const MeasuringError& e) {
              errors.push_back(e);
              state = e.hold ? ChannelState::kHold : ChannelState::kError;
              work.active = false;
            }};
  }

  /// The interpreter's next block into the block in work.
  void NextBlock() { ASSERT_TRUE(work.interpreter->Next(work.block)); }

  /// Runs the instruction in work to its end: the PLC acknowledges each Q function, the axes
  /// arrive at once, and on the measuring path the X drive latches `contact` (sphere centre)
  /// if given, and the PLC reports it with event 7.
  bool RunInstruction(std::optional<double> contact) {
    bool done = false;
    for (int i = 0; i < 100 && measuring.in_work() && state == ChannelState::kRunning; ++i) {
      for (const nc::AuxFunction& f : aux.functions) q_functions.push_back(f.value);
      aux.functions.clear();
      if (work.active) {
        if (events.own[30] && contact) {
          commanded[0] = *contact;
          at.feedback[0].probe.probe1.positive = {true, *contact, *contact};
          measuring.WatchMove(Link(), at);
          EXPECT_FALSE(work.active) << "the latch ends the measuring path";
          at.feedback[0].probe = {};
          events.own[7] = true;
        } else {
          commanded = work.motion.end;
          work.active = false;
        }
      }
      done = measuring.Cycle(Link());
    }
    return done;
  }

  nc::ParseResult parsed;
  ChannelConfig config = LatheConfig();
  measure::MeasuringPages pages;
  FastMeasurement measuring{config};
  ProgramInWork work;
  std::vector<double> commanded{50, 5};
  std::vector<double> translation{0, 0};
  ChannelState state = ChannelState::kRunning;
  ProgramEvents events;
  AuxOutput aux;
  AmplifierTelegram at;
  std::vector<MeasuringError> errors;
  std::vector<std::string> guarded;
  std::vector<std::vector<double>> guard_ends;
  bool guard_stops = false;
  std::vector<double> q_functions;
};

constexpr const char* kProbe =
    "N1 SETTING(X,Z,,18,48,15,1)\n"
    "N2 PROBE(1,1,30,5,,X,-2,100,1,1,0)\n";

TEST(FastMeasurementTest, ProbeMeasuresAtTheLatchAndEscapesToTheStart) {
  Rig r(kProbe);
  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  EXPECT_TRUE(r.RunInstruction(std::nullopt));
  ASSERT_TRUE(r.measuring.setting());
  EXPECT_EQ(r.measuring.setting()->axis[0], 'X');
  ASSERT_EQ(r.q_functions, std::vector<double>{9992});  // SETTING's Q function (6.1)

  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  // The sphere (r 3) meets the surface X30 with its centre at X33.
  EXPECT_TRUE(r.RunInstruction(30 + kSphereRadius));
  EXPECT_TRUE(r.errors.empty()) << r.errors.front().text;
  EXPECT_FALSE(r.measuring.in_work());
  const measure::PointPage* p = r.pages.Point(0, 1);
  ASSERT_NE(p, nullptr);
  EXPECT_NEAR(p->value.actual, 30, 1e-9);
  EXPECT_NEAR(p->value.deviation, 0, 1e-9);
  // Escape (variant 1): back where it started; the interpreter goes on from there.
  EXPECT_NEAR(r.commanded[0], 50, 1e-9);
  EXPECT_NEAR(r.commanded[1], 5, 1e-9);
  EXPECT_EQ(r.work.block.block, 1);  // the instruction's block is back in work
  EXPECT_FALSE(r.events.own[30]);
}

TEST(FastMeasurementTest, TheMeasuringPathIsCheckedUpToTheNominalSurface) {
  Rig r(kProbe);
  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  r.RunInstruction(std::nullopt);
  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  r.RunInstruction(30 + kSphereRadius);
  ASSERT_GE(r.guarded.size(), 2u);
  EXPECT_EQ(r.guarded[0], "probe approach");
  EXPECT_EQ(r.guarded[1], "measuring path");
  // The doubled path goes 2 mm beyond the surface; PathGuard is asked only up to the touch.
  EXPECT_NEAR(r.guard_ends[1][0], 30 + kSphereRadius, 1e-9);
}

TEST(FastMeasurementTest, PathGuardStoppingTheApproachStopsTheInstruction) {
  Rig r(kProbe);
  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  r.RunInstruction(std::nullopt);
  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  r.guard_stops = true;
  EXPECT_FALSE(r.measuring.Cycle(r.Link()));
  EXPECT_FALSE(r.work.active);
  EXPECT_EQ(r.guarded, std::vector<std::string>{"probe approach"});
}

TEST(FastMeasurementTest, NoContactIsTestPointNotFoundAsAValueWithQ9999) {
  Rig r(kProbe);
  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  r.RunInstruction(std::nullopt);
  r.q_functions.clear();
  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  EXPECT_FALSE(r.RunInstruction(std::nullopt));
  ASSERT_EQ(r.errors.size(), 1u);
  const MeasuringError& e = r.errors[0];
  EXPECT_NE(e.text.find("TEST POINT NOT FOUND"), std::string::npos) << e.text;
  EXPECT_EQ(e.number, kMsgMeasuringReverseOnly);
  EXPECT_EQ(e.block, 1);
  EXPECT_FALSE(e.hold);
  ASSERT_EQ(r.aux.functions.size(), 1u);  // waits for the reverse program's acknowledgement
  EXPECT_EQ(r.aux.functions[0].value, 9999);
}

TEST(FastMeasurementTest, AnInstructionWithOtherSyntaxIsRefusedAtItsBlock) {
  Rig r("N1 SETTING(X,Z,,18,48,15,1) X10\n");
  r.NextBlock();
  EXPECT_FALSE(r.measuring.Start(r.Link()));
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_NE(r.errors[0].text.find("no other NC syntax (4.1)"), std::string::npos);
  EXPECT_EQ(r.errors[0].number, kMsgMeasuringInstruction);
  EXPECT_EQ(r.errors[0].block, 0);
  EXPECT_FALSE(r.measuring.in_work());
}

TEST(FastMeasurementTest, WithoutPagesAnInstructionIsAnError) {
  Rig r(kProbe, false);
  r.NextBlock();
  EXPECT_FALSE(r.measuring.Start(r.Link()));
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_NE(r.errors[0].text.find("machine data pages (7.1)"), std::string::npos);
}

TEST(FastMeasurementTest, AProbeDisplacedWhileWatchedStopsWithQ9999) {
  Rig r(kProbe);
  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  r.RunInstruction(std::nullopt);
  r.events.own[29] = true;  // collision monitoring, as a MOVE leaves it
  r.work.active = true;
  r.measuring.WatchCollision(r.Link(), r.at, false);  // free: the contact is open
  r.at.feedback[0].probe.probe1.level = true;
  r.measuring.WatchCollision(r.Link(), r.at, true);  // the reverse program is not watched
  EXPECT_TRUE(r.errors.empty());
  r.measuring.WatchCollision(r.Link(), r.at, false);
  EXPECT_TRUE(r.errors.empty()) << "the free level counts only since it was seen again";
  r.at.feedback[0].probe.probe1.level = false;
  r.measuring.WatchCollision(r.Link(), r.at, false);
  r.at.feedback[0].probe.probe1.level = true;
  r.measuring.WatchCollision(r.Link(), r.at, false);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].number, kMsgMeasuringReverseOnly);
  EXPECT_NE(r.errors[0].text.find("probe displaced outside the measuring path"), std::string::npos);
  EXPECT_FALSE(r.work.active);
  ASSERT_EQ(r.aux.functions.size(), 1u);
  EXPECT_EQ(r.aux.functions[0].value, 9999);
}

TEST(FastMeasurementTest, BlockSearchSimulatesTheProbesPathWithAWarning) {
  Rig r(
      "N1 SETTING(X,Z,,18,48,15,1)\n"
      "N2 PROBE(1,1,30,5,,X,-2,100,1,3,0)\n");
  std::vector<double> position = r.commanded;
  std::vector<std::string> warnings;
  nc::PreparedBlock b;
  ASSERT_TRUE(r.work.interpreter->Next(b));
  ASSERT_TRUE(r.measuring.Simulate(r.Link(), b, position, warnings));
  EXPECT_TRUE(r.measuring.setting());  // SETTING runs as in a run, its Q function too
  ASSERT_EQ(r.aux.functions.size(), 1u);
  EXPECT_EQ(r.aux.functions[0].value, 9992);
  EXPECT_TRUE(warnings.empty());
  ASSERT_TRUE(r.work.interpreter->Next(b));
  ASSERT_TRUE(r.measuring.Simulate(r.Link(), b, position, warnings));
  // Without escape (variant 3) the stylus would stay at the setup position, 2 mm off the
  // nominal surface; nothing was measured.
  EXPECT_NEAR(position[0], 30 + 2 + kSphereRadius, 1e-9);
  EXPECT_EQ(r.pages.Point(0, 1)->value.actual, 0);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("p.mtc:2:"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("simulated without measuring"), std::string::npos);
  EXPECT_FALSE(r.measuring.in_work());
}

TEST(FastMeasurementTest, ResetDropsTheSettingAndTheInstruction) {
  Rig r(kProbe);
  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  r.RunInstruction(std::nullopt);
  r.NextBlock();
  ASSERT_TRUE(r.measuring.Start(r.Link()));
  EXPECT_TRUE(r.measuring.in_work());
  r.measuring.Reset();
  EXPECT_FALSE(r.measuring.in_work());
  EXPECT_FALSE(r.measuring.setting());
}

}  // namespace
}  // namespace vmt::control::channel
