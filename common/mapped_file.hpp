#pragma once
// Reading a file whole without copying it.

#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "common/input_file.hpp"

namespace vmt::common {

/// A file's bytes, mapped read-only; NC programs are read this way. A generated 1M-block program
/// is 33 MB: copying it into a string first faults in, zeroes and fills 8k fresh pages (~11-20 us
/// each on the project's VMs), while a mapping with MAP_POPULATE takes the page cache's pages as
/// they are. The NC parser keeps nothing of the text, so a program's mapping lives only as long
/// as its parse.
class MappedFile {
 public:
  MappedFile(MappedFile&& o) noexcept
      : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}
  MappedFile& operator=(MappedFile&& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    return *this;
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  ~MappedFile() {
    if (data_ != nullptr) munmap(data_, size_);
  }

  std::string_view text() const { return {static_cast<const char*>(data_), size_}; }
  operator std::string_view() const { return text(); }

  /// nullopt when the file cannot be read (missing, a directory, a FIFO, unreadable); `why`, if
  /// given, receives the reason.
  static std::optional<MappedFile> Read(const std::string& path, std::string* why = nullptr) {
    std::string reason;
    size_t size = 0;
    const int fd = OpenRegularFile(path, reason, size);
    std::optional<MappedFile> file;
    if (fd >= 0) {
      if (size == 0) {
        file = MappedFile(nullptr, 0);  // mmap refuses a length of 0
      } else {
        void* data = mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
        if (data != MAP_FAILED)
          file = MappedFile(data, size);
        else
          reason = std::strerror(errno);
      }
      close(fd);  // the mapping stays valid without the descriptor
    }
    if (why) *why = reason;
    return file;
  }

 private:
  MappedFile(void* data, size_t size) : data_(data), size_(size) {}

  void* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace vmt::common
