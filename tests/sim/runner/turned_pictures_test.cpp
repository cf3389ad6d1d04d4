// Pictures show the workpiece as the stock cutter has turned it at the picture's tick: the
// renderer draws a turned profile (built once per version), an uncut profile looks like the
// scene's part, and a picture rendered after the run shows the part as it was at its tick.

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "../sim_test_support.hpp"
#include "render/image.hpp"
#include "render/mesh_primitives.hpp"
#include "sim/collision/turned_stock.hpp"
#include "sim/runner/runner.hpp"
#include "sim/runner/scene_renderer.hpp"
#include "sim/scene/scene.hpp"

namespace vmt::sim {
namespace {

using testing::OutputDir;
using testing::SourcePath;

int PixelsApart(const render::Image& a, const render::Image& b) {
  int n = 0;
  for (size_t i = 0; i + 3 < a.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c)
      if (a.rgba[i + c] != b.rgba[i + c]) {
        ++n;
        break;
      }
  return n;
}

TEST(TurnedPictures, TheRendererDrawsThePartAsTurned) {
  const Scene scene = LoadScene(SourcePath("scenes/turning.yaml"));
  SceneRenderer renderer(*scene.model, scene.workpiece);
  const std::vector<double> q(scene.model->joints.size(), 0.0);
  const NamedCamera& camera = *scene.Camera("tool");
  const render::Image raw = renderer.Render(q, camera, 160, 120);

  // Uncut, the stock cutter's profile is the scene's bar.
  TurnedStock stock = TurnedStock::FromPart(scene.workpiece.part, 0.0005);
  TurnedProfile profile{1, stock.Cylinders(1e-6)};
  EXPECT_EQ(PixelsApart(renderer.Render(q, camera, 160, 120, &profile), raw), 0);

  // Turned down to 20 mm over its free half: the picture changes.
  const double z0 = stock.z0_m, length = stock.slice_m * stock.slices.size();
  for (double z = z0 + length / 2; z < z0 + length; z += stock.slice_m / 2)
    stock.TurnDown(z, 0.02, 0);
  const TurnedProfile turned{2, stock.Cylinders(1e-6)};
  ASSERT_GT(turned.cylinders.size(), profile.cylinders.size());
  const render::Image cut = renderer.Render(q, camera, 160, 120, &turned);
  EXPECT_GT(PixelsApart(cut, raw), 100);

  // The mesh is built per version: the same version draws what it drew.
  profile.version = 2;
  EXPECT_EQ(PixelsApart(renderer.Render(q, camera, 160, 120, &profile), cut), 0);
  profile.version = 3;
  EXPECT_EQ(PixelsApart(renderer.Render(q, camera, 160, 120, &profile), raw), 0);
}

TEST(TurnedPictures, ABoreAndAFaceGrooveShowInTheEndFace) {
  const Scene scene = LoadScene(SourcePath("scenes/turning.yaml"));
  SceneRenderer renderer(*scene.model, scene.workpiece);
  std::vector<double> q(scene.model->joints.size(), 0.0);
  q[scene.model->JointIndex("tailstock")] = 0.7;  // out of the way
  // Looking at the bar's free end face from the tailstock's side, a little from above.
  const NamedCamera camera{"face", {0.08, 0.06, 0.4}, {0.0, 0.0, 0.21}, {0, 1, 0}, 30};
  TurnedStock stock = TurnedStock::FromPart(scene.workpiece.part, 0.0005);
  const TurnedProfile solid{1, stock.Cylinders(1e-6)};
  const render::Image before = renderer.Render(q, camera, 160, 120, &solid);
  // A d 20 bore 10 mm deep and a face groove from radius 20 to 24 mm, 5 mm deep, into the
  // face at z 220 mm, cut by boxes as a drill and a blade would be.
  const auto box = [](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    const render::Mesh m = render::MakeBox(lo, hi);
    std::vector<Eigen::Vector3d> corners;
    for (const uint32_t i : m.indices)
      corners.emplace_back(m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]);
    return corners;
  };
  ASSERT_TRUE(stock.CutSolid(box({-0.007, -0.007, 0.21}, {0.007, 0.007, 0.3}), 0));
  ASSERT_TRUE(stock.CutSolid(box({0.02, -0.001, 0.215}, {0.024, 0.001, 0.3}), 0));
  const TurnedProfile cut{2, stock.Cylinders(1e-6)};
  const render::Image after = renderer.Render(q, camera, 160, 120, &cut);
  EXPECT_GT(PixelsApart(after, before), 200);
  if (const char* dir = std::getenv("VMT_TEST_PICTURES")) {
    render::WritePng(std::string(dir) + "/face_before.png", before);
    render::WritePng(std::string(dir) + "/face_after.png", after);
  }
}

TEST(TurnedPictures, PicturesAfterTheRunShowThePartAsItWasAtTheirTick) {
  Scene scene = LoadScene(SourcePath("scenes/turning.yaml"));
  for (SnapshotSpec& s : scene.snapshots) s.width = 160, s.height = 120;
  RunOptions options;
  options.until_s = 16.5;
  std::vector<std::string> dirs;
  for (const bool after : {false, true}) {
    options.out_dir = OutputDir(after ? "turned_pictures_after" : "turned_pictures_at_once");
    options.snapshots_after_run = after;
    const RunResult r = RunScene(scene, options);
    ASSERT_EQ(r.snapshot_files.size(), 2u);
    dirs.push_back(options.out_dir);
  }
  for (const char* file : {"/roughing.png", "/finishing.png"})
    EXPECT_EQ(testing::ReadBytes(dirs[0] + file), testing::ReadBytes(dirs[1] + file)) << file;

  // Roughing and finishing show two contours: drawn with the bar as the scene made it, each
  // picture differs from the one the run took.
  SceneRenderer raw(*scene.model, scene.workpiece);
  for (const auto& [file, at_s] : {std::pair{"/roughing.png", 4.0}, {"/finishing.png", 16.0}}) {
    RunOptions to;
    to.until_s = at_s;
    to.snapshots = false;
    const RunResult r = RunScene(scene, to);
    const render::Image bar = raw.Render(r.final_joint_positions, *scene.Camera("tool"), 160, 120);
    EXPECT_GT(PixelsApart(render::ReadPng(dirs[0] + file), bar), 100) << file;
  }
}

}  // namespace
}  // namespace vmt::sim
