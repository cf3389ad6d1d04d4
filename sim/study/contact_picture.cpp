#include "sim/study/contact_picture.hpp"

#include <cmath>
#include <memory>
#include <set>
#include <stdexcept>

#include "render/mesh_primitives.hpp"
#include "render/offscreen_renderer.hpp"
#include "sim/study/study_conclusions.hpp"

namespace vmt::sim::study {
namespace {

// Colours no model part has (lathe-c1's probe is red, its inserts gold): the two parts that
// meet, and the contact point.
constexpr render::Rgba kMet{0.92f, 0.10f, 0.80f, 1.0f};
constexpr render::Rgba kMarker{0.0f, 0.85f, 1.0f, 1.0f};

// The axes at the contact (machine units) onto the joints they drive.
void PoseAtContact(const MachineModel& m, const CaseResult& r, std::vector<double>& q) {
  const auto& at = Field(r, "contact_position");
  if (!at.is_object()) return;
  for (const auto& [axis, v] : at.items()) {
    if (!v.is_number()) continue;
    for (const DriveParams& d : m.drives) {
      if (d.info.name != axis) continue;
      const double si =
          v.get<double>() / (d.info.kind == control::AxisKind::kRotary ? kDegPerRad : kMmPerM);
      if (d.motor_joint >= 0 && d.motor_joint < static_cast<int>(q.size()))
        q[d.motor_joint] = si * d.ratio;
      if (d.load_joint >= 0 && d.load_joint < static_cast<int>(q.size())) q[d.load_joint] = si;
    }
  }
}

// A part that turns with a spindle (a chuck jaw) is checked as the ring it sweeps while the
// spindle turns, so the contact may lie where the part is not now: the spindle is turned until
// the part's centre faces the contact point about the spindle's axis.
void TurnToContact(const MachineModel& m, const std::set<std::string>& met,
                   const Eigen::Vector3d& point_m, std::vector<double>& q) {
  const std::vector<Eigen::Isometry3d> X_WLink = LinkPoses(m, q);
  for (size_t l = 0; l < m.links.size(); ++l) {
    const int j = m.links[l].parent_joint;
    if (j < 0 ||
        (m.joints[j].type != JointType::kRevolute && m.joints[j].type != JointType::kContinuous))
      continue;
    for (const Visual& v : m.links[l].visuals) {
      if (!met.count(v.name) || !v.mesh || v.mesh->positions.size() < 3) continue;
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      const size_t n = v.mesh->positions.size() / 3;
      for (size_t i = 0; i < n; ++i)
        centre += Eigen::Vector3d(v.mesh->positions[3 * i], v.mesh->positions[3 * i + 1],
                                  v.mesh->positions[3 * i + 2]);
      centre = X_WLink[l] * v.X_LinkVisual * (centre / static_cast<double>(n));
      const Joint& joint = m.joints[j];
      const Eigen::Isometry3d X_WJoint = X_WLink[joint.parent_link] * joint.X_ParentJoint;
      const Eigen::Vector3d axis = (X_WJoint.linear() * joint.axis).normalized();
      const Eigen::Vector3d o = X_WJoint.translation();
      const auto radial = [&](const Eigen::Vector3d& p) {
        const Eigen::Vector3d d = p - o;
        return Eigen::Vector3d(d - d.dot(axis) * axis);
      };
      const Eigen::Vector3d from = radial(centre), to = radial(point_m);
      if (from.norm() < 1e-6 || to.norm() < 1e-6) continue;
      q[j] += std::atan2(axis.dot(from.cross(to)), from.dot(to));
      return;
    }
  }
}

}  // namespace

render::Image ContactImage(const Scene& scene, const ContactStage& stage, const CaseResult& r,
                           const SnapshotSpec& look) {
  const MachineModel& m = *scene.model;
  const NamedCamera* named = scene.Camera(look.camera);
  if (!named) throw std::runtime_error("the scene has no camera " + look.camera);
  std::set<std::string> met;
  if (Field(r, "parts").is_array())
    for (const auto& p : Field(r, "parts"))
      if (p.is_string()) met.insert(p.get<std::string>());

  std::vector<double> q = stage.joints;
  q.resize(m.joints.size(), 0.0);
  PoseAtContact(m, r, q);
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();
  const auto& p = Field(r, "point");
  const bool marked =
      p.is_array() && p.size() == 3 && p[0].is_number() && p[1].is_number() && p[2].is_number();
  if (marked) {
    point_m = Eigen::Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>()) / kMmPerM;
    TurnToContact(m, met, point_m, q);
  }
  const std::vector<Eigen::Isometry3d> X_WLink = LinkPoses(m, q);
  std::vector<render::DrawItem> items;
  for (size_t l = 0; l < m.links.size(); ++l)
    for (const Visual& v : m.links[l].visuals)
      items.push_back(
          {v.mesh.get(), X_WLink[l] * v.X_LinkVisual, met.count(v.name) ? kMet : v.colour});

  // The workpiece: as turned, else as the scene gives it.
  std::vector<std::unique_ptr<render::Mesh>> meshes;
  const auto add = [&](const std::string& link, double r_in, double r_out, double z, double len,
                       const std::string& name) {
    const int li = m.LinkIndex(link);
    if (li < 0 || len <= 0 || r_out <= 0) return;
    meshes.push_back(std::make_unique<render::Mesh>(
        r_in > 0 ? render::MakeTube(r_in, r_out, len, 96) : render::MakeCylinder(r_out, len, 96)));
    Eigen::Isometry3d X_LinkPart = Eigen::Isometry3d::Identity();
    X_LinkPart.translation().z() = z;
    const bool hit = met.count(name) || met.count(scene.workpiece.part.name);
    items.push_back(
        {meshes.back().get(), X_WLink[li] * X_LinkPart, hit ? kMet : scene.workpiece.colour});
  };
  if (!stage.stock.empty()) {
    for (const CylinderPart& c : stage.stock)
      add(c.link, c.inner_radius_m, c.radius_m, c.z_m, c.length_m, c.name);
  } else if (scene.workpiece.present) {
    for (const RevolvedSection& s : scene.workpiece.part.sections)
      add(scene.workpiece.part.link, s.r_inner_m, s.r_outer_m, s.z0_m, s.z1_m - s.z0_m,
          scene.workpiece.part.name);
  }

  // A cross of three bars at the contact point, 40 mm across: half of it may be inside a part.
  if (marked) {
    const double a = 0.02, t = 0.0015;
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Vector3d half(t, t, t);
      half[axis] = a;
      meshes.push_back(std::make_unique<render::Mesh>(render::MakeBox(-half, half)));
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.translation() = point_m;
      items.push_back({meshes.back().get(), X, kMarker});
    }
  }

  // The scene's camera, moved along with its target onto the contact point.
  render::Camera cam;
  const Eigen::Vector3d shift =
      marked ? Eigen::Vector3d(point_m - named->target_m) : Eigen::Vector3d::Zero();
  cam.eye = named->eye_m + shift;
  cam.target = named->target_m + shift;
  cam.up = named->up;
  cam.fov_y_deg = named->fov_y_deg;
  render::OffscreenRenderer renderer(look.width, look.height);
  return renderer.Draw(cam, items);
}

}  // namespace vmt::sim::study
