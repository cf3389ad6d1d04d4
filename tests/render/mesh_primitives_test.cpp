#include "render/mesh_primitives.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <stdexcept>

namespace vmt::render {
namespace {

Eigen::Vector3d Position(const Mesh& mesh, uint32_t i) {
  return {mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]};
}
Eigen::Vector3d Normal(const Mesh& mesh, uint32_t i) {
  return {mesh.normals[3 * i], mesh.normals[3 * i + 1], mesh.normals[3 * i + 2]};
}

// Every triangle is counter-clockwise seen from the side its vertex normals point to, and the
// mesh is well formed.
void ExpectConsistent(const Mesh& mesh) {
  ASSERT_EQ(mesh.positions.size() % 3, 0u);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  ASSERT_EQ(mesh.indices.size() % 3, 0u);
  const uint32_t vertices = uint32_t(mesh.positions.size() / 3);
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    ASSERT_LT(a, vertices);
    ASSERT_LT(b, vertices);
    ASSERT_LT(c, vertices);
    const Eigen::Vector3d face =
        (Position(mesh, b) - Position(mesh, a)).cross(Position(mesh, c) - Position(mesh, a));
    ASSERT_GT(face.norm(), 0) << "degenerate triangle " << t / 3;
    for (const uint32_t v : {a, b, c}) {
      EXPECT_NEAR(Normal(mesh, v).norm(), 1.0, 1e-6);
      EXPECT_GT(face.dot(Normal(mesh, v)), 0) << "triangle " << t / 3 << " wound inwards";
    }
  }
}

TEST(MeshPrimitivesTest, CylinderShapeAndWinding) {
  const Mesh mesh = MakeCylinder(0.05, 0.2, 32);
  EXPECT_EQ(mesh.indices.size(), 4u * 32 * 3);
  ExpectConsistent(mesh);
  for (uint32_t i = 0; i < mesh.positions.size() / 3; ++i) {
    const Eigen::Vector3d p = Position(mesh, i);
    EXPECT_LE(p.head<2>().norm(), 0.05 + 1e-6);
    EXPECT_GE(p.z(), 0.0);
    EXPECT_LE(p.z(), 0.2 + 1e-6);
  }
}

TEST(MeshPrimitivesTest, TubeShapeAndWinding) {
  const Mesh mesh = MakeTube(0.015, 0.05, 0.01, 32);
  EXPECT_EQ(mesh.indices.size(), 8u * 32 * 3);
  ExpectConsistent(mesh);
  for (uint32_t i = 0; i < mesh.positions.size() / 3; ++i) {
    const Eigen::Vector3d p = Position(mesh, i);
    EXPECT_GE(p.head<2>().norm(), 0.015 - 1e-6);
    EXPECT_LE(p.head<2>().norm(), 0.05 + 1e-6);
    EXPECT_GE(p.z(), 0.0);
    EXPECT_LE(p.z(), 0.01 + 1e-6);
  }
}

TEST(MeshPrimitivesTest, BoxShapeAndWinding) {
  const Mesh mesh = MakeBox({-1, 0, 2}, {1, 0.5, 3});
  EXPECT_EQ(mesh.indices.size(), 12u * 3);
  ExpectConsistent(mesh);
  Eigen::Vector3d low = Position(mesh, 0), high = low;
  for (uint32_t i = 0; i < mesh.positions.size() / 3; ++i) {
    low = low.cwiseMin(Position(mesh, i));
    high = high.cwiseMax(Position(mesh, i));
  }
  EXPECT_EQ(low, Eigen::Vector3d(-1, 0, 2));
  EXPECT_EQ(high, Eigen::Vector3d(1, 0.5, 3));
}

TEST(MeshPrimitivesTest, SphereShapeAndWinding) {
  const int rings = 8, segments = 12;
  const Mesh mesh = MakeSphere(0.02, rings, segments);
  // A fan of triangles round each pole, two per quad in the rows between.
  EXPECT_EQ(mesh.indices.size(), size_t(2 * segments + 2 * segments * (rings - 2)) * 3);
  EXPECT_EQ(mesh.positions.size() / 3, size_t(2 + segments * (rings - 1)));
  ExpectConsistent(mesh);
  Eigen::Vector3d low = Position(mesh, 0), high = low;
  for (uint32_t i = 0; i < mesh.positions.size() / 3; ++i) {
    const Eigen::Vector3d p = Position(mesh, i);
    EXPECT_NEAR(p.norm(), 0.02, 1e-6);
    EXPECT_TRUE(Normal(mesh, i).isApprox(p.normalized(), 1e-6));
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  EXPECT_NEAR(low.z(), -0.02, 1e-7);  // both poles are vertices
  EXPECT_NEAR(high.z(), 0.02, 1e-7);
}

TEST(MeshPrimitivesTest, BadArgumentsThrow) {
  EXPECT_THROW(MakeCylinder(0, 1, 8), std::runtime_error);
  EXPECT_THROW(MakeCylinder(1, -1, 8), std::runtime_error);
  EXPECT_THROW(MakeCylinder(1, 1, 2), std::runtime_error);
  EXPECT_THROW(MakeTube(0, 1, 1, 8), std::runtime_error);
  EXPECT_THROW(MakeTube(1, 1, 1, 8), std::runtime_error);
  EXPECT_THROW(MakeBox({0, 0, 0}, {1, -1, 1}), std::runtime_error);
  EXPECT_THROW(MakeSphere(0, 8, 8), std::runtime_error);
  EXPECT_THROW(MakeSphere(1, 1, 8), std::runtime_error);
  EXPECT_THROW(MakeSphere(1, 8, 2), std::runtime_error);
}

}  // namespace
}  // namespace vmt::render
