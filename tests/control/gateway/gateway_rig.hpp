#pragma once
// Shared by the gateway tests of the lathe's X/Z channel: the channel through the gateway on an
// ideal machine (X and Z follow their setpoints), NC cycle by NC cycle, its signals by name.

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/gateway/channel_gateway.hpp"
#include "control/nc/parser.hpp"
#include "tests/control/gateway/lathe_layout.hpp"
#include "tests/support/ideal_drive_bus.hpp"

namespace vmt::control::gateway::testing {

struct GatewayRig : test_support::IdealDriveBus {
  /// X A01 (drive 0), Z A02 (drive 1), main spindle A03 (drive 2). `spindle_at_speed`: the
  /// spindle reaches its commanded speed at once and says so (at speed / standstill).
  /// `configure` may change the channel's parameters before the channel is built.
  explicit GatewayRig(const std::string& program, bool handshake = false,
                      bool spindle_at_speed = false,
                      const std::function<void(channel::ChannelConfig&)>& configure = {})
      : IdealDriveBus(3), image(BuildSignalTable(LatheLayout())) {
    parsed = nc::ParseProgram(program, "p.mtc", nc::Dialect::kMtc200);
    EXPECT_TRUE(parsed.ok());
    channel::ChannelConfig config;
    for (int d = 0; d < 2; ++d) {
      channel::ChannelAxis a;
      a.name = d == 0 ? "X" : "Z";
      a.number = d + 1;
      a.drive = d;
      a.rapid_per_s = 400;
      a.acceleration = 4000;
      config.axes.push_back(a);
    }
    config.spindle_drive = 2;
    config.aux_handshake = handshake;
    if (configure) configure(config);
    ch = std::make_unique<channel::Channel>(config,
                                            std::vector<const nc::Program*>{&parsed.program});
    gateway = std::make_unique<ChannelGateway>(image, 0, std::vector<int>{1, 2}, 3, 2);
    ChannelGateway* gw = gateway.get();
    ch->SetEventSource([gw](int n) { return gw->Event(n); });
    ch->SetEventSink([gw](int n, bool v) { gw->SetEvent(n, v); });
    drives[0] = drives[1] = test_support::IdealDrive::Follow();
    if (spindle_at_speed) drives[2] = test_support::IdealDrive::InstantSpindle();
  }
  // One NC cycle (4 drive ticks).
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
  bool Get(const char* name) const { return image.Bool(image.Require(name)); }
  int64_t GetInt(const char* name) const { return image.Int(image.Require(name)); }
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

}  // namespace vmt::control::gateway::testing
