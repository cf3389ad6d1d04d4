// Offscreen drawing cost: one 640x480 frame of about 10k triangles (ten 256-segment cylinders
// around a box), steady state after the first frame has compiled its shaders.
#include <benchmark/benchmark.h>

#include <vector>

#include "render/mesh_primitives.hpp"
#include "render/offscreen_renderer.hpp"

namespace {

using vmt::render::Camera;
using vmt::render::DrawItem;
using vmt::render::Mesh;

void BM_Draw640x480(benchmark::State& state) {
  const int supersample = int(state.range(0));
  const Mesh cylinder = vmt::render::MakeCylinder(0.03, 0.25, 256);  // 1024 triangles
  const Mesh box = vmt::render::MakeBox({-0.4, -0.4, -0.05}, {0.4, 0.4, 0});
  std::vector<DrawItem> items;
  for (int i = 0; i < 10; ++i) {
    const double x = -0.3 + 0.15 * (i % 5), y = i < 5 ? -0.1 : 0.1;
    items.push_back(
        {&cylinder, Eigen::Isometry3d(Eigen::Translation3d(x, y, 0)), {0.8f, 0.2f, 0.1f, 1}});
  }
  items.push_back({&box, Eigen::Isometry3d::Identity(), {0.6f, 0.6f, 0.6f, 1}});
  Camera camera;
  camera.eye = {0.6, -0.9, 0.7};
  camera.target = {0, 0, 0.1};
  camera.up = {0, 0, 1};

  vmt::render::OffscreenRenderer renderer(640, 480, supersample);
  renderer.Draw(camera, items);  // shader compilation and upload
  for (auto _ : state) {
    benchmark::DoNotOptimize(renderer.Draw(camera, items));
  }
  state.counters["triangles"] = double(10 * cylinder.indices.size() / 3 + box.indices.size() / 3);
}
BENCHMARK(BM_Draw640x480)->ArgName("supersample")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// The first frame of a new renderer: context creation, shader compilation, upload.
void BM_FirstFrame640x480(benchmark::State& state) {
  const Mesh cylinder = vmt::render::MakeCylinder(0.03, 0.25, 256);
  const std::vector<DrawItem> items{
      {&cylinder, Eigen::Isometry3d::Identity(), {0.8f, 0.2f, 0.1f, 1}}};
  Camera camera;
  camera.eye = {0.6, -0.9, 0.7};
  camera.up = {0, 0, 1};
  for (auto _ : state) {
    vmt::render::OffscreenRenderer renderer(640, 480);
    benchmark::DoNotOptimize(renderer.Draw(camera, items));
  }
}
BENCHMARK(BM_FirstFrame640x480)->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace
