#pragma once
// Opening a file the user named as input: only a regular file is read, and a file that cannot
// be read says why. A FIFO would block the open until a writer comes (forever, in a batch run),
// a device may never end and a directory fails deep inside a stream with an unhelpful text, so
// every loader (scene, model, URDF, mesh, NC program, PNG, operator file, study) opens its
// input here.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstring>
#include <string>

namespace vmt::common {

/// Largest scene, model, URDF or operator file read whole (16 MiB): the biggest shipped one is
/// a few kilobytes, and a parser's tree costs hundreds of bytes per input byte.
inline constexpr size_t kMaxInputFileBytes = size_t{16} << 20;

/// Opens `path` read-only and returns its descriptor if it is a regular file; otherwise -1 and
/// `why` says why ("No such file or directory", "Is a directory", "Permission denied", "not a
/// regular file (a FIFO, device or socket)"). `size` receives the file's length.
inline int OpenRegularFile(const std::string& path, std::string& why, size_t& size) {
  if (path.empty()) {
    why = "no file name given";
    return -1;
  }
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below.
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    why = std::strerror(errno);
    return -1;
  }
  struct stat st {};
  if (fstat(fd, &st) != 0) {
    why = std::strerror(errno);
    close(fd);
    return -1;
  }
  if (!S_ISREG(st.st_mode)) {
    why = S_ISDIR(st.st_mode) ? std::strerror(EISDIR)
                              : "not a regular file (a FIFO, device or socket)";
    close(fd);
    return -1;
  }
  // Back to blocking reads: a regular file never waits, but stdio and libraries expect it.
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  size = static_cast<size_t>(st.st_size);
  return fd;
}

/// Why `path` cannot be read as an input file, or "" when it can: for libraries that open the
/// file by name themselves (meshes).
inline std::string InputFileProblem(const std::string& path) {
  std::string why;
  size_t size = 0;
  const int fd = OpenRegularFile(path, why, size);
  if (fd >= 0) close(fd);
  return why;
}

/// Reads a regular file whole into `text`. False with `why` set when it cannot be opened, is
/// not a regular file, is larger than `max_bytes` or fails to read.
inline bool ReadInputFile(const std::string& path, std::string& text, std::string& why,
                          size_t max_bytes = kMaxInputFileBytes) {
  size_t size = 0;
  const int fd = OpenRegularFile(path, why, size);
  if (fd < 0) return false;
  if (size > max_bytes) {
    why = "the file is " + std::to_string(size) + " bytes, more than the limit of " +
          std::to_string(max_bytes) + " bytes";
    close(fd);
    return false;
  }
  text.assign(size, '\0');
  size_t done = 0;
  while (done < size) {
    const ssize_t n = read(fd, text.data() + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      why = std::strerror(errno);
      close(fd);
      return false;
    }
    if (n == 0) break;  // the file shrank while read: keep what is there
    done += static_cast<size_t>(n);
  }
  text.resize(done);
  close(fd);
  return true;
}

}  // namespace vmt::common
