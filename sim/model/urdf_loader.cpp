#include "sim/model/urdf_loader.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "common/input_file.hpp"
#include "render/mesh_primitives.hpp"
#include "sim/model/mesh_loader.hpp"
#include "sim/model/model_error.hpp"
#include "sim/model/nesting_depth.hpp"

namespace vmt::sim {
namespace {

// urdfdom reports its parse errors through console_bridge; collect them for our message
// instead of letting them go to stderr out of context.
class CollectingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN)
      messages += (messages.empty() ? "" : "; ") + text;
  }
  std::string messages;
};

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  X.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  return X;
}

// A machine fits in a room: origins beyond 100 m, a mesh scale outside 1e-6..1000 or a limit
// beyond 1000 (m or rad) are typos, and huge numbers stall the mesh and collision code.
constexpr double kMaxOriginM = 100, kMaxJointLimit = 1000;

void RequireSensiblePose(const std::string& urdf_path, const std::string& where,
                         const urdf::Pose& pose) {
  const urdf::Vector3& p = pose.position;
  for (const double v : {p.x, p.y, p.z})
    if (!(std::abs(v) <= kMaxOriginM))
      throw ModelError(urdf_path, where, "<origin xyz> must be within +-100 m");
  const urdf::Rotation& r = pose.rotation;
  for (const double v : {r.x, r.y, r.z, r.w})
    if (!std::isfinite(v)) throw ModelError(urdf_path, where, "<origin rpy> must be finite");
}

Primitive ToPrimitive(const std::string& urdf_path, const std::string& where,
                      const urdf::Geometry& geometry) {
  // As big as a machine gets, and no flat or empty solid.
  auto size = [&](double v, const char* what) {
    if (!(v > 0 && v <= kMaxOriginM))
      throw ModelError(urdf_path, where, std::string(what) + " must be > 0 and at most 100 m");
    return v;
  };
  Primitive p;
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const urdf::Vector3& dim = static_cast<const urdf::Box&>(geometry).dim;
      p.kind = Primitive::Kind::kBox;
      p.box_m = {size(dim.x, "<box size>"), size(dim.y, "<box size>"), size(dim.z, "<box size>")};
      return p;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(geometry);
      p.kind = Primitive::Kind::kCylinder;
      p.radius_m = size(c.radius, "<cylinder radius>");
      p.length_m = size(c.length, "<cylinder length>");
      return p;
    }
    case urdf::Geometry::SPHERE:
      p.kind = Primitive::Kind::kSphere;
      p.radius_m = size(static_cast<const urdf::Sphere&>(geometry).radius, "<sphere radius>");
      return p;
    default:
      throw ModelError(urdf_path, where,
                       "geometry not supported (a <mesh>, <box>, <cylinder> or <sphere> is)");
  }
}

/// The primitive's surface for the pictures (and the cutting parts' corners): fine enough that
/// a facet's sag stays below 0.2 % of the radius.
render::Mesh PrimitiveMesh(const Primitive& p) {
  constexpr int kSegments = 48;
  switch (p.kind) {
    case Primitive::Kind::kBox:
      return render::MakeBox(-p.box_m / 2, p.box_m / 2);
    case Primitive::Kind::kCylinder: {
      render::Mesh mesh = render::MakeCylinder(p.radius_m, p.length_m, kSegments);
      // MakeCylinder runs from z = 0; URDF's cylinder is centred on its origin.
      for (size_t i = 2; i < mesh.positions.size(); i += 3)
        mesh.positions[i] -= static_cast<float>(p.length_m / 2);
      return mesh;
    }
    case Primitive::Kind::kSphere:
      return render::MakeSphere(p.radius_m, kSegments / 2, kSegments);
    case Primitive::Kind::kNone:
      break;
  }
  return {};
}

Visual ToVisual(const std::string& urdf_path, const std::string& where,
                const urdf::GeometrySharedPtr& geometry, const urdf::Pose& origin,
                const urdf::MaterialSharedPtr& material, MeshCache& meshes) {
  Visual v;
  v.X_LinkVisual = ToIsometry(origin);
  if (!geometry) throw ModelError(urdf_path, where, "missing <geometry>");
  RequireSensiblePose(urdf_path, where, origin);
  if (material)
    v.colour = {static_cast<float>(material->color.r), static_cast<float>(material->color.g),
                static_cast<float>(material->color.b), static_cast<float>(material->color.a)};
  if (geometry->type != urdf::Geometry::MESH) {
    v.primitive = ToPrimitive(urdf_path, where, *geometry);
    v.mesh = std::make_shared<const render::Mesh>(PrimitiveMesh(v.primitive));
    return v;
  }
  const auto* mesh = static_cast<const urdf::Mesh*>(geometry.get());
  v.mesh_file = mesh->filename;
  const std::filesystem::path full =
      std::filesystem::path(urdf_path).parent_path() / mesh->filename;
  const Eigen::Vector3d scale(mesh->scale.x, mesh->scale.y, mesh->scale.z);
  for (const double v : {scale.x(), scale.y(), scale.z()})
    if (!(std::abs(v) >= 1e-6 && std::abs(v) <= 1000))
      throw ModelError(urdf_path, where, "<mesh scale> must be within 1e-6..1000 in magnitude");
  try {
    v.mesh = meshes.Load(full.string(), scale);
  } catch (const std::exception& e) {
    throw ModelError(urdf_path, where, e.what());
  }
  return v;
}

}  // namespace

