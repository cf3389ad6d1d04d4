#include "render/image.hpp"

#include <png.h>
#include <unistd.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "common/input_file.hpp"
#include "common/output_file.hpp"

namespace vmt::render {
namespace {

// Larger pictures are more likely a corrupt header than a snapshot; refuse before allocating.
constexpr png_uint_32 kMaxSide = 16384;
// A picture read is at most 32 Mi pixels (128 MiB as RGBA8): snapshots are at most 4096 x 4096
// and contact sheets 2048 wide. A 200-byte header may claim 16384 x 16384 (1 GiB).
constexpr size_t kMaxPngPixels = size_t{1} << 25;

// libpng reports errors by longjmp. The functions that call setjmp hold only objects whose
// destructors a longjmp may skip safely (none run between setjmp and libpng's frames), and the
// message is carried out in this sink to be thrown as an exception from ordinary C++ code.
struct PngErrorSink {
  char message[256] = "unknown libpng error";
};

void OnPngError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngErrorSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", message);
  png_longjmp(png, 1);
}

// Warnings (e.g. an odd iCCP profile) do not change the pixels; stay quiet.
void OnPngWarning(png_structp, png_const_charp) {}

struct File {
  std::FILE* f = nullptr;
  ~File() {
    if (f) std::fclose(f);
  }
};

std::string Describe(const std::string& path, const char* what) {
  return "'" + path + "': " + what;
}

// Returns false with sink.message filled when libpng fails.
bool ReadPngRaw(std::FILE* file, Image& image, PngErrorSink& sink) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &sink, OnPngError, OnPngWarning);
  if (!png) {
    std::snprintf(sink.message, sizeof sink.message, "out of memory");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_init_io(png, file);
  png_set_user_limits(png, kMaxSide, kMaxSide);
  png_read_info(png, info);
  // The header alone decides the allocation: refuse a picture beyond the limit before it.
  if (size_t{png_get_image_width(png, info)} * png_get_image_height(png, info) > kMaxPngPixels) {
    png_error(png, "larger than the limit of 33554432 pixels (e.g. 8192 x 4096)");
  }

  // Convert everything to RGBA8 and keep the stored values: no gamma handling, so a golden
  // picture compares as the bytes it holds.
  const int colour_type = png_get_color_type(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (bit_depth == 16) png_set_scale_16(png);
  if (colour_type == PNG_COLOR_TYPE_GRAY || colour_type == PNG_COLOR_TYPE_GRAY_ALPHA) {
    png_set_gray_to_rgb(png);
  }
  png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);  // no-op where alpha exists already
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);

  const png_uint_32 width = png_get_image_width(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  if (png_get_rowbytes(png, info) != size_t{width} * 4) {
    png_error(png, "unexpected row layout after conversion to RGBA8");
  }
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.rgba.assign(size_t{width} * height * 4, 0);
  for (int pass = 0; pass < passes; ++pass) {
    for (png_uint_32 y = 0; y < height; ++y) {
      png_read_row(png, image.rgba.data() + size_t{y} * width * 4, nullptr);
    }
  }
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

void AppendPngBytes(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::string*>(png_get_io_ptr(png))
      ->append(reinterpret_cast<const char*>(data), length);
}
void FlushNothing(png_structp) {}

// The PNG's bytes into `bytes` (in memory: the file is written whole or not at all).
bool WritePngRaw(std::string& bytes, const Image& image, PngErrorSink& sink) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, OnPngError, OnPngWarning);
  if (!png) {
    std::snprintf(sink.message, sizeof sink.message, "out of memory");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &bytes, AppendPngBytes, FlushNothing);
  // Fixed settings so the bytes depend on the pixels only (libpng's defaults could change).
  png_set_compression_level(png, 6);
  png_set_compression_strategy(png, 0 /* Z_DEFAULT_STRATEGY */);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, image.rgba.data() + size_t(y) * size_t(image.width) * 4);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void WritePng(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 || image.width > int(kMaxSide) ||
      image.height > int(kMaxSide)) {
    throw std::runtime_error(Describe(path, "cannot write a PNG of size ") +
                             std::to_string(image.width) + "x" + std::to_string(image.height));
  }
  if (image.rgba.size() != size_t(image.width) * size_t(image.height) * 4) {
    throw std::runtime_error(Describe(path, "image has ") + std::to_string(image.rgba.size()) +
                             " bytes, expected width * height * 4");
  }
  std::string bytes;
  PngErrorSink sink;
  if (!WritePngRaw(bytes, image, sink)) throw std::runtime_error(Describe(path, sink.message));
  common::WriteFileAtomically(path, bytes);
}

Image ReadPng(const std::string& path) {
  std::string why;
  size_t size = 0;
  const int fd = common::OpenRegularFile(path, why, size);
  if (fd < 0) throw std::runtime_error(Describe(path, why.c_str()));
  File file{fdopen(fd, "rb")};
  if (!file.f) {
    close(fd);
    throw std::runtime_error(Describe(path, std::strerror(errno)));
  }
  png_byte signature[8] = {};
  if (std::fread(signature, 1, sizeof signature, file.f) != sizeof signature ||
      png_sig_cmp(signature, 0, sizeof signature) != 0) {
    throw std::runtime_error(Describe(path, "not a PNG file"));
  }
  std::rewind(file.f);
  Image image;
  PngErrorSink sink;
  if (!ReadPngRaw(file.f, image, sink)) throw std::runtime_error(Describe(path, sink.message));
  return image;
}

}  // namespace vmt::render
