#pragma once
// The FCL solid for one collision mesh: the cheapest FCL geometry that is the same solid. A box
// along its frame's axes becomes FCL's box, any other convex mesh FCL's convex (GJK walks its
// vertices), and only a mesh with a hollow or a recess (a bored section) stays a tree of its
// triangles. Between two trees FCL walks both and measures triangle against triangle, tens of
// microseconds a query; a box or a convex solid takes a few GJK iterations. Distances agree
// with the tree's to rounding when GJK runs to a tight tolerance (CollisionWorld asks 1e-10 m).
// A tree is only a surface, a box or convex solid is solid: a part wholly inside one touches it.

#include <fcl/geometry/collision_geometry.h>
#include <fcl/narrowphase/collision_object.h>

#include <Eigen/Geometry>
#include <memory>

#include "render/mesh.hpp"
#include "sim/model/machine_model.hpp"

namespace vmt::sim {

struct CollisionShape {
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  /// Where the geometry's frame sits in the mesh's frame (FCL's box is centred on its origin).
  Eigen::Isometry3d X_MeshShape = Eigen::Isometry3d::Identity();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< bounding sphere, mesh frame, m
  double radius = 0;                                 ///< bounding sphere, m
};

/// The solid of `mesh` (closed and outward-wound, as the model's collision meshes are).
CollisionShape ShapeOfMesh(const render::Mesh& mesh);

/// ShapeOfMesh built once per mesh in the process, for as long as the mesh lives: every run of
/// a model (a study's cases run from the start, its saved cases, the station's reset, a scene
/// run again) would otherwise build the same trees and hulls again, a tenth of a short run.
/// Thread-safe; queries only read a geometry, but make its objects with ObjectOf.
CollisionShape SharedShapeOfMesh(const std::shared_ptr<const render::Mesh>& mesh);

/// An FCL object of `geometry`, shared or not. FCL's object recomputes its geometry's local
/// bounding box when it is made (the same numbers every time): one at a time, so that worlds
/// built in two threads do not write a shared geometry at once.
std::unique_ptr<fcl::CollisionObjectd> ObjectOf(
    const std::shared_ptr<fcl::CollisionGeometryd>& geometry);

/// The URDF primitive's own solid (not its mesh: a cylinder's facets lie inside it).
CollisionShape ShapeOfPrimitive(const Primitive& primitive);

}  // namespace vmt::sim
