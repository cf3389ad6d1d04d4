#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vmt::render {

/// An 8-bit RGBA picture, rows top-down, 4 bytes per pixel, no padding:
/// rgba.size() == width * height * 4.
struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
};

/// Writes `image` as an 8-bit RGBA PNG. The bytes depend only on the pixels (no time or text
/// chunks, fixed compression settings), so equal pictures give equal files.
/// The file is written whole or not at all (common::OutputFile). Throws std::runtime_error
/// naming `path` if the image is malformed, common::WriteError if the file cannot be written.
void WritePng(const std::string& path, const Image& image);

/// Reads a PNG of any colour type and depth (gray, gray+alpha, RGB, RGBA, palette, 1..16 bit)
/// and converts it to RGBA8: stored values are kept (no gamma correction), 16-bit is scaled
/// down, missing alpha becomes 255. Throws std::runtime_error naming `path` if the file is
/// missing, not a PNG, corrupt or larger than 16384 x 16384.
Image ReadPng(const std::string& path);

}  // namespace vmt::render
