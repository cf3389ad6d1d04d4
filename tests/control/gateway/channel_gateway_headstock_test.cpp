// The headstock's signals through the gateway (C-axis manual 2.3, 4.2): the spindle keys
// AxxC.M3/M4/M5/M19 and the spindle override AxxC.SOVR of the main spindle, the process
// enabling signal PxxC.ENABL, the spindle's reference AxxS.HOMED. Lathe layout: X A01, Z A02,
// main spindle S1 A03 (drive 2), C servo A04 (drive 3).

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string_view>

#include "control/gateway/channel_gateway.hpp"
#include "control/gateway/signal_catalog.hpp"
#include "control/nc/parser.hpp"
#include "tests/control/gateway/lathe_channel.hpp"
#include "tests/control/gateway/lathe_layout.hpp"
#include "tests/support/ideal_drive_bus.hpp"

namespace vmt::control::gateway {
namespace {

struct HeadstockRig : test_support::IdealDriveBus {
  HeadstockRig() : IdealDriveBus(4, 0), image(BuildSignalTable(testing::LatheLayout())) {
    parsed = nc::ParseProgram("N1 RET\n", "p.mtc", nc::Dialect::kMtc200);
    EXPECT_TRUE(parsed.ok());
    channel::ChannelConfig config = testing::LatheChannel();
    config.spindle.name = "S1";
    config.spindle.jog_per_s = 600;
    config.spindle.jog_spindle_position = 45;
    config.spindle.homed_at_start = false;
    ch = std::make_unique<channel::Channel>(config,
                                            std::vector<const nc::Program*>{&parsed.program});
    gateway = std::make_unique<ChannelGateway>(image, 0, std::vector<int>{1, 2, 4}, 3, 2, 4);
    // Ideal drives at their command at once, reporting their enable; standing on a position
    // command they report no velocity.
    for (test_support::IdealDrive& d : drives) {
      d = test_support::IdealDrive::Servo();
      d.standstill_window = 1e-9;
      d.enabled = true;
      d.orients = true;
    }
    Set("A03.SPMOD_Q", true);  // the PLC: spindle mode, both drives enabled
    Set("A03C.READY", true);
    Set("A04C.READY", true);
  }
  // One NC cycle on ideal drives; the PLC acknowledges the changeover at once.
  void Cycle(int n = 1) {
    for (int k = 0; k < n; ++k) {
      if (const axes::HeadstockChangeover* hs = ch->headstock();
          hs && (hs->busy() || hs->mode() != axes::HeadstockMode::kNone)) {
        Set("A03.ROTMOD_Q", hs->rotmod());
        Set("A03.SPMOD_Q", hs->spmod());
      }
      gateway->ReadControls(*ch);
      for (int i = 0; i < 4; ++i) {
        ch->Tick(at, mdt);
        Answer();
      }
      gateway->WriteStatus(*ch, at);
    }
  }
  void Set(const char* name, bool v) { image.SetBool(image.Require(name), v); }
  bool Get(const char* name) const { return image.Bool(image.Require(name)); }
  void Press(const char* name) {
    Set(name, true);
    Cycle();
    Set(name, false);
    Cycle();
  }

  nc::ParseResult parsed;
  SignalImage image;
  std::unique_ptr<channel::Channel> ch;
  std::unique_ptr<ChannelGateway> gateway;
};

TEST(ChannelGatewayHeadstock, SpindleKeysOverrideAndReference) {
  HeadstockRig r;
  r.Press("P00C.MANU");
  ASSERT_EQ(r.ch->mode(), channel::ChannelMode::kManual);
  EXPECT_FALSE(r.Get("A03S.HOMED"));
  r.Press("A03C.M3");
  r.Cycle(4);
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 600);
  r.image.SetInt(r.image.Require("A03C.SOVR"), 50);
  r.Cycle();
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 300);
  r.image.SetInt(r.image.Require("P00C.FOVR"), 10);  // the feed override does not act
  r.Cycle();
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 300);
  r.Press("A03C.M4");
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, -300);
  r.Press("A03C.M19");
  r.Cycle(2);
  EXPECT_DOUBLE_EQ(r.at.feedback[2].position, 45);
  EXPECT_TRUE(r.Get("A03S.HOMED"));  // M19 referenced the spindle
  r.Press("A03C.M5");
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 0);
  // Jogging C selects rotary axis mode; M3 selects spindle mode again.
  r.Set("A04C.JGPOS", true);
  r.Cycle(20);
  EXPECT_TRUE(r.Get("A03.ROTMOD"));
  r.Set("A04C.JGPOS", false);
  r.Press("A03C.M3");
  r.Cycle(20);
  EXPECT_TRUE(r.Get("A03.SPMOD"));
  EXPECT_EQ(r.ch->HeadstockAxisName(), "S1");
}

