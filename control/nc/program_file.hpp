#pragma once
// Reading an NC program file whole.

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace vmt::control::nc {

/// An NC program file's bytes, mapped read-only. A generated 1M-block program is 33 MB: copying
/// it into a string first faults in, zeroes and fills 8k fresh pages (~11-20 us each on the
/// project's VMs), while a mapping with MAP_POPULATE takes the page cache's pages as they are.
/// The parser keeps nothing of the text, so the mapping need live only as long as the parse.
class ProgramFile {
 public:
  ProgramFile(ProgramFile&& o) noexcept
      : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}
  ProgramFile& operator=(ProgramFile&& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    return *this;
  }
  ProgramFile(const ProgramFile&) = delete;
  ProgramFile& operator=(const ProgramFile&) = delete;
  ~ProgramFile() {
    if (data_ != nullptr) munmap(data_, size_);
  }

  std::string_view text() const { return {static_cast<const char*>(data_), size_}; }
  operator std::string_view() const { return text(); }

  /// nullopt when the file cannot be read (missing, a directory, unreadable).
  static std::optional<ProgramFile> Read(const std::string& path) {
    // O_NONBLOCK: a FIFO is no program, and opening one must not wait for a writer.
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return std::nullopt;
    struct stat st {};
    std::optional<ProgramFile> file;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
      if (st.st_size == 0) {
        file = ProgramFile(nullptr, 0);  // mmap refuses a length of 0
      } else {
        const auto size = static_cast<size_t>(st.st_size);
        void* data = mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
        if (data != MAP_FAILED) file = ProgramFile(data, size);
      }
    }
    close(fd);  // the mapping stays valid without the descriptor
    return file;
  }

 private:
  ProgramFile(void* data, size_t size) : data_(data), size_(size) {}

  void* data_ = nullptr;
  size_t size_ = 0;
};

inline std::optional<ProgramFile> ReadProgramFile(const std::string& path) {
  return ProgramFile::Read(path);
}

}  // namespace vmt::control::nc
