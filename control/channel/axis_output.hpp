#pragma once
// Where the channel commands its axes and whether it holds them: the positions of the last two
// NC cycles (fine interpolation between them to the drive tick), and the hand-over of the feed
// axes to and from a JogOfPath channel (block search 4.2.1), taken at standstill only.

#include <vector>

namespace vmt::control::channel {

struct AxisOutput {
  std::vector<double> commanded, previous;  ///< per channel axis, this and the last NC cycle
  int tick_in_cycle = 0;
  bool holding = false;            ///< once started, the channel owns its axes' setpoints
  bool take_over_pending = false;  ///< own the axes' setpoints from the next tick on
  bool suspend_requested = false;  ///< HLI.channel.SuspendAxisOutput
  bool axes_elsewhere = false;     ///< another channel still holds the axes
  bool suspended = false;          ///< the output is suspended: the axes are lent
};

}  // namespace vmt::control::channel
