#pragma once

#include <filesystem>
#include <string>

namespace vmt::render::testing {

/// A path for a file a test writes, in the build tree so it can be looked at afterwards.
inline std::string OutputPath(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(VMT_BINARY_DIR) / "test_output" / "render";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

}  // namespace vmt::render::testing
