#include "control/channel/channel_types.hpp"

namespace vmt::control::channel {

const char* ToString(ChannelState s) {
  switch (s) {
    case ChannelState::kIdle:
      return "idle";
    case ChannelState::kRunning:
      return "running";
    case ChannelState::kHold:
      return "hold";
    case ChannelState::kEnded:
      return "ended";
    case ChannelState::kError:
      return "error";
  }
  return "?";
}

const char* ToString(ChannelMode m) {
  switch (m) {
    case ChannelMode::kAutomatic:
      return "automatic";
    case ChannelMode::kManual:
      return "manual";
    case ChannelMode::kMdi:
      return "mdi";
  }
  return "?";
}

}  // namespace vmt::control::channel
