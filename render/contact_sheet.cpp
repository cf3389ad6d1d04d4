#include "render/contact_sheet.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vmt::render {
namespace {

// 3x5 pixel glyphs, a row per entry, the high bit of three on the left.
struct Glyph {
  char c;
  uint8_t rows[5];
};
constexpr Glyph kFont[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'-', {0, 0, 7, 0, 0}},
    {':', {0, 2, 0, 2, 0}}, {'=', {0, 7, 0, 7, 0}}, {'s', {0, 7, 6, 3, 7}}, {'t', {2, 7, 2, 2, 3}},
    {'i', {2, 0, 2, 2, 2}},
};
constexpr int kCaptionScale = 2;
constexpr int kCaptionHeight = 5 * kCaptionScale + 6;  // the glyphs and a margin
constexpr int kGap = 4;                                // between cells and at the border

void CheckLayout(const Image& image) {
  if (image.width < 0 || image.height < 0 ||
      image.rgba.size() != size_t(image.width) * size_t(image.height) * 4)
    throw std::runtime_error("ContactSheet: a picture of " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + " has " +
                             std::to_string(image.rgba.size()) + " bytes");
}

// `image` scaled down by an integer factor, each pixel the mean of a factor x factor box.
Image Shrink(const Image& image, int factor) {
  if (factor <= 1) return image;
  Image out;
  out.width = std::max(1, image.width / factor);
  out.height = std::max(1, image.height / factor);
  out.rgba.resize(size_t(out.width) * size_t(out.height) * 4);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      int sum[4] = {0, 0, 0, 0}, n = 0;
      for (int dy = 0; dy < factor && y * factor + dy < image.height; ++dy) {
        for (int dx = 0; dx < factor && x * factor + dx < image.width; ++dx) {
          const uint8_t* p =
              &image.rgba[(size_t(y * factor + dy) * image.width + (x * factor + dx)) * 4];
          for (int c = 0; c < 4; ++c) sum[c] += p[c];
          ++n;
        }
      }
      uint8_t* o = &out.rgba[(size_t(y) * out.width + x) * 4];
      for (int c = 0; c < 4; ++c) o[c] = uint8_t((sum[c] + n / 2) / std::max(n, 1));
    }
  }
  return out;
}

void Fill(Image& image, int x0, int y0, int w, int h, const uint8_t rgba[4]) {
  for (int y = std::max(y0, 0); y < std::min(y0 + h, image.height); ++y)
    for (int x = std::max(x0, 0); x < std::min(x0 + w, image.width); ++x)
      std::copy(rgba, rgba + 4, &image.rgba[(size_t(y) * image.width + x) * 4]);
}

}  // namespace

void DrawCaption(Image& image, int x, int y, const std::string& text, int scale,
                 const uint8_t rgba[4]) {
  for (size_t k = 0; k < text.size(); ++k) {
    const Glyph* glyph = nullptr;
    for (const Glyph& g : kFont)
      if (g.c == text[k]) glyph = &g;
    if (!glyph) continue;
    const int left = x + int(k) * 4 * scale;
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (glyph->rows[row] & (4 >> col))
          Fill(image, left + col * scale, y + row * scale, scale, scale, rgba);
  }
}

Image ContactSheet(const std::vector<Image>& pictures, const std::vector<std::string>& captions) {
  if (pictures.empty()) return {};
  int cell_w = 1, cell_h = 1;
  for (const Image& p : pictures) {
    CheckLayout(p);
    cell_w = std::max(cell_w, p.width), cell_h = std::max(cell_h, p.height);
  }
  const int n = int(pictures.size());
  const int columns = int(std::ceil(std::sqrt(double(n))));
  const int rows = (n + columns - 1) / columns;
  // The smallest integer factor that keeps the sheet within its widest.
  int factor = 1;
  while (columns * (cell_w / factor + kGap) + kGap > kContactSheetMaxWidth && cell_w / factor > 16)
    ++factor;
  cell_w = std::max(1, cell_w / factor), cell_h = std::max(1, cell_h / factor);

  Image sheet;
  sheet.width = columns * (cell_w + kGap) + kGap;
  sheet.height = rows * (cell_h + kCaptionHeight + kGap) + kGap;
  sheet.rgba.assign(size_t(sheet.width) * size_t(sheet.height) * 4, 255);
  const uint8_t ink[4] = {0, 0, 0, 255};
  for (int i = 0; i < n; ++i) {
    const int x0 = kGap + (i % columns) * (cell_w + kGap);
    const int y0 = kGap + (i / columns) * (cell_h + kCaptionHeight + kGap);
    const Image cell = Shrink(pictures[size_t(i)], factor);
    for (int y = 0; y < std::min(cell.height, cell_h); ++y)
      std::copy_n(&cell.rgba[size_t(y) * cell.width * 4], size_t(std::min(cell.width, cell_w)) * 4,
                  &sheet.rgba[(size_t(y0 + y) * sheet.width + x0) * 4]);
    if (size_t(i) < captions.size())
      DrawCaption(sheet, x0 + 2, y0 + cell_h + 3, captions[size_t(i)], kCaptionScale, ink);
  }
  return sheet;
}

}  // namespace vmt::render
