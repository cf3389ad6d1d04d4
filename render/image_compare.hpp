#pragma once

#include "render/image.hpp"

namespace vmt::render {

/// How close two pictures must be to count as equal.
struct CompareOptions {
  /// A pixel differs when any channel (r, g, b or a) differs by more than this, 0..255.
  int channel_tolerance = 2;
  /// Fraction of pixels (0..1) allowed to differ before the pictures count as different.
  double allowed_fraction = 0.0;
};

/// The outcome of CompareImages.
struct CompareResult {
  /// Same size and differing_fraction <= allowed_fraction.
  bool equal = false;
  /// The sizes differ; nothing else was compared and diff is empty.
  bool size_mismatch = false;
  /// Pixels where some channel differs by more than channel_tolerance.
  int differing_pixels = 0;
  /// differing_pixels / (width * height); 0 for empty pictures.
  double differing_fraction = 0;
  /// Largest channel difference over all pixels, 0..255, including those within tolerance.
  int max_channel_delta = 0;
  /// A faded grey copy of `a` with the differing pixels in opaque red.
  Image diff;
};

/// Compares two pictures pixel by pixel. A size mismatch is a result, not an error; a
/// malformed Image (rgba.size() != width * height * 4) throws std::runtime_error.
CompareResult CompareImages(const Image& a, const Image& b, const CompareOptions& options = {});

}  // namespace vmt::render
