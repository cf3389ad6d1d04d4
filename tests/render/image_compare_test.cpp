#include "render/image_compare.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace vmt::render {
namespace {

Image Filled(int width, int height, uint8_t r, uint8_t g, uint8_t b) {
  Image image{width, height, std::vector<uint8_t>(size_t(width) * size_t(height) * 4)};
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    image.rgba[i] = r, image.rgba[i + 1] = g, image.rgba[i + 2] = b, image.rgba[i + 3] = 255;
  }
  return image;
}

uint8_t* Pixel(Image& image, int x, int y) {
  return &image.rgba[(size_t(y) * image.width + x) * 4];
}

bool IsRed(const Image& image, int x, int y) {
  const uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
  return p[0] == 255 && p[1] == 0 && p[2] == 0 && p[3] == 255;
}

TEST(CompareImagesTest, EqualPictures) {
  const Image a = Filled(8, 6, 10, 20, 30);
  const CompareResult result = CompareImages(a, a, {});
  EXPECT_TRUE(result.equal);
  EXPECT_FALSE(result.size_mismatch);
  EXPECT_EQ(result.differing_pixels, 0);
  EXPECT_EQ(result.differing_fraction, 0.0);
  EXPECT_EQ(result.max_channel_delta, 0);
  EXPECT_EQ(result.diff.width, 8);
  EXPECT_EQ(result.diff.height, 6);
  EXPECT_FALSE(IsRed(result.diff, 0, 0));
}

TEST(CompareImagesTest, DifferenceWithinToleranceIsEqual) {
  const Image a = Filled(8, 6, 10, 20, 30);
  Image b = a;
  Pixel(b, 3, 2)[1] += 2;
  const CompareResult result =
      CompareImages(a, b, {.channel_tolerance = 2, .allowed_fraction = 0, .mask = {}});
  EXPECT_TRUE(result.equal);
  EXPECT_EQ(result.differing_pixels, 0);
  EXPECT_EQ(result.max_channel_delta, 2);
}

TEST(CompareImagesTest, OnePixelBeyondToleranceDiffers) {
  const Image a = Filled(10, 10, 10, 20, 30);
  Image b = a;
  Pixel(b, 3, 2)[2] = 30 + 3;
  const CompareResult result =
      CompareImages(a, b, {.channel_tolerance = 2, .allowed_fraction = 0, .mask = {}});
  EXPECT_FALSE(result.equal);
  EXPECT_FALSE(result.size_mismatch);
  EXPECT_EQ(result.differing_pixels, 1);
  EXPECT_DOUBLE_EQ(result.differing_fraction, 0.01);
  EXPECT_EQ(result.max_channel_delta, 3);
}

TEST(CompareImagesTest, AlphaCounts) {
  const Image a = Filled(2, 2, 10, 20, 30);
  Image b = a;
  Pixel(b, 1, 1)[3] = 0;
  EXPECT_EQ(CompareImages(a, b, {}).differing_pixels, 1);
}

TEST(CompareImagesTest, AllowedFractionAcceptsFewDifferingPixels) {
  const Image a = Filled(10, 10, 10, 20, 30);
  Image b = a;
  Pixel(b, 3, 2)[0] = 200;
  EXPECT_TRUE(
      CompareImages(a, b, {.channel_tolerance = 2, .allowed_fraction = 0.01, .mask = {}}).equal);
  EXPECT_TRUE(
      CompareImages(a, b, {.channel_tolerance = 2, .allowed_fraction = 0.05, .mask = {}}).equal);
  EXPECT_FALSE(
      CompareImages(a, b, {.channel_tolerance = 2, .allowed_fraction = 0.005, .mask = {}}).equal);
}

TEST(CompareImagesTest, SizeMismatchIsAResultNotAnError) {
  const CompareResult result = CompareImages(Filled(4, 4, 0, 0, 0), Filled(4, 5, 0, 0, 0), {});
  EXPECT_FALSE(result.equal);
  EXPECT_TRUE(result.size_mismatch);
  EXPECT_TRUE(result.diff.rgba.empty());
}

TEST(CompareImagesTest, DiffMarksOnlyTheDifferingPixel) {
  const Image a = Filled(5, 4, 0, 0, 255);  // pure blue: its faded grey is not red
  Image b = a;
  Pixel(b, 4, 1)[0] = 100;
  const CompareResult result = CompareImages(a, b, {});
  ASSERT_EQ(result.diff.rgba.size(), a.rgba.size());
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 5; ++x) {
      EXPECT_EQ(IsRed(result.diff, x, y), x == 4 && y == 1) << x << "," << y;
    }
  }
  // Unchanged pixels are grey.
  const uint8_t* p = &result.diff.rgba[0];
  EXPECT_EQ(p[0], p[1]);
  EXPECT_EQ(p[1], p[2]);
}

