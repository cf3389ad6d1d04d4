#include "render/offscreen_renderer.hpp"

#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <vector>

#include "render/image_compare.hpp"
#include "render/mesh_primitives.hpp"
#include "tests/render/test_paths.hpp"

namespace vmt::render {
namespace {

using testing::OutputPath;

constexpr int kWidth = 64, kHeight = 48;
constexpr Rgba kGrey{0.6f, 0.6f, 0.6f, 1};
constexpr Rgba kRed{0.9f, 0.1f, 0.1f, 1};

std::array<uint8_t, 4> At(const Image& image, int x, int y) {
  const uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
  return {p[0], p[1], p[2], p[3]};
}

Camera FrontCamera() {
  Camera camera;
  camera.eye = {0, 0, 1};
  camera.target = {0, 0, 0};
  camera.up = {0, 1, 0};
  return camera;
}

Eigen::Isometry3d Translation(double x, double y, double z) {
  return Eigen::Isometry3d(Eigen::Translation3d(x, y, z));
}

// Fraction of pixels in the given rectangle that differ from the background pixel (0, 0).
double Covered(const Image& image, int x0, int y0, int x1, int y1) {
  const auto background = At(image, 0, 0);
  int covered = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) covered += At(image, x, y) != background;
  }
  return double(covered) / double((x1 - x0) * (y1 - y0));
}

TEST(OffscreenRendererTest, EmptySceneIsBackground) {
  OffscreenRenderer renderer(kWidth, kHeight);
  const Image image = renderer.Draw(FrontCamera(), {}, {0.93f, 0.94f, 0.96f, 1});
  ASSERT_EQ(image.width, kWidth);
  ASSERT_EQ(image.height, kHeight);
  ASSERT_EQ(image.rgba.size(), size_t(kWidth) * kHeight * 4);
  const auto pixel = At(image, 0, 0);
  EXPECT_NEAR(pixel[0], 0.93 * 255, 1);
  EXPECT_NEAR(pixel[1], 0.94 * 255, 1);
  EXPECT_NEAR(pixel[2], 0.96 * 255, 1);
  EXPECT_EQ(pixel[3], 255);
  EXPECT_EQ(Covered(image, 0, 0, kWidth, kHeight), 0.0);
}

TEST(OffscreenRendererTest, BoxInFrontCoversCentreNotCorners) {
  const Mesh box = MakeBox({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1});
  const std::vector<DrawItem> items{{&box, Eigen::Isometry3d::Identity(), kGrey}};
  OffscreenRenderer renderer(kWidth, kHeight);
  const Image background = renderer.Draw(FrontCamera(), {});
  const Image image = renderer.Draw(FrontCamera(), items);
  WritePng(OutputPath("box_front.png"), image);
  const auto centre = At(image, kWidth / 2, kHeight / 2);
  EXPECT_NE(centre, At(background, kWidth / 2, kHeight / 2));
  // Lit grey: neither black nor saturated, r = g = b.
  EXPECT_GT(centre[0], 60);
  EXPECT_LT(centre[0], 250);
  EXPECT_EQ(centre[0], centre[1]);
  EXPECT_EQ(centre[1], centre[2]);
  for (const auto& [x, y] :
       {std::pair{0, 0}, {kWidth - 1, 0}, {0, kHeight - 1}, {kWidth - 1, kHeight - 1}}) {
    EXPECT_EQ(At(image, x, y), At(background, x, y)) << x << "," << y;
  }
}

TEST(OffscreenRendererTest, RowsAreTopDownAndXIsRight) {
  const Mesh box = MakeBox({-0.05, -0.05, -0.05}, {0.05, 0.05, 0.05});
  for (const int supersample : {1, 2, 3}) {
    SCOPED_TRACE(supersample);
    OffscreenRenderer renderer(kWidth, kHeight, supersample);
    // World +y is up in this camera: a box above the centre lands in the top rows.
    const std::vector<DrawItem> up{{&box, Translation(0, 0.15, 0), kGrey}};
    const Image above = renderer.Draw(FrontCamera(), up);
    EXPECT_GT(Covered(above, 0, 0, kWidth, kHeight / 2), 0.01);
    EXPECT_EQ(Covered(above, 0, kHeight / 2, kWidth, kHeight), 0.0);
    // World +x is to the right.
    const std::vector<DrawItem> right{{&box, Translation(0.2, 0, 0), kGrey}};
    const Image to_right = renderer.Draw(FrontCamera(), right);
    EXPECT_GT(Covered(to_right, kWidth / 2, 0, kWidth, kHeight), 0.01);
    EXPECT_EQ(Covered(to_right, 0, 0, kWidth / 2, kHeight), 0.0);
  }
}

