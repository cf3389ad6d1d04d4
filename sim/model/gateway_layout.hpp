#pragma once
// What the gateway's signal table is instantiated for on a machine model: its NC process, the
// NC axes and the main spindle (numbered as the Axx of the signals) and the machine I/O.

#include "control/gateway/signal_table.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

/// The NC axes keep their Cxx numbers; the main spindle takes the next free number.
control::gateway::GatewayLayout GatewayLayoutOf(const MachineModel& model);

}  // namespace vmt::sim