// 4.2: AxxC.HOME homes the rotary axis like the other axes, in rotary axis mode: as C's jog keys
// do, the key selects it first, and C travels to its reference point once it is there.
TEST(ChannelGatewayHeadstock, HomeKeyOfTheRotaryAxisSelectsRotaryAxisMode) {
  HeadstockRig r;
  r.Press("P00C.MANU");
  r.Cycle(5);
  ASSERT_EQ(r.ch->headstock()->mode(), axes::HeadstockMode::kSpindle);
  r.at.feedback[3].position = 100;  // C reads the spindle at 100 deg; its reference point is 0
  r.Cycle();
  r.Press("A04C.HOME");
  r.Cycle(20);
  EXPECT_TRUE(r.Get("A03.ROTMOD"));
  r.Cycle(4000);  // 100 deg at a tenth of C's rapid
  EXPECT_EQ(r.ch->headstock()->mode(), axes::HeadstockMode::kRotary);
  EXPECT_NEAR(r.at.feedback[3].position, 0, 1e-9);
  EXPECT_TRUE(r.Get("A04S.HOMED"));
  EXPECT_FALSE(r.Get("A04S.MVNEG"));
}

// 2.3 / 3.3 Homing: a main spindle is homed by positioning (M19 crosses the zero impulse); its
// HOME key positions it to its reference point, and the reference is there when it is in
// position. Outside manual mode the key does nothing.
TEST(ChannelGatewayHeadstock, HomeKeyOfTheMainSpindlePositionsItToItsReference) {
  HeadstockRig r;
  r.at.feedback[2].position = 200;
  r.Press("A03C.HOME");
  r.Cycle(5);
  EXPECT_FALSE(r.Get("A03S.HOMED"));
  EXPECT_DOUBLE_EQ(r.at.feedback[2].position, 200);
  r.Press("P00C.MANU");
  r.Press("A03C.HOME");
  r.Cycle(5);
  EXPECT_EQ(r.mdt.setpoints[2].mode, DriveMode::kPosition);
  EXPECT_DOUBLE_EQ(r.at.feedback[2].position, 0);
  EXPECT_TRUE(r.Get("A03S.HOMED"));
}

TEST(ChannelGatewayHeadstock, ProcessEnableRemovedStopsAndBlocksTheSpindleKeys) {
  HeadstockRig r;
  r.Set("P00C.ENABL", true);
  r.Press("P00C.MANU");
  r.Press("A03C.M3");
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 600);
  r.Set("P00C.ENABL", false);
  r.Cycle();
  EXPECT_FALSE(r.ch->process_enabled());
  r.Press("A03C.M5");  // a stop is always taken
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 0);
  r.Press("A03C.M3");  // nothing starts
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 0);
  r.Set("P00C.ENABL", true);
  r.Cycle();
  r.Press("A03C.M3");
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 600);
}

