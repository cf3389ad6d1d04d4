#pragma once
// The channel's function for an NC-controlled tool storage axis (REPOS manual 3.4, 4.2, 6.2): its
// command, jogging by PxxC.MGPOS / MGNEG as the jog mode jogs the feed axes, the program's
// traverses (a T word's indexing to the tool's station, MTP back to the interruption's position)
// and the setpoint of its drive. It owns the axis' state; the channel hands it the drive's
// actual position, what its jog mode allows, and PathGuard as two checks, and keeps the program's
// side (errors at a block, MRY's wait).

#include <functional>
#include <optional>
#include <string>

#include "control/axes/axis_parameters.hpp"
#include "control/channel/channel_config.hpp"
#include "control/channel/tool_storage_state.hpp"
#include "control/drive_bus.hpp"

namespace vmt::control::channel {

/// PathGuard as the channel applies it to the tool storage axis (channel_turret_guard.cpp).
struct TurretGuard {
  /// An index from `from` to `to` (deg | mm), checked whole before it starts: false if stopped.
  std::function<bool(const std::string& move, double from, double to)> index;
  /// A continuous jog (`direction` +1 / -1, 0 at rest) that could reach `to` before it stops,
  /// checked ahead as the feed axes' jogs: true if it stopped the jog.
  std::function<bool(int direction, double from, double to)> jog;
};

/// What the channel's jog mode makes of the keys this NC cycle (channel_jog.cpp's rules).
struct ToolStorageJog {
  bool keys = false;       ///< manual mode with the process enabling signal: keys move the axis
  bool handwheel = false;  ///< the handwheel moves the feed axes only: keys do nothing
  double speed = 0;        ///< jogging speed, override applied (deg | mm per s)
  double increment = 0;    ///< one press' distance; 0: continuous while held
};

class ToolStorageControl {
 public:
  explicit ToolStorageControl(const ChannelConfig& config);

  /// NC-controlled (ChannelConfig::tool_storage_nc): the channel commands the drive.
  bool nc() const { return nc_; }
  const ToolStorageAxis& axis() const { return axis_; }

  /// PxxC.MGPOS / MGNEG (+1, -1, 0 released); `manual`: the channel is in manual mode, else the
  /// key is let go. True when a key is pressed: the channel then holds its drives.
  bool SetKey(int direction, bool manual);
  void ReleaseKey() { axis_.key = 0; }
  /// Control-Reset and the program's end: no traverse of the program goes on or is waited for.
  void ForgetProgramTraverse() { axis_.positioning = axis_.programmed = false; }

  /// The command (deg | mm), NaN before the axis is taken.
  double command() const;
  /// Where tool `tool`'s station is (deg, 0 .. 360); nullopt for T0, a tool beyond the stations
  /// or a turret without stations.
  std::optional<double> StationOf(int tool) const;
  /// The program's traverse to `position` for `move` (the word asking for it), from `actual`
  /// if the axis has not been taken yet; an endless axis goes the short way. False if the guard
  /// stopped it before it started.
  bool TraverseTo(double position, const std::string& move, double actual,
                  const TurretGuard& guard);
  /// The program's last traverse has ended and the drive (at `actual`) stands within
  /// kToolStorageWindow of its place; true if the last traverse was a jog's.
  bool Arrived(double actual) const;

  /// One NC cycle of `dt` s: the traverse, the increment or the continuous jog under way.
  void Cycle(double dt, double actual, bool process_enable, const ToolStorageJog& jog,
             const TurretGuard& guard);
  /// The drive's setpoint, `f` of the way from the last NC cycle's command to this one's.
  void WriteSetpoint(double f, MasterTelegram& mdt) const;

 private:
  /// Moves the command towards `target` at most at `speed`, braking onto it; true on arrival.
  bool Traverse(double target, double speed, double dt);
  void Take(double actual);
  double acceleration() const;
  void Jog(double dt, const ToolStorageJog& jog, const TurretGuard& guard);

  bool nc_;
  int drive_;
  axes::AxisParameters parameters_;
  int stations_;
  int guard_every_;  ///< NC cycles between the checks ahead of a continuous jog
  ToolStorageAxis axis_;
};

}  // namespace vmt::control::channel
