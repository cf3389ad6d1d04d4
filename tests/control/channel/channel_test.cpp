// The channel on an ideal machine (actual = setpoint): block timing, G00 synchronisation, arcs,
// feed override and feed hold on the path.

#include "control/channel/channel.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "control/nc/parser.hpp"

namespace vmt::control::channel {
namespace {

ChannelAxis Axis(const std::string& name, int drive, double rapid_per_s) {
  ChannelAxis a;
  a.name = name;
  a.number = drive + 1;
  a.drive = drive;
  a.rapid_per_s = rapid_per_s;
  a.acceleration = 4000;
  return a;
}

struct Machine {
  explicit Machine(const std::string& program, double x = 0, double z = 0,
                   const std::function<void(ChannelConfig&)>& configure = {},
                   nc::Dialect dialect = nc::Dialect::kMtc200) {
    parsed = nc::ParseProgram(program, dialect == nc::Dialect::kIsg ? "p.isg" : "p.mtc", dialect);
    EXPECT_TRUE(parsed.ok()) << nc::Format(parsed.errors[0], parsed.program.files);
    ChannelConfig config;
    config.axes = {Axis("X", 0, 400), Axis("Z", 1, 500)};
    config.spindle_drive = 2;
    if (configure) configure(config);
    channel = std::make_unique<Channel>(config, std::vector<const nc::Program*>{&parsed.program});
    at.feedback.resize(3);
    for (DriveFeedback& f : at.feedback) f.status = drive_status::kReady;  // drives ready
    at.feedback[0].position = x;
    at.feedback[1].position = z;
    mdt.setpoints.resize(3);
  }
  // One drive tick of an ideal machine: the actual position is the setpoint.
  void Tick() {
    channel->Tick(at, mdt);
    for (int d = 0; d < 2; ++d)
      if (mdt.setpoints[d].mode == DriveMode::kPosition)
        at.feedback[d].position = mdt.setpoints[d].value;
    t += 250e-6;
  }
  double RunUntilEnd(double limit = 60) {
    while (channel->state() != ChannelState::kEnded && channel->state() != ChannelState::kError &&
           t < limit)
      Tick();
    return t;
  }
  double X() const { return at.feedback[0].position; }
  double Z() const { return at.feedback[1].position; }

  nc::ParseResult parsed;
  std::unique_ptr<Channel> channel;
  AmplifierTelegram at;
  MasterTelegram mdt;
  double t = 0;
};

TEST(ChannelTest, LinearMoveTakesFeedAndAccelerationTime) {
  Machine m("N1 G01 X100 F6000\nN2 RET\n");  // 100 mm at 100 mm/s, accel 4000 mm/s^2
  m.channel->Start();
  const double t = m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.X(), 100);
  // Trapezoid: 100/100 + 100/4000 = 1.025 s, plus a few NC cycles of block change.
  EXPECT_NEAR(t, 1.025, 0.01);
}

TEST(ChannelTest, RapidMovesEveryAxisAtItsLimitAndEndsThemTogether) {
  Machine m("N1 G00 X200 Z100\nN2 RET\n");
  m.channel->Start();
  double x_done = -1, z_done = -1;
  double max_ratio_error = 0;
  while (m.channel->state() == ChannelState::kRunning && m.t < 5) {
    m.Tick();
    if (x_done < 0 && m.X() == 200) x_done = m.t;
    if (z_done < 0 && m.Z() == 100) z_done = m.t;
    // Straight in axis space: Z/X stays 1/2.
    if (m.X() > 1) max_ratio_error = std::max(max_ratio_error, std::abs(m.Z() / m.X() - 0.5));
  }
  EXPECT_NEAR(x_done, z_done, 1e-9);
  EXPECT_LT(max_ratio_error, 1e-9);
  // X limits (200 mm at 400 mm/s, 4000 mm/s^2): 0.5 + 0.1 s.
  EXPECT_NEAR(x_done, 0.6, 0.01);
}

TEST(ChannelTest, ArcStaysOnItsCircle) {
  Machine m("N1 G18 G02 X23 Z134 I4 K0 F600\nN2 RET\n", 19, 138);
  m.channel->Start();
  double worst = 0;
  while (m.channel->state() == ChannelState::kRunning && m.t < 5) {
    m.Tick();
    worst = std::max(worst, std::abs(std::hypot(m.Z() - 138, m.X() - 23) - 4));
  }
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_LT(worst, 1e-4);
  EXPECT_DOUBLE_EQ(m.X(), 23);
  EXPECT_DOUBLE_EQ(m.Z(), 134);
}

TEST(ChannelTest, FeedHoldStopsOnThePathAndResumes) {
  Machine m("N1 G01 X100 Z50 F6000\nN2 RET\n");
  m.channel->Start();
  while (m.t < 0.3) m.Tick();
  m.channel->Stop();
  for (int i = 0; i < 1000; ++i) m.Tick();
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  const double x = m.X(), z = m.Z();
  EXPECT_GT(x, 10);
  EXPECT_LT(x, 100);
  EXPECT_NEAR(z, x / 2, 1e-9);  // the stop point lies on the programmed line
  for (int i = 0; i < 100; ++i) m.Tick();
  EXPECT_EQ(m.X(), x);  // standing
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(m.X(), 100);
}

TEST(ChannelTest, SingleBlockHoldsAfterEachBlock) {
  Machine m("N1 G01 X10 F6000\nN2 X20\nN3 X30\nN4 RET\n");
  m.channel->SetSingleBlock(true);
  std::vector<double> stops;
  for (int start = 0; start < 10 && m.channel->state() != ChannelState::kEnded; ++start) {
    m.channel->Start();
    for (int i = 0; i < 4000 && m.channel->state() == ChannelState::kRunning; ++i) m.Tick();
    for (int i = 0; i < 8; ++i) m.Tick();  // fine interpolation trails the NC cycle by one cycle
    stops.push_back(m.X());
  }
  EXPECT_EQ(stops, (std::vector<double>{10, 20, 30, 30}));
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
}

TEST(ChannelTest, ContinuousJogWhileTheKeyIsHeld) {
  Machine m("N1 RET\n", 50, 0);
  m.channel->Jog(0, +1);  // automatic mode: ignored
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.X(), 50);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Jog(0, +1);
  for (int i = 0; i < 4000; ++i) m.Tick();  // 1 s at 40 mm/s (a tenth of the rapid)
  EXPECT_EQ(m.channel->AxisMotion(0), 1);
  EXPECT_NEAR(m.X(), 50 + 40 - 40 * 40 / (2 * 4000.0), 0.05);
  m.channel->Jog(0, 0);
  for (int i = 0; i < 400; ++i) m.Tick();
  const double stopped = m.X();
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.X(), stopped);
  EXPECT_EQ(m.channel->AxisMotion(0), 0);
  EXPECT_EQ(m.Z(), 0);
}

