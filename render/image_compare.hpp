#pragma once

#include <string>
#include <vector>

#include "render/image.hpp"

namespace vmt::render {

/// The project's tolerance for a picture against its golden: a pixel differs when a channel
/// differs by more than 2 levels, and at most 0.05 % of the pixels may differ. llvmpipe on
/// another CPU (other shader code, down to no SSE/AVX at all) changed at most 0.021 % of the
/// goldens' pixels, edge pixels by up to 91 levels; 0.05 % is 2.4 times that and half of what
/// the smallest deliberate change of a golden (a turret detail: 0.10 %) changed.
inline constexpr int kGoldenChannelTolerance = 2;
inline constexpr double kGoldenAllowedFraction = 0.0005;

/// A rectangle of pixels, from the top left corner.
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
};

/// How close two pictures must be to count as equal.
struct CompareOptions {
  /// A pixel differs when any channel (r, g, b or a) differs by more than this, 0..255.
  int channel_tolerance = kGoldenChannelTolerance;
  /// Fraction of the compared pixels (0..1) allowed to differ before the pictures count as
  /// different.
  double allowed_fraction = kGoldenAllowedFraction;
  /// Pixels left out of the comparison (a clock, a moving detail); parts outside the pictures
  /// are ignored.
  std::vector<PixelRect> mask;
};

/// The outcome of CompareImages.
struct CompareResult {
  /// Same size and differing_fraction <= allowed_fraction.
  bool equal = false;
  /// The sizes differ; nothing else was compared and diff is empty.
  bool size_mismatch = false;
  /// Pixels where some channel differs by more than channel_tolerance (masked ones not).
  int differing_pixels = 0;
  /// Pixels compared: all but the masked ones.
  int compared_pixels = 0;
  /// Pixels in the mask, left out.
  int masked_pixels = 0;
  /// differing_pixels / compared_pixels; 0 when none are compared.
  double differing_fraction = 0;
  /// Largest channel difference over the compared pixels, 0..255, including those within
  /// tolerance.
  int max_channel_delta = 0;
  /// A faded grey copy of `a` with the differing pixels in opaque red and the masked ones in
  /// a blue and white hatch.
  Image diff;
};

/// Compares two pictures pixel by pixel. A size mismatch is a result, not an error; a
/// malformed Image (rgba.size() != width * height * 4) throws std::runtime_error.
CompareResult CompareImages(const Image& a, const Image& b, const CompareOptions& options = {});

/// One line for a person: "equal (3 pixels beyond tolerance 2)", "different: 412 pixels
/// (0.1341 % of 307200 compared, allowed 0.0500 %) beyond tolerance 2, max channel delta 91",
/// "different sizes: 640x480 vs 320x240"; masked pixels are counted where there are some.
std::string DescribeComparison(const Image& a, const Image& b, const CompareResult& result,
                               const CompareOptions& options);

}  // namespace vmt::render
