#pragma once
// What the file-reading fuzz targets share: a scratch tree beside the sources, so that a scene or
// machine file written from the fuzzer's bytes finds the models, NC programs and meshes its
// originals refer to (by relative paths), and nothing is written into the sources.

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace vmt::fuzz {

/// The scratch tree: scenes/ holds links to every entry of the sources' scenes/ (but no .yaml
/// of its own), models and examples are links. Made once per process (per job with -jobs) and
/// removed when it exits normally; a crash leaves it for the reproducer.
class ScratchDir {
 public:
  ScratchDir()
      : root_(std::filesystem::temp_directory_path() / ("vmt-fuzz-" + std::to_string(::getpid()))) {
    namespace fs = std::filesystem;
    const fs::path src = VMT_SOURCE_DIR;
    fs::remove_all(root_);  // left by a crashed run of a process with the same id
    fs::create_directories(root_ / "scenes");
    for (const auto& e : fs::directory_iterator(src / "scenes"))
      if (e.path().extension() != ".yaml")
        fs::create_directory_symlink(e.path(), root_ / "scenes" / e.path().filename());
    fs::create_directory_symlink(src / "models", root_ / "models");
    fs::create_directory_symlink(src / "examples", root_ / "examples");
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(root_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;
};

inline const std::filesystem::path& ScratchTree() {
  static const ScratchDir tree;
  return tree.root();
}

/// Writes the input; a write that fails would fuzz the previous input's file again, so it
/// stops the run instead.
inline void WriteFile(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
}

}  // namespace vmt::fuzz
