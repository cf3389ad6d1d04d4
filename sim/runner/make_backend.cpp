#include "sim/runner/make_backend.hpp"

#include "sim/kinematic/kinematic_backend.hpp"
#include "sim/physics/physics_backend.hpp"

namespace vmt::sim {

std::unique_ptr<MachineBackend> MakeBackend(BackendKind kind, const MachineModel& model,
                                            const InitialState& init) {
  if (kind == BackendKind::kPhysics) return std::make_unique<PhysicsBackend>(model, init);
  return std::make_unique<KinematicBackend>(model, init);
}

}  // namespace vmt::sim
