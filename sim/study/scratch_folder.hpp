#pragma once
// A work folder inside a study folder (a reference run, a picture's run, a case being saved):
// removed when it goes out of scope, so that a failed run or a full disk leaves none behind.

#include <filesystem>
#include <string>
#include <system_error>
#include <utility>

namespace vmt::sim::study {

class ScratchFolder {
 public:
  /// Makes `path` anew (empty).
  explicit ScratchFolder(std::string path) : path_(std::move(path)) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  ~ScratchFolder() {
    std::error_code ignored;  // nothing to report from here; a leftover is only disk space
    if (!path_.empty()) std::filesystem::remove_all(path_, ignored);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace vmt::sim::study
