#pragma once
// Reading an NC program file whole.

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

namespace vmt::control::nc {

/// The file's bytes in one sized read: a generated 1M-block program is 33 MB, which a stream
/// iterator reads in twice the time the parser needs for it. nullopt when it cannot be read
/// (missing, a directory, unreadable).
inline std::optional<std::string> ReadProgramFile(const std::string& path) {
  // A directory opens as a stream on Linux, and its size reads as a huge number.
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return std::nullopt;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return std::nullopt;
  const std::streamsize size = in.tellg();
  if (size < 0) return std::nullopt;
  std::string text(static_cast<size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(text.data(), size)) return std::nullopt;
  return text;
}

}  // namespace vmt::control::nc
