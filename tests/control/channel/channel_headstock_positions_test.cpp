// The rotary axis' position across changeovers in the channel (C-axis manual 1.2, 2.3): block
// preparation waits until the changeover ends, and rotary axis mode starts where the spindle
// stopped, in program coordinates with the rotary axis' zero offsets back; the position
// indication shows 0..360. On a main spindle with rotary axis capability (section 2: C on the
// spindle's drive), an ideal drive (position: actual = command; velocity: the speed at once) and
// a PLC that acknowledges every changeover at once.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/nc/parser.hpp"

namespace vmt::control::channel {
namespace {

using axes::HeadstockMode;
constexpr double kTick = 250e-6;

// Drives: 0 X, 1 Z, 2 S1 with its rotary axis mode C. Channel axes: X, Z, C. G54 shifts C by +30.
struct Headstock {
  explicit Headstock(const std::string& program) {
    parsed = nc::ParseProgram(program, "p.mtc", nc::Dialect::kMtc200);
    EXPECT_TRUE(parsed.ok()) << nc::Format(parsed.errors[0], parsed.program.files);
    ChannelConfig config;
    for (int a = 0; a < 3; ++a) {
      ChannelAxis axis;
      axis.name = a == 0 ? "X" : a == 1 ? "Z" : "C";
      axis.number = a + 1;
      axis.drive = a;
      axis.rotary = a == 2;
      axis.rapid_per_s = a == 2 ? 3600 : 400;
      axis.acceleration = a == 2 ? 36000 : 4000;
      config.axes.push_back(axis);
    }
    config.spindle_drive = 2;
    config.spindle.name = "S1";
    axes::HeadstockConfig h;
    h.spindle_drive = h.rotary_drive = 2;
    config.headstock = h;
    config.rotary_axis = 2;
    config.zero_offsets.g54_to_g59[0] = {0, 0, 30};
    channel = std::make_unique<Channel>(config, std::vector<const nc::Program*>{&parsed.program});
    at.feedback.resize(3);
    for (DriveFeedback& f : at.feedback)
      f.status = drive_status::kReady | drive_status::kStandstill;
    mdt.setpoints.resize(3);
    plc.spmod_q = true;
  }

  void Tick() {
    const axes::HeadstockChangeover& hs = *channel->headstock();
    if (hs.busy() || hs.mode() != HeadstockMode::kNone) {
      plc.rotmod_q = hs.rotmod();
      plc.spmod_q = hs.spmod();
    }
    channel->SetHeadstockPlc(plc);
    channel->Tick(at, mdt);
    for (size_t d = 0; d < 3; ++d) {
      DriveFeedback& f = at.feedback[d];
      const DriveSetpoint& sp = mdt.setpoints[d];
      f.velocity = 0;
      if (sp.mode == DriveMode::kPosition) {
        f.velocity = (sp.value - f.position) / kTick;
        f.position = sp.value;
      } else if (sp.mode == DriveMode::kVelocity) {
        f.velocity = sp.value;
        f.position += sp.value * kTick;
      }
      f.status = drive_status::kReady;
      if (std::abs(f.velocity) < 1e-9) f.status |= drive_status::kStandstill;
      if (sp.mode == DriveMode::kPosition) f.status |= drive_status::kInPosition;
    }
  }
  // Single block: starts the next block and runs it to its end (the channel holds after it).
  void Step() {
    channel->Start();
    for (int i = 0; i < 80000 && channel->state() == ChannelState::kRunning; ++i) Tick();
    for (int i = 0; i < 8; ++i) Tick();  // the drive reaches the last fine interpolation point
  }

  nc::ParseResult parsed;
  std::unique_ptr<Channel> channel;
  AmplifierTelegram at;
  MasterTelegram mdt;
  axes::HeadstockPlc plc;
};

// C-axis manual 1.2 and 2.3: after M3 / M5 the spindle stands somewhere the program does not
// know; G91 C10 right after the changeover counts from there, in program coordinates with G54's
// C offset (re-activated by rotary axis mode), and so does the interpreter for the next blocks.
TEST(ChannelHeadstockPositions, IncrementAfterChangeoverStartsWhereTheSpindleStopped) {
  Headstock m(
      "N1 G54 G90 G01 C10 F36000\n"
      "N2 M03 S100\n"
      "N3 G04 F0.37\n"
      "N4 M05\n"
      "N5 G91 G01 C10 F3600\n"
      "N6 C-5\n"
      "N7 G90 C0\n"
      "N8 G91 C-20\n"
      "N9 RET\n");
  m.channel->SetSingleBlock(true);
  for (int block = 1; block <= 4; ++block) m.Step();
  // 100 rpm for 0.37 s after C10 (machine 40): the spindle stopped near 40 + 222 = 262 deg.
  const double stopped = m.at.feedback[2].position;
  EXPECT_NEAR(stopped, 262, 5);
  m.Step();
  EXPECT_EQ(m.channel->headstock()->mode(), HeadstockMode::kRotary);
  EXPECT_NEAR(m.channel->position(2), stopped + 10, 1e-9);
  EXPECT_NEAR(m.channel->HeadstockPosition(), stopped + 10 - 30, 1e-9);  // program coordinates
  m.Step();
  EXPECT_NEAR(m.channel->position(2), stopped + 5, 1e-9);
  m.Step();
  EXPECT_NEAR(m.channel->position(2), 30, 1e-9);  // G90 C0 with G54's +30
  m.Step();
  EXPECT_NEAR(m.channel->position(2), 10, 1e-9);
  EXPECT_NEAR(m.at.feedback[2].position, 10, 1e-9);
  m.Step();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

// 2.3 Position Indication: C in the representation of a rotary axis, 0..360, though the
// program runs it past a turn (the manual's C-270, 1.2).
TEST(ChannelHeadstockPositions, IndicationShowsZeroToThreeSixty) {
  Headstock m("N1 G54 G90 G01 C-270 F72000\nN2 G04 F0.1\nN3 G53 C-400\nN4 RET\n");
  m.channel->SetSingleBlock(true);
  m.Step();
  EXPECT_EQ(m.channel->HeadstockAxisName(), "C");
  EXPECT_NEAR(m.channel->position(2), -240, 1e-9);        // machine: G54's +30
  EXPECT_NEAR(m.channel->HeadstockPosition(), 90, 1e-9);  // -270 in program coordinates
  m.Step();
  m.Step();
  EXPECT_NEAR(m.channel->position(2), -400, 1e-9);
  EXPECT_NEAR(m.channel->HeadstockPosition(), 320, 1e-9);
  m.Step();
  EXPECT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
}

}  // namespace
}  // namespace vmt::control::channel
