// RGB canvas drawing, the viridis colour map and PNG encoding.
#include "io/image.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "io/writers.hpp"

namespace sablier {
namespace {

// Control colours of matplotlib's viridis (van der Walt & Smith, 2015):
// every 16th entry of the 256-entry table `_viridis_data` in
// lib/matplotlib/_cm_listed.py, plus the last. Linear interpolation between
// them stays within about 1/255 of the full table.
struct ControlPoint {
  int index;  // position in the 256-entry table
  double r, g, b;
};
constexpr ControlPoint kViridis[] = {
    {0, 0.267004, 0.004874, 0.329415},   {16, 0.282327, 0.094955, 0.417331},
    {32, 0.278826, 0.175490, 0.483397},  {48, 0.258965, 0.251537, 0.524736},
    {64, 0.229739, 0.322361, 0.545706},  {80, 0.199430, 0.387607, 0.554642},
    {96, 0.172719, 0.448791, 0.557885},  {112, 0.149039, 0.508051, 0.557250},
    {128, 0.127568, 0.566949, 0.550556}, {144, 0.120638, 0.625828, 0.533488},
    {160, 0.157851, 0.683765, 0.501686}, {176, 0.246070, 0.738910, 0.452024},
    {192, 0.369214, 0.788888, 0.382914}, {208, 0.515992, 0.831158, 0.294279},
    {224, 0.678489, 0.863742, 0.189503}, {240, 0.845561, 0.887322, 0.099702},
    {255, 0.993248, 0.906157, 0.143936},
};

std::uint8_t to_byte(double v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

}  // namespace

Rgb viridis(double t) {
  if (!(t >= 0.0)) t = 0.0;  // also catches NaN
  const double x = std::min(t, 1.0) * 255.0;
  constexpr int n = sizeof kViridis / sizeof kViridis[0];
  int k = 0;
  while (k + 2 < n && x > kViridis[k + 1].index) ++k;
  const ControlPoint& a = kViridis[k];
  const ControlPoint& b = kViridis[k + 1];
  const double w = (x - a.index) / (b.index - a.index);
  return {to_byte(a.r + w * (b.r - a.r)), to_byte(a.g + w * (b.g - a.g)),
          to_byte(a.b + w * (b.b - a.b))};
}

Rgb shade(Rgb c, double k) {
  k = std::clamp(k, 0.0, 1.0);
  return {static_cast<std::uint8_t>(std::lround(c.r * k)),
          static_cast<std::uint8_t>(std::lround(c.g * k)),
          static_cast<std::uint8_t>(std::lround(c.b * k))};
}

Canvas::Canvas(int width, int height, Rgb background) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::invalid_argument("canvas size must be at least 1x1");
  rgb_.resize(3 * static_cast<std::size_t>(width) * height);
  for (std::size_t i = 0; i < rgb_.size(); i += 3)
    rgb_[i] = background.r, rgb_[i + 1] = background.g, rgb_[i + 2] = background.b;
}

Rgb Canvas::at(int x, int y) const {
  if (!inside(x, y)) return {};
  const std::size_t i = 3 * (static_cast<std::size_t>(y) * width_ + x);
  return {rgb_[i], rgb_[i + 1], rgb_[i + 2]};
}

void Canvas::set(int x, int y, Rgb c) {
  if (!inside(x, y)) return;
  const std::size_t i = 3 * (static_cast<std::size_t>(y) * width_ + x);
  rgb_[i] = c.r, rgb_[i + 1] = c.g, rgb_[i + 2] = c.b;
}

void Canvas::fill_rect(int x0, int y0, int x1, int y1, Rgb c) {
  x0 = std::max(x0, 0), y0 = std::max(y0, 0);
  x1 = std::min(x1, width_), y1 = std::min(y1, height_);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) set(x, y, c);
}

void Canvas::rect(int x0, int y0, int x1, int y1, Rgb c) {
  fill_rect(x0, y0, x1 + 1, y0 + 1, c);
  fill_rect(x0, y1, x1 + 1, y1 + 1, c);
  fill_rect(x0, y0, x0 + 1, y1 + 1, c);
  fill_rect(x1, y0, x1 + 1, y1 + 1, c);
}

