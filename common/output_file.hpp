#pragma once
// Every file vmt writes for its user goes through OutputFile, so that a full disk, a quota or a
// lost mount is an error naming the file ("cannot write out/trace.csv: No space left on
// device"), never a file silently cut short, and no reader ever sees half of a finished file.

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace vmt::common {

/// A file vmt could not write; what() is "cannot write PATH: REASON".
class WriteError : public std::runtime_error {
 public:
  WriteError(const std::string& path, int error)
      : std::runtime_error("cannot write " + path + ": " + std::strerror(error)), path_(path) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

class OutputFile {
 public:
  enum class Mode {
    /// Written to PATH.tmp-PID beside it and renamed over PATH by Commit: PATH is the old file
    /// or the whole new one, never a part. A file left unfinished is removed.
    kReplace,
    /// Written at PATH as it goes (events.jsonl: followed with tail -f while the run goes on).
    /// It only ever holds whole Write()s: a failed write cuts it back to the last one that went
    /// through whole (give a Write a whole line).
    kStream,
  };

  /// Creates the file (for kReplace, its temporary). Throws WriteError.
  explicit OutputFile(std::string path, Mode mode = Mode::kReplace)
      : path_(std::move(path)), mode_(mode) {
    written_path_ = mode_ == Mode::kReplace ? path_ + ".tmp-" + std::to_string(::getpid()) : path_;
    fd_ = ::open(written_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) throw WriteError(path_, errno);
    buffer_.reserve(kBlock);
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile() { Discard(); }

  const std::string& path() const { return path_; }
  /// The errno of the first failed write, 0 while every write went through.
  int error() const { return error_; }
  bool open() const { return fd_ >= 0; }

  /// Buffers `data`. Does not throw (the trace writes a row per tick): a failure is kept and
  /// reported by Flush, Commit or Check; the writes after it are dropped.
  void Write(std::string_view data) {
    if (fd_ < 0 || error_ != 0) return;
    buffer_.append(data);
    if (buffer_.size() >= kBlock) WriteOut();
  }

  /// Throws WriteError if a write has failed.
  void Check() const {
    if (error_ != 0) throw WriteError(path_, error_);
  }

  /// Hands what is buffered to the kernel. Throws WriteError.
  void Flush() {
    WriteOut();
    Check();
  }

  /// Completes the file: flushes, closes and (kReplace) renames it over PATH. Throws
  /// WriteError (the temporary is removed then). Once only.
  void Commit() {
    if (fd_ < 0) return Check();
    WriteOut();
    if (error_ == 0 && ::close(std::exchange(fd_, -1)) != 0) error_ = errno;
    if (error_ == 0 && mode_ == Mode::kReplace) {
      if (std::rename(written_path_.c_str(), path_.c_str()) != 0)
        error_ = errno;
      else
        removed_ = true;
    }
    if (error_ != 0) Discard();
    Check();
  }

  /// Leaves the file unfinished: kReplace removes the temporary (its space is free again, PATH
  /// untouched); kStream keeps what was written, whole writes only.
  void Discard() {
    if (mode_ == Mode::kStream) WriteOut();
    if (fd_ >= 0) ::close(std::exchange(fd_, -1));
    if (mode_ == Mode::kReplace && !removed_) {
      std::remove(written_path_.c_str());
      removed_ = true;
    }
    buffer_.clear();
  }

 private:
  static constexpr size_t kBlock = size_t{1} << 16;

  void WriteOut() {
    if (fd_ < 0 || error_ != 0) return;
    size_t done = 0;
    while (done < buffer_.size()) {
      const ssize_t n = ::write(fd_, buffer_.data() + done, buffer_.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return Fail(n < 0 ? errno : ENOSPC);
      done += static_cast<size_t>(n);
    }
    good_bytes_ += static_cast<off_t>(done);
    buffer_.clear();
  }

  void Fail(int error) {
    error_ = error;
    buffer_.clear();
    if (mode_ == Mode::kReplace) {
      // Nothing of it will be used: free its space at once, for the files still to come.
      Discard();
      return;
    }
    // Back to the last whole write (a reader of a stream must never see a cut line).
    const int cut = ::ftruncate(fd_, good_bytes_);
    static_cast<void>(cut);  // the write's error is the one to report
  }

  std::string path_, written_path_;
  Mode mode_;
  int fd_ = -1;
  int error_ = 0;
  bool removed_ = false;
  off_t good_bytes_ = 0;
  std::string buffer_;
};

/// Writes `text` as the whole of `path` (temporary and rename). Throws WriteError.
inline void WriteFileAtomically(const std::string& path, std::string_view text) {
  OutputFile file(path);
  file.Write(text);
  file.Commit();
}

/// Copies `from` whole to `to` (temporary and rename). Throws WriteError, or
/// std::runtime_error "cannot read FROM: REASON".
inline void CopyFileAtomically(const std::string& from, const std::string& to) {
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) throw std::runtime_error("cannot read " + from + ": " + std::strerror(errno));
  OutputFile out(to);
  char block[1 << 16];
  ssize_t n = 0;
  while ((n = ::read(in, block, sizeof block)) > 0 || (n < 0 && errno == EINTR))
    if (n > 0) out.Write(std::string_view(block, static_cast<size_t>(n)));
  const int read_error = errno;
  ::close(in);
  if (n < 0) throw std::runtime_error("cannot read " + from + ": " + std::strerror(read_error));
  out.Commit();
}

}  // namespace vmt::common