TEST(ChannelTest, IncrementalJogMovesExactlyOneIncrementPerPress) {
  Machine m("N1 RET\n", 50, 20);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogIncrement(0.1);
  for (int press = 0; press < 3; ++press) {
    m.channel->Jog(1, -1);
    for (int i = 0; i < 800; ++i) m.Tick();
    m.channel->Jog(1, 0);
    for (int i = 0; i < 40; ++i) m.Tick();
  }
  EXPECT_NEAR(m.Z(), 19.7, 1e-9);
  EXPECT_EQ(m.X(), 50);
}

TEST(ChannelTest, ModeChangeWaitsForTheProgramToStop) {
  Machine m("N1 G01 X100 F600\nN2 RET\n");
  m.channel->Start();
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_FALSE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Stop();
  for (int i = 0; i < 400; ++i) m.Tick();
  // Interrupted: jog away in manual, come back, continue the program.
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(m.X(), 100);
}

TEST(ChannelTest, JoggedAwayProgramDoesNotJumpBackToThePath) {
  Machine m("N1 G01 X100 F600\nN2 RET\n");
  m.channel->Start();
  for (int i = 0; i < 2000; ++i) m.Tick();
  m.channel->Stop();
  for (int i = 0; i < 400; ++i) m.Tick();
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->Jog(1, +1);  // Z away from the contour
  for (int i = 0; i < 400; ++i) m.Tick();
  m.channel->Jog(1, 0);
  for (int i = 0; i < 400; ++i) m.Tick();
  const double z = m.Z();
  ASSERT_GT(z, 1);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("axis Z has left the contour"));
  EXPECT_EQ(m.Z(), z);  // nothing jumped
}

TEST(ChannelTest, OverrideScalesTheFeed) {
  Machine full("N1 G01 X100 F3000\nN2 RET\n"), half("N1 G01 X100 F3000\nN2 RET\n");
  half.channel->SetFeedOverride(0.5);
  full.channel->Start();
  half.channel->Start();
  EXPECT_NEAR(half.RunUntilEnd() / full.RunUntilEnd(), 2, 0.02);
}

TEST(ChannelTest, SpindleAndErrors) {
  Machine m("N1 M03 S1200\nN2 G01 X10\nN3 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.mdt.setpoints[2].mode, DriveMode::kVelocity);
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[2].value, 7200);
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("p.mtc:2:1: error: no feed programmed"));

  Machine arc("N1 G02 X10 Z0 I3 K0 F100\nN2 RET\n");
  arc.channel->Start();
  arc.RunUntilEnd();
  EXPECT_THAT(arc.channel->error(), ::testing::HasSubstr("end point not on the arc"));
  arc.channel->Reset();
  EXPECT_EQ(arc.channel->state(), ChannelState::kIdle);
  EXPECT_EQ(arc.channel->error(), "");
}

void WithOffsetsAndTools(ChannelConfig& c) {
  c.zero_offsets.g54_to_g59[0] = {5, 100};   // G54: X+5, Z+100
  c.zero_offsets.g54_to_g59[1] = {-2, 200};  // G55
  c.tools.edges = {{1, 1, {0, 0}, 0.8, 3}, {2, 1, {1.5, -4}, 0.4, 3}};
}

