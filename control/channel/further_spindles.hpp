#pragma once
// The channel's spindles besides the main one (lathe-c1's driven tool spindle S2). The main
// spindle S1 has a rotary axis mode, jog keys, an override and M19; a further spindle here is a
// plain speed-controlled spindle, addressed by its index j as the REPOS manual addresses
// spindles ('G77 Sj 0', 4.2): Sj=<rpm> gives its speed, Mj=3 / Mj=4 / Mj=5 its direction or
// stop. The manuals give no syntax for programming a second spindle outside G77; vmt reads the
// index of the S and M addresses as the spindle's, the way G77 Sj=0 does.

#include <string>
#include <vector>

#include "control/drive_bus.hpp"

namespace vmt::control::channel {

/// One further spindle of the channel, from the machine's drives (a spindle drive named Sj).
struct ChannelSpindle {
  int index = 2;  ///< j of Sj (2, 3): 1 and no index address the main spindle
  int drive = -1;
  std::string name;  ///< "S2"
};

/// A further spindle's programmed state: speed and direction (M3 / M4 / M5 of the spindle).
struct FurtherSpindleState {
  double rpm = 0;  ///< the last Sj= value
  int m = 5;       ///< 3, 4 or 5
  /// The drive command: rpm * 6 deg/s, signed by the direction; 0 under M5.
  DriveSetpoint Command() const {
    return {DriveMode::kVelocity, m == 3 ? rpm * 6 : m == 4 ? -rpm * 6 : 0.0, 0};
  }
};

/// A further spindle on the REPOS screen (2.2): every spindle of the channel counts (7.3).
struct ReposFurtherSpindleStatus {
  std::string name;
  double actual_rpm = 0;   ///< signed
  double command_rpm = 0;  ///< before the interruption, signed
  int actual_m = 5;        ///< the M function it runs under now
  int command_m = 5;       ///< the one it had before the interruption
  bool adjust = false;
};

/// The spindle index of an S or M address: "S" and "S1" are the main spindle (1).
inline int SpindleIndex(int address_index) { return address_index == 0 ? 1 : address_index; }

}  // namespace vmt::control::channel
