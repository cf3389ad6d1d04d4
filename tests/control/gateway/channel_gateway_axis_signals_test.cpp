// The axis signals of the C-axis manual's table (4.2) that the NC derives from an axis' drive and
// switches: waypoints WP0..7, the position strobe STRBP, the safety limit switch OTRVL, the
// thermal protection switch MTAS, and the spindle drive's threshold status MD_MDX, P_PX, LOAD90.

#include <gtest/gtest.h>

#include "control/channel/channel_messages.hpp"
#include "control/gateway/channel_gateway.hpp"
#include "tests/control/gateway/gateway_rig.hpp"

namespace vmt::control::gateway {
namespace {

using Rig = testing::GatewayRig;

double Real(const Rig& r, const char* name) { return r.image.Real(r.image.Require(name)); }

// 4.2 / 2.2: WPn shows the axis at or beyond its waypoint Cxx.025+n; a waypoint not set never
// shows.
TEST(ChannelGatewayAxisSignals, WaypointsFollowTheActualPosition) {
  Rig r("N1 G00 X20\nN2 M00\nN3 G00 X60\nN4 M00\nN5 G00 X5\nN6 RET\n", false, false,
        [](channel::ChannelConfig& c) {
          c.axes[0].waypoints[0] = 10;
          c.axes[0].waypoints[1] = 50;
        });
  r.Cycle();
  EXPECT_FALSE(r.Get("A01S.WP0"));
  r.Press("P00C.START");
  r.Cycle(500);
  ASSERT_EQ(r.ch->state(), channel::ChannelState::kHold);  // at M00, X at 20
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 20);
  EXPECT_TRUE(r.Get("A01S.WP0"));
  EXPECT_FALSE(r.Get("A01S.WP1"));
  EXPECT_FALSE(r.Get("A01S.WP2"));  // not set
  EXPECT_FALSE(r.Get("A02S.WP0"));  // Z has none
  r.Press("P00C.START");
  r.Cycle(500);
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 60);
  EXPECT_TRUE(r.Get("A01S.WP0"));
  EXPECT_TRUE(r.Get("A01S.WP1"));
  r.Press("P00C.START");
  r.Cycle(500);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded);
  EXPECT_FALSE(r.Get("A01S.WP0"));
  EXPECT_FALSE(r.Get("A01S.WP1"));
}

// 4.2: "The waypoint signals only become valid after homing has been completed."
TEST(ChannelGatewayAxisSignals, WaypointsWaitForTheReference) {
  Rig r("N1 G74 Z0\nN2 RET\n", false, false, [](channel::ChannelConfig& c) {
    c.axes[1].homed_at_start = false;
    c.axes[1].reference_position = 30;
    c.axes[1].waypoints[3] = -1000;  // every position of Z lies beyond it
  });
  r.Cycle(5);
  EXPECT_FALSE(r.Get("A02S.HOMED"));
  EXPECT_FALSE(r.Get("A02S.WP3"));
  r.Press("P00C.START");
  r.Cycle(2000);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded);
  EXPECT_TRUE(r.Get("A02S.HOMED"));
  EXPECT_TRUE(r.Get("A02S.WP3"));
}

// A spindle's waypoints are angles within the turn: its position counts modulo 360 (4.2: the
// NC updates them in main spindle mode too).
TEST(ChannelGatewayAxisSignals, SpindleWaypointsAreWithinTheTurn) {
  Rig r("N1 RET\n", false, false, [](channel::ChannelConfig& c) { c.spindle.waypoints[7] = 90; });
  const double positions[] = {80, 90, 359.5, 360 + 45, 720 + 95, -200, -300};
  const bool passed[] = {false, true, true, false, true, true, false};
  for (size_t k = 0; k < std::size(positions); ++k) {
    r.at.feedback[2].position = positions[k];
    r.Cycle();
    EXPECT_EQ(r.Get("A03S.WP7"), passed[k]) << positions[k];
  }
}

