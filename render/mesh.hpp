#pragma once

#include <cstdint>
#include <vector>

namespace vmt::render {

/// A triangle mesh in its own frame. Plain data: the renderer validates it when it first draws
/// it (sizes multiple of 3, normals as many as positions or none, indices in range).
struct Mesh {
  /// xyz per vertex, metres.
  std::vector<float> positions;
  /// xyz per vertex, unit length; empty means "no normals" (drawn with a constant normal).
  std::vector<float> normals;
  /// Three vertex indices per triangle, counter-clockwise seen from outside.
  std::vector<uint32_t> indices;
};

/// A colour with components in 0..1; a < 1 draws translucent.
struct Rgba {
  float r, g, b, a;
};

}  // namespace vmt::render
