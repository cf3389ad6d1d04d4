#pragma once
// The channel as PathGuard's client: the guard it asks, the checks it made, and the continuous
// jogs it checks ahead as they run (channel_path_guard.cpp, channel_turret_guard.cpp).

#include <optional>
#include <vector>

#include "control/channel/channel_types.hpp"
#include "control/path_guard.hpp"

namespace vmt::control::channel {

struct GuardedMoves {
  PathGuard* guard = nullptr;        ///< null: no geometry to check against
  std::vector<GuardRecord> records;  ///< the checks since the last TakeGuardRecords
  /// A continuous jog of the feed axes, of X1/Y1 and of the turret being checked, each summed
  /// up as one record; NC cycles until each is checked ahead again.
  std::optional<GuardRecord> jog, turret_jog;
  int jog_countdown = 0, fictive_jog_countdown = 0, turret_jog_countdown = 0;
};

}  // namespace vmt::control::channel