TEST(OffscreenRendererTest, TranslucentItemBlendsAndKeepsPictureOpaque) {
  const Mesh back = MakeBox({-0.2, -0.2, -0.3}, {0.2, 0.2, -0.2});
  const Mesh front = MakeBox({-0.1, -0.1, 0}, {0.1, 0.1, 0.01});
  OffscreenRenderer renderer(kWidth, kHeight);
  const std::vector<DrawItem> opaque_only{{&back, Eigen::Isometry3d::Identity(), kRed}};
  // Listed before the opaque item on purpose: translucent items are drawn last anyway.
  const std::vector<DrawItem> with_glass{
      {&front, Eigen::Isometry3d::Identity(), {0.1f, 0.1f, 0.9f, 0.5f}},
      {&back, Eigen::Isometry3d::Identity(), kRed}};
  const auto red = At(renderer.Draw(FrontCamera(), opaque_only), kWidth / 2, kHeight / 2);
  const auto mixed = At(renderer.Draw(FrontCamera(), with_glass), kWidth / 2, kHeight / 2);
  EXPECT_LT(mixed[0], red[0]);  // some red shows through, dimmed
  EXPECT_GT(mixed[0], 40);
  EXPECT_GT(mixed[2], red[2] + 40);  // and the blue glass adds blue
  EXPECT_EQ(mixed[3], 255);
}

TEST(OffscreenRendererTest, NearerItemHidesFartherOne) {
  const Mesh box = MakeBox({-0.1, -0.1, -0.01}, {0.1, 0.1, 0.01});
  // Drawn far-first and near-first: the depth test, not the order, decides.
  const std::vector<DrawItem> far_first{{&box, Translation(0, 0, -0.2), kGrey},
                                        {&box, Translation(0, 0, 0.2), kRed}};
  const std::vector<DrawItem> near_first{far_first[1], far_first[0]};
  OffscreenRenderer renderer(kWidth, kHeight);
  const auto a = At(renderer.Draw(FrontCamera(), far_first), kWidth / 2, kHeight / 2);
  const auto b = At(renderer.Draw(FrontCamera(), near_first), kWidth / 2, kHeight / 2);
  EXPECT_EQ(a, b);
  EXPECT_GT(a[0], 2 * a[1]);
}

TEST(OffscreenRendererTest, RedCylinderIsRed) {
  const Mesh cylinder = MakeCylinder(0.05, 0.3, 64);
  // Lying along x, seen from the side.
  const Eigen::Isometry3d X_WorldCylinder =
      Translation(-0.15, 0, 0) * Eigen::AngleAxisd(EIGEN_PI / 2, Eigen::Vector3d::UnitY());
  const std::vector<DrawItem> items{{&cylinder, X_WorldCylinder, kRed}};
  OffscreenRenderer renderer(kWidth, kHeight);
  const Image image = renderer.Draw(FrontCamera(), items);
  WritePng(OutputPath("red_cylinder.png"), image);
  const auto centre = At(image, kWidth / 2, kHeight / 2);
  EXPECT_GT(centre[0], 100);
  EXPECT_GT(centre[0], 3 * centre[1]);
  EXPECT_GT(centre[0], 3 * centre[2]);
}

TEST(OffscreenRendererTest, SameSceneGivesIdenticalBytes) {
  const Mesh cylinder = MakeCylinder(0.05, 0.2, 48);
  const Mesh box = MakeBox({-0.2, -0.2, -0.3}, {0.2, -0.1, 0.1});
  Camera camera;
  camera.eye = {0.4, 0.3, 0.6};
  camera.target = {0, 0, 0.05};
  const std::vector<DrawItem> items{
      {&cylinder, Eigen::Isometry3d::Identity(), kRed},
      {&box, Eigen::Isometry3d::Identity(), kGrey},
      {&box, Translation(0, 0.25, 0), {0.2f, 0.4f, 0.9f, 0.5f}},
  };
  OffscreenRenderer renderer(160, 120);
  const Image first = renderer.Draw(camera, items);
  const Image second = renderer.Draw(camera, items);
  EXPECT_EQ(first.rgba, second.rgba);
  // A fresh context gives the same bytes too.
  OffscreenRenderer other(160, 120);
  EXPECT_EQ(other.Draw(camera, items).rgba, first.rgba);
  WritePng(OutputPath("determinism_scene.png"), first);
}

TEST(OffscreenRendererTest, RenderersInSequenceAndSideBySide) {
  const Mesh box = MakeBox({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1});
  const std::vector<DrawItem> items{{&box, Eigen::Isometry3d::Identity(), kGrey}};
  Image first;
  {
    OffscreenRenderer renderer(kWidth, kHeight);
    first = renderer.Draw(FrontCamera(), items);
  }
  {
    OffscreenRenderer renderer(kWidth, kHeight);
    EXPECT_EQ(renderer.Draw(FrontCamera(), items).rgba, first.rgba);
  }
  // Two alive at once, used in turns, with different sizes.
  OffscreenRenderer a(kWidth, kHeight), b(32, 32, 1);
  const Image from_a = a.Draw(FrontCamera(), items);
  const Image from_b = b.Draw(FrontCamera(), items);
  EXPECT_EQ(from_b.width, 32);
  EXPECT_GT(Covered(from_b, 12, 12, 20, 20), 0.9);
  EXPECT_EQ(a.Draw(FrontCamera(), items).rgba, from_a.rgba);
  EXPECT_EQ(from_a.rgba, first.rgba);
  // A moved renderer keeps working.
  OffscreenRenderer moved = std::move(a);
  EXPECT_EQ(moved.Draw(FrontCamera(), items).rgba, first.rgba);
}

