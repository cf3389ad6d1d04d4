#include "control/channel/jog_of_path.hpp"

#include <cstddef>
#include <vector>

namespace vmt::control::channel {

ChannelConfig JogOfPathConfig(const ChannelConfig& block_search_channel) {
  ChannelConfig c = block_search_channel;
  if (c.headstock && c.rotary_axis >= 0 && static_cast<size_t>(c.rotary_axis) < c.axes.size()) {
    // Without the rotary axis; the tables per channel axis lose its column with it.
    const size_t r = static_cast<size_t>(c.rotary_axis);
    const auto drop = [r](std::vector<double>& per_axis) {
      if (r < per_axis.size()) per_axis.erase(per_axis.begin() + static_cast<std::ptrdiff_t>(r));
    };
    c.axes.erase(c.axes.begin() + static_cast<std::ptrdiff_t>(r));
    for (std::vector<double>& row : c.zero_offsets.g54_to_g59) drop(row);
    for (axes::ToolEdge& edge : c.tools.edges) drop(edge.length);
  }
  c.headstock.reset();
  c.rotary_axis = -1;
  c.spindle_drive = -1;
  c.spindles.clear();
  c.tool_storage_drive = -1;
  c.tool_storage_nc = false;
  c.tool_storage_stations = 0;
  c.aux_handshake = false;
  c.output_suspended_at_start = true;
  c.approach_program = true;
  return c;
}

void HandOverAxes(Channel& block_search_channel, Channel& jog_of_path) {
  jog_of_path.SetSuspendOutput(!(block_search_channel.suspend_output_requested() &&
                                 block_search_channel.output_suspended()));
  block_search_channel.SetAxesElsewhere(!jog_of_path.output_suspended());
  block_search_channel.FollowAxesOf(jog_of_path);
  jog_of_path.FollowAxesOf(block_search_channel);
}

}  // namespace vmt::control::channel