TEST(ChannelTest, ZeroOffsetsShiftTheProgram) {
  Machine m("N1 G54 G00 X10 Z0\nN2 G55 X10 Z0\nN3 G53 X10 Z0\nN4 RET\n", 0, 0, WithOffsetsAndTools);
  m.channel->Start();
  std::vector<std::pair<double, double>> stops;
  for (uint32_t line = 0; m.channel->state() == ChannelState::kRunning && m.t < 10;) {
    m.Tick();
    if (m.channel->line() != line) {
      if (line != 0) stops.emplace_back(m.channel->position(0), m.channel->position(1));
      line = m.channel->line();
    }
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.X(), 10);
  EXPECT_DOUBLE_EQ(m.Z(), 0);
  ASSERT_GE(stops.size(), 2u);
  EXPECT_NEAR(stops[0].first, 15, 1e-9);  // G54 reached before N2 begins
  EXPECT_NEAR(stops[0].second, 100, 1e-9);
  EXPECT_NEAR(stops[1].first, 8, 1e-9);
  EXPECT_NEAR(stops[1].second, 200, 1e-9);
}

TEST(ChannelTest, IncrementalMoveAfterAnOffsetChangeIsInProgramCoordinates) {
  // G91 X1 after G55: one mm in the G55 frame, from where the axes stand in it.
  Machine m("N1 G54 G00 X10 Z0\nN2 G55 G91 X1\nN3 RET\n", 0, 0, WithOffsetsAndTools);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 10 + 1 - 2, 1e-9);  // program X was 10, is 11, under G55's -2
}

TEST(ChannelTest, ToolLengthG48AddsAndG49SubtractsTheEdge) {
  Machine plus("N1 G48 T2 D1 G00 X10 Z0\nN2 RET\n", 0, 0, WithOffsetsAndTools);
  plus.channel->Start();
  plus.RunUntilEnd();
  ASSERT_EQ(plus.channel->state(), ChannelState::kEnded) << plus.channel->error();
  EXPECT_NEAR(plus.X(), 10 - 1.5, 1e-9);  // the tip is 1.5 mm further out than the reference
  EXPECT_NEAR(plus.Z(), 0 + 4, 1e-9);
  Machine minus("N1 G49 T2 D1 G00 X10 Z0\nN2 RET\n", 0, 0, WithOffsetsAndTools);
  minus.channel->Start();
  minus.RunUntilEnd();
  EXPECT_NEAR(minus.X(), 10 + 1.5, 1e-9);
  Machine off("N1 G47 T2 D1 G00 X10 Z0\nN2 RET\n", 0, 0, WithOffsetsAndTools);
  off.channel->Start();
  off.RunUntilEnd();
  EXPECT_NEAR(off.X(), 10, 1e-9);
}

TEST(ChannelTest, ToolMissingFromTheListIsAnError) {
  Machine m("N1 G00 X1\nN2 G48 T7 D2 X10\nN3 RET\n", 0, 0, WithOffsetsAndTools);
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgToolNotInList);
  EXPECT_STREQ(MessageText(m.channel->error_number()), "tool correction not in the tool list");
  EXPECT_THAT(m.channel->error(),
              ::testing::HasSubstr("p.mtc:2:1: error: T7 D2 is not in the tool list (G48)"));
  EXPECT_NEAR(m.X(), 1, 1e-9);
}

TEST(ChannelTest, GCodesActBeforeTheCoordinatesOfTheirBlock) {
  Machine m("N1 X40 G16 G01 F6000\nN2 X2 G91\nN3 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 21, 1e-9);  // diameter 40 -> radius 20, then +1 (incremental diameter 2)
}

TEST(ChannelTest, G92SetsTheCurrentPositionUntilReset) {
  Machine m("N1 G00 X10 Z20\nN2 G92 X0 Z0\nN3 G00 X5 Z5\nN4 M30\n", 0, 0, {}, nc::Dialect::kIsg);
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 15, 1e-9);
  EXPECT_NEAR(m.Z(), 25, 1e-9);
  EXPECT_NEAR(m.channel->Translation(0), 10, 1e-9);
  m.channel->Reset();
  EXPECT_NEAR(m.channel->Translation(0), 0, 1e-9);
}