TEST(OffscreenRendererTest, ChangedMeshIsRedrawnAfterForgetOrReallocation) {
  Mesh mesh = MakeBox({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1});
  const std::vector<DrawItem> items{{&mesh, Eigen::Isometry3d::Identity(), kGrey}};
  OffscreenRenderer renderer(kWidth, kHeight);
  const Image big = renderer.Draw(FrontCamera(), items);
  // In-place change: visible after Forget.
  for (float& coordinate : mesh.positions) coordinate *= 0.5f;
  renderer.Forget(&mesh);
  const Image small = renderer.Draw(FrontCamera(), items);
  EXPECT_LT(Covered(small, 0, 0, kWidth, kHeight), Covered(big, 0, 0, kWidth, kHeight));
  // A new mesh assigned into the same object reallocates and is picked up without Forget.
  mesh = MakeCylinder(0.02, 0.1, 16);
  const Image cylinder = renderer.Draw(FrontCamera(), items);
  EXPECT_LT(Covered(cylinder, 0, 0, kWidth, kHeight), Covered(small, 0, 0, kWidth, kHeight));
  renderer.ForgetAll();
  EXPECT_EQ(renderer.Draw(FrontCamera(), items).rgba, cylinder.rgba);
}

TEST(OffscreenRendererTest, MeshWithoutNormalsAndEmptyMeshDraw) {
  Mesh flat = MakeBox({-0.1, -0.1, 0}, {0.1, 0.1, 0});
  flat.normals.clear();
  const Mesh empty;
  const std::vector<DrawItem> items{{&flat, Eigen::Isometry3d::Identity(), kGrey},
                                    {&empty, Eigen::Isometry3d::Identity(), kRed}};
  OffscreenRenderer renderer(kWidth, kHeight);
  const Image image = renderer.Draw(FrontCamera(), items);
  EXPECT_GT(Covered(image, kWidth / 2 - 2, kHeight / 2 - 2, kWidth / 2 + 2, kHeight / 2 + 2), 0.99);
}

TEST(OffscreenRendererTest, BadInputThrows) {
  EXPECT_THROW(OffscreenRenderer(0, 10), std::runtime_error);
  EXPECT_THROW(OffscreenRenderer(10, 10, 0), std::runtime_error);
  EXPECT_THROW(OffscreenRenderer(100000, 10), std::runtime_error);

  OffscreenRenderer renderer(kWidth, kHeight);
  Mesh bad = MakeBox({0, 0, 0}, {1, 1, 1});
  bad.indices.back() = 1000;
  const std::vector<DrawItem> bad_items{{&bad, Eigen::Isometry3d::Identity(), kGrey}};
  EXPECT_THROW(renderer.Draw(FrontCamera(), bad_items), std::runtime_error);
  Mesh odd = MakeBox({0, 0, 0}, {1, 1, 1});
  odd.positions.pop_back();
  const std::vector<DrawItem> odd_items{{&odd, Eigen::Isometry3d::Identity(), kGrey}};
  EXPECT_THROW(renderer.Draw(FrontCamera(), odd_items), std::runtime_error);
  const std::vector<DrawItem> null_items{{nullptr, Eigen::Isometry3d::Identity(), kGrey}};
  EXPECT_THROW(renderer.Draw(FrontCamera(), null_items), std::runtime_error);

  Camera camera = FrontCamera();
  camera.target = camera.eye;
  EXPECT_THROW(renderer.Draw(camera, {}), std::runtime_error);
  camera = FrontCamera();
  camera.up = {0, 0, 1};
  EXPECT_THROW(renderer.Draw(camera, {}), std::runtime_error);
  camera = FrontCamera();
  camera.near_m = 0;
  EXPECT_THROW(renderer.Draw(camera, {}), std::runtime_error);

  // A bad item among good ones: nothing drawn, nothing left half-set.
  const Mesh good = MakeBox({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1});
  const std::vector<DrawItem> mixed_items{{&good, Eigen::Isometry3d::Identity(), {1, 1, 1, 0.5f}},
                                          {&bad, Eigen::Isometry3d::Identity(), kGrey}};
  EXPECT_THROW(renderer.Draw(FrontCamera(), mixed_items), std::runtime_error);

  // The renderer still works after refusing bad input.
  const Mesh box = MakeBox({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1});
  const std::vector<DrawItem> items{{&box, Eigen::Isometry3d::Identity(), kGrey}};
  const Image image = renderer.Draw(FrontCamera(), items);
  EXPECT_GT(Covered(image, kWidth / 2 - 2, kHeight / 2 - 2, kWidth / 2 + 2, kHeight / 2 + 2), 0.99);
}

}  // namespace
}  // namespace vmt::render
