// libFuzzer target for the NC interpreter and channel: any bytes as the NC program of a
// kinematic lathe-c1 scene (its PLC, PathGuard and stock cutter included), run for 0.3 s of
// machine time; the program runs, stops with a message or is refused; never a crash, a
// sanitizer report or a hang.

#include <cstddef>
#include <cstdint>
#include <exception>

#include "sim/runner/runner.hpp"
#include "sim/scene/scene.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const auto scene = [] {
    const auto path = vmt::fuzz::ScratchTree() / "scenes" / "fuzz_nc.yaml";
    vmt::fuzz::WriteFile(path,
                         "scene: fuzz_nc\n"
                         "model: ../models/lathe-c1/machine.yaml\n"
                         "backend: kinematic\n"
                         "duration: 0.3\n"
                         "workpiece: {diameter: 60, length: 160, z: 60}\n"
                         "initial: {Z: 300, X: 150, T: 0, W: 200}\n"
                         "nc: {program: fuzz.mtc, axes: [X, Z], spindle: S1}\n");
    return path;
  }();
  vmt::fuzz::WriteFile(scene.parent_path() / "fuzz.mtc",
                       {reinterpret_cast<const char*>(data), size});
  try {
    const vmt::sim::Scene s = vmt::sim::LoadScene(scene.string());
    vmt::sim::RunOptions options;
    options.snapshots = false;
    (void)vmt::sim::RunScene(s, options);
  } catch (const std::exception&) {
  }
  return 0;
}
