#pragma once
#include <string>

#include "sim/model/machine_model.hpp"

namespace vmt::sim {

/// Fills model.links and model.joints from a URDF file (metres, radians) and loads the meshes
/// it names through assimp. Throws ModelError naming the file and the element at fault.
void LoadUrdf(const std::string& urdf_path, MachineModel& model);

}  // namespace vmt::sim
