#include "sim/runner/scene_renderer.hpp"

#include "render/mesh_primitives.hpp"

namespace vmt::sim {

SceneRenderer::SceneRenderer(const MachineModel& model, const Workpiece& workpiece)
    : model_(&model), workpiece_(workpiece) {
  for (const RevolvedSection& section : workpiece.part.sections) {
    if (!workpiece.present) break;
    const double length = section.z1_m - section.z0_m;
    workpiece_meshes_.emplace_back(
        std::make_unique<render::Mesh>(
            section.r_inner_m > 0
                ? render::MakeTube(section.r_inner_m, section.r_outer_m, length, 96)
                : render::MakeCylinder(section.r_outer_m, length, 96)),
        section.z0_m);
  }
}

SceneRenderer::~SceneRenderer() = default;

render::Image SceneRenderer::Render(const std::vector<double>& q, const NamedCamera& camera,
                                    int width, int height) {
  auto& renderer = renderers_[{width, height}];
  if (!renderer) renderer = std::make_unique<render::OffscreenRenderer>(width, height);

  const std::vector<Eigen::Isometry3d> X_WLink = LinkPoses(*model_, q);
  std::vector<render::DrawItem> items;
  for (size_t l = 0; l < model_->links.size(); ++l)
    for (const Visual& v : model_->links[l].visuals)
      items.push_back({v.mesh.get(), X_WLink[l] * v.X_LinkVisual, v.colour});
  for (const auto& [mesh, z_m] : workpiece_meshes_) {
    Eigen::Isometry3d X_LinkPart = Eigen::Isometry3d::Identity();
    X_LinkPart.translation().z() = z_m;
    items.push_back({mesh.get(), X_WLink[model_->LinkIndex(workpiece_.part.link)] * X_LinkPart,
                     workpiece_.colour});
  }
  render::Camera cam;
  cam.eye = camera.eye_m;
  cam.target = camera.target_m;
  cam.up = camera.up;
  cam.fov_y_deg = camera.fov_y_deg;
  return renderer->Draw(cam, items);
}

}  // namespace vmt::sim
