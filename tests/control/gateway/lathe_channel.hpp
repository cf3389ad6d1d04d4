#pragma once
// The channel of the lathe of lathe_layout.hpp with its headstock (C-axis manual section 3):
// X A01 (drive 0), Z A02 (drive 1), main spindle S1 A03 (drive 2), C servo A04 (drive 3).

#include "control/channel/channel.hpp"

namespace vmt::control::gateway::testing {

inline channel::ChannelConfig LatheChannel() {
  channel::ChannelConfig config;
  const char* names[] = {"X", "Z", "C"};
  const int numbers[] = {1, 2, 4}, drives[] = {0, 1, 3};
  for (int a = 0; a < 3; ++a) {
    channel::ChannelAxis axis;
    axis.name = names[a];
    axis.number = numbers[a];
    axis.drive = drives[a];
    axis.rotary = a == 2;
    axis.rapid_per_s = 400;
    axis.acceleration = 4000;
    config.axes.push_back(axis);
  }
  config.spindle_drive = 2;
  axes::HeadstockConfig h;
  h.spindle_drive = 2;
  h.rotary_drive = 3;
  config.headstock = h;
  config.rotary_axis = 2;
  return config;
}

}  // namespace vmt::control::gateway::testing
