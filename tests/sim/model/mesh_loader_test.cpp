// A machine builder's meshes come as OBJ or PLY (the shipped models are PLY): the same solid
// written either way loads as the same triangles, corner by corner, with the normals it carries
// and the URDF's scale applied; a file without triangles is refused by name.

#include "sim/model/mesh_loader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace vmt::sim {
namespace {

std::string Folder() {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "vmt-mesh-loader-test").string();
  std::filesystem::create_directories(dir);
  return dir;
}

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = Folder() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// Two triangles of a unit square in the z = 0 plane, facing +z; the OBJ shares its corners.
constexpr const char* kObj =
    "v 0.000000 0.000000 0.000000\nv 1.000000 0.000000 0.000000\n"
    "v 1.000000 1.000000 0.000000\nv 0.000000 1.000000 0.000000\nvn 0.000000 0.000000 1.000000\n"
    "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";
constexpr const char* kPly =
    "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
    "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "0.000000 0.000000 0.000000 0.000000 0.000000 1.000000\n"
    "1.000000 0.000000 0.000000 0.000000 0.000000 1.000000\n"
    "1.000000 1.000000 0.000000 0.000000 0.000000 1.000000\n"
    "0.000000 0.000000 0.000000 0.000000 0.000000 1.000000\n"
    "1.000000 1.000000 0.000000 0.000000 0.000000 1.000000\n"
    "0.000000 1.000000 0.000000 0.000000 0.000000 1.000000\n"
    "3 0 1 2\n3 3 4 5\n";

TEST(MeshLoaderTest, ObjAndPlyOfOneSolidLoadAlike) {
  MeshCache cache;
  const auto obj = cache.Load(Write("square.obj", kObj), Eigen::Vector3d(2, 3, 1));
  const auto ply = cache.Load(Write("square.ply", kPly), Eigen::Vector3d(2, 3, 1));
  EXPECT_EQ(obj->positions, ply->positions);
  EXPECT_EQ(obj->normals, ply->normals);
  EXPECT_EQ(obj->indices, ply->indices);
  ASSERT_EQ(ply->positions.size(), 18u);
  EXPECT_FLOAT_EQ(ply->positions[6], 2.0f);  // the third corner, (1, 1, 0) scaled
  EXPECT_FLOAT_EQ(ply->positions[7], 3.0f);
  EXPECT_FLOAT_EQ(ply->normals[2], 1.0f);
}

TEST(MeshLoaderTest, AFileWithoutTrianglesIsRefusedByName) {
  MeshCache cache;
  const std::string path = Write("points.ply",
                                 "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                 "property float y\nproperty float z\nend_header\n0 0 0\n");
  try {
    cache.Load(path, Eigen::Vector3d::Ones());
    FAIL() << "a mesh without triangles was loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("points.ply"));
  }
}

}  // namespace
}  // namespace vmt::sim
