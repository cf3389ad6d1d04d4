#pragma once
// A work folder inside a study folder (a reference run, a picture's run, a case being saved):
// removed when it goes out of scope, so that a failed run or a full disk leaves none behind.

#include <signal.h>

#include <cerrno>
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

/// The process id a leftover's name ends with (.reference-PID, .snapshot-PID, NAME.tmp-PID),
/// 0 for any other name.
inline long LeftoverPid(const std::string& name) {
  size_t at = std::string::npos;
  if (name.rfind(".reference-", 0) == 0) {
    at = 11;
  } else if (name.rfind(".snapshot-", 0) == 0) {
    at = 10;
  } else if (const size_t tmp = name.rfind(".tmp-"); tmp != std::string::npos) {
    at = tmp + 5;
  }
  if (at >= name.size() || name.size() - at > 9 ||
      name.find_first_not_of("0123456789", at) != std::string::npos)
    return 0;
  return std::stol(name.substr(at));
}

/// Removes what a study killed outright (kill -9, a power cut) left in `dir`: its scratch
/// folders and unfinished files, each only when its process is gone (another shard may be
/// running in the same folder).
inline void RemoveDeadScratch(const std::string& dir) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    const long pid = LeftoverPid(entry.path().filename().string());
    if (pid <= 0 || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    std::filesystem::remove_all(entry.path(), error);
  }
}

}  // namespace vmt::sim::study
