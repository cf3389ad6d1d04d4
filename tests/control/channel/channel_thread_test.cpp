// G33 thread cutting, G63 and G64 tapping in the channel (spindle_synchronous_motion.hpp): the
// thread's law against the spindle's actual position, the same groove at any speed, overrides,
// the spindle-not-turning error, the headstock's changeover to spindle mode, G63's path velocity
// and G64's spindle interpolated with the axis. The machine is ideal: the axes are where they
// are commanded, the spindle ramps its speed at 7200 deg/s^2 and, in position control, is where
// it is commanded.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel {
namespace {

using testing::Axis;
using ::testing::HasSubstr;

constexpr int kX = 0, kZ = 1, kS1 = 2, kC = 3;  // drives

struct Lathe : test_support::IdealDriveBus {
  // X, Z and S1; with a headstock also C, a servo on drive 3 through a clutch (C-axis manual
  // section 3), whose PLC side acknowledges ROTMOD / SPMOD after a few cycles.
  explicit Lathe(const std::string& program, bool headstock = false,
                 nc::Dialect dialect = nc::Dialect::kMtc200,
                 const std::function<void(ChannelConfig&)>& configure = {})
      : IdealDriveBus(headstock ? 4 : 3), headstock_(headstock) {
    parsed = nc::ParseProgram(program, dialect == nc::Dialect::kIsg ? "p.isg" : "p.mtc", dialect);
    EXPECT_TRUE(parsed.ok()) << nc::Format(parsed.errors[0], parsed.program.files);
    ChannelConfig config;
    config.axes = {Axis("X", kX, 400), Axis("Z", kZ, 500)};
    config.spindle_drive = kS1;
    if (headstock) {
      ChannelAxis c = Axis("C", kC, 360);
      c.rotary = true;
      c.acceleration = 3600;
      config.axes.push_back(c);
      axes::HeadstockConfig h;
      h.spindle_drive = kS1;
      h.rotary_drive = kC;
      config.headstock = h;
      config.rotary_axis = 2;
      plc.rotmod_q = true;  // power-on in rotary axis mode
    }
    if (configure) configure(config);
    channel = std::make_unique<Channel>(config, std::vector<const nc::Program*>{&parsed.program});
    // Ideal drives whose velocity ramps at 7200 deg/s^2; S1's position mode orients it (M19)
    // unless it is interpolated (G64).
    for (test_support::IdealDrive& d : drives) d = test_support::IdealDrive::Servo(7200);
    drives[kS1].orients = true;
    at.feedback[kZ].position = 10;
    at.feedback[kX].position = 30;
    at.feedback[kS1].position = 37.5;  // not on a zero mark
  }

  void Tick() {
    if (headstock_ && tick % 4 == 0) {
      const auto& hs = *channel->headstock();
      const bool want_rot = hs.rotmod() && !plc.rotmod_q, want_sp = hs.spmod() && !plc.spmod_q;
      waited = want_rot || want_sp ? waited + 1 : 0;
      if (waited > 20) plc.rotmod_q = want_rot, plc.spmod_q = want_sp, waited = 0;
      channel->SetHeadstockPlc(plc);
    }
    channel->Tick(at, mdt);
    Answer();
    ++tick;
    if (observe) observe();
  }
  void RunUntilEnd(int limit = 800000) {
    channel->Start();
    for (int i = 0; i < limit && channel->state() != ChannelState::kEnded &&
                    channel->state() != ChannelState::kError;
         ++i)
      Tick();
  }
  double Z() const { return at.feedback[kZ].position; }
  double S() const { return at.feedback[kS1].position; }
  uint32_t Line() const { return channel->line(); }

