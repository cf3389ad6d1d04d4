#include "sim/runner/scene_renderer.hpp"

#include "render/mesh_primitives.hpp"

namespace vmt::sim {
namespace {

constexpr int kSegments = 96;  ///< around the spindle axis: smooth at the showcase's sizes

render::Mesh SectionMesh(double r_inner_m, double r_outer_m, double length_m) {
  return r_inner_m > 0 ? render::MakeTube(r_inner_m, r_outer_m, length_m, kSegments)
                       : render::MakeCylinder(r_outer_m, length_m, kSegments);
}

// `part` moved `z_m` along z and appended to `mesh`.
void Append(render::Mesh& mesh, const render::Mesh& part, double z_m) {
  const auto first = static_cast<uint32_t>(mesh.positions.size() / 3);
  for (size_t i = 0; i < part.positions.size(); ++i)
    mesh.positions.push_back(part.positions[i] + (i % 3 == 2 ? static_cast<float>(z_m) : 0.0f));
  mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
  for (const uint32_t index : part.indices) mesh.indices.push_back(first + index);
}

}  // namespace

SceneRenderer::SceneRenderer(const MachineModel& model, const Workpiece& workpiece)
    : model_(&model), workpiece_(workpiece) {
  for (const RevolvedSection& section : workpiece.part.sections) {
    if (!workpiece.present) break;
    workpiece_meshes_.emplace_back(
        std::make_unique<render::Mesh>(
            SectionMesh(section.r_inner_m, section.r_outer_m, section.z1_m - section.z0_m)),
        section.z0_m);
  }
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::UseProfile(const TurnedProfile& turned) {
  if (turned_mesh_ && turned.version == turned_version_) return;
  // The renderers keep what they uploaded by the mesh's address: let them drop the old one.
  if (turned_mesh_)
    for (auto& [size, renderer] : renderers_) renderer->Forget(turned_mesh_.get());
  auto mesh = std::make_unique<render::Mesh>();
  for (const CylinderPart& c : turned.cylinders)
    if (c.radius_m > c.inner_radius_m && c.length_m > 0)  // a slice cut through is no part
      Append(*mesh, SectionMesh(c.inner_radius_m, c.radius_m, c.length_m), c.z_m);
  turned_mesh_ = std::move(mesh);
  turned_version_ = turned.version;
}

render::Image SceneRenderer::Render(const std::vector<double>& q, const NamedCamera& camera,
                                    int width, int height, const TurnedProfile* turned) {
  auto& renderer = renderers_[{width, height}];
  if (!renderer) renderer = std::make_unique<render::OffscreenRenderer>(width, height);

  const std::vector<Eigen::Isometry3d> X_WLink = LinkPoses(*model_, q);
  std::vector<render::DrawItem> items;
  for (size_t l = 0; l < model_->links.size(); ++l)
    for (const Visual& v : model_->links[l].visuals)
      items.push_back({v.mesh.get(), X_WLink[l] * v.X_LinkVisual, v.colour});
  if (workpiece_.present) {
    const Eigen::Isometry3d X_WPart = X_WLink[model_->LinkIndex(workpiece_.part.link)];
    if (turned) {
      UseProfile(*turned);
      if (!turned_mesh_->indices.empty())
        items.push_back({turned_mesh_.get(), X_WPart, workpiece_.colour});
    } else {
      for (const auto& [mesh, z_m] : workpiece_meshes_) {
        Eigen::Isometry3d X_PartSection = Eigen::Isometry3d::Identity();
        X_PartSection.translation().z() = z_m;
        items.push_back({mesh.get(), X_WPart * X_PartSection, workpiece_.colour});
      }
    }
  }
  render::Camera cam;
  cam.eye = camera.eye_m;
  cam.target = camera.target_m;
  cam.up = camera.up;
  cam.fov_y_deg = camera.fov_y_deg;
  return renderer->Draw(cam, items);
}

}  // namespace vmt::sim
