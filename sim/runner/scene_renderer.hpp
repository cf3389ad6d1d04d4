#pragma once
// Pictures of a machine state: the model's visuals (and the workpiece) posed by the joint
// positions, drawn by render/. Keeps one renderer per picture size.

#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "render/image.hpp"
#include "render/mesh.hpp"
#include "render/offscreen_renderer.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {

class SceneRenderer {
 public:
  SceneRenderer(const MachineModel& model, const Workpiece& workpiece);
  ~SceneRenderer();
  render::Image Render(const std::vector<double>& joint_positions, const NamedCamera& camera,
                       int width, int height);

 private:
  const MachineModel* model_;
  Workpiece workpiece_;
  /// One mesh per section of the workpiece, with where it starts along the link's z.
  std::vector<std::pair<std::unique_ptr<render::Mesh>, double>> workpiece_meshes_;
  std::map<std::pair<int, int>, std::unique_ptr<render::OffscreenRenderer>> renderers_;
};

}  // namespace vmt::sim
