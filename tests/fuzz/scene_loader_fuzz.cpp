// libFuzzer target for the scene loader: any bytes as a scene file (next to the repository's
// scenes, so its model and NC program paths resolve) load or are refused with an error; never
// a crash, a sanitizer report or a hang.

#include <cstddef>
#include <cstdint>
#include <exception>

#include "sim/scene/scene.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = vmt::fuzz::ScratchTree() / "scenes" / "fuzz.yaml";
  vmt::fuzz::WriteFile(path, {reinterpret_cast<const char*>(data), size});
  try {
    (void)vmt::sim::LoadScene(path.string());
  } catch (const std::exception&) {
    // a refusal: what it says is the CLI tests' business
  }
  return 0;
}
