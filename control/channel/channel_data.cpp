#include "control/channel/channel_data.hpp"

namespace vmt::control::channel {

ChannelData::ChannelData(const ChannelConfig& config)
    : zero_offsets_(config.zero_offsets),
      tools_(config.tools),
      sync_(config.axes, config.spindle_drive, config.spindle),
      guard_(config.path_guard, config.path_guard_every),
      further_(config.spindles),
      headstock_(config.headstock),
      tool_storage_(config),
      measuring_(config) {
  const size_t n = config.axes.size();
  jog_.axes.resize(n);
  out_.commanded.assign(n, 0.0);
  out_.previous = out_.commanded;
  // A JogOfPath channel's output is suspended until the axes are handed to it.
  out_.suspend_requested = out_.suspended = config.output_suspended_at_start;
  frames_.translation.assign(n, 0.0);
  frames_.shift.assign(n, 0.0);
  frames_.homed.resize(n);
  for (size_t a = 0; a < n; ++a) frames_.homed[a] = config.axes[a].homed_at_start;
  sp_.command = {DriveMode::kVelocity, 0, 0};
  sp_.homed = config.spindle.homed_at_start;
  last_modal_ = config.initial;
}

}  // namespace vmt::control::channel