TEST(ChannelTest, G74HomesTheAxesInTheirOrder) {
  auto configure = [](ChannelConfig& c) {
    c.axes[0].reference_position = 200;
    c.axes[1].reference_position = 400;
    c.axes[0].homing_per_s = 100;
    c.axes[1].homing_per_s = 100;
    c.axes[0].homed_at_start = c.axes[1].homed_at_start = false;
  };
  // ISG: G74 X1 Z2 homes X first, then Z.
  Machine m("N10 G74 X1 Z2\nN20 G00 X150 Z300\nN30 M30\n", 50, 100, configure, nc::Dialect::kIsg);
  EXPECT_FALSE(m.channel->homed(0));
  m.channel->Start();
  bool z_moved_before_x_home = false, x_home = false;
  while (m.channel->state() == ChannelState::kRunning && m.t < 20) {
    m.Tick();
    x_home = x_home || m.X() == 200;
    if (!x_home && m.Z() != 100) z_moved_before_x_home = true;
  }
  EXPECT_TRUE(x_home);
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_FALSE(z_moved_before_x_home);
  EXPECT_TRUE(m.channel->homed(0));
  EXPECT_TRUE(m.channel->homed(1));
  EXPECT_DOUBLE_EQ(m.X(), 150);
  EXPECT_DOUBLE_EQ(m.Z(), 300);

  // Without homing a move is refused.
  Machine unhomed("N1 G00 X10\nN2 RET\n", 0, 0, configure);
  unhomed.channel->Start();
  unhomed.RunUntilEnd();
  EXPECT_EQ(unhomed.channel->error_number(), kMsgNotHomed);
  EXPECT_THAT(unhomed.channel->error(), ::testing::HasSubstr("axis X has no reference"));
}

TEST(ChannelTest, MdiRunsTypedBlocksInTheModalStateOfTheLastProgram) {
  Machine m("N1 G91 G01 X10 F6000\nN2 RET\n");
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kMdi));
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);
  ASSERT_TRUE(m.channel->Mdi("X5 Z-3\nX1 Z1\n"));
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_NEAR(m.X(), 16, 1e-9);  // G91 carried over: 10 + 5 + 1
  EXPECT_NEAR(m.Z(), -2, 1e-9);
  // A text that does not parse is refused with its message; Control-Reset clears it.
  EXPECT_FALSE(m.channel->Mdi("X5 Z-3 Y"));
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgMdiSyntax);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("MDI:1:"));
  m.channel->Reset();
  EXPECT_EQ(m.channel->state(), ChannelState::kIdle);
  // Back in automatic, start runs the program again from its top.
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kAutomatic));
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_NEAR(m.X(), 26, 1e-9);  // G91 X10 from 16
}

TEST(ChannelTest, ReverseContinuesAtHome) {
  Machine m("N1 G01 X100 F600\nN2 X0\nN3 RET\n.HOME\nN10 G00 Z50\nN11 G00 X-20\nN12 RET\n");
  m.channel->Start();
  for (int i = 0; i < 2000; ++i) m.Tick();
  EXPECT_FALSE(m.channel->Reverse());  // only when interrupted
  m.channel->Stop();
  for (int i = 0; i < 800; ++i) m.Tick();
  const double x = m.X();
  ASSERT_GT(x, 1);
  ASSERT_LT(x, 99);
  ASSERT_TRUE(m.channel->Reverse());
  EXPECT_TRUE(m.channel->reversing());
  bool x_still_while_z = true;
  while (m.channel->state() == ChannelState::kRunning && m.t < 20) {
    m.Tick();
    if (m.Z() > 0 && m.Z() < 50 && std::abs(m.X() - x) > 1e-9) x_still_while_z = false;
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_FALSE(m.channel->reversing());
  EXPECT_TRUE(x_still_while_z);
  EXPECT_DOUBLE_EQ(m.Z(), 50);
  EXPECT_DOUBLE_EQ(m.X(), -20);

  Machine none("N1 G01 X100 F600\nN2 RET\n");
  none.channel->Start();
  for (int i = 0; i < 400; ++i) none.Tick();
  none.channel->Stop();
  for (int i = 0; i < 400; ++i) none.Tick();
  EXPECT_FALSE(none.channel->Reverse());
  EXPECT_EQ(none.channel->error_number(), kMsgNoHomeLabel);
}

TEST(ChannelTest, JogModesRapidParametricAndHandwheel) {
  auto configure = [](ChannelConfig& c) {
    c.axes[0].jog_per_s = 20;
    c.axes[0].jog_rapid_per_s = 80;
    c.axes[0].jog_distance = 2.5;
  };
  Machine m("N1 RET\n", 0, 0, configure);
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kRapid));
  m.channel->Jog(0, +1);
  for (int i = 0; i < 4000; ++i) m.Tick();
  m.channel->Jog(0, 0);
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_NEAR(m.X(), 80, 0.5);  // 1 s at 80 mm/s
  const double x0 = m.X();
  m.channel->SetJogMode(static_cast<int>(JogMode::kParametric));
  m.channel->Jog(0, -1);
  for (int i = 0; i < 4000; ++i) m.Tick();
  m.channel->Jog(0, 0);
  EXPECT_NEAR(m.X(), x0 - 2.5, 1e-9);
  m.channel->SetJogMode(static_cast<int>(JogMode::kIncrement100));
  m.channel->Jog(0, +1);
  for (int i = 0; i < 400; ++i) m.Tick();
  m.channel->Jog(0, 0);
  EXPECT_NEAR(m.X(), x0 - 2.4, 1e-9);
  // Handwheel: 250 counts of 0.01 mm, the keys do nothing.
  m.channel->SetJogMode(static_cast<int>(JogMode::kHandwheel));
  m.channel->Jog(1, +1);
  m.channel->Handwheel(0, 250);
  for (int i = 0; i < 4000; ++i) m.Tick();
  EXPECT_NEAR(m.X(), x0 - 2.4 + 2.5, 1e-9);
  EXPECT_EQ(m.Z(), 0);
}