// 4.2: "The position strobe signal causes the NC to save the current position": the rising
// edge saves the actual position, which stays until the next edge.
TEST(ChannelGatewayAxisSignals, PositionStrobeSavesTheActualPosition) {
  Rig r("N1 G00 X20 Z-7.5\nN2 M00\nN3 G00 X60\nN4 RET\n");
  r.Cycle();
  r.Press("P00C.START");
  r.Cycle(500);
  ASSERT_EQ(r.ch->state(), channel::ChannelState::kHold);
  EXPECT_DOUBLE_EQ(Real(r, "A01S.STRBPOS"), 0);
  r.Press("A01C.STRBP");
  r.Press("A02C.STRBP");
  EXPECT_DOUBLE_EQ(Real(r, "A01S.STRBPOS"), 20);
  EXPECT_DOUBLE_EQ(Real(r, "A02S.STRBPOS"), -7.5);
  // Held on: the edge counts, not the level.
  r.Set("A01C.STRBP", true);
  r.Cycle();
  r.Press("P00C.START");
  r.Cycle(500);
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 60);
  EXPECT_DOUBLE_EQ(Real(r, "A01S.STRBPOS"), 20);
  r.Set("A01C.STRBP", false);
  r.Cycle();
  r.Press("A01C.STRBP");
  EXPECT_DOUBLE_EQ(Real(r, "A01S.STRBPOS"), 60);
}

// 4.2: "The homing signal initiates homing like it does for the remaining axes": in manual
// mode the axis travels to its reference point as G74 takes it, and is homed on arrival.
TEST(ChannelGatewayAxisSignals, HomeKeyHomesTheAxis) {
  Rig r("N1 G00 Z10\nN2 RET\n", false, false, [](channel::ChannelConfig& c) {
    c.axes[1].homed_at_start = false;
    c.axes[1].reference_position = 30;
    c.axes[1].homing_per_s = 100;
  });
  r.Cycle();
  // Not homed: the program refuses to move Z (message 501).
  r.Press("P00C.START");
  r.Cycle(10);
  EXPECT_EQ(r.GetInt("P00S.ERRNR"), channel::kMsgNotHomed);
  r.Press("P00C.RESET");
  // In automatic mode the key does nothing.
  r.Press("A02C.HOME");
  r.Cycle(100);
  EXPECT_EQ(r.at.feedback[1].position, 0);
  r.Press("P00C.MANU");
  // Without the axis enabling signal it does nothing either.
  r.Set("A02C.ENABL", true);
  r.Cycle();
  r.Set("A02C.ENABL", false);
  r.Press("A02C.HOME");
  r.Cycle(100);
  EXPECT_EQ(r.at.feedback[1].position, 0);
  r.Set("A02C.ENABL", true);
  r.Press("A02C.HOME");
  r.Cycle(100);  // 0.1 s at 100 mm/s: under way
  EXPECT_TRUE(r.Get("A02S.MVPOS"));
  EXPECT_FALSE(r.Get("A02S.HOMED"));
  EXPECT_GT(r.at.feedback[1].position, 0);
  EXPECT_LT(r.at.feedback[1].position, 30);
  r.Cycle(400);
  EXPECT_DOUBLE_EQ(r.at.feedback[1].position, 30);
  EXPECT_TRUE(r.Get("A02S.HOMED"));
  EXPECT_FALSE(r.Get("A02S.MVPOS"));
  EXPECT_EQ(r.at.feedback[0].position, 0);  // X is not homed by Z's key
  // Homed, the program runs.
  r.Press("P00C.AUTO");
  r.Press("P00C.START");
  r.Cycle(500);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(r.at.feedback[1].position, 10);
}

// A safety limit switch that opens during a move: immediate stop, message 508 to the PLC;
// Control-Reset clears it and the axis can be jogged off the switch.
TEST(ChannelGatewayAxisSignals, SafetyLimitSwitchStopsTheChannel) {
  Rig r("N1 G01 X100 F3000\nN2 RET\n");
  r.Set("A01C.OTRVL", true);
  r.Set("A02C.OTRVL", true);
  r.Cycle();
  r.Press("P00C.START");
  r.Cycle(300);
  ASSERT_TRUE(r.Get("P00S.RUN"));
  r.Set("A01C.OTRVL", false);
  r.Cycle();
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kError);
  EXPECT_TRUE(r.Get("P00S.ERROR"));
  EXPECT_EQ(r.GetInt("P00S.ERRNR"), channel::kMsgSafetyLimitSwitch);
  EXPECT_NE(r.ch->error().find("axis X (A01): safety limit switch"), std::string::npos)
      << r.ch->error();
  const double stopped = r.at.feedback[0].position;
  EXPECT_GT(stopped, 0);
  EXPECT_LT(stopped, 100);
  r.Cycle(200);
  EXPECT_EQ(r.at.feedback[0].position, stopped);
  EXPECT_FALSE(r.Get("A01S.MVPOS"));
  // Control-Reset, then the operator jogs X back off the switch, which closes again.
  r.Press("P00C.RESET");
  EXPECT_FALSE(r.Get("P00S.ERROR"));
  r.Press("P00C.MANU");
  r.Set("A01C.JGNEG", true);
  r.Cycle(100);
  EXPECT_LT(r.at.feedback[0].position, stopped);
  r.Set("A01C.JGNEG", false);
  r.Set("A01C.OTRVL", true);
  r.Cycle(100);
  EXPECT_FALSE(r.Get("P00S.ERROR"));
}

