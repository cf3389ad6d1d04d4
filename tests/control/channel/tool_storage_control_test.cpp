// An NC-controlled tool storage axis on its own: stations, the program's traverse the short way
// round, its arrival, PathGuard refusing an index, and a continuous jog that PathGuard stops
// staying stopped until its key is released.

#include "control/channel/tool_storage_control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace vmt::control::channel {
namespace {

constexpr double kDt = 1e-3;

ChannelConfig Turret() {
  ChannelConfig c;
  c.tool_storage_nc = true;
  c.tool_storage_drive = 0;
  c.tool_storage_stations = 12;
  c.tool_storage.name = "T";
  c.tool_storage.rotary = true;  // endless: no travel limits
  c.tool_storage.rapid_per_s = 360;
  c.tool_storage.acceleration = 720;
  return c;
}

/// A guard that lets everything through, recording what it was asked.
struct Recorder {
  std::vector<std::string> moves;
  double stop_jog_beyond = 1e9;  ///< the jog check fails once `to` passes this
  TurretGuard Guard() {
    return {[this](const std::string& move, double, double) {
              moves.push_back(move);
              return true;
            },
            [this](int, double, double to) { return to > stop_jog_beyond; }};
  }
};

TEST(ToolStorageControlTest, StationsAreEvenlySpacedOverATurn) {
  ToolStorageControl t(Turret());
  EXPECT_FALSE(t.StationOf(0));
  EXPECT_DOUBLE_EQ(*t.StationOf(1), 0);
  EXPECT_DOUBLE_EQ(*t.StationOf(4), 90);
  EXPECT_FALSE(t.StationOf(13));
  EXPECT_TRUE(std::isnan(t.command()));  // not taken yet
}

TEST(ToolStorageControlTest, AnIndexGoesTheShortWayAndArrives) {
  ToolStorageControl t(Turret());
  Recorder r;
  // From 350 deg, station 2 (30 deg) is 40 deg ahead, not 320 back.
  ASSERT_TRUE(t.TraverseTo(30, "turret index T2", 350, r.Guard()));
  EXPECT_DOUBLE_EQ(t.axis().target, 390);
  EXPECT_FALSE(t.Arrived(350));
  double actual = 350;
  for (int i = 0; i < 2000 && t.axis().positioning; ++i) {
    t.Cycle(kDt, actual, true, {}, r.Guard());
    actual = t.command();
  }
  EXPECT_FALSE(t.axis().positioning);
  EXPECT_DOUBLE_EQ(t.command(), 390);
  EXPECT_TRUE(t.Arrived(30));  // the same station, a turn on
  EXPECT_FALSE(t.Arrived(31));
  ASSERT_EQ(r.moves.size(), 1u);
  EXPECT_EQ(r.moves[0], "turret index T2");
}

TEST(ToolStorageControlTest, AnIndexPathGuardStopsDoesNotStart) {
  ToolStorageControl t(Turret());
  TurretGuard refuse{[](const std::string&, double, double) { return false; },
                     [](int, double, double) { return false; }};
  EXPECT_FALSE(t.TraverseTo(90, "turret index T4", 0, refuse));
  EXPECT_FALSE(t.axis().positioning);
  t.Cycle(kDt, 0, true, {}, refuse);
  EXPECT_DOUBLE_EQ(t.command(), 0);
}

TEST(ToolStorageControlTest, WithoutTheProcessEnableAnIndexBrakesAndGoesOnLater) {
  ToolStorageControl t(Turret());
  Recorder r;
  ASSERT_TRUE(t.TraverseTo(90, "turret index T4", 0, r.Guard()));
  for (int i = 0; i < 100; ++i) t.Cycle(kDt, t.command(), true, {}, r.Guard());
  const double moving = t.axis().velocity;
  ASSERT_GT(moving, 0);
  for (int i = 0; i < 1000; ++i) t.Cycle(kDt, t.command(), false, {}, r.Guard());
  EXPECT_EQ(t.axis().velocity, 0);
  EXPECT_TRUE(t.axis().positioning);
  for (int i = 0; i < 2000 && t.axis().positioning; ++i)
    t.Cycle(kDt, t.command(), true, {}, r.Guard());
  EXPECT_DOUBLE_EQ(t.command(), 90);
}

TEST(ToolStorageControlTest, AJogPathGuardStopsStaysStoppedUntilTheKeyIsReleased) {
  ToolStorageControl t(Turret());
  Recorder r;
  r.stop_jog_beyond = 45;
  ToolStorageJog jog{true, false, 60, 0};
  ASSERT_TRUE(t.SetKey(1, true));
  t.Cycle(kDt, 0, true, jog, r.Guard());  // taken where it stands
  for (int i = 0; i < 3000; ++i) t.Cycle(kDt, t.command(), true, jog, r.Guard());
  EXPECT_EQ(t.axis().blocked, 1);
  EXPECT_EQ(t.axis().velocity, 0);
  EXPECT_LT(t.command(), 45);  // braked before the place the check refused
  const double stopped_at = t.command();
  for (int i = 0; i < 100; ++i) t.Cycle(kDt, t.command(), true, jog, r.Guard());
  EXPECT_DOUBLE_EQ(t.command(), stopped_at);  // the held key moves nothing
  t.SetKey(0, true);
  t.Cycle(kDt, t.command(), true, jog, r.Guard());
  EXPECT_EQ(t.axis().blocked, 0);
  t.SetKey(-1, true);  // the other way is free
  for (int i = 0; i < 100; ++i) t.Cycle(kDt, t.command(), true, jog, r.Guard());
  EXPECT_LT(t.command(), stopped_at);
}

TEST(ToolStorageControlTest, KeysOutsideManualModeOrForAPlcTurretDoNothing) {
  ToolStorageControl t(Turret());
  EXPECT_FALSE(t.SetKey(1, false));
  EXPECT_EQ(t.axis().key, 0);
  ChannelConfig plc = Turret();
  plc.tool_storage_nc = false;
  ToolStorageControl p(plc);
  EXPECT_FALSE(p.SetKey(1, true));
}

TEST(ToolStorageControlTest, TheSetpointIsInterpolatedBetweenNcCycles) {
  ToolStorageControl t(Turret());
  Recorder r;
  ASSERT_TRUE(t.TraverseTo(90, "turret index T4", 0, r.Guard()));
  for (int i = 0; i < 50; ++i) t.Cycle(kDt, t.command(), true, {}, r.Guard());
  MasterTelegram mdt;
  mdt.setpoints.resize(1);
  t.WriteSetpoint(1.0, mdt);
  EXPECT_EQ(mdt.setpoints[0].mode, DriveMode::kPosition);
  EXPECT_DOUBLE_EQ(mdt.setpoints[0].value, t.command());
  t.WriteSetpoint(0.5, mdt);
  EXPECT_LT(mdt.setpoints[0].value, t.command());
  EXPECT_GT(mdt.setpoints[0].value, t.axis().previous);
}

}  // namespace
}  // namespace vmt::control::channel
