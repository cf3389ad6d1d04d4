#pragma once
// The NC-controlled tool storage axis of the channel tests (REPOS manual 3.4, 4.2, 6.2): the
// ideal machine of channel_test_support.hpp with a 12-station endless turret on drive 3, whose
// parametric jogging distance is one station, as lathe-c1's turret (`nc: tool_storage_nc`).
// Shared by the jog, repositioning and program tests of the tool storage axis.

#include <functional>
#include <string>

#include "channel_test_support.hpp"
#include "control/channel/channel.hpp"

namespace vmt::control::channel::testing {

/// The turret's configuration: NC-controlled, endless, 12 stations, jogging 30 deg/s, rapid
/// 180 deg/s, 720 deg/s^2; Bxx.045 `bxx045`.
inline void NcTurret(ChannelConfig& c, bool bxx045 = true) {
  c.tool_storage_drive = 3;
  c.tool_storage_nc = true;
  c.tool_storage.name = "T";
  c.tool_storage.rotary = true;  // no travel limits: endless
  c.tool_storage.jog_per_s = 30;
  c.tool_storage.jog_rapid_per_s = 180;
  c.tool_storage.jog_distance = 30;
  c.tool_storage.acceleration = 720;
  c.tool_storage_stations = 12;
  c.process.reposition_tool_storage = bxx045;
}

/// The channel with the turret (NcTurret, then `configure`) standing at `turret` deg.
struct NcTurretMachine : Machine {
  explicit NcTurretMachine(const std::string& program, double turret = 60, bool bxx045 = true,
                           const std::function<void(ChannelConfig&)>& configure = {})
      : Machine(program, 0, 0, [&](ChannelConfig& c) {
          NcTurret(c, bxx045);
          if (configure) configure(c);
        }) {
    Resize(4);  // the turret answers only in TickAll: Tick() holds it back
    at.feedback[3].position = turret;
  }
  /// One drive tick; the turret follows its setpoint.
  void TickAll() {
    Tick();
    Answer(3, test_support::IdealDrive::Follow());
  }
  void RunFor(double s) {
    for (int i = 0; i < s / 250e-6; ++i) TickAll();
  }
  double T() const { return at.feedback[3].position; }
};

}  // namespace vmt::control::channel::testing