// The switch stops a jog too, and a key held on moves nothing until it is pressed again.
TEST(ChannelGatewayAxisSignals, SafetyLimitSwitchStopsAJog) {
  Rig r("N1 RET\n");
  r.Set("A02C.OTRVL", true);
  r.Press("P00C.MANU");
  r.Set("A02C.JGPOS", true);
  r.Cycle(100);
  ASSERT_TRUE(r.Get("A02S.MVPOS"));
  r.Set("A02C.OTRVL", false);
  r.Cycle();
  const double stopped = r.at.feedback[1].position;
  r.Cycle(100);
  EXPECT_EQ(r.at.feedback[1].position, stopped);
  EXPECT_EQ(r.GetInt("P00S.ERRNR"), channel::kMsgSafetyLimitSwitch);
  r.Press("P00C.RESET");
  r.Cycle(100);
  EXPECT_EQ(r.at.feedback[1].position, stopped);
}

// The main spindle's thermal protection switch: the spindle is stopped with the channel.
TEST(ChannelGatewayAxisSignals, ThermalProtectionSwitchStopsTheSpindle) {
  Rig r("N1 M03 S1000\nN2 G01 X100 F300\nN3 RET\n", false, true);
  r.Set("A03C.MTAS", true);
  r.Cycle();
  r.Press("P00C.START");
  r.Cycle(300);
  ASSERT_EQ(r.mdt.setpoints[2].mode, DriveMode::kVelocity);
  ASSERT_GT(r.mdt.setpoints[2].value, 0);
  r.Set("A03C.MTAS", false);
  r.Cycle();
  EXPECT_EQ(r.GetInt("P00S.ERRNR"), channel::kMsgThermalSwitch);
  EXPECT_NE(r.ch->error().find("spindle S1 (A03): thermal protection switch"), std::string::npos)
      << r.ch->error();
  EXPECT_EQ(r.mdt.setpoints[2].mode, DriveMode::kVelocity);
  EXPECT_EQ(r.mdt.setpoints[2].value, 0);
}

// A PLC that never writes the switches (they read 0 from the start) leaves the axes working.
TEST(ChannelGatewayAxisSignals, UnwrittenSwitchesStopNothing) {
  Rig r("N1 G01 X100 F3000\nN2 RET\n");
  r.Cycle();
  r.Press("P00C.START");
  r.Cycle(3000);
  EXPECT_EQ(r.ch->state(), channel::ChannelState::kEnded);
  EXPECT_DOUBLE_EQ(r.at.feedback[0].position, 100);
}

// MD_MDX, P_PX and LOAD90 show the spindle drive's threshold status bits.
TEST(ChannelGatewayAxisSignals, SpindleThresholdStatusFromTheDrive) {
  Rig r("N1 RET\n");
  const struct {
    uint32_t bit;
    const char* signal;
  } bits[] = {{drive_status::kTorqueThreshold, "A03S.MD_MDX"},
              {drive_status::kPowerThreshold, "A03S.P_PX"},
              {drive_status::kLoad90, "A03S.LOAD90"}};
  for (const auto& b : bits) {
    r.at.feedback[2].status = drive_status::kReady | b.bit;
    r.Cycle();
    for (const auto& other : bits) EXPECT_EQ(r.Get(other.signal), &other == &b) << other.signal;
  }
  r.at.feedback[2].status = drive_status::kReady;
  r.Cycle();
  for (const auto& b : bits) EXPECT_FALSE(r.Get(b.signal));
}

}  // namespace
}  // namespace vmt::control::gateway
