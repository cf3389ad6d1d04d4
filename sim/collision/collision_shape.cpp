#include "sim/collision/collision_shape.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>

namespace vmt::sim {
namespace {

using Points = std::vector<fcl::Vector3d>;

/// Whether every vertex lies on the inner side of every face's plane (to 1e-12 m: the text of an
/// OBJ file rounds, and a flat quad split in two triangles is flat only to rounding).
bool IsConvex(const Points& points, const std::vector<uint32_t>& indices, const Points& unique) {
  for (size_t i = 0; i + 2 < indices.size(); i += 3) {
    const fcl::Vector3d& a = points[indices[i]];
    const fcl::Vector3d n = (points[indices[i + 1]] - a).cross(points[indices[i + 2]] - a);
    const double area2 = n.norm();
    if (area2 == 0) continue;  // a degenerate sliver bounds nothing
    for (const fcl::Vector3d& p : unique)
      if (n.dot(p - a) > 1e-12 * area2) return false;
  }
  return true;
}

std::shared_ptr<fcl::CollisionGeometryd> TriangleTree(const Points& points,
                                                      const std::vector<uint32_t>& indices) {
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(indices.size() / 3);
  for (size_t i = 0; i + 2 < indices.size(); i += 3)
    triangles.emplace_back(indices[i], indices[i + 1], indices[i + 2]);
  auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  bvh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
  bvh->addSubModel(points, triangles);
  bvh->endModel();
  return bvh;
}

std::mutex& SharedShapesMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

CollisionShape ShapeOfMesh(const render::Mesh& mesh) {
  // A vertex repeats once per face normal it carries (a box's corner three times): the solid
  // needs each position once.
  Points points;
  points.reserve(mesh.positions.size() / 3);
  Points unique;
  std::map<std::array<double, 3>, int> index_of;
  std::vector<int> unique_index;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e30), hi = -lo;
  for (size_t i = 0; i + 2 < mesh.positions.size(); i += 3) {
    const std::array<double, 3> p = {mesh.positions[i], mesh.positions[i + 1],
                                     mesh.positions[i + 2]};
    points.emplace_back(p[0], p[1], p[2]);
    lo = lo.cwiseMin(points.back());
    hi = hi.cwiseMax(points.back());
    const auto [it, added] = index_of.emplace(p, static_cast<int>(unique.size()));
    if (added) unique.push_back(points.back());
    unique_index.push_back(it->second);
  }
  CollisionShape shape;
  shape.centre = points.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d((lo + hi) / 2);
  for (const fcl::Vector3d& p : unique)
    shape.radius = std::max(shape.radius, (p - shape.centre).norm());
  if (points.empty() || mesh.indices.empty()) {
    shape.geometry = TriangleTree(points, mesh.indices);
    return shape;
  }

  bool box = unique.size() == 8;
  for (const fcl::Vector3d& p : unique)
    for (int k = 0; k < 3; ++k) box = box && (p[k] == lo[k] || p[k] == hi[k]);
  if (box && (hi - lo).minCoeff() > 0) {
    shape.geometry = std::make_shared<fcl::Boxd>(hi - lo);
    shape.X_MeshShape.translation() = shape.centre;
    return shape;
  }
  if (IsConvex(points, mesh.indices, unique)) {
    auto vertices = std::make_shared<Points>(unique);
    auto faces = std::make_shared<std::vector<int>>();
    faces->reserve(mesh.indices.size() / 3 * 4);
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      faces->push_back(3);
      for (size_t k = 0; k < 3; ++k) faces->push_back(unique_index[mesh.indices[i + k]]);
    }
    shape.geometry =
        std::make_shared<fcl::Convexd>(vertices, static_cast<int>(mesh.indices.size() / 3), faces);
    return shape;
  }
  shape.geometry = TriangleTree(points, mesh.indices);
  return shape;
}

CollisionShape SharedShapeOfMesh(const std::shared_ptr<const render::Mesh>& mesh) {
  // Keyed by the mesh's ownership, not its address: a mesh freed and another made at the same
  // address is a different key, and an expired entry is dropped when the next one is added.
  static std::map<std::weak_ptr<const render::Mesh>, CollisionShape, std::owner_less<>> shapes;
  const std::lock_guard<std::mutex> lock(SharedShapesMutex());
  if (auto it = shapes.find(mesh); it != shapes.end()) return it->second;
  std::erase_if(shapes, [](const auto& entry) { return entry.first.expired(); });
  return shapes.emplace(mesh, ShapeOfMesh(*mesh)).first->second;
}

std::unique_ptr<fcl::CollisionObjectd> ObjectOf(
    const std::shared_ptr<fcl::CollisionGeometryd>& geometry) {
  const std::lock_guard<std::mutex> lock(SharedShapesMutex());
  return std::make_unique<fcl::CollisionObjectd>(geometry);
}

CollisionShape ShapeOfPrimitive(const Primitive& primitive) {
  CollisionShape shape;
  switch (primitive.kind) {
    case Primitive::Kind::kBox:
      shape.geometry = std::make_shared<fcl::Boxd>(primitive.box_m);
      shape.radius = primitive.box_m.norm() / 2;
      break;
    case Primitive::Kind::kCylinder:
      shape.geometry = std::make_shared<fcl::Cylinderd>(primitive.radius_m, primitive.length_m);
      shape.radius = std::hypot(primitive.radius_m, primitive.length_m / 2);
      break;
    case Primitive::Kind::kSphere:
      shape.geometry = std::make_shared<fcl::Sphered>(primitive.radius_m);
      shape.radius = primitive.radius_m;
      break;
    case Primitive::Kind::kNone:
      break;
  }
  return shape;
}

}  // namespace vmt::sim
