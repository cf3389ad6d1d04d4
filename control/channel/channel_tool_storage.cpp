// An NC-controlled tool storage axis (REPOS manual 3.4, 4.2 Tool Storage Axis, 6.2): the
// channel commands its drive, jogs it with PxxC.MGPOS / MGNEG in manual mode as the jog mode
// jogs the feed axes - also during repositioning and NC-block restart, where an endless one
// may pass its target - and MTP in the REPOS subroutine traverses it back to its position at
// the interruption. In the program a T word (and MTP outside the REPOS subroutine) indexes it
// to the tool's station, asynchronously to the other axes, and MRY waits for it (4.2: "As in
// NC-program controlled mode, the tool storage axis can sometimes traverse asynchronously").
// A tool storage axis the PLC controls (lathe-c1's turret by default) is the PLC's to move:
// the channel only compares its position (Bxx.045).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "control/channel/channel.hpp"
#include "control/channel/jog_follow.hpp"

namespace vmt::control::channel {

void Channel::JogToolStorage(int direction) {
  if (!config_.tool_storage_nc || mode_ != ChannelMode::kManual) {
    tool_storage_.key = 0;
    return;
  }
  tool_storage_.key = direction > 0 ? 1 : direction < 0 ? -1 : 0;
  if (tool_storage_.key != 0) take_over_pending_ = true;
}

double Channel::tool_storage_command() const {
  return ToolStorageNc() && tool_storage_.taken ? tool_storage_.command
                                                : std::numeric_limits<double>::quiet_NaN();
}

bool Channel::ReturnToolStorage() {
  if (!ToolStorageNc() || !repos_.interruption) return true;
  return TraverseToolStorageTo(repos_.interruption->tool_storage, "turret index MTP");
}

bool Channel::TraverseToolStorageTo(double position, const std::string& move) {
  ToolStorageAxis& t = tool_storage_;
  if (!t.taken) {  // a traverse before the axis' first NC cycle starts where it stands
    t.command = t.previous = drive_positions_[config_.tool_storage_drive];
    t.taken = true;
  }
  // The short way round for an endless axis: the station, not the turns (4.2: the location).
  // One with travel limits goes to the position itself, back the way it came.
  const double target = t.command - ReposDistanceToGo(config_.tool_storage, t.command, position);
  if (!GuardTurretIndex(move, target)) return false;
  t.target = target;
  t.positioning = t.programmed = true;
  t.stepping = false;
  return true;
}

std::optional<double> Channel::StationOf(int tool) const {
  if (config_.tool_storage_stations <= 0 || tool < 1 || tool > config_.tool_storage_stations)
    return std::nullopt;
  return (tool - 1) * 360.0 / config_.tool_storage_stations;
}

bool Channel::IndexToolStorage(int tool, const nc::Program& program, int32_t block) {
  // T0 selects no tool: nothing to index to, the turret stays.
  if (!ToolStorageNc() || config_.tool_storage_stations <= 0 || tool == 0) return true;
  const std::optional<double> station = StationOf(tool);
  if (!station) {
    // Indexing a station T does not name would put another tool at the work than the one
    // whose corrections the block selects.
    Fail(program, block,
         "T" + std::to_string(tool) + " has no station on the tool storage axis " +
             config_.tool_storage.name + " (T1..T" +
             std::to_string(config_.tool_storage_stations) + ")",
         kMsgProgramError);
    return false;
  }
  return TraverseToolStorageTo(*station, "turret index T" + std::to_string(tool));
}

bool Channel::IndexToolStorage(const nc::PreparedBlock& b, const nc::Program& program) {
  if (!ToolStorageNc()) return true;
  // The channel has one tool storage axis: T (index 0) is its tool; indexed addresses belong
  // to tool storages the channel does not have.
  for (const nc::AuxFunction& f : b.aux)
    if (f.letter == 'T' && f.index == 0 &&
        !IndexToolStorage(static_cast<int>(std::lround(f.value)), program, b.block))
      return false;
  return true;
}

bool Channel::ToolStorageArrived() const {
  if (!ToolStorageNc() || !tool_storage_.programmed) return true;
  if (tool_storage_.positioning) return false;
  const double actual = drive_positions_[config_.tool_storage_drive];
  return std::abs(ReposDistanceToGo(config_.tool_storage, tool_storage_.target, actual)) <=
         kToolStorageWindow;
}

bool Channel::TraverseToolStorage(double target, double speed, double dt) {
  ToolStorageAxis& t = tool_storage_;
  const double accel = config_.tool_storage.acceleration > 0 ? config_.tool_storage.acceleration
                                                             : 360;
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

void Channel::ToolStorageCycle(double dt) {
  if (!ToolStorageNc()) return;
  ToolStorageAxis& t = tool_storage_;
  if (!t.taken) {
    t.command = t.previous = drive_positions_[config_.tool_storage_drive];
    t.taken = true;
  }
  t.previous = t.command;
  const axes::AxisParameters& axis = config_.tool_storage;
  if (!process_enable_ && (t.positioning || t.stepping)) {
    // C-axis manual 2.3: without the process enabling signal the axes come to a standstill. An
    // index or increment under way brakes and goes on to its target when the signal is back.
    const double accel = axis.acceleration > 0 ? axis.acceleration : 360;
    t.velocity = t.velocity > 0 ? std::max(0.0, t.velocity - accel * dt)
                                : std::min(0.0, t.velocity + accel * dt);
    t.command += t.velocity * dt;
    return;
  }
  if (t.positioning) {
    // T, MTP: at the jogging rapid speed (4.2: no speed is programmed), braking onto the
    // target. It runs on through a feed hold and in manual mode, as a turret the PLC indexes
    // completes its index: the block that started it has been left, so no hold belongs to it.
    const double rapid = JogRapid(axis) > 0 ? JogRapid(axis) : 90;
    if (TraverseToolStorage(t.target, rapid, dt)) t.positioning = false;
    return;
  }
  // 3.4: "as it would in jog mode" - the channel's jog mode decides, as for the feed axes. No
  // target and no zone stops it (an endless one may pass its target).
  const bool jogging = mode_ == ChannelMode::kManual && process_enable_;
  const double speed = JogSpeed(axis);
  const double increment = JogIncrement(axis);
  if (JogStepping(t.stepping, increment, t.velocity)) {
    // Incremental: a key press starts one increment, which then runs to its end.
    if (!t.stepping && t.key != 0 && jogging) {
      // The increment's sweep is checked whole before it starts, as a feed axis' increment.
      const double target = t.command + t.key * increment;
      if (GuardTurretIndex(t.key > 0 ? "turret index MGPOS" : "turret index MGNEG", target)) {
        t.stepping = true;
        t.programmed = false;
        t.target = target;
      }
      t.key = 0;  // one increment per press
    }
    if (t.stepping && TraverseToolStorage(t.target, speed, dt)) t.stepping = false;
    return;
  }
  // Continuous while a key is held, braking when it is released; the handwheel moves the feed
  // axes only, so there the keys do nothing.
  const bool keys = jogging && jog_.mode != JogMode::kHandwheel && increment == 0;
  const double accel = axis.acceleration > 0 ? axis.acceleration : 360;
  GuardTurretJog(keys ? t.key : 0, dt);
  const double wanted = keys && t.key != t.blocked ? t.key * speed : 0;
  if (wanted != 0) t.programmed = false;
  t.velocity = std::clamp(wanted, t.velocity - accel * dt, t.velocity + accel * dt);
  t.command += t.velocity * dt;
}

void Channel::WriteToolStorage(MasterTelegram& mdt) const {
  if (!ToolStorageNc() || !tool_storage_.taken) return;
  const size_t d = static_cast<size_t>(config_.tool_storage_drive);
  if (d >= mdt.setpoints.size()) return;
  const double f = static_cast<double>(tick_in_cycle_ + 1) / config_.ticks_per_cycle;
  const ToolStorageAxis& t = tool_storage_;
  mdt.setpoints[d] = {DriveMode::kPosition, t.previous + (t.command - t.previous) * f, 0};
}

}  // namespace vmt::control::channel
