// The program's side of an NC-controlled tool storage axis (tool_storage_control.hpp): the T
// words that index it, MTP's return to the interruption's position, MRY's wait, the keys of
// manual mode, and its NC cycle and setpoint with the jog mode's rules and PathGuard's checks.
#include <cmath>
#include <limits>
#include <string>

#include "control/channel/channel.hpp"

namespace vmt::control::channel {

void Channel::JogToolStorage(int direction) {
  if (tool_storage_.SetKey(direction, mode_ == ChannelMode::kManual)) out_.take_over_pending = true;
}

double Channel::tool_storage_command() const {
  return ToolStorageNc() ? tool_storage_.command() : std::numeric_limits<double>::quiet_NaN();
}

TurretGuard Channel::TurretGuardOf() {
  return {[this](const std::string& move, double from, double to) {
            return GuardTurretIndex(move, from, to);
          },
          [this](int direction, double from, double to) {
            return GuardTurretJog(direction, from, to);
          }};
}

bool Channel::ReturnToolStorage() {
  if (!ToolStorageNc() || !repos_.interruption()) return true;
  return tool_storage_.TraverseTo(repos_.interruption()->tool_storage, "turret index MTP",
                                  drive_positions_[config_.tool_storage_drive], TurretGuardOf());
}

bool Channel::IndexToolStorage(int tool, const nc::Program& program, int32_t block) {
  // T0 selects no tool: nothing to index to, the turret stays.
  if (!ToolStorageNc() || config_.tool_storage_stations <= 0 || tool == 0) return true;
  const std::optional<double> station = tool_storage_.StationOf(tool);
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
  return tool_storage_.TraverseTo(*station, "turret index T" + std::to_string(tool),
                                  drive_positions_[config_.tool_storage_drive], TurretGuardOf());
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
  return !ToolStorageNc() || tool_storage_.Arrived(drive_positions_[config_.tool_storage_drive]);
}

void Channel::ToolStorageCycle(double dt) {
  if (!ToolStorageNc()) return;
  // 3.4: the keys jog it "as it would in jog mode": the feed axes' rules decide.
  ToolStorageJog jog;
  jog.keys = mode_ == ChannelMode::kManual && enable_.process;
  jog.handwheel = jog_.mode == JogMode::kHandwheel;
  jog.speed = jog_rules().Speed(config_.tool_storage);
  jog.increment = jog_rules().Increment(config_.tool_storage);
  tool_storage_.Cycle(dt, drive_positions_[config_.tool_storage_drive], enable_.process, jog,
                      TurretGuardOf());
}

}  // namespace vmt::control::channel
