// Each collision mesh becomes the cheapest FCL solid that is the same solid: these compare the
// solid chosen with the triangle tree it replaces, on distance and contact.

#include "sim/collision/collision_shape.hpp"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <gtest/gtest.h>

#include <random>

#include "render/mesh_primitives.hpp"

namespace vmt::sim {
namespace {

std::shared_ptr<fcl::CollisionGeometryd> Tree(const render::Mesh& mesh) {
  std::vector<fcl::Vector3d> points;
  for (size_t i = 0; i + 2 < mesh.positions.size(); i += 3)
    points.emplace_back(mesh.positions[i], mesh.positions[i + 1], mesh.positions[i + 2]);
  std::vector<fcl::Triangle> triangles;
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
    triangles.emplace_back(mesh.indices[i], mesh.indices[i + 1], mesh.indices[i + 2]);
  auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  bvh->beginModel();
  bvh->addSubModel(points, triangles);
  bvh->endModel();
  return bvh;
}

struct Pair {
  double distance;
  bool contact;
};

Pair Query(const std::shared_ptr<fcl::CollisionGeometryd>& a, const Eigen::Isometry3d& X_a,
           const std::shared_ptr<fcl::CollisionGeometryd>& b, const Eigen::Isometry3d& X_b) {
  fcl::CollisionObjectd oa(a, X_a), ob(b, X_b);
  fcl::DistanceRequestd dreq;
  dreq.distance_tolerance = 1e-10;  // as CollisionWorld asks
  fcl::DistanceResultd dres;
  fcl::distance(&oa, &ob, dreq, dres);
  fcl::CollisionRequestd creq;
  fcl::CollisionResultd cres;
  fcl::collide(&oa, &ob, creq, cres);
  return {std::max(0.0, dres.min_distance), cres.isCollision()};
}

/// `mesh` as chosen and as a tree, against a rod (a tree, too long and too thin for either to
/// hold the other: a tree is only its surface) at random poses around it: the same contacts away
/// from grazing, and the same distances to rounding.
void ExpectSameSolid(const render::Mesh& mesh) {
  const CollisionShape shape = ShapeOfMesh(mesh);
  const auto tree = Tree(mesh), probe = Tree(render::MakeCylinder(0.01, 0.3, 24));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> offset(-0.08, 0.08), angle(-3.2, 3.2);
  int contacts = 0;
  for (int k = 0; k < 2000; ++k) {
    Eigen::Isometry3d X_probe = Eigen::Isometry3d::Identity();
    X_probe.translation() = Eigen::Vector3d(offset(rng), offset(rng), offset(rng) - 0.15);
    X_probe.rotate(
        Eigen::AngleAxisd(angle(rng), Eigen::Vector3d(offset(rng), offset(rng), 1).normalized()));
    const Pair want = Query(tree, Eigen::Isometry3d::Identity(), probe, X_probe);
    const Pair got = Query(shape.geometry, shape.X_MeshShape, probe, X_probe);
    EXPECT_NEAR(got.distance, want.distance, 1e-12 + 1e-9 * want.distance) << k;
    if (want.distance > 1e-5 || got.distance > 1e-5) {
      EXPECT_EQ(got.contact, want.contact) << k;
    }
    contacts += want.contact;
  }
  EXPECT_GT(contacts, 200);
  EXPECT_LT(contacts, 1800);
}

TEST(CollisionShape, AnAxisAlignedBoxIsFclsBoxAtItsCentre) {
  const render::Mesh box = render::MakeBox({0.01, -0.02, 0.03}, {0.05, 0.02, 0.13});
  const CollisionShape shape = ShapeOfMesh(box);
  ASSERT_EQ(shape.geometry->getNodeType(), fcl::GEOM_BOX);
  EXPECT_TRUE(shape.X_MeshShape.translation().isApprox(Eigen::Vector3d(0.03, 0, 0.08), 1e-7));
  EXPECT_TRUE(shape.centre.isApprox(Eigen::Vector3d(0.03, 0, 0.08), 1e-7));
  EXPECT_NEAR(shape.radius, Eigen::Vector3d(0.04, 0.04, 0.1).norm() / 2, 1e-7);
  ExpectSameSolid(box);
}

TEST(CollisionShape, ACylinderIsFclsConvex) {
  const render::Mesh cylinder = render::MakeCylinder(0.04, 0.1, 48);
  ASSERT_EQ(ShapeOfMesh(cylinder).geometry->getNodeType(), fcl::GEOM_CONVEX);
  ExpectSameSolid(cylinder);
}

TEST(CollisionShape, ATubeStaysATriangleTree) {
  // Its bore is a hollow: a convex solid would fill it.
  const render::Mesh tube = render::MakeTube(0.02, 0.04, 0.1, 32);
  ASSERT_EQ(ShapeOfMesh(tube).geometry->getNodeType(), fcl::BV_OBBRSS);
  // A pin standing in the bore touches nothing.
  const render::Mesh pin = render::MakeCylinder(0.01, 0.2, 16);
  const Pair in_bore = Query(ShapeOfMesh(tube).geometry, Eigen::Isometry3d::Identity(), Tree(pin),
                             Eigen::Isometry3d(Eigen::Translation3d(0, 0, -0.05)));
  EXPECT_FALSE(in_bore.contact);
  EXPECT_NEAR(in_bore.distance, 0.01, 1e-3);
}

TEST(CollisionShape, ABoxTurnedInItsFrameIsConvexNotABox) {
  render::Mesh box = render::MakeBox({-0.02, -0.01, -0.03}, {0.02, 0.01, 0.03});
  const Eigen::Matrix3f R = Eigen::AngleAxisf(0.3f, Eigen::Vector3f::UnitZ()).toRotationMatrix();
  for (size_t i = 0; i + 2 < box.positions.size(); i += 3) {
    const Eigen::Vector3f p =
        R * Eigen::Vector3f(box.positions[i], box.positions[i + 1], box.positions[i + 2]);
    for (int k = 0; k < 3; ++k) box.positions[i + k] = p[k];
  }
  ASSERT_EQ(ShapeOfMesh(box).geometry->getNodeType(), fcl::GEOM_CONVEX);
  ExpectSameSolid(box);
}

TEST(CollisionShape, AMeshsSharedSolidIsBuiltOnceWhileTheMeshLives) {
  auto tube = std::make_shared<const render::Mesh>(render::MakeTube(0.02, 0.04, 0.1, 32));
  const CollisionShape first = SharedShapeOfMesh(tube);
  const CollisionShape fresh = ShapeOfMesh(*tube);
  EXPECT_EQ(SharedShapeOfMesh(tube).geometry, first.geometry);
  EXPECT_EQ(first.geometry->getNodeType(), fresh.geometry->getNodeType());
  EXPECT_EQ(first.centre, fresh.centre);
  EXPECT_EQ(first.radius, fresh.radius);
  EXPECT_TRUE(first.X_MeshShape.isApprox(fresh.X_MeshShape, 0));
  // The same solid as a fresh one, bit for bit, against a pin in the bore and one outside.
  const auto pin = Tree(render::MakeCylinder(0.01, 0.2, 16));
  for (const double x : {0.0, 0.057, 0.1}) {
    const Eigen::Isometry3d X_pin(Eigen::Translation3d(x, 0.003, -0.05));
    const Pair shared = Query(first.geometry, Eigen::Isometry3d::Identity(), pin, X_pin);
    const Pair built = Query(fresh.geometry, Eigen::Isometry3d::Identity(), pin, X_pin);
    EXPECT_EQ(shared.distance, built.distance) << x;
    EXPECT_EQ(shared.contact, built.contact) << x;
  }

  // Another mesh, even equal in every number, is another key; so is a mesh made where a freed
  // one stood.
  auto twin = std::make_shared<const render::Mesh>(*tube);
  EXPECT_NE(SharedShapeOfMesh(twin).geometry, first.geometry);
  const std::weak_ptr<fcl::CollisionGeometryd> was = first.geometry;
  const fcl::CollisionGeometryd* const raw = first.geometry.get();
  tube.reset();
  auto box = std::make_shared<const render::Mesh>(render::MakeBox({0, 0, 0}, {0.01, 0.01, 0.01}));
  const CollisionShape other = SharedShapeOfMesh(box);
  EXPECT_EQ(other.geometry->getNodeType(), fcl::GEOM_BOX);
  // Adding it dropped the freed mesh's entry: its solid is gone with the last holder here.
  EXPECT_EQ(was.use_count(), 1);
  EXPECT_NE(other.geometry.get(), raw);
}

TEST(CollisionShape, AnObjectOfASharedSolidLeavesItsBoundingBoxAsItWas) {
  auto cylinder = std::make_shared<const render::Mesh>(render::MakeCylinder(0.04, 0.1, 48));
  const CollisionShape shape = SharedShapeOfMesh(cylinder);
  const std::unique_ptr<fcl::CollisionObjectd> a = ObjectOf(shape.geometry);
  const fcl::AABBd box = shape.geometry->aabb_local;
  const std::unique_ptr<fcl::CollisionObjectd> b = ObjectOf(shape.geometry);
  EXPECT_EQ(shape.geometry->aabb_local.min_, box.min_);
  EXPECT_EQ(shape.geometry->aabb_local.max_, box.max_);
  EXPECT_EQ(a->collisionGeometry(), b->collisionGeometry());
  EXPECT_NEAR(box.max_.x(), 0.04, 1e-6);
}

}  // namespace
}  // namespace vmt::sim
