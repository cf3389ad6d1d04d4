#pragma once
// The NC channel's constant configuration, built from the machine and the scene's `nc:` choices
// as the scene loads, so that every run of the scene starts its channel from the same data.

#include "control/channel/channel_config.hpp"
#include "sim/model/machine_model.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {

/// The channel of `nc` on `m`: axes, spindles (the further ones Sj by their drives' names S2,
/// S3), offsets, tools, start-up state, headstock, PathGuard and tool storage axis.
control::channel::ChannelConfig ChannelConfigOf(const MachineModel& m, const NcSetup& nc);

}  // namespace vmt::sim