TEST(ChannelTest, AuxFunctionsWaitForThePlcAcknowledgement) {
  Machine m("N1 M08 H12 G01 X10 F6000\nN2 RET\n", 0, 0,
            [](ChannelConfig& c) { c.aux_handshake = true; });
  m.channel->Start();
  for (int i = 0; i < 400; ++i) m.Tick();
  ASSERT_EQ(m.channel->aux_output().size(), 2u);
  EXPECT_EQ(m.channel->aux_output()[0].letter, 'M');
  EXPECT_EQ(m.channel->aux_output()[0].value, 8);
  EXPECT_EQ(m.channel->aux_output()[1].letter, 'H');
  EXPECT_EQ(m.channel->aux_strobe(), 1u);
  EXPECT_EQ(m.X(), 0);  // the block waits
  m.channel->AcknowledgeAux();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(m.X(), 10);
}

TEST(ChannelTest, SoftwareLimitsStopProgramsBeforeAndJogsAtTheLimit) {
  auto configure = [](ChannelConfig& c) { c.axes[0].travel_min = 0, c.axes[0].travel_max = 300; };
  Machine m("N1 G00 X100\nN2 G00 X301\nN3 RET\n", 0, 0, configure);
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->error_number(), kMsgSoftwareLimit);
  EXPECT_THAT(
      m.channel->error(),
      ::testing::HasSubstr("p.mtc:2:1: error: axis X target 301.0000 is beyond its travel"));
  EXPECT_DOUBLE_EQ(m.X(), 100);
  m.channel->Reset();
  ASSERT_TRUE(m.channel->SetMode(ChannelMode::kManual));
  m.channel->SetJogMode(static_cast<int>(JogMode::kRapid));  // 200 mm/s
  m.channel->Jog(0, +1);
  double highest = 0;
  for (int i = 0; i < 12000; ++i) m.Tick(), highest = std::max(highest, m.X());
  EXPECT_DOUBLE_EQ(highest, 300);
  EXPECT_DOUBLE_EQ(m.X(), 300);
  m.channel->Jog(0, 0);
}

TEST(ChannelTest, ToolNoseRadiusCompensationPutsTheTipOnTheContour) {
  // Turning tool T1 D1: nose radius 0.8, edge position 3; G42 on an outside diameter.
  Machine m(
      "N1 G00 X30 Z110\nN2 G42 T1 D1 G01 X20 Z100 F6000\nN3 Z50\nN4 G02 X25 Z45 I5 K0\n"
      "N5 G01 Z30\nN6 G40 G00 X40\nN7 RET\n",
      30, 110, WithOffsetsAndTools);
  m.channel->Start();
  double worst_n3 = 0, worst_n5 = 0, worst_arc = 0;
  bool saw_n3 = false, saw_arc = false;
  while (m.channel->state() == ChannelState::kRunning && m.t < 20) {
    m.Tick();
    const double x = m.channel->position(0), z = m.channel->position(1);
    if (m.channel->line() == 3) saw_n3 = true, worst_n3 = std::max(worst_n3, std::abs(x - 20));
    // N4 ends going +X, N5 goes -Z: an outer corner, its arc (tagged N5) ends at Z44.2.
    if (m.channel->line() == 5 && z < 44.2 - 1e-9) worst_n5 = std::max(worst_n5, std::abs(x - 25));
    if (m.channel->line() == 4) {
      // G02 from (Z50, X20) to (Z45, X25) about (Z50, X25) (I5 K0): the nose centre (tip +
      // (0.8, 0.8)) runs on the inside, at radius 5 - 0.8.
      saw_arc = true;
      const double r = std::hypot(z + 0.8 - 50, x + 0.8 - 25);
      worst_arc = std::max(worst_arc, std::abs(r - (5 - 0.8)));
    }
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_TRUE(saw_n3);
  EXPECT_TRUE(saw_arc);
  EXPECT_LT(worst_n3, 1e-9);
  EXPECT_LT(worst_n5, 1e-9);
  EXPECT_LT(worst_arc, 1e-6);
  EXPECT_NEAR(m.X(), 40, 1e-9);  // G40: back on the programmed point
  EXPECT_NEAR(m.Z(), 30, 1e-9);
}

TEST(ChannelTest, ToolNoseRadiusCompensationReportsAGouge) {
  // A 1 mm groove is narrower than the 1.6 mm nose: a contour violation before it is cut.
  Machine m(
      "N1 G00 X30 Z110\nN2 G42 T1 D1 G01 X20 Z100 F6000\nN3 Z60\nN4 X15\nN5 Z59\nN6 X20\n"
      "N7 Z40\nN8 G40 G00 X40\nN9 RET\n",
      30, 110, WithOffsetsAndTools);
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgGouge);
  EXPECT_THAT(m.channel->error(), ::testing::HasSubstr("contour violation (gouge)"));
  // One block of look-ahead: N4 runs down the groove's first wall (nose centre Z59.2, tip
  // Z58.4); N5 is found too short for the nose when N6 arrives, before N5 runs.
  EXPECT_GE(m.channel->position(1), 58.4 - 1e-9);
  EXPECT_GE(m.channel->position(0), 15 - 1e-9);
  EXPECT_LE(m.channel->line(), 5u);
}

