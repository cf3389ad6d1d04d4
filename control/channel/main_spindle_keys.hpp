#pragma once
// What the main spindle's manual keys ask of it (C-axis manual 4.2-4.4): M3/M4/M5/M19 and
// homing turn it at its jogging speed, stop it or position it; the jog keys turn it while held
// or move it one increment per press, as the jog mode says. Plain functions of the key and the
// spindle's machine data, so the rules can be tested without a channel; the channel adds the
// enabling signals, the changeover to spindle mode, PathGuard and repositioning's restore.
#include <optional>

#include "control/axes/axis_parameters.hpp"
#include "control/channel/axis_jog.hpp"
#include "control/drive_bus.hpp"

namespace vmt::control::channel {

/// The spindle's command after a key, and what the channel keeps of why.
struct SpindleKeyMove {
  DriveSetpoint command;
  bool jogging = false;      ///< turning because a jog key is held: releasing it brakes
  bool referencing = false;  ///< positioning to establish the reference (M19, homing)
};

/// M3 / M4 at the spindle's jogging speed, M5 to a stop, M19 to its jogging spindle position;
/// nothing for any other number.
std::optional<SpindleKeyMove> SpindleMKey(int m, const axes::AxisParameters& spindle);

/// Homing (AxxC.HOME): to the reference position, establishing the reference there.
SpindleKeyMove SpindleHomeKey(const axes::AxisParameters& spindle);

/// A jog key pressed (`direction` +1, -1) with the spindle at `position` deg: continuous and
/// rapid modes turn it at its jogging speed (its rapid one), the increments and the parametric
/// distance position it that many degrees on; nothing in handwheel mode, where keys move no axis.
std::optional<SpindleKeyMove> SpindleJogKey(int direction, const JogRules& rules, double position,
                                            const axes::AxisParameters& spindle);

}  // namespace vmt::control::channel
