// Pictures show the workpiece as the stock cutter has turned it at the picture's tick: the
// renderer draws a turned profile (built once per version), an uncut profile looks like the
// scene's part, and a picture rendered after the run shows the part as it was at its tick.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../sim_test_support.hpp"
#include "render/image.hpp"
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
  const double z0 = stock.z0_m, length = stock.slice_m * stock.radius_m.size();
  for (double z = z0 + length / 2; z < z0 + length; z += stock.slice_m / 2) stock.Cut(z, 0.02, 0);
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
