// Milliseconds per 640x480 snapshot of the lathe-c1 (all its visuals and a workpiece), steady
// state after the first frame has compiled llvmpipe's shaders.

#include <benchmark/benchmark.h>

#include "sim/runner/scene_renderer.hpp"
#include "sim/scene/scene.hpp"

namespace {

using namespace vmt;

void BM_LatheSnapshot640x480(benchmark::State& state) {
  const sim::Scene scene = sim::LoadScene(std::string(VMT_SOURCE_DIR) + "/scenes/drive-timeline.yaml");
  sim::SceneRenderer renderer(*scene.model, scene.workpiece);
  std::vector<double> q = sim::InitialJointPositions(*scene.model, scene.initial);
  const sim::NamedCamera& camera = *scene.Camera("iso");
  renderer.Render(q, camera, 640, 480);  // first frame: shader compilation
  size_t triangles = 0;
  for (const sim::Link& l : scene.model->links)
    for (const sim::Visual& v : l.visuals) triangles += v.mesh->indices.size() / 3;
  for (auto _ : state) {
    q[scene.model->JointIndex("spindle")] += 0.1;  // a new pose each frame, as in a run
    benchmark::DoNotOptimize(renderer.Render(q, camera, 640, 480).rgba.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}

BENCHMARK(BM_LatheSnapshot640x480)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
