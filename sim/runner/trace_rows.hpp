#pragma once
// The trace's rows (trace.csv, and the digest that pins a scene's behaviour): per drive its
// command, position and velocity (rpm for spindles and rotary axes, the parameter set where it
// has several), each clutch's state, and the NC's state and line. Fixed formatting, so that
// the bytes, and so the digest, depend only on the simulation.

#include <string>
#include <vector>

#include "control/channel/channel.hpp"
#include "control/drive_bus.hpp"
#include "sim/backend/dog_clutch.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

/// The header row; `nc`: the run has an NC channel.
std::string TraceHeader(const MachineModel& m, bool nc);
/// The row at time `t`; `channel` null without one.
std::string TraceRow(double t, const MachineModel& m, const control::AmplifierTelegram& at,
                     const control::MasterTelegram& mdt, const std::vector<ClutchState>& clutches,
                     const control::channel::Channel* channel);

}  // namespace vmt::sim
