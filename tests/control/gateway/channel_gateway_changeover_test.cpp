// The headstock changeover through the gateway (C-axis manual 4.1-4.3): ROTMOD / SPMOD out,
// ROTMOD_Q / SPMOD_Q and AxxC.READY in, the AXD idents 65012..65015 of both drives with the
// acknowledgement bits written back into 65012, on lathe-c1's layout (S1 = A03, C servo = A04).

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "control/gateway/channel_gateway.hpp"
#include "control/nc/parser.hpp"
#include "tests/control/gateway/lathe_channel.hpp"
#include "tests/control/gateway/lathe_layout.hpp"
#include "tests/support/ideal_drive_bus.hpp"

namespace vmt::control::gateway {
namespace {

struct Rig : test_support::IdealDriveBus {
  explicit Rig(const std::string& program)
      : IdealDriveBus(4, drive_status::kReady | drive_status::kStandstill),
        image(BuildSignalTable(testing::LatheLayout())) {
    parsed = nc::ParseProgram(program, "p.mtc", nc::Dialect::kMtc200);
    EXPECT_TRUE(parsed.ok());
    const channel::ChannelConfig config = testing::LatheChannel();
    ch = std::make_unique<channel::Channel>(config,
                                            std::vector<const nc::Program*>{&parsed.program});
    gateway = std::make_unique<ChannelGateway>(image, 0, std::vector<int>{1, 2, 4}, 3, 2, 4);
    for (test_support::IdealDrive& d : drives) d = test_support::IdealDrive::Follow();
  }
  // One NC cycle (4 drive ticks) on an ideal machine.
  void Cycle(int n = 1) {
    for (int k = 0; k < n; ++k) {
      gateway->ReadControls(*ch);
      for (int i = 0; i < 4; ++i) {
        ch->Tick(at, mdt);
        Answer();
      }
      gateway->WriteStatus(*ch, at);
    }
  }
  void Set(const char* name, bool v) { image.SetBool(image.Require(name), v); }
  void SetInt(const char* name, int64_t v) { image.SetInt(image.Require(name), v); }
  bool Get(const char* name) const { return image.Bool(image.Require(name)); }
  int64_t GetInt(const char* name) const { return image.Int(image.Require(name)); }

  nc::ParseResult parsed;
  SignalImage image;
  std::unique_ptr<channel::Channel> ch;
  std::unique_ptr<ChannelGateway> gateway;
};

TEST(ChannelGatewayChangeover, ChangeoverThroughTheSignals) {
  Rig r("N1 G01 C90 F3000\nN2 RET\n");
  r.Set("A03.SPMOD_Q", true);  // power-on: spindle mode
  r.Set("A03C.READY", true);
  r.Set("A04C.READY", true);
  r.Set("P00C.AUTO", true);
  r.Cycle();
  r.Set("P00C.START", true);
  r.Cycle(2);
  // N1 needs rotary axis mode: the changeover from spindle mode has begun.
  ASSERT_TRUE(r.ch->headstock()->busy());
  ASSERT_EQ(r.ch->headstock()->target(), axes::HeadstockMode::kRotary);
  for (int i = 0; i < 200 && !r.Get("A03.ROTMOD"); ++i) r.Cycle();
  ASSERT_TRUE(r.Get("A03.ROTMOD"));
  EXPECT_FALSE(r.Get("A03.SPMOD"));
  // The PLC hunts on the servo (A04's 65012 bit 0); the drive answers in bit 8.
  r.SetInt("A04.AXD.65012", axes::axd::kHunting);
  r.Cycle(3);
  EXPECT_EQ(r.GetInt("A04.AXD.65012"), axes::axd::kHunting | axes::axd::kHuntingAck);
  EXPECT_EQ(r.GetInt("A03.AXD.65012"), 0);
  EXPECT_EQ(r.mdt.setpoints[3].mode, DriveMode::kVelocity);
  EXPECT_NE(r.mdt.setpoints[3].value, 0);
  // The clutch has switched: hunting off (the acknowledgement bit goes), the spindle's enable
  // off, ROTMOD_Q instead of SPMOD_Q.
  r.SetInt("A04.AXD.65012", 0);
  r.Cycle(2);
  EXPECT_EQ(r.GetInt("A04.AXD.65012"), 0);
  r.Set("A03C.READY", false);
  r.Set("A03.SPMOD_Q", false);
  r.Set("A03.ROTMOD_Q", true);
  r.Cycle(2);
  EXPECT_EQ(r.ch->headstock()->mode(), axes::HeadstockMode::kRotary);
  EXPECT_TRUE(r.Get("A03.ROTMOD"));
  EXPECT_EQ(r.mdt.setpoints[2].mode, DriveMode::kOff);
  for (int i = 0; i < 2000 && r.ch->state() == channel::ChannelState::kRunning; ++i) r.Cycle();
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded) << r.ch->error();
  EXPECT_NEAR(r.at.feedback[3].position, 90, 1e-9);
  // Outside the changeover the PLC's requests get no answer.
  r.SetInt("A04.AXD.65012", axes::axd::kSpeedSpec);
  r.Cycle(3);
  EXPECT_EQ(r.GetInt("A04.AXD.65012"), axes::axd::kSpeedSpec);
  // ROTMOD_Q removed in rotary axis mode: error 506 on P00S.ERRNR.
  r.Set("A03.ROTMOD_Q", false);
  r.Cycle(2);
  EXPECT_TRUE(r.Get("P00S.ERROR"));
  EXPECT_EQ(r.GetInt("P00S.ERRNR"), channel::kMsgChangeoverAck);
}

}  // namespace
}  // namespace vmt::control::gateway
