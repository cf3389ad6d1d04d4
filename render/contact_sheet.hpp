#pragma once
// A contact sheet: pictures of a series in one grid, each with a caption (its time), so that a
// series can be looked at, and reviewed in a commit, as one picture.

#include <string>
#include <vector>

#include "render/image.hpp"

namespace vmt::render {

/// The widest sheet, px: wider grids scale their pictures down (box filter, an integer factor).
inline constexpr int kContactSheetMaxWidth = 2048;

/// The pictures in rows of ceil(sqrt(n)), left to right, top to bottom, in the order given; each
/// cell is as large as the largest picture (smaller ones sit at its top left) with its caption
/// below it, drawn in a built-in pixel font that has the digits, '.', '-', ':', '=', ' ', 's',
/// 't' and 'i' (other characters leave a gap). Opaque white background. No pictures: an empty
/// Image. Throws std::runtime_error for a malformed picture.
Image ContactSheet(const std::vector<Image>& pictures, const std::vector<std::string>& captions);

/// Draws `text` in the pixel font with its top left corner at (x, y), each font pixel `scale`
/// pixels square, clipped to the picture.
void DrawCaption(Image& image, int x, int y, const std::string& text, int scale,
                 const uint8_t rgba[4]);

}  // namespace vmt::render