  nc::ParseResult parsed;
  std::unique_ptr<Channel> channel;
  axes::HeadstockPlc plc;
  std::function<void()> observe;
  bool headstock_;
  int waited = 0;
  int64_t tick = 0;
};

// Samples of a G33 pass on `line` away from its ramps: the thread's phase, (Z0 - Z) / k - phi,
// which the law keeps at a multiple of 360 (the zero mark).
struct ThreadPass {
  ThreadPass(double z0_mm, double mm_per_deg, double ramps_mm)
      : z0(z0_mm), k(mm_per_deg), ramp_mm(ramps_mm) {}
  double z0, k;    // start, mm per degree
  double ramp_mm;  // samples this far from either end are left out (ramp-in and run-out)
  std::vector<double> phase_deg, error_mm, z_velocity;
  void Sample(const Lathe& m, double z_end) {
    const double z = m.Z();
    if (z > z0 - ramp_mm || z < z_end + ramp_mm) return;
    const double offset = (z0 - z) / k - m.S();
    const double mark = std::round(offset / 360) * 360;
    phase_deg.push_back(offset);
    error_mm.push_back(k * (offset - mark));
    z_velocity.push_back(m.at.feedback[kZ].velocity);
  }
  double MaxError() const {
    double e = 0;
    for (double v : error_mm) e = std::max(e, std::abs(v));
    return e;
  }
};

// ---- G33 --------------------------------------------------------------------------------------

TEST(ChannelThreadTest, G33FollowsTheSpindlesActualPositionFromAZeroMark) {
  Lathe m("N1 M3 S600\nN2 G33 Z-30 F1.5\nN3 G00 X40\nN4 RET\n");
  // v = 1.5 mm x 10 rev/s = 15 mm/s; ramp v^2 / (2 x 4000) = 0.028 mm.
  ThreadPass pass(10, 1.5 / 360, 0.05);
  m.observe = [&] {
    if (m.Line() == 2) pass.Sample(m, -30);
  };
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  ASSERT_GT(pass.error_mm.size(), 8000u);  // 40 mm at 15 mm/s, 4 samples a ms
  EXPECT_LT(pass.MaxError(), 1e-3);        // within 1 um of the law
  for (double v : pass.z_velocity) ASSERT_NEAR(v, -15, 1e-6);
  EXPECT_DOUBLE_EQ(m.Z(), -30);  // exactly at the target
  EXPECT_DOUBLE_EQ(m.at.feedback[kX].position, 40);
}

TEST(ChannelThreadTest, PassesAtDifferentSpeedsCutTheSameGroove) {
  // Two passes from the same start at 600 and 1000 rpm, the spindle somewhere else each time.
  Lathe m(
      "N1 M3 S600\nN2 G33 Z-30 F2\nN3 G00 X40\nN4 Z10\nN5 X30\nN6 S1000\nN7 G04 F0.0137\n"
      "N8 G33 Z-30\nN9 RET\n");
  // Ramps: (2 x 1000 / 60)^2 / (2 x 4000) = 0.14 mm at 1000 rpm.
  ThreadPass first(10, 2.0 / 360, 0.2), second(10, 2.0 / 360, 0.2);
  std::vector<double> starts;  // the spindle's angle when Z starts to move in each pass
  m.observe = [&] {
    const uint32_t line = m.Line();
    const size_t pass = line == 2 ? 0 : 1;
    if ((line == 2 || line == 8) && starts.size() == pass && m.Z() < 10 - 1e-9)
      starts.push_back(m.S());
    if (line == 2) first.Sample(m, -30);
    if (line == 8) second.Sample(m, -30);
  };
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  ASSERT_EQ(starts.size(), 2u);
  // The spindle stood at different angles when the passes began ...
  EXPECT_GT(std::abs(std::remainder(starts[0] - starts[1], 360.0)), 1.0);
  // ... and both cut on the groove through the zero mark.
  ASSERT_FALSE(first.error_mm.empty());
  ASSERT_FALSE(second.error_mm.empty());
  EXPECT_LT(first.MaxError(), 1e-3);
  EXPECT_LT(second.MaxError(), 1e-3);
  EXPECT_NEAR(second.z_velocity.front(), -2.0 * 1000 / 60, 1e-6);
  EXPECT_NEAR(first.z_velocity.front(), -2.0 * 600 / 60, 1e-6);
}

TEST(ChannelThreadTest, FeedOverrideAndFeedHoldDoNotActInG33) {
  Lathe m("N1 M3 S600\nN2 G33 Z-30 F1.5\nN3 G00 X40\nN4 RET\n");
  m.channel->SetFeedOverride(0.5);
  ThreadPass pass(10, 1.5 / 360, 0.05);
  bool held = false;
  m.observe = [&] {
    if (m.Line() != 2) return;
    pass.Sample(m, -30);
    if (!held && m.Z() < -10) m.channel->Stop(), held = true;  // feed hold mid-thread
  };
  m.channel->Start();
  for (int i = 0;
       i < 400000 && m.channel->state() != ChannelState::kError && !(held && m.Line() != 2); ++i)
    m.Tick();
  for (int i = 0; i < 4000; ++i) m.Tick();
  EXPECT_EQ(m.channel->state(), ChannelState::kHold);
  EXPECT_DOUBLE_EQ(m.Z(), -30);  // the thread ran to its end, then the channel held
  EXPECT_DOUBLE_EQ(m.at.feedback[kX].position, 30);
  EXPECT_LT(pass.MaxError(), 1e-3);
  for (double v : pass.z_velocity) ASSERT_NEAR(v, -15, 1e-6);  // not 7.5 mm/s
}

TEST(ChannelThreadTest, SpindleOverrideActsInG33ThroughTheSpindle) {
  Lathe m("N1 M3 S600\nN2 G33 Z-30 F1.5\nN3 RET\n");
  m.channel->SetSpindleOverride(0.5);
  ThreadPass pass(10, 1.5 / 360, 0.05);
  m.observe = [&] {
    if (m.Line() == 2) pass.Sample(m, -30);
  };
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_LT(pass.MaxError(), 1e-3);
  ASSERT_FALSE(pass.z_velocity.empty());
  EXPECT_NEAR(pass.z_velocity.front(), -7.5, 1e-6);
}

TEST(ChannelThreadTest, SpindleNotTurningIsAnError) {
  for (const std::string program : {"N1 G33 Z-10 F1\nN2 RET\n", "N1 M5\nN2 G63 Z-10 F1\nN3 RET\n",
                                    "N1 G64 Z-10 F1\nN2 RET\n"}) {
    Lathe m(program);
    m.RunUntilEnd();
    EXPECT_EQ(m.channel->state(), ChannelState::kError) << program;
    EXPECT_EQ(m.channel->error_number(), kMsgSpindleStill);
    EXPECT_THAT(m.channel->error(), HasSubstr("error: spindle not turning for G"));
    EXPECT_EQ(m.Z(), 10);
  }
  EXPECT_STREQ(MessageText(kMsgSpindleStill), "spindle not turning for G33/G63/G64");
}

TEST(ChannelThreadTest, LeadTooFastForTheAxesIsAnError) {
  Lathe m("N1 M3 S3000\nN2 G33 Z-30 F20\nN3 RET\n");  // 1000 mm/s, Z's rapid is 500
  m.RunUntilEnd();
  EXPECT_EQ(m.channel->state(), ChannelState::kError);
  EXPECT_EQ(m.channel->error_number(), kMsgLeadTooFast);
  // 1000 mm/s, or what the spindle really turns within 1 % of its 3000 rpm.
  EXPECT_THAT(m.channel->error(), HasSubstr("p.mtc:2:1: error: G33 at 9"));
  EXPECT_THAT(m.channel->error(), HasSubstr("mm/s is faster than the axes' 500.000 mm/s"));
}

TEST(ChannelThreadTest, TaperThreadLeadIsAlongTheLongerAxis) {
  // Z travels 40, X 10: the lead 2 is along Z, the path 41.23 mm advances 2.06 mm a turn.
  Lathe m("N1 M3 S300\nN2 G33 X40 Z-30 F2\nN3 RET\n");
  std::vector<double> vz, vx;
  m.observe = [&] {
    if (m.Line() == 2 && m.Z() < 0 && m.Z() > -20)
      vz.push_back(m.at.feedback[kZ].velocity), vx.push_back(m.at.feedback[kX].velocity);
  };
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  ASSERT_FALSE(vz.empty());
  EXPECT_NEAR(vz.front(), -2.0 * 5, 1e-6);  // lead x 5 rev/s along Z
  EXPECT_NEAR(vx.front(), 2.0 * 5 / 4, 1e-6);
  EXPECT_DOUBLE_EQ(m.Z(), -30);
  EXPECT_DOUBLE_EQ(m.at.feedback[kX].position, 40);
}

TEST(ChannelThreadTest, IsgG33WithK) {
  Lathe m("%t\nN10 M3 S600\nN20 G33 Z-30 K1.5\nN30 M30\n", false, nc::Dialect::kIsg);
  ThreadPass pass(10, 1.5 / 360, 0.05);
  m.observe = [&] {
    if (m.Line() == 3) pass.Sample(m, -30);
  };
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  ASSERT_GT(pass.error_mm.size(), 1000u);
  EXPECT_LT(pass.MaxError(), 1e-3);
}

TEST(ChannelThreadTest, G33InRotaryAxisModeChangesOverToSpindleModeFirst) {
  // C positioned (rotary axis mode), then a thread: the block waits for spindle mode.
  Lathe m("N1 M3 S600\nN2 G01 C90 F3000\nN3 G33 Z-30 F1.5\nN4 RET\n", true);
  ThreadPass pass(10, 1.5 / 360, 0.05);
  bool rotary_during_c = false, waited_for_spindle = false;
  m.observe = [&] {
    const auto& hs = *m.channel->headstock();
    if (m.Line() == 2 && hs.mode() == axes::HeadstockMode::kRotary) rotary_during_c = true;
    // After C, the changeover back to spindle mode runs before Z moves.
    if (rotary_during_c && m.Line() != 2 && hs.busy()) {
      waited_for_spindle = true;
      EXPECT_DOUBLE_EQ(m.Z(), 10);
    }
    if (hs.mode() != axes::HeadstockMode::kSpindle) {
      EXPECT_DOUBLE_EQ(m.Z(), 10);
    }
    if (m.Line() == 3) pass.Sample(m, -30);
  };
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  EXPECT_TRUE(rotary_during_c);
  EXPECT_TRUE(waited_for_spindle);
  EXPECT_EQ(m.channel->headstock()->mode(), axes::HeadstockMode::kSpindle);
  ASSERT_GT(pass.error_mm.size(), 1000u);
  EXPECT_LT(pass.MaxError(), 1e-3);
  EXPECT_DOUBLE_EQ(m.Z(), -30);
}

// ---- G63 --------------------------------------------------------------------------------------

TEST(ChannelThreadTest, G63RunsAtLeadTimesSWithBothOverridesHeld) {
  Lathe m("N1 M3 S500\nN2 G63 Z-20 F1.25\nN3 G04 F0.1\nN4 RET\n");
  m.channel->SetFeedOverride(0.5);
  m.channel->SetSpindleOverride(0.8);
  std::vector<double> vz, spindle_cmd;
  m.observe = [&] {
    if (m.Line() == 2 && m.Z() < 5 && m.Z() > -15) {
      vz.push_back(m.at.feedback[kZ].velocity);
      spindle_cmd.push_back(m.mdt.setpoints[kS1].value);
    }
  };
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  ASSERT_FALSE(vz.empty());
  for (double v : vz) ASSERT_NEAR(v, -1.25 * 500 / 60, 1e-6);
  for (double s : spindle_cmd) ASSERT_DOUBLE_EQ(s, 3000);  // 500 rpm, override held at 100 %
  EXPECT_DOUBLE_EQ(m.mdt.setpoints[kS1].value, 2400);      // and back to 80 % after it
  EXPECT_DOUBLE_EQ(m.Z(), -20);
}

// ---- G64 --------------------------------------------------------------------------------------

TEST(ChannelThreadTest, G64InterpolatesTheSpindleWithTheAxisAndM4Reverses) {
  Lathe m("N1 M3 S600\nN2 G04 F0.5\nN3 G64 Z-20 F1\nN4 G64 Z10 M4\nN5 G04 F0.1\nN6 RET\n");
  const double k = 1.0 / 360;  // mm of Z per spindle degree
  double phi0 = std::nan(""), worst = 0, worst_back = 0;
  bool position_mode = true, reversed = false;
  int samples = 0;
  m.observe = [&] {
    const DriveSetpoint& sp = m.mdt.setpoints[kS1];
    const uint32_t line = m.Line();
    if (line != 3 && line != 4) return;
    if (std::abs(m.Z() - 10) < 1e-12 && line == 3) {
      phi0 = m.S();  // the spindle braked and stands in position control until Z moves
      return;
    }
    position_mode = position_mode && sp.mode == DriveMode::kPosition && sp.interpolated;
    // phi = phi0 + dir s / k: going in (M3) the spindle turns forward, coming out backwards.
    const double law = phi0 + (10 - m.Z()) / k;
    (line == 3 ? worst : worst_back) =
        std::max(line == 3 ? worst : worst_back, std::abs(m.S() - law) * k);
    if (line == 4 && m.at.feedback[kS1].velocity < 0) reversed = true;
    ++samples;
  };
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  ASSERT_FALSE(std::isnan(phi0));
  EXPECT_GT(samples, 10000);
  EXPECT_TRUE(position_mode);
  EXPECT_LT(worst, 1e-6);  // mm: the spindle within 1 um of the law (0.00036 deg)
  EXPECT_LT(worst_back, 1e-6);
  EXPECT_TRUE(reversed);
  EXPECT_DOUBLE_EQ(m.Z(), 10);
  EXPECT_NEAR(m.S(), phi0, 1e-9);  // back where it started: 30 turns in, 30 out
  // After the block the spindle stands in position control at its end position.
  EXPECT_EQ(m.mdt.setpoints[kS1].mode, DriveMode::kPosition);
  EXPECT_NEAR(m.mdt.setpoints[kS1].value, phi0, 1e-9);
}

TEST(ChannelThreadTest, G64IsLimitedByTheSpindleAndFollowsItsOverride) {
  // 2000 rpm x 1 mm = 33 mm/s asked; the spindle may only turn 3600 deg/s (the runner fills
  // these limits from the drive): 10 mm/s.
  Lathe m("N1 M3 S2000\nN2 G64 Z-40 F1\nN3 M3\nN4 RET\n", false, nc::Dialect::kMtc200,
          [](ChannelConfig& c) {
            c.spindle.rapid_per_s = 3600;
            c.spindle.acceleration = 20000;
          });
  m.channel->SetFeedOverride(0.3);  // no effect
  std::vector<double> vz;
  m.observe = [&] {
    if (m.Line() == 2 && m.Z() < 0 && m.Z() > -30) vz.push_back(m.at.feedback[kZ].velocity);
  };
  m.RunUntilEnd();
  ASSERT_EQ(m.channel->state(), ChannelState::kEnded) << m.channel->error();
  ASSERT_FALSE(vz.empty());
  EXPECT_NEAR(vz[vz.size() / 2], -10, 1e-6);
  // M3 selects speed control again.
  EXPECT_EQ(m.mdt.setpoints[kS1].mode, DriveMode::kVelocity);

  // The spindle override (50 %) halves it; it can never raise it beyond the limit.
  for (const double override : {0.5, 1.5}) {
    Lathe o("N1 M3 S2000\nN2 G64 Z-40 F1\nN3 RET\n", false, nc::Dialect::kMtc200,
            [](ChannelConfig& c) {
              c.spindle.rapid_per_s = 3600;
              c.spindle.acceleration = 20000;
            });
    o.channel->SetSpindleOverride(override);
    std::vector<double> v;
    o.observe = [&] {
      if (o.Line() == 2 && o.Z() < 0 && o.Z() > -30) v.push_back(o.at.feedback[kZ].velocity);
    };
    o.RunUntilEnd();
    ASSERT_EQ(o.channel->state(), ChannelState::kEnded) << o.channel->error();
    ASSERT_FALSE(v.empty());
    EXPECT_NEAR(v[v.size() / 2], override < 1 ? -5 : -10, 1e-6) << override;
  }
}

}  // namespace
}  // namespace vmt::control::channel
