#include "sim/scene/nc_channel_config.hpp"

#include <string>

#include "sim/backend/machine_backend.hpp"

namespace vmt::sim {

control::channel::ChannelConfig ChannelConfigOf(const MachineModel& m, const NcSetup& nc) {
  control::channel::ChannelConfig config;
  config.axes = nc.data.axes;
  config.process = nc.data.process;
  config.spindle_drive = nc.data.spindle_drive;
  config.spindle = nc.data.spindle;
  if (config.spindle_drive >= 0) {
    // The spindle's limits bound G64's interpolation of it (its spindle set 0).
    const DriveParams& d = m.drives[config.spindle_drive];
    config.spindle.name = d.info.name;
    config.spindle.rapid_per_s = d.parameter_sets.at(0).velocity_limit * kDegPerRad;
    config.spindle.acceleration = d.parameter_sets.at(0).acceleration_limit * kDegPerRad;
  }
  // The further spindles (S2, S3): the machine's other spindle drives, addressed by the
  // index of their name as the REPOS manual addresses them (G77 Sj=0, 4.2).
  for (size_t d = 0; d < m.drives.size(); ++d) {
    const std::string& name = m.drives[d].info.name;
    if (!m.drives[d].spindle || static_cast<int>(d) == config.spindle_drive ||
        name.size() != 2 || name[0] != 'S' || name[1] < '2' || name[1] > '3')
      continue;
    config.spindles.push_back({name[1] - '0', static_cast<int>(d), name});
  }
  config.zero_offsets = nc.data.zero_offsets;
  config.tools = nc.data.tools;
  config.initial = nc.initial;
  config.aux_handshake = nc.aux_handshake;
  config.tick_s = kDriveTickS;
  if (nc.data.rotary_axis >= 0 && nc.data.spindle_drive >= 0) {
    control::axes::HeadstockConfig h;
    h.spindle_drive = nc.data.spindle_drive;
    h.rotary_drive = nc.data.axes[nc.data.rotary_axis].drive;
    h.rotary_parameter_set = static_cast<uint8_t>(nc.data.rotary_parameter_set);
    h.stall_message_s = nc.data.changeover_message_s;
    config.headstock = h;
    config.rotary_axis = nc.data.rotary_axis;
  }
  config.path_guard = nc.data.path_guard;
  config.tool_storage_drive = nc.data.tool_storage_drive;
  config.tool_storage = nc.data.tool_storage;
  config.tool_storage_stations = nc.data.tool_storage_stations;
  config.tool_storage_nc = nc.tool_storage_nc;
  return config;
}

}  // namespace vmt::sim