TEST(ChannelTest, ProgramEventsAndInstructionsOfLaterIssues) {
  // SE sets an event the program itself tests with BES; RE clears it.
  Machine m(
      "N1 SE 29\nN2 BES .SET 29\nN3 G00 X1\n.SET\nN4 RE 29\nN5 BES .BAD 29\nN6 G00 X2\n"
      "N7 RET\n.BAD\nN8 G00 X3\nN9 RET\n");
  std::vector<std::pair<int, bool>> seen;
  m.channel->SetEventSink([&](int n, bool v) { seen.emplace_back(n, v); });
  m.channel->Start();
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.X(), 2);
  EXPECT_EQ(seen, (std::vector<std::pair<int, bool>>{{29, true}, {29, false}}));
  // An instruction the channel does not execute yet stops the program, it is not skipped.
  Machine mtp("N1 G00 X5\nN2 MTP\nN3 G00 X9\nN4 RET\n");
  mtp.channel->Start();
  mtp.RunUntilEnd();
  EXPECT_EQ(mtp.channel->error_number(), kMsgNotAvailable);
  EXPECT_THAT(mtp.channel->error(),
              ::testing::HasSubstr("p.mtc:2:4: error: instruction MTP is not available"));
  EXPECT_DOUBLE_EQ(mtp.X(), 5);
}

// Speeds per NC cycle (mm/s) of a run to the end, X and Z.
std::vector<std::pair<double, double>> CycleSpeeds(Machine& m) {
  std::vector<std::pair<double, double>> v;
  double x = m.X(), z = m.Z();
  while (m.channel->state() == ChannelState::kRunning && m.t < 30) {
    for (int i = 0; i < 4; ++i) m.Tick();
    v.emplace_back((m.X() - x) / 1e-3, (m.Z() - z) / 1e-3);
    x = m.X(), z = m.Z();
  }
  return v;
}

TEST(ChannelTest, LookAheadRunsThroughCollinearAndTangentJoinsAtFeed) {
  // Two collinear G01 blocks: no stop between them; as fast as one block of the whole length.
  Machine two("N1 G01 X50 F6000\nN2 X100\nN3 RET\n"), one("N1 G01 X100 F6000\nN2 RET\n");
  two.channel->Start();
  one.channel->Start();
  const auto v = CycleSpeeds(two);
  CycleSpeeds(one);
  ASSERT_EQ(two.channel->state(), ChannelState::kEnded) << two.channel->error();
  EXPECT_DOUBLE_EQ(two.X(), 100);
  EXPECT_NEAR(two.t, one.t, 0.003);
  double slowest_inside = 1e9, worst_change = 0;
  // Between the ramps (the join at X50 is in the middle): steady 100 mm/s.
  for (size_t i = 100; i + 100 < v.size(); ++i) {
    worst_change = std::max(worst_change, std::abs(v[i].first - v[i - 1].first));
    slowest_inside = std::min(slowest_inside, v[i].first);
  }
  EXPECT_GT(slowest_inside, 99.999);
  EXPECT_LT(worst_change, 1e-6);

  // A line into a tangent arc keeps the feed too.
  Machine arc("N1 G01 X10 Z0 F3000\nN2 G01 Z-20\nN3 G02 X20 Z-30 I10 K0\nN4 RET\n", 10, 0);
  arc.channel->Start();
  const auto va = CycleSpeeds(arc);
  ASSERT_EQ(arc.channel->state(), ChannelState::kEnded) << arc.channel->error();
  double slowest = 1e9;
  for (size_t i = 50; i + 50 < va.size(); ++i)
    slowest = std::min(slowest, std::hypot(va[i].first, va[i].second));
  EXPECT_GT(slowest, 45);  // 50 mm/s, the arc's centripetal limit sqrt(4000 x 10) = 200 is above
}

