#pragma once
// Reading a file whole without copying it.

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <optional>
#include <string>
#include <string_view>
#include <utility>

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

  /// nullopt when the file cannot be read (missing, a directory, unreadable).
  static std::optional<MappedFile> Read(const std::string& path) {
    // O_NONBLOCK: opening a FIFO must not wait for a writer (a FIFO is refused below).
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return std::nullopt;
    struct stat st {};
    std::optional<MappedFile> file;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
      if (st.st_size == 0) {
        file = MappedFile(nullptr, 0);  // mmap refuses a length of 0
      } else {
        const auto size = static_cast<size_t>(st.st_size);
        void* data = mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
        if (data != MAP_FAILED) file = MappedFile(data, size);
      }
    }
    close(fd);  // the mapping stays valid without the descriptor
    return file;
  }

 private:
  MappedFile(void* data, size_t size) : data_(data), size_(size) {}

  void* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace vmt::common
