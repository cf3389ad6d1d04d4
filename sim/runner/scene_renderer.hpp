#pragma once
// Pictures of a machine state: the model's visuals (and the workpiece) posed by the joint
// positions, drawn by render/. Keeps one renderer per picture size.
//
// The workpiece is drawn as the scene made it, or -- given the stock cutter's profile at the
// picture's tick -- as turned: the same cylinders PathGuard checks against (the solid core per
// run of slices, the bored sections as tubes). Its mesh is built once per profile version, so
// a series of pictures between two cuts shares one.

#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "render/image.hpp"
#include "render/mesh.hpp"
#include "render/offscreen_renderer.hpp"
#include "sim/collision/collision_world.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {

/// The workpiece as turned: the stock cutter's cylinders (TurnedStock::Cylinders, in the
/// workpiece link's frame) and a version that changes whenever they do (the run's count of
/// cuts).
struct TurnedProfile {
  int64_t version = 0;
  std::vector<CylinderPart> cylinders;
};

class SceneRenderer {
 public:
  SceneRenderer(const MachineModel& model, const Workpiece& workpiece);
  ~SceneRenderer();
  /// `turned` (may be null: the part as the scene made it) draws the workpiece as turned.
  render::Image Render(const std::vector<double>& joint_positions, const NamedCamera& camera,
                       int width, int height, const TurnedProfile* turned = nullptr);

 private:
  void UseProfile(const TurnedProfile& turned);

  const MachineModel* model_;
  Workpiece workpiece_;
  /// One mesh per section of the workpiece, with where it starts along the link's z.
  std::vector<std::pair<std::unique_ptr<render::Mesh>, double>> workpiece_meshes_;
  /// The turned profile's cylinders in one mesh (link frame), and the version it shows.
  std::unique_ptr<render::Mesh> turned_mesh_;
  int64_t turned_version_ = -1;
  std::map<std::pair<int, int>, std::unique_ptr<render::OffscreenRenderer>> renderers_;
};

}  // namespace vmt::sim