TEST(ChannelTest, LookAheadSlowsForCornersAndStopsWhereItMust) {
  // A right-angle corner: the path passes the corner slowly but without a stop. The cycle that
  // passes it commands a point before and one after it: the straight line between them (the
  // fine interpolation) cuts the corner by less than the corner deviation.
  Machine m("N1 G01 X50 F6000\nN2 Z50\nN3 RET\n");
  m.channel->Start();
  double cut = 1e9, min_speed = 1e9;
  while (m.channel->state() == ChannelState::kRunning && m.t < 10) {
    const double x = m.channel->position(0), z = m.channel->position(1);
    for (int i = 0; i < 4; ++i) m.Tick();
    const double x1 = m.channel->position(0), z1 = m.channel->position(1);
    const double speed = std::hypot(x1 - x, z1 - z) / 1e-3;
    // Distance of the corner (50, 0) from this cycle's chord.
    const double len2 = (x1 - x) * (x1 - x) + (z1 - z) * (z1 - z);
    const double f =
        len2 > 0 ? std::clamp(((50 - x) * (x1 - x) + (0 - z) * (z1 - z)) / len2, 0.0, 1.0) : 0.0;
    cut = std::min(cut, std::hypot(x + f * (x1 - x) - 50, z + f * (z1 - z)));
    if (x1 > 49 && z1 < 1) min_speed = std::min(min_speed, speed);
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_LT(cut, kCornerDeviation);
  EXPECT_LT(min_speed, 20);  // slow at the corner ...
  EXPECT_GT(min_speed, 1);   // ... but not stopped
  // A block with an M function, single block, and rapid moves still stop.
  Machine aux("N1 G01 X50 F6000\nN2 X100 M08\nN3 RET\n");
  aux.channel->Start();
  const auto v = CycleSpeeds(aux);
  double slowest_mid = 1e9;
  for (size_t i = 100; i + 100 < v.size(); ++i) slowest_mid = std::min(slowest_mid, v[i].first);
  EXPECT_LT(slowest_mid, 5);  // at rest at X50 (one cycle's start-up at most)
}

TEST(ChannelTest, FeedHoldJustBeforeABlendedJoinBrakesIntoTheNextBlock) {
  Machine m("N1 G01 X50 F6000\nN2 X100\nN3 RET\n");
  m.channel->Start();
  while (m.channel->position(0) < 49.9 && m.t < 5) m.Tick();
  m.channel->Stop();
  for (int i = 0; i < 2000; ++i) m.Tick();
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  const double x = m.X();
  EXPECT_GT(x, 49.9);
  EXPECT_LT(x, 49.9 + 100 * 100 / (2 * 4000.0) + 0.2);  // the braking distance from 100 mm/s
  for (int i = 0; i < 400; ++i) m.Tick();
  EXPECT_EQ(m.X(), x);  // at rest
  m.channel->Start();
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_DOUBLE_EQ(m.X(), 100);
}

TEST(ChannelTest, LookAheadUnderToolNoseRadiusCompensation) {
  // The tip path of N3 - fillet N4 - corner arc - N5 is tangent throughout: no stop on it.
  Machine m(
      "N1 G00 X30 Z110\nN2 G42 T1 D1 G01 X20 Z100 F6000\nN3 Z50\nN4 G02 X25 Z45 I5 K0\n"
      "N5 G01 Z30\nN6 G40 G00 X40\nN7 RET\n",
      30, 110, WithOffsetsAndTools);
  m.channel->Start();
  double slowest = 1e9;
  while (m.channel->state() == ChannelState::kRunning && m.t < 20) {
    const double x = m.channel->position(0), z = m.channel->position(1);
    for (int i = 0; i < 4; ++i) m.Tick();
    const double speed = std::hypot(m.channel->position(0) - x, m.channel->position(1) - z) / 1e-3;
    if (z < 60 && z > 35) slowest = std::min(slowest, speed);
  }
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_GT(slowest, 40);  // the 0.8 mm corner arc allows sqrt(4000 x 0.8) = 57 mm/s
}

std::string Program(const std::vector<std::string>& blocks) {
  std::string text;
  for (size_t i = 0; i < blocks.size(); ++i)
    text += "N" + std::to_string(i + 1) + " " + blocks[i] + "\n";
  return text;
}

TEST(ChannelTest, LookAheadPlansOverManyShortBlocks) {
  // 200 collinear blocks of 0.5 mm at 100 mm/s: stopping from the feed takes 1.25 mm, more
  // than two blocks, so the feed is only reached when the look-ahead sees several blocks.
  std::vector<std::string> blocks = {"G01 X0.5 F6000"};
  for (int i = 2; i <= 200; ++i) blocks.push_back("X" + std::to_string(i * 0.5));
  blocks.push_back("RET");
  Machine many(Program(blocks)), one("N1 G01 X100 F6000\nN2 RET\n");
  many.channel->Start();
  one.channel->Start();
  const auto v = CycleSpeeds(many);
  CycleSpeeds(one);
  ASSERT_EQ(many.channel->state(), ChannelState::kEnded) << many.channel->error();
  EXPECT_DOUBLE_EQ(many.X(), 100);
  double slowest_inside = 1e9;
  for (size_t i = 100; i + 100 < v.size(); ++i)
    slowest_inside = std::min(slowest_inside, v[i].first);
  EXPECT_GT(slowest_inside, 99.99);
  EXPECT_NEAR(many.t, one.t, 0.003);

  // The same with jerk-limited axes: a braking takes about 2.5 mm, five blocks, and runs on
  // through their ends, so the feed is kept between the ramps here too.
  const auto jerk_limited = [](ChannelConfig& c) {
    for (ChannelAxis& a : c.axes) a.jerk = 200000;
  };
  Machine smooth(Program(blocks), 0, 0, jerk_limited),
      smooth_one("N1 G01 X100 F6000\nN2 RET\n", 0, 0, jerk_limited);
  smooth.channel->Start();
  smooth_one.channel->Start();
  const auto vs = CycleSpeeds(smooth);
  CycleSpeeds(smooth_one);
  ASSERT_EQ(smooth.channel->state(), ChannelState::kEnded) << smooth.channel->error();
  EXPECT_DOUBLE_EQ(smooth.X(), 100);
  double slowest_smooth = 1e9;
  for (size_t i = 100; i + 100 < vs.size(); ++i)
    slowest_smooth = std::min(slowest_smooth, vs[i].first);
  EXPECT_GT(slowest_smooth, 99.99);
  EXPECT_NEAR(smooth.t, smooth_one.t, 0.003);

  // A polyline turning by 3 degrees per 0.5 mm block (a finely segmented arc of 9.5 mm radius,
  // whose centripetal limit sqrt(4000 x 9.5) = 195 mm/s is above the feed) runs at the feed.
  std::vector<std::string> arc = {"G01 F6000"};
  double x = 0, z = 0;
  for (int i = 0; i < 60; ++i) {
    const double angle = i * 3 * std::numbers::pi / 180;
    x += 0.5 * std::sin(angle), z -= 0.5 * std::cos(angle);
    char block[64];
    std::snprintf(block, sizeof block, "X%.6f Z%.6f", x, z);
    arc.push_back(block);
  }
  arc.push_back("RET");
  Machine polyline(Program(arc));
  polyline.channel->Start();
  const auto vp = CycleSpeeds(polyline);
  ASSERT_EQ(polyline.channel->state(), ChannelState::kEnded) << polyline.channel->error();
  double slowest = 1e9;
  for (size_t i = 60; i + 60 < vp.size(); ++i)
    slowest = std::min(slowest, std::hypot(vp[i].first, vp[i].second));
  EXPECT_GT(slowest, 95);
}

TEST(ChannelTest, LookAheadStopsAtAReversal) {
  // Back along the same line: the path comes to rest at X50 before it turns back (jerk-limited
  // axes: no step in the speed anywhere), and the reversal of an acute zigzag is slow too.
  const auto jerk_limited = [](ChannelConfig& c) {
    for (ChannelAxis& a : c.axes) a.jerk = 200000;
  };
  Machine m("N1 G01 X50 F6000\nN2 X0\nN3 RET\n", 0, 0, jerk_limited);
  m.channel->Start();
  const auto v = CycleSpeeds(m);
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  double worst_change = 0;
  for (size_t i = 1; i < v.size(); ++i)
    worst_change = std::max(worst_change, std::abs(v[i].first - v[i - 1].first));
  EXPECT_LE(worst_change, 4000 * 1e-3 + 1e-6);  // the axis' acceleration, no jump
  Machine zigzag("N1 G01 X50 Z0 F6000\nN2 X0 Z5\nN3 RET\n");
  zigzag.channel->Start();
  const auto vz = CycleSpeeds(zigzag);
  ASSERT_EQ(zigzag.channel->state(), ChannelState::kEnded) << zigzag.channel->error();
  double slowest_mid = 1e9;
  for (size_t i = 100; i + 100 < vz.size(); ++i)
    slowest_mid = std::min(slowest_mid, std::hypot(vz[i].first, vz[i].second));
  EXPECT_LT(slowest_mid, 5);
}

TEST(ChannelTest, EffectiveDistanceGivesTheRotaryAxisItsPathSpeed) {
  // C-axis manual 1.2: RX, RY, RZ are the tool contact point's position; the C axis (about Z)
  // moves it at the rotation times its distance from Z. C90 at RX50: 78.5 mm at 20 mm/s.
  const auto with_c = [](ChannelConfig& c) {
    ChannelAxis axis = Axis("C", 2, 3600);
    axis.rotary = true;
    axis.acceleration = 100000;
    c.axes.push_back(axis);
    c.spindle_drive = -1;
  };
  const auto seconds = [&](const std::string& block) {
    Machine m("N1 " + block + "\nN2 RET\n", 0, 0, with_c);
    m.channel->Start();
    m.RunUntilEnd();
    EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
    EXPECT_NEAR(m.channel->position(2), 90, 1e-9);
    return m.t;
  };
  const double rx = seconds("G01 C90 RX50 F1200");
  EXPECT_NEAR(rx, 50 * std::numbers::pi / 2 / 20, 0.02);
  EXPECT_NEAR(seconds("G01 C90 RX30 RY40 F1200"), rx, 1e-3);    // the same distance from Z
  EXPECT_NEAR(seconds("G01 C90 RZ50 F1200"), 90 / 20.0, 0.02);  // along Z: no distance, in deg
  EXPECT_NEAR(seconds("G01 C90 F1200"), 90 / 20.0, 0.02);       // no effective distance: deg
}

}  // namespace
}  // namespace vmt::control::channel
