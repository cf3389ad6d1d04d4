#include "render/image.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/render/test_paths.hpp"

namespace vmt::render {
namespace {

using testing::OutputPath;

Image Pattern(int width, int height) {
  Image image{width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      uint8_t* p = &image.rgba[(size_t(y) * width + x) * 4];
      p[0] = uint8_t(x * 37);
      p[1] = uint8_t(y * 53);
      p[2] = uint8_t((x + y) * 11);
      p[3] = uint8_t(255 - x * y);
    }
  }
  return image;
}

std::vector<char> Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Expects `f` to throw std::runtime_error whose message contains `text`.
template <typename F>
void ExpectThrowsWith(F f, const std::string& text) {
  try {
    f();
    ADD_FAILURE() << "no exception; expected one mentioning " << text;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

// Writes a PNG in a colour type WritePng does not produce; rows are given packed.
void WriteRawPng(const std::string& path, int width, int height, int bit_depth, int colour_type,
                 const std::vector<std::vector<uint8_t>>& rows,
                 const std::vector<png_color>& palette = {},
                 const std::vector<uint8_t>& palette_alpha = {}) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  ASSERT_NE(file, nullptr);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, file);
  png_set_IHDR(png, info, width, height, bit_depth, colour_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
  if (!palette.empty()) png_set_PLTE(png, info, palette.data(), int(palette.size()));
  if (!palette_alpha.empty()) {
    png_set_tRNS(png, info, palette_alpha.data(), int(palette_alpha.size()), nullptr);
  }
  png_write_info(png, info);
  for (const auto& row : rows) png_write_row(png, row.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(file);
}

TEST(PngTest, RoundTripKeepsPixels) {
  const Image image = Pattern(13, 7);
  const std::string path = OutputPath("round_trip.png");
  WritePng(path, image);
  const Image back = ReadPng(path);
  EXPECT_EQ(back.width, 13);
  EXPECT_EQ(back.height, 7);
  EXPECT_EQ(back.rgba, image.rgba);
}

TEST(PngTest, WritingTwiceGivesIdenticalBytes) {
  const Image image = Pattern(64, 32);
  const std::string first = OutputPath("twice_1.png"), second = OutputPath("twice_2.png");
  WritePng(first, image);
  WritePng(second, image);
  const std::vector<char> bytes = Bytes(first);
  EXPECT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes, Bytes(second));
}

TEST(PngTest, ReadMissingFileThrowsWithPath) {
  const std::string path = OutputPath("does_not_exist.png");
  std::remove(path.c_str());
  ExpectThrowsWith([&] { ReadPng(path); }, path);
}

TEST(PngTest, ReadNonPngThrowsWithPath) {
  const std::string path = OutputPath("not_a_png.png");
  WriteBytes(path, "this is text, not a picture\n");
  ExpectThrowsWith([&] { ReadPng(path); }, path);
  ExpectThrowsWith([&] { ReadPng(path); }, "not a PNG");
}

TEST(PngTest, ReadEmptyAndTruncatedFilesThrowWithPath) {
  const std::string empty = OutputPath("empty.png");
  WriteBytes(empty, "");
  ExpectThrowsWith([&] { ReadPng(empty); }, empty);

  const std::string whole = OutputPath("whole.png");
  WritePng(whole, Pattern(40, 40));
  const std::vector<char> bytes = Bytes(whole);
  const std::string truncated = OutputPath("truncated.png");
  WriteBytes(truncated, std::string(bytes.begin(), bytes.begin() + bytes.size() / 2));
  ExpectThrowsWith([&] { ReadPng(truncated); }, truncated);
}

TEST(PngTest, WriteBadImageOrPathThrowsWithPath) {
  const std::string path = OutputPath("bad_image.png");
  Image image = Pattern(4, 4);
  image.rgba.pop_back();
  ExpectThrowsWith([&] { WritePng(path, image); }, path);
  ExpectThrowsWith([&] { WritePng(path, Image{}); }, path);
  const std::string unwritable = OutputPath("no_such_dir/x.png");
  ExpectThrowsWith([&] { WritePng(unwritable, Pattern(2, 2)); }, unwritable);
}

TEST(PngTest, ReadConvertsGrayToRgba) {
  const std::string path = OutputPath("gray8.png");
  WriteRawPng(path, 3, 1, 8, PNG_COLOR_TYPE_GRAY, {{0, 128, 255}});
  const Image image = ReadPng(path);
  EXPECT_EQ(image.rgba,
            (std::vector<uint8_t>{0, 0, 0, 255, 128, 128, 128, 255, 255, 255, 255, 255}));
}

TEST(PngTest, ReadConvertsOneBitGrayToRgba) {
  const std::string path = OutputPath("gray1.png");
  WriteRawPng(path, 2, 1, 1, PNG_COLOR_TYPE_GRAY, {{0b01000000}});
  const Image image = ReadPng(path);
  EXPECT_EQ(image.rgba, (std::vector<uint8_t>{0, 0, 0, 255, 255, 255, 255, 255}));
}

TEST(PngTest, ReadScalesSixteenBitRgbWithoutGamma) {
  const std::string path = OutputPath("rgb16.png");
  // Big-endian 16-bit samples: 0xFFFF, 0x8080, 0x0000.
  WriteRawPng(path, 1, 1, 16, PNG_COLOR_TYPE_RGB, {{0xFF, 0xFF, 0x80, 0x80, 0x00, 0x00}});
  const Image image = ReadPng(path);
  EXPECT_EQ(image.rgba, (std::vector<uint8_t>{255, 128, 0, 255}));
}

TEST(PngTest, ReadConvertsPaletteWithTransparency) {
  const std::string path = OutputPath("palette.png");
  WriteRawPng(path, 2, 1, 8, PNG_COLOR_TYPE_PALETTE, {{1, 0}},
              {png_color{10, 20, 30}, png_color{200, 100, 50}}, {0});
  const Image image = ReadPng(path);
  EXPECT_EQ(image.rgba, (std::vector<uint8_t>{200, 100, 50, 255, 10, 20, 30, 0}));
}

TEST(PngTest, ReadConvertsGrayAlpha) {
  const std::string path = OutputPath("gray_alpha.png");
  WriteRawPng(path, 1, 1, 8, PNG_COLOR_TYPE_GRAY_ALPHA, {{77, 99}});
  const Image image = ReadPng(path);
  EXPECT_EQ(image.rgba, (std::vector<uint8_t>{77, 77, 77, 99}));
}

}  // namespace
}  // namespace vmt::render