void Canvas::disc(double cx, double cy, double radius, Rgb c) {
  // Hard edges: every pixel whose centre lies in the disc. Anti-aliased
  // edges looked no better at particle sizes of a few pixels but made the
  // PNG files about five times larger (every edge pixel a new colour).
  const int x0 = std::max(0, static_cast<int>(std::floor(cx - radius)));
  const int x1 = std::min(width_ - 1, static_cast<int>(std::ceil(cx + radius)));
  const int y0 = std::max(0, static_cast<int>(std::floor(cy - radius)));
  const int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(cy + radius)));
  const double r2 = radius * radius;
  for (int y = y0; y <= y1; ++y) {
    const double dy = y + 0.5 - cy;
    for (int x = x0; x <= x1; ++x) {
      const double dx = x + 0.5 - cx;
      if (dx * dx + dy * dy <= r2) set(x, y, c);
    }
  }
}

void Canvas::line(double x0, double y0, double x1, double y1, Rgb c, int width) {
  const double dx = x1 - x0, dy = y1 - y0;
  const int steps = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(dx), std::abs(dy)))));
  const int lo = -(width - 1) / 2, hi = width / 2;
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    const int x = static_cast<int>(std::floor(x0 + t * dx));
    const int y = static_cast<int>(std::floor(y0 + t * dy));
    for (int oy = lo; oy <= hi; ++oy)
      for (int ox = lo; ox <= hi; ++ox) set(x + ox, y + oy, c);
  }
}

void Canvas::text(int x, int y, const std::string& s, Rgb c, int scale) {
  for (std::size_t k = 0; k < s.size(); ++k) {
    const std::uint8_t* rows = glyph(s[k]);
    const int gx = x + static_cast<int>(k) * kGlyphAdvance * scale;
    for (int row = 0; row < kGlyphHeight; ++row)
      for (int col = 0; col < kGlyphWidth; ++col)
        if (rows[row] & (0x10 >> col))
          fill_rect(gx + col * scale, y + row * scale, gx + (col + 1) * scale,
                    y + (row + 1) * scale, c);
  }
}

int text_width(const std::string& s, int scale) {
  if (s.empty()) return 0;
  return (static_cast<int>(s.size()) * kGlyphAdvance - (kGlyphAdvance - kGlyphWidth)) * scale;
}

namespace {

void append_png_bytes(png_structp png, png_bytep data, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), n);
}
void flush_nothing(png_structp) {}

// libpng reports errors by longjmp back to the setjmp. Keeping the setjmp in
// a function whose locals are all trivial means the jump skips no destructor
// and no local is left indeterminate.
bool write_png_rows(png_structp png, png_infop info, int width, int height, png_bytepp rows,
                    std::string* out) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, out, append_png_bytes, flush_nothing);
  // The pictures are flat colours and text: maximum compression keeps the
  // files small at little cost.
  png_set_compression_level(png, 9);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

std::string encode_png(const Canvas& canvas) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) throw IoError("cannot encode PNG: out of memory");
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw IoError("cannot encode PNG: out of memory");
  }
  // libpng takes non-const row pointers but only reads through them.
  std::vector<png_bytep> rows(canvas.height());
  auto* base = const_cast<png_bytep>(canvas.pixels().data());
  const std::size_t stride = 3 * static_cast<std::size_t>(canvas.width());
  for (int y = 0; y < canvas.height(); ++y) rows[y] = base + stride * y;
  std::string out;
  const bool ok = write_png_rows(png, info, canvas.width(), canvas.height(), rows.data(), &out);
  png_destroy_write_struct(&png, &info);
  if (!ok) throw IoError("cannot encode PNG");
  return out;
}

std::string format_number(double v, int digits) {
  char buf[64];
  const double a = std::abs(v);
  if (a == 0.0) return "0";
  if (a >= 1e-3 && a < 1e5) {
    // Enough decimals for `digits` significant digits, none below the units
    // for large numbers.
    const int decimals = std::max(0, digits - 1 - static_cast<int>(std::floor(std::log10(a))));
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    std::string s = buf;
    if (s.find('.') != std::string::npos) {  // trailing zeros say nothing
      s.erase(s.find_last_not_of('0') + 1);
      if (s.back() == '.') s.pop_back();
    }
    return s;
  }
  // Exponent form, kept short for labels: "2.01e-04" becomes "2.01e-4".
  std::snprintf(buf, sizeof buf, "%.*e", std::max(0, digits - 1), v);
  std::string s = buf;
  const std::size_t e = s.find('e');
  std::string mantissa = s.substr(0, e);
  if (mantissa.find('.') != std::string::npos) {
    mantissa.erase(mantissa.find_last_not_of('0') + 1);
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  const int exponent = std::atoi(s.c_str() + e + 1);
  return mantissa + "e" + std::to_string(exponent);
}

}  // namespace sablier