void LoadUrdf(const std::string& urdf_path, MachineModel& model) {
  std::string text, why;
  if (!common::ReadInputFile(urdf_path, text, why))
    throw ModelError(urdf_path, "", "cannot open URDF file: " + why);
  // urdfdom's XML parser recurses per element: refuse a nesting that would overflow the stack.
  if (const int line = XmlNestingBeyond(text, kMaxNestingDepth))
    throw ModelError(urdf_path + ":" + std::to_string(line), "",
                     "elements nested deeper than " + std::to_string(kMaxNestingDepth) + " levels");

  CollectingHandler handler;
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(text);
  console_bridge::restorePreviousOutputHandler();
  if (!urdf)
    throw ModelError(urdf_path, "<robot>",
                     "invalid URDF" + (handler.messages.empty() ? "" : ": " + handler.messages));

  MeshCache& meshes = MeshCache::Shared();
  model.links.clear();
  model.joints.clear();
  std::map<std::string, int> link_index;

  // Breadth-first from the root: parents always precede children.
  std::vector<urdf::LinkConstSharedPtr> queue{urdf->getRoot()};
  for (size_t head = 0; head < queue.size(); ++head) {
    const urdf::LinkConstSharedPtr& ul = queue[head];
    Link link;
    link.name = ul->name;
    const std::string where = "<link name=\"" + ul->name + "\">";
    if (ul->inertial) {
      link.mass_kg = ul->inertial->mass;
      link.com_m = ToIsometry(ul->inertial->origin).translation();
      link.inertia_kgm2 = {ul->inertial->ixx, ul->inertial->iyy, ul->inertial->izz};
      if (!(link.mass_kg >= 0 && link.inertia_kgm2.minCoeff() >= 0) ||
          !std::isfinite(link.mass_kg) || !link.inertia_kgm2.allFinite())
        throw ModelError(urdf_path, where, "negative or infinite mass or inertia");
      RequireSensiblePose(urdf_path, where + " <inertial>", ul->inertial->origin);
    }
    for (const auto& uv : ul->visual_array) {
      link.visuals.push_back(
          ToVisual(urdf_path, where + " <visual>", uv->geometry, uv->origin, uv->material, meshes));
      link.visuals.back().name = uv->name;
    }
    for (const auto& uc : ul->collision_array) {
      link.collisions.push_back(
          ToVisual(urdf_path, where + " <collision>", uc->geometry, uc->origin, nullptr, meshes));
      link.collisions.back().name = uc->name;
    }

    const int index = static_cast<int>(model.links.size());
    link_index[ul->name] = index;
    if (ul->parent_joint) {
      const urdf::Joint& uj = *ul->parent_joint;
      const std::string jwhere = "<joint name=\"" + uj.name + "\">";
      Joint joint;
      joint.name = uj.name;
      switch (uj.type) {
        case urdf::Joint::FIXED:
          joint.type = JointType::kFixed;
          break;
        case urdf::Joint::PRISMATIC:
          joint.type = JointType::kPrismatic;
          break;
        case urdf::Joint::REVOLUTE:
          joint.type = JointType::kRevolute;
          break;
        case urdf::Joint::CONTINUOUS:
          joint.type = JointType::kContinuous;
          break;
        default:
          throw ModelError(urdf_path, jwhere,
                           "joint type not supported (fixed, prismatic, revolute, continuous)");
      }
      joint.parent_link = link_index.at(uj.parent_link_name);
      joint.child_link = index;
      RequireSensiblePose(urdf_path, jwhere, uj.parent_to_joint_origin_transform);
      joint.X_ParentJoint = ToIsometry(uj.parent_to_joint_origin_transform);
      joint.axis = Eigen::Vector3d(uj.axis.x, uj.axis.y, uj.axis.z);
      if (joint.type != JointType::kFixed) {
        if (joint.axis.norm() < 1e-9) throw ModelError(urdf_path, jwhere, "zero <axis>");
        joint.axis.normalize();
      }
      if (uj.limits) {
        joint.lower = uj.limits->lower;
        joint.upper = uj.limits->upper;
        if (!(std::abs(joint.lower) <= kMaxJointLimit && std::abs(joint.upper) <= kMaxJointLimit))
          throw ModelError(urdf_path, jwhere, "<limit> lower and upper must be within +-1000");
      }
      if (uj.dynamics) {
        joint.damping = uj.dynamics->damping;
        joint.friction = uj.dynamics->friction;
      }
      link.parent_joint = static_cast<int>(model.joints.size());
      model.joints.push_back(joint);
    }
    model.links.push_back(std::move(link));
    for (const auto& child : ul->child_links) queue.push_back(child);
  }
}

}  // namespace vmt::sim