// 4.2: "the axis cannot be moved in manual mode without the axis enabling signal", whatever
// the mode of the headstock: jog keys and spindle keys start nothing, a continuous jog brakes.
TEST(ChannelGatewayHeadstock, AxisEnablingSignalGatesManualMotion) {
  HeadstockRig r;
  // Like PxxC.ENABL the signals act when they change: unwritten (0) the axes are enabled.
  EXPECT_FALSE(r.Get("A01C.ENABL"));
  r.Press("P00C.MANU");
  r.Set("A03C.JGPOS", true);
  r.Cycle(4);
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 600);
  r.Set("A03C.JGPOS", false);
  r.Cycle(4);
  for (const char* enabl : {"A01C.ENABL", "A02C.ENABL", "A03C.ENABL", "A04C.ENABL"})
    r.Set(enabl, true);
  r.Cycle();
  r.Set("A01C.ENABL", false);
  r.Set("A01C.JGPOS", true);
  r.Cycle(200);
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 0);
  r.Set("A01C.ENABL", true);
  r.Cycle(200);
  EXPECT_GT(r.at.feedback[0].position, 1);
  r.Set("A01C.ENABL", false);  // under way: brakes to a standstill with the key still held
  r.Cycle(200);
  const double stopped = r.at.feedback[0].position;
  r.Cycle(50);
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, stopped);
  r.Set("A01C.JGPOS", false);
  r.Set("A01C.ENABL", true);
  // The spindle's own signal gates its keys: M3 and its jog keys.
  r.Set("A03C.ENABL", false);
  r.Press("A03C.M3");
  r.Set("A03C.JGPOS", true);
  r.Cycle(4);
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 0);
  r.Set("A03C.ENABL", true);  // the key still held acts now, as a feed axis' does
  r.Cycle(4);
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 600);
  r.Set("A03C.ENABL", false);  // the jog key's turning stops
  r.Cycle(4);
  EXPECT_DOUBLE_EQ(r.at.feedback[2].velocity, 0);
  r.Set("A03C.JGPOS", false);
  // The rotary axis' signal gates jogging C, and with it the changeover C's key would start.
  r.Set("A04C.ENABL", false);
  r.Set("A04C.JGPOS", true);
  r.Cycle(40);
  EXPECT_FALSE(r.ch->headstock()->busy());
  EXPECT_EQ(r.ch->headstock()->mode(), axes::HeadstockMode::kSpindle);
}

// 4.2 status signals: RF, the controller enable the NC gives the drive, and BBDIG, the drive
// ready; NC_NMAX, the speed command at the spindle's limit.
TEST(ChannelGatewayHeadstock, DriveStatusAndSpeedLimitSignals) {
  HeadstockRig r;
  r.Cycle(2);
  for (int d : {0, 2}) r.at.feedback[d].status = drive_status::kReady | drive_status::kEnabled;
  r.gateway->WriteStatus(*r.ch, r.at);
  EXPECT_TRUE(r.Get("A01S.RF"));
  EXPECT_TRUE(r.Get("A01S.BBDIG"));
  EXPECT_TRUE(r.Get("A03S.RF"));
  EXPECT_TRUE(r.Get("A03S.BBDIG"));
  EXPECT_FALSE(r.Get("A02S.RF"));  // Z's drive: ready, never given its controller enable
  EXPECT_TRUE(r.Get("A02S.BBDIG"));
  r.at.feedback[0].status = 0;  // a drive fault: neither ready nor enabled
  r.gateway->WriteStatus(*r.ch, r.at);
  EXPECT_FALSE(r.Get("A01S.RF"));
  EXPECT_FALSE(r.Get("A01S.BBDIG"));
  r.at.feedback[2].status = drive_status::kReady;  // ready, controller enable off
  r.gateway->WriteStatus(*r.ch, r.at);
  EXPECT_FALSE(r.Get("A03S.RF"));
  EXPECT_TRUE(r.Get("A03S.BBDIG"));
}

