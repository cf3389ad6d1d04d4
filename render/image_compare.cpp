#include "render/image_compare.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace vmt::render {
namespace {

void CheckLayout(const Image& image, const char* name) {
  if (image.width < 0 || image.height < 0 ||
      image.rgba.size() != size_t(image.width) * size_t(image.height) * 4) {
    throw std::runtime_error(std::string("CompareImages: image ") + name + " (" +
                             std::to_string(image.width) + "x" + std::to_string(image.height) +
                             ") has " + std::to_string(image.rgba.size()) +
                             " bytes, expected width * height * 4");
  }
}

// One byte per pixel, 1 where a mask rectangle covers it (clipped to the picture).
std::vector<uint8_t> MaskOf(const std::vector<PixelRect>& rects, int width, int height) {
  std::vector<uint8_t> masked(size_t(width) * size_t(height), 0);
  for (const PixelRect& r : rects) {
    const int x0 = std::max(r.x, 0), x1 = std::min(r.x + std::max(r.width, 0), width);
    const int y0 = std::max(r.y, 0), y1 = std::min(r.y + std::max(r.height, 0), height);
    for (int y = y0; y < y1; ++y)
      std::fill(masked.begin() + y * width + x0, masked.begin() + y * width + std::max(x0, x1), 1);
  }
  return masked;
}

}  // namespace

CompareResult CompareImages(const Image& a, const Image& b, const CompareOptions& options) {
  CheckLayout(a, "a");
  CheckLayout(b, "b");
  CompareResult result;
  if (a.width != b.width || a.height != b.height) {
    result.size_mismatch = true;
    return result;
  }
  const size_t pixels = size_t(a.width) * size_t(a.height);
  const std::vector<uint8_t> masked = MaskOf(options.mask, a.width, a.height);
  result.diff.width = a.width;
  result.diff.height = a.height;
  result.diff.rgba.resize(pixels * 4);
  for (size_t i = 0; i < pixels; ++i) {
    const uint8_t* pa = &a.rgba[i * 4];
    const uint8_t* pb = &b.rgba[i * 4];
    uint8_t* out = &result.diff.rgba[i * 4];
    if (masked[i]) {
      // Diagonal stripes, so that a masked area reads as "not compared" at any size.
      const size_t x = i % size_t(a.width), y = i / size_t(a.width);
      const bool stripe = (x + y) % 8 < 4;
      out[0] = stripe ? 90 : 235, out[1] = stripe ? 120 : 240, out[2] = 255, out[3] = 255;
      ++result.masked_pixels;
      continue;
    }
    int delta = 0;
    for (int c = 0; c < 4; ++c) delta = std::max(delta, std::abs(int(pa[c]) - int(pb[c])));
    result.max_channel_delta = std::max(result.max_channel_delta, delta);
    if (delta > options.channel_tolerance) {
      ++result.differing_pixels;
      out[0] = 255, out[1] = 0, out[2] = 0, out[3] = 255;
    } else {
      // Integer luma (BT.601) faded two thirds towards white, so red marks stand out.
      const int luma = (299 * pa[0] + 587 * pa[1] + 114 * pa[2] + 500) / 1000;
      const auto faded = uint8_t((luma + 2 * 255) / 3);
      out[0] = out[1] = out[2] = faded;
      out[3] = 255;
    }
  }
  result.compared_pixels = int(pixels) - result.masked_pixels;
  result.differing_fraction =
      result.compared_pixels ? double(result.differing_pixels) / result.compared_pixels : 0.0;
  result.equal = result.differing_fraction <= options.allowed_fraction;
  return result;
}

std::string DescribeComparison(const Image& a, const Image& b, const CompareResult& r,
                               const CompareOptions& options) {
  char text[256];
  if (r.size_mismatch) {
    std::snprintf(text, sizeof text, "different sizes: %dx%d vs %dx%d", a.width, a.height, b.width,
                  b.height);
    return text;
  }
  std::string masked;
  if (r.masked_pixels > 0) masked = ", " + std::to_string(r.masked_pixels) + " masked";
  if (r.equal) {
    std::snprintf(text, sizeof text, "equal (%d pixels beyond tolerance %d%s)", r.differing_pixels,
                  options.channel_tolerance, masked.c_str());
  } else {
    std::snprintf(text, sizeof text,
                  "different: %d pixels (%.4f %% of %d compared, allowed %.4f %%) beyond "
                  "tolerance %d, max channel delta %d%s",
                  r.differing_pixels, 100 * r.differing_fraction, r.compared_pixels,
                  100 * options.allowed_fraction, options.channel_tolerance, r.max_channel_delta,
                  masked.c_str());
  }
  return text;
}

}  // namespace vmt::render
