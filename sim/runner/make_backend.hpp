#pragma once
// The machine backend a run steps, of the kind the scene (or the command line) names.

#include <memory>

#include "sim/backend/machine_backend.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {

std::unique_ptr<MachineBackend> MakeBackend(BackendKind kind, const MachineModel& model,
                                            const InitialState& init);

}  // namespace vmt::sim