TEST(ChannelGatewayHeadstock, SpeedCommandAtTheLimitSetsNcNmax) {
  HeadstockRig r;
  channel::ChannelConfig config = r.ch->config();
  config.spindle.max_spindle_rpm = 100;  // the jogging speed, 600 deg/s, is the limit
  r.ch = std::make_unique<channel::Channel>(config,
                                            std::vector<const nc::Program*>{&r.parsed.program});
  r.Press("P00C.MANU");
  r.Cycle();
  EXPECT_FALSE(r.Get("A03S.NC_NMAX"));
  r.Press("A03C.M3");
  EXPECT_TRUE(r.Get("A03S.NC_NMAX"));
  r.image.SetInt(r.image.Require("A03C.SOVR"), 50);
  r.Cycle();
  EXPECT_FALSE(r.Get("A03S.NC_NMAX"));
}

// The C-axis signals of 4.2 that vmt evaluates are tested above (and the others of the table in
// the tests of the gateway and the changeover); the rest say in the signal table that vmt does
// not evaluate them, and why.
TEST(ChannelGatewayHeadstock, EveryAxisSignalIsEvaluatedOrMarkedNot) {
  // (channel_gateway_axis_signals_test.cpp: HOME, STRBP, OTRVL, MTAS, WP0..7, MD_MDX, P_PX,
  // LOAD90.)
  const std::set<std::string_view> tested = {
      "AxxC.HOME",  "AxxC.ENABL", "AxxS.RF",   "AxxS.BBDIG", "AxxS.NC_NMAX", "AxxC.JGPOS",  "AxxC.JGNEG",
      "AxxC.STRBP", "AxxC.OTRVL", "AxxC.MTAS", "AxxS.WP0",     "AxxS.WP1",    "AxxS.WP2",
      "AxxS.WP3",   "AxxS.WP4",  "AxxS.WP5",   "AxxS.WP6",     "AxxS.WP7",    "AxxS.MD_MDX",
      "AxxS.P_PX",  "AxxS.LOAD90"};
  const std::set<std::string_view> listed = {
      "AxxC.ENABL", "AxxC.HOME",    "AxxC.HOMLS",  "AxxC.STRBP",   "AxxC.OTRVL",
      "AxxC.MTAS",  "AxxC.GEAR1",   "AxxC.GEAR2",  "AxxC.GEAR3",   "AxxS.RF",
      "AxxS.BBDIG", "AxxS.WP0",     "AxxS.WP1",    "AxxS.WP2",     "AxxS.WP3",
      "AxxS.WP4",   "AxxS.WP5",     "AxxS.WP6",    "AxxS.WP7",     "AxxS.MD_MDX",
      "AxxS.NC_NMAX", "AxxS.P_PX",  "AxxS.LOAD90", "AxxS.SYNCHRON", "AxxC.JGPOS",
      "AxxC.JGNEG"};
  size_t seen = 0;
  for (const SignalFamily& f : SignalFamilies()) {
    if (!listed.count(f.pattern)) continue;
    ++seen;
    if (tested.count(f.pattern))
      EXPECT_TRUE(f.not_evaluated.empty()) << f.pattern;
    else
      EXPECT_FALSE(f.not_evaluated.empty()) << f.pattern << " is neither tested nor marked";
  }
  EXPECT_EQ(seen, listed.size());
  // And the signal table carries the mark to the PLC engineer.
  const std::vector<Signal> table = BuildSignalTable(testing::LatheLayout());
  for (const Signal& s : table) {
    if (s.name == "A03S.SYNCHRON") {
      EXPECT_NE(s.not_evaluated.find("coupling"), std::string::npos);
    }
  }
}

// 2.3 / 3.3 Power-On State: the PLC presents rotary axis mode (ROTMOD_Q, the spindle's enable
// off as the manual's PLC leaves it): the display shows C at once and jogging C needs no
// changeover.
TEST(ChannelGatewayHeadstock, RotaryModeAtPowerOnShowsCWithoutAChangeover) {
  HeadstockRig r;
  r.Set("A03.SPMOD_Q", false);
  r.Set("A03.ROTMOD_Q", true);
  r.Set("A03C.READY", false);
  r.Cycle();
  EXPECT_EQ(r.ch->HeadstockAxisName(), "C");
  EXPECT_TRUE(r.Get("A03.ROTMOD"));
  EXPECT_FALSE(r.Get("A03.SPMOD"));
  r.Press("P00C.MANU");
  r.Set("A04C.JGPOS", true);
  bool changed_over = false;
  for (int k = 0; k < 40; ++k) {
    r.Cycle();
    changed_over = changed_over || r.ch->headstock()->busy();
  }
  r.Set("A04C.JGPOS", false);
  EXPECT_FALSE(changed_over);
  EXPECT_GT(r.at.feedback[3].position, 0.5);
  EXPECT_EQ(r.ch->HeadstockAxisName(), "C");
}

