// A small RGB raster for the `render` and `plot` commands: discs, lines,
// rectangles, 5x7 bitmap text, and PNG encoding (libpng). Everything is
// clipped to the canvas, so callers may draw partly outside it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sablier {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
  bool operator!=(const Rgb& o) const { return !(*this == o); }
};

// The perceptual colour map: matplotlib's viridis, t in [0, 1] (clamped).
Rgb viridis(double t);
// `c` with its brightness scaled by `k` (0 = black, 1 = unchanged).
Rgb shade(Rgb c, double k);

class Canvas {
 public:
  Canvas(int width, int height, Rgb background);

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb at(int x, int y) const;
  // Row-major RGB bytes, 3 per pixel, top row first (what PNG wants).
  const std::vector<std::uint8_t>& pixels() const { return rgb_; }

  void set(int x, int y, Rgb c);
  // Filled rectangle [x0, x1) x [y0, y1).
  void fill_rect(int x0, int y0, int x1, int y1, Rgb c);
  // Outline of the rectangle whose corners are the pixels (x0, y0) and (x1, y1).
  void rect(int x0, int y0, int x1, int y1, Rgb c);
  // Filled disc centred at (cx, cy) in pixel units (pixel centres at k + 0.5):
  // the pixels whose centre it covers.
  void disc(double cx, double cy, double radius, Rgb c);
  // Line between two points in pixel units, `width` pixels thick.
  void line(double x0, double y0, double x1, double y1, Rgb c, int width = 1);
  // Text with its top-left corner at (x, y), each font pixel `scale` wide.
  void text(int x, int y, const std::string& s, Rgb c, int scale = 1);

 private:
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  int width_, height_;
  std::vector<std::uint8_t> rgb_;
};

// The 5x7 font: every glyph is 5 pixels wide plus one of spacing, 7 high.
constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;
// Width in pixels of `s` drawn at `scale`.
int text_width(const std::string& s, int scale = 1);
// The glyph's rows, top first, bit 4 = leftmost column. Upper-case letters
// have their own glyphs; characters outside the font get a '?'.
const std::uint8_t* glyph(char c);

// An 8-bit RGB PNG of the canvas, encoded in memory. Throws IoError.
std::string encode_png(const Canvas& canvas);

// A short label for a number with `digits` significant digits: plain for
// magnitudes in [1e-3, 1e5) ("1000", "0.25"), else a short exponent form
// ("2.01e-4", "1.5e6"). Trailing zeros are dropped.
std::string format_number(double v, int digits = 3);

}  // namespace sablier