TEST(CompareImagesTest, MalformedImageThrows) {
  Image bad = Filled(2, 2, 0, 0, 0);
  bad.rgba.resize(3);
  EXPECT_THROW(CompareImages(bad, bad, {}), std::runtime_error);
}

TEST(CompareImagesTest, EmptyImagesAreEqual) {
  EXPECT_TRUE(CompareImages(Image{}, Image{}, {}).equal);
}

TEST(CompareImagesTest, ProjectToleranceByDefault) {
  const CompareOptions options;
  EXPECT_EQ(options.channel_tolerance, kGoldenChannelTolerance);
  EXPECT_EQ(options.allowed_fraction, kGoldenAllowedFraction);
  // 0.05 %: 1 pixel in 2000 passes, 2 do not.
  const Image a = Filled(100, 20, 10, 20, 30);
  Image b = a;
  Pixel(b, 7, 7)[0] = 200;
  EXPECT_TRUE(CompareImages(a, b).equal);
  Pixel(b, 8, 7)[0] = 200;
  EXPECT_FALSE(CompareImages(a, b).equal);
}

TEST(CompareImagesTest, MaskedPixelsAreLeftOutAndShownMasked) {
  const Image a = Filled(10, 10, 10, 20, 30);
  Image b = a;
  for (int y = 2; y < 5; ++y)
    for (int x = 1; x < 4; ++x) Pixel(b, x, y)[0] = 250;  // a 3x3 block changed
  Pixel(b, 9, 9)[1] = 250;                                // and one pixel outside the mask
  const CompareOptions options{
      .channel_tolerance = 2, .allowed_fraction = 0, .mask = {{1, 2, 3, 3}}};
  const CompareResult result = CompareImages(a, b, options);
  EXPECT_EQ(result.masked_pixels, 9);
  EXPECT_EQ(result.compared_pixels, 91);
  EXPECT_EQ(result.differing_pixels, 1);
  EXPECT_DOUBLE_EQ(result.differing_fraction, 1.0 / 91);
  EXPECT_EQ(result.max_channel_delta, 250 - 20);  // the masked 240 is not counted
  EXPECT_FALSE(result.equal);
  // Masked pixels are neither red nor grey: blue, in stripes.
  for (int y = 2; y < 5; ++y) {
    for (int x = 1; x < 4; ++x) {
      const uint8_t* p = &result.diff.rgba[(size_t(y) * 10 + x) * 4];
      EXPECT_EQ(p[2], 255) << x << "," << y;
      EXPECT_LT(p[0], p[2]) << x << "," << y;
    }
  }
  EXPECT_TRUE(IsRed(result.diff, 9, 9));
  // Masking the other pixel too makes them equal; a rectangle beyond the edge is clipped.
  const CompareOptions both{
      .channel_tolerance = 2, .allowed_fraction = 0, .mask = {{1, 2, 3, 3}, {8, 8, 5, 5}}};
  const CompareResult all = CompareImages(a, b, both);
  EXPECT_TRUE(all.equal);
  EXPECT_EQ(all.masked_pixels, 9 + 4);
  EXPECT_EQ(all.compared_pixels, 100 - 13);
}

TEST(CompareImagesTest, DescriptionsNameTheFigures) {
  const Image a = Filled(10, 10, 10, 20, 30);
  Image b = a;
  Pixel(b, 0, 0)[0] = 200;
  const CompareOptions options{
      .channel_tolerance = 2, .allowed_fraction = 0, .mask = {{5, 5, 2, 2}}};
  EXPECT_EQ(DescribeComparison(a, b, CompareImages(a, b, options), options),
            "different: 1 pixels (1.0417 % of 96 compared, allowed 0.0000 %) beyond tolerance 2, "
            "max channel delta 190, 4 masked");
  EXPECT_EQ(DescribeComparison(a, a, CompareImages(a, a), {}),
            "equal (0 pixels beyond tolerance 2)");
  const Image c = Filled(4, 3, 0, 0, 0);
  EXPECT_EQ(DescribeComparison(a, c, CompareImages(a, c), {}), "different sizes: 10x10 vs 4x3");
}

}  // namespace
}  // namespace vmt::render
