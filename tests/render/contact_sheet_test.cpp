// The contact sheet of a snapshot series: a grid in the order given, each picture captioned,
// wide series scaled down to stay within kContactSheetMaxWidth.

#include "render/contact_sheet.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace vmt::render {
namespace {

Image Filled(int width, int height, uint8_t r, uint8_t g, uint8_t b) {
  Image image{width, height, std::vector<uint8_t>(size_t(width) * size_t(height) * 4)};
  for (size_t i = 0; i < image.rgba.size(); i += 4)
    image.rgba[i] = r, image.rgba[i + 1] = g, image.rgba[i + 2] = b, image.rgba[i + 3] = 255;
  return image;
}

const uint8_t* At(const Image& image, int x, int y) {
  return &image.rgba[(size_t(y) * image.width + x) * 4];
}

bool IsColour(const Image& image, int x, int y, uint8_t r, uint8_t g, uint8_t b) {
  const uint8_t* p = At(image, x, y);
  return p[0] == r && p[1] == g && p[2] == b && p[3] == 255;
}

int DarkPixels(const Image& image, int x0, int y0, int w, int h) {
  int n = 0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) n += At(image, x, y)[0] < 128 ? 1 : 0;
  return n;
}

TEST(ContactSheetTest, GridInOrderWithCaptions) {
  // Five pictures: rows of ceil(sqrt(5)) = 3, two rows.
  const std::vector<Image> pictures = {Filled(40, 30, 255, 0, 0), Filled(40, 30, 0, 255, 0),
                                       Filled(40, 30, 0, 0, 255), Filled(40, 30, 255, 255, 0),
                                       Filled(40, 30, 0, 255, 255)};
  const Image sheet = ContactSheet(pictures, {"2 s", "2.25 s", "2.5 s", "2.75 s", "3 s"});
  // Cells of 40x30 plus a 16 px caption, 4 px gaps around.
  EXPECT_EQ(sheet.width, 3 * (40 + 4) + 4);
  EXPECT_EQ(sheet.height, 2 * (30 + 16 + 4) + 4);
  ASSERT_EQ(sheet.rgba.size(), size_t(sheet.width) * size_t(sheet.height) * 4);
  EXPECT_TRUE(IsColour(sheet, 4 + 20, 4 + 15, 255, 0, 0));                // first, top left
  EXPECT_TRUE(IsColour(sheet, 4 + 44 + 20, 4 + 15, 0, 255, 0));           // second, beside it
  EXPECT_TRUE(IsColour(sheet, 4 + 88 + 20, 4 + 15, 0, 0, 255));           // third
  EXPECT_TRUE(IsColour(sheet, 4 + 20, 4 + 50 + 15, 255, 255, 0));         // fourth, next row
  EXPECT_TRUE(IsColour(sheet, 4 + 44 + 20, 4 + 50 + 15, 0, 255, 255));    // fifth
  EXPECT_TRUE(IsColour(sheet, 4 + 88 + 20, 4 + 50 + 15, 255, 255, 255));  // an empty cell
  EXPECT_TRUE(IsColour(sheet, 1, 1, 255, 255, 255));                      // the border
  // Each caption is drawn in black under its picture; a longer caption has more ink.
  const int first = DarkPixels(sheet, 4, 4 + 30, 40, 16);
  const int second = DarkPixels(sheet, 48, 4 + 30, 40, 16);
  EXPECT_GT(first, 0);
  EXPECT_GT(second, first);
  EXPECT_EQ(DarkPixels(sheet, 4 + 88, 4 + 50 + 30, 40, 16), 0);  // no sixth caption
}

TEST(ContactSheetTest, WideSeriesAreScaledDown) {
  // Nine 800 px pictures: three columns would be 2412 px wide; halved they fit.
  const std::vector<Image> pictures(9, Filled(800, 600, 10, 20, 30));
  const Image sheet = ContactSheet(pictures, {});
  EXPECT_LE(sheet.width, kContactSheetMaxWidth);
  EXPECT_EQ(sheet.width, 3 * (400 + 4) + 4);
  EXPECT_EQ(sheet.height, 3 * (300 + 16 + 4) + 4);
  EXPECT_TRUE(IsColour(sheet, 4 + 200, 4 + 150, 10, 20, 30));
}

TEST(ContactSheetTest, NoPicturesNoSheetAndMalformedThrows) {
  EXPECT_EQ(ContactSheet({}, {}).width, 0);
  Image bad = Filled(4, 4, 0, 0, 0);
  bad.rgba.resize(5);
  EXPECT_THROW(ContactSheet({bad}, {}), std::runtime_error);
}

TEST(ContactSheetTest, CaptionGlyphs) {
  Image image = Filled(40, 10, 255, 255, 255);
  const uint8_t ink[4] = {0, 0, 0, 255};
  DrawCaption(image, 0, 0, "1", 1, ink);
  // '1' is 010/110/010/010/111 in 3x5.
  EXPECT_TRUE(IsColour(image, 1, 0, 0, 0, 0));
  EXPECT_TRUE(IsColour(image, 0, 0, 255, 255, 255));
  EXPECT_TRUE(IsColour(image, 0, 1, 0, 0, 0));
  EXPECT_TRUE(IsColour(image, 2, 4, 0, 0, 0));
  EXPECT_EQ(DarkPixels(image, 0, 0, 40, 10), 8);
  DrawCaption(image, 38, 8, "8", 1, ink);  // clipped at the edge, no crash
}

}  // namespace
}  // namespace vmt::render
