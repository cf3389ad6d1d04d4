// libFuzzer target for the machine model loader: any bytes as lathe-c1's machine.yaml (beside
// its URDF and meshes) load or are refused with an error; never a crash or a hang.

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>

#include "sim/model/machine_model.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace fs = std::filesystem;
  static const fs::path dir = [] {
    const fs::path d = vmt::fuzz::ScratchTree() / "model";
    fs::create_directories(d);
    for (const char* entry : {"machine.urdf", "meshes"})
      fs::create_symlink(fs::path(VMT_SOURCE_DIR) / "models/lathe-c1" / entry, d / entry);
    return d;
  }();
  vmt::fuzz::WriteFile(dir / "machine.yaml", {reinterpret_cast<const char*>(data), size});
  try {
    (void)vmt::sim::LoadMachineModel((dir / "machine.yaml").string());
  } catch (const std::exception&) {
  }
  return 0;
}
