// An NC-controlled tool storage axis (REPOS manual 3.4, 4.2 Tool Storage Axis, 6.2). In manual
// mode PxxC.MGPOS / MGNEG jog it as the jog mode jogs the feed axes - also during
// repositioning and NC-block restart, where an endless one may pass its target. In the program a
// T word (and MTP outside the REPOS subroutine) indexes it to the tool's station, asynchronously
// to the other axes (4.2: "As in NC-program controlled mode, the tool storage axis can sometimes
// traverse asynchronously"), and MTP in the REPOS subroutine traverses it back to its position
// at the interruption. A tool storage axis the PLC controls (lathe-c1's turret by default) is the
// PLC's to move; the channel only compares its position (Bxx.045).
#include "control/channel/tool_storage_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/channel/jog_follow.hpp"
#include "control/channel/repositioning.hpp"

namespace vmt::control::channel {

ToolStorageControl::ToolStorageControl(const ChannelConfig& config)
    : nc_(config.tool_storage_nc),
      drive_(config.tool_storage_drive),
      parameters_(config.tool_storage),
      stations_(config.tool_storage_stations),
      guard_every_(config.path_guard_every) {}

bool ToolStorageControl::SetKey(int direction, bool manual) {
  if (!nc_ || !manual) {
    axis_.key = 0;
    return false;
  }
  axis_.key = direction > 0 ? 1 : direction < 0 ? -1 : 0;
  return axis_.key != 0;
}

double ToolStorageControl::command() const {
  return axis_.taken ? axis_.command : std::numeric_limits<double>::quiet_NaN();
}

double ToolStorageControl::acceleration() const {
  return parameters_.acceleration > 0 ? parameters_.acceleration : 360;
}

void ToolStorageControl::Take(double actual) {
  if (axis_.taken) return;
  axis_.command = axis_.previous = actual;
  axis_.taken = true;
}

std::optional<double> ToolStorageControl::StationOf(int tool) const {
  if (stations_ <= 0 || tool < 1 || tool > stations_) return std::nullopt;
  return (tool - 1) * 360.0 / stations_;
}

bool ToolStorageControl::TraverseTo(double position, const std::string& move, double actual,
                                    const TurretGuard& guard) {
  ToolStorageAxis& t = axis_;
  Take(actual);  // a traverse before the axis' first NC cycle starts where it stands
  // The short way round for an endless axis: the station, not the turns (4.2: the location).
  // One with travel limits goes to the position itself, back the way it came.
  const double target = t.command - ReposDistanceToGo(parameters_, t.command, position);
  if (!guard.index(move, t.command, target)) return false;
  t.target = target;
  t.positioning = t.programmed = true;
  t.stepping = false;
  return true;
}

bool ToolStorageControl::Arrived(double actual) const {
  if (!axis_.programmed) return true;
  if (axis_.positioning) return false;
  return std::abs(ReposDistanceToGo(parameters_, axis_.target, actual)) <= kToolStorageWindow;
}

bool ToolStorageControl::Traverse(double target, double speed, double dt) {
  ToolStorageAxis& t = axis_;
  const double accel = acceleration();
  const double step = accel * dt;
  const double to_go = target - t.command;
  const double wanted =
      std::copysign(std::min(speed, std::sqrt(2 * accel * std::abs(to_go))), to_go);
  t.velocity = std::clamp(wanted, t.velocity - step, t.velocity + step);
  if (std::abs(to_go) <= std::abs(t.velocity * dt) + 1e-9) {
    t.command = target;
    t.velocity = 0;
    return true;
  }
  t.command += t.velocity * dt;
  return false;
}

void ToolStorageControl::Cycle(double dt, double actual, bool process_enable,
                               const ToolStorageJog& jog, const TurretGuard& guard) {
  ToolStorageAxis& t = axis_;
  Take(actual);
  t.previous = t.command;
  if (!process_enable && (t.positioning || t.stepping)) {
    // C-axis manual 2.3: without the process enabling signal the axes come to a standstill. An
    // index or increment under way brakes and goes on to its target when the signal is back.
    const double accel = acceleration();
    t.velocity = t.velocity > 0 ? std::max(0.0, t.velocity - accel * dt)
                                : std::min(0.0, t.velocity + accel * dt);
    t.command += t.velocity * dt;
    return;
  }
  if (t.positioning) {
    // T, MTP: at the jogging rapid speed (4.2: no speed is programmed), braking onto the
    // target. It runs on through a feed hold and in manual mode, as a turret the PLC indexes
    // completes its index: the block that started it has been left, so no hold belongs to it.
    const double rapid = JogRapid(parameters_) > 0 ? JogRapid(parameters_) : 90;
    if (Traverse(t.target, rapid, dt)) t.positioning = false;
    return;
  }
  Jog(dt, jog, guard);
}

void ToolStorageControl::Jog(double dt, const ToolStorageJog& jog, const TurretGuard& guard) {
  // 3.4: "as it would in jog mode" - the channel's jog mode decides, as for the feed axes. No
  // target and no zone stops it (an endless one may pass its target).
  ToolStorageAxis& t = axis_;
  if (JogStepping(t.stepping, jog.increment, t.velocity)) {
    // Incremental: a key press starts one increment, which then runs to its end.
    if (!t.stepping && t.key != 0 && jog.keys) {
      // The increment's sweep is checked whole before it starts, as a feed axis' increment.
      const double target = t.command + t.key * jog.increment;
      if (guard.index(t.key > 0 ? "turret index MGPOS" : "turret index MGNEG", t.command, target)) {
        t.stepping = true;
        t.programmed = false;
        t.target = target;
      }
      t.key = 0;  // one increment per press
    }
    if (t.stepping && Traverse(t.target, jog.speed, dt)) t.stepping = false;
    return;
  }
  // Continuous while a key is held, braking when it is released; the handwheel moves the feed
  // axes only, so there the keys do nothing.
  const bool keys = jog.keys && !jog.handwheel && jog.increment == 0;
  const double accel = acceleration();
  const int key = keys ? t.key : 0;
  // A stopped key stays stopped until it is released (or the other way is pressed).
  if (t.blocked != 0 && key != t.blocked) t.blocked = 0;
  const int pressed = key != t.blocked ? key : 0;
  const int direction = pressed != 0 ? pressed : t.velocity > 0 ? 1 : t.velocity < 0 ? -1 : 0;
  // Checked ahead as a feed axis' jog: where the turret would stand if it braked at the next
  // check, having run on (and sped up) for one check interval first while the key is held.
  double ahead = t.command;
  if (direction != 0) {
    const double interval = guard_every_ * dt + dt;
    const double v = pressed == 0 ? std::abs(t.velocity)
                                  : std::min(std::abs(t.velocity) + accel * interval,
                                             std::max(jog.speed, std::abs(t.velocity)));
    ahead += direction * (v * v / (2 * accel) + v * (pressed == 0 ? dt : interval));
  }
  if (guard.jog(direction, t.command, ahead)) t.blocked = pressed != 0 ? pressed : direction;
  const double wanted = keys && t.key != t.blocked ? t.key * jog.speed : 0;
  if (wanted != 0) t.programmed = false;
  t.velocity = std::clamp(wanted, t.velocity - accel * dt, t.velocity + accel * dt);
  t.command += t.velocity * dt;
}

void ToolStorageControl::WriteSetpoint(double f, MasterTelegram& mdt) const {
  if (!axis_.taken || drive_ < 0 || static_cast<size_t>(drive_) >= mdt.setpoints.size()) return;
  mdt.setpoints[drive_] = {DriveMode::kPosition,
                           axis_.previous + (axis_.command - axis_.previous) * f, 0};
}

}  // namespace vmt::control::channel
