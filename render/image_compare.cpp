#include "render/image_compare.hpp"

#include <algorithm>
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
  result.diff.width = a.width;
  result.diff.height = a.height;
  result.diff.rgba.resize(pixels * 4);
  for (size_t i = 0; i < pixels; ++i) {
    const uint8_t* pa = &a.rgba[i * 4];
    const uint8_t* pb = &b.rgba[i * 4];
    int delta = 0;
    for (int c = 0; c < 4; ++c) delta = std::max(delta, std::abs(int(pa[c]) - int(pb[c])));
    result.max_channel_delta = std::max(result.max_channel_delta, delta);
    uint8_t* out = &result.diff.rgba[i * 4];
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
  result.differing_fraction = pixels ? double(result.differing_pixels) / double(pixels) : 0.0;
  result.equal = result.differing_fraction <= options.allowed_fraction;
  return result;
}

}  // namespace vmt::render