// lathe-c2's headstock (section 2): S1 with rotary axis capability is one axis, A03, named C in
// rotary axis mode, on drive 2.
struct OneDriveRig : HeadstockRig {
  OneDriveRig() {
    GatewayLayout layout;
    layout.processes = {0};
    layout.axes = {{1, "X", false, false}, {2, "Z", false, false}, {3, "C", true, false}};
    image = SignalImage(BuildSignalTable(layout));
    channel::ChannelConfig config;
    const char* names[3] = {"X", "Z", "C"};
    for (int a = 0; a < 3; ++a) {
      channel::ChannelAxis axis;
      axis.name = names[a];
      axis.number = a + 1;
      axis.drive = a;
      axis.rotary = a == 2;
      axis.rapid_per_s = 400;
      axis.acceleration = 4000;
      config.axes.push_back(axis);
    }
    config.spindle_drive = 2;
    config.spindle.name = "S1";
    config.spindle.jog_per_s = 600;
    axes::HeadstockConfig h;
    h.spindle_drive = h.rotary_drive = 2;
    h.rotary_parameter_set = 1;
    config.headstock = h;
    config.rotary_axis = 2;
    ch = std::make_unique<channel::Channel>(config,
                                            std::vector<const nc::Program*>{&parsed.program});
    gateway = std::make_unique<ChannelGateway>(image, 0, std::vector<int>{1, 2, 3}, 3, 2, 3);
    Set("A03C.READY", true);
  }
  int64_t Errnr() const { return image.Int(image.Require("P00S.ERRNR")); }
};

// 4.2: "The NC employs the 'axis ready' control signal to monitor the ready state of a main
// spindle with rotary axis capability in rotary axis mode and in main spindle mode": A03C.READY
// removed while the axis is in use stops the NC with 503 in either mode.
TEST(ChannelGatewayHeadstock, OneDriveAxisReadyMonitoredInBothModes) {
  {
    OneDriveRig r;  // spindle mode at power-on
    r.Set("A03.SPMOD_Q", true);
    r.Press("P00C.MANU");
    r.Press("A03C.M3");
    ASSERT_DOUBLE_EQ(r.at.feedback[2].velocity, 600);
    r.Set("A03C.READY", false);
    r.Cycle(2);
    EXPECT_TRUE(r.Get("P00S.ERROR"));
    EXPECT_EQ(r.Errnr(), 503);
    EXPECT_EQ(r.mdt.setpoints[2].mode, DriveMode::kOff);
  }
  {
    OneDriveRig r;  // rotary axis mode at power-on
    r.Set("A03.SPMOD_Q", false);
    r.Set("A03.ROTMOD_Q", true);
    r.Cycle();
    EXPECT_EQ(r.ch->HeadstockAxisName(), "C");
    r.Press("P00C.MANU");
    r.Set("A03C.JGPOS", true);
    r.Cycle(10);
    ASSERT_FALSE(r.Get("P00S.ERROR"));
    ASSERT_TRUE(r.Get("A03S.MVPOS"));
    r.Set("A03C.READY", false);
    r.Cycle(2);
    EXPECT_TRUE(r.Get("P00S.ERROR"));
    EXPECT_EQ(r.Errnr(), 503);
    EXPECT_EQ(r.mdt.setpoints[2].mode, DriveMode::kOff);
    EXPECT_EQ(r.ch->headstock()->mode(), axes::HeadstockMode::kRotary);
  }
}

}  // namespace
}  // namespace vmt::control::gateway
