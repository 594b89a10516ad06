// Particle pictures: layout, projection, disc and sphere splats, colour bar.
#include "io/render.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include "io/obstacle_geometry.hpp"
#include "io/render_obstacles.hpp"
#include "io/writers.hpp"

namespace sablier {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Where things go in a picture. Text is drawn at twice the font size in
// pictures wide enough for it to stay legible once scaled down on a page.
struct Layout {
  int scale;           // font pixel size
  int x0, y0, x1, y1;  // plot area [x0, x1) x [y0, y1): the box fits in it
};

constexpr int kLabelChars = 7;  // room kept for a colour bar label

int text_scale(int width) { return width >= 600 ? 2 : 1; }

// Margins: time label above, colour bar and its labels on the right.
void margins(int s, int* top, int* right, int* bottom, int* left) {
  const int pad = 6 * s;
  *top = kGlyphHeight * s + 2 * pad;
  *bottom = *left = pad;
  *right = 2 * pad + 6 * s + 4 * s + (kLabelChars * kGlyphAdvance - 1) * s + pad;
}

Layout layout(int width, int height) {
  Layout l{};
  l.scale = text_scale(width);
  int top, right, bottom, left;
  margins(l.scale, &top, &right, &bottom, &left);
  l.x0 = left, l.y0 = top;
  l.x1 = std::max(l.x0 + 1, width - right);
  l.y1 = std::max(l.y0 + 1, height - bottom);
  return l;
}

// Screen axes of a view: right, up, and the direction towards the viewer.
void view_axes(View view, double right[3], double up[3], double back[3]) {
  const double az = view.azimuth * kPi / 180.0, el = view.elevation * kPi / 180.0;
  // The looking direction.
  const double f[3] = {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), -std::sin(el)};
  // right = f x z normalised, which is (cos az, -sin az, 0) for any
  // elevation in [-90, 90] (and stays defined looking straight down).
  const double r[3] = {std::cos(az), -std::sin(az), 0.0};
  for (int a = 0; a < 3; ++a) right[a] = r[a], back[a] = -f[a];
  up[0] = r[1] * f[2] - r[2] * f[1];
  up[1] = r[2] * f[0] - r[0] * f[2];
  up[2] = r[0] * f[1] - r[1] * f[0];
}

double dot(const double* a, const double* b, int d) {
  double s = 0.0;
  for (int k = 0; k < d; ++k) s += a[k] * b[k];
  return s;
}

// Projected extent of the box's corners along the screen axes.
void projected_extent(const Box& box, const double* right, const double* up, double* smin,
                      double* smax, double* tmin, double* tmax) {
  const int d = box.dimension;
  *smin = *tmin = kInf, *smax = *tmax = -kInf;
  for (int corner = 0; corner < (1 << d); ++corner) {
    double p[3];
    for (int a = 0; a < d; ++a) p[a] = (corner >> a) & 1 ? box.hi[a] : box.lo[a];
    const double s = dot(p, right, d), t = dot(p, up, d);
    *smin = std::min(*smin, s), *smax = std::max(*smax, s);
    *tmin = std::min(*tmin, t), *tmax = std::max(*tmax, t);
  }
}

void screen_axes(const Box& box, View view, double right[3], double up[3], double back[3]) {
  if (box.dimension == 2) {
    right[0] = 1, right[1] = 0, right[2] = 0;
    up[0] = 0, up[1] = 1, up[2] = 0;
    back[0] = 0, back[1] = 0, back[2] = 1;
  } else {
    view_axes(view, right, up, back);
  }
}

// Grain radius from its volume: disc area in 2D, sphere in 3D.
double grain_radius(double volume, int dimension) {
  volume = std::max(volume, 0.0);
  return dimension == 2 ? std::sqrt(volume / kPi) : std::cbrt(3.0 * volume / (4.0 * kPi));
}

}  // namespace

bool parse_color_by(const std::string& name, ColorBy* out) {
  static const std::pair<const char*, ColorBy> names[] = {{"speed", ColorBy::speed},
                                                          {"pressure", ColorBy::pressure},
                                                          {"phi", ColorBy::phi},
                                                          {"shear_rate", ColorBy::shear_rate},
                                                          {"id", ColorBy::id}};
  for (const auto& [n, c] : names)
    if (name == n) return *out = c, true;
  return false;
}

bool parse_view(const std::string& name, View* out) {
  static const std::pair<const char*, View> names[] = {{"front", View::front()},
                                                       {"side", View::side()},
                                                       {"top", View::top()},
                                                       {"iso", View::iso()}};
  for (const auto& [n, v] : names)
    if (name == n) return *out = v, true;
  // "AZIMUTH,ELEVATION" in degrees.
  const std::size_t comma = name.find(',');
  if (comma == std::string::npos) return false;
  const std::string a = name.substr(0, comma), e = name.substr(comma + 1);
  char* end = nullptr;
  const double az = std::strtod(a.c_str(), &end);
  if (a.empty() || *end != '\0') return false;
  const double el = std::strtod(e.c_str(), &end);
  if (e.empty() || *end != '\0') return false;
  if (!std::isfinite(az) || !std::isfinite(el) || el < -90.0 || el > 90.0) return false;
  *out = View{az, el};
  return true;
}

std::string color_by_label(ColorBy c) {
  switch (c) {
    case ColorBy::speed:
      return "speed m/s";
    case ColorBy::pressure:
      return "pressure Pa";
    case ColorBy::phi:
      return "phi";
    case ColorBy::shear_rate:
      return "shear rate 1/s";
    case ColorBy::id:
      return "id";
  }
  return "";
}

std::optional<Box> read_scene_box(const std::string& path) {
  try {
    const toml::table doc = toml::parse_file(path);
    const toml::array* size = doc.at_path("grid.size").as_array();
    if (!size || size->size() < 2 || size->size() > 3) return std::nullopt;
    Box box = empty_box(static_cast<int>(size->size()));
    for (int a = 0; a < box.dimension; ++a) {
      const std::optional<double> v = (*size)[a].value<double>();
      if (!v || !(*v > 0.0)) return std::nullopt;
      box.lo[a] = 0.0, box.hi[a] = *v;
    }
    return box;
  } catch (const std::exception&) {  // missing or unreadable: fall back on the particles
    return std::nullopt;
  }
}

Box empty_box(int dimension) {
  Box box;
  box.dimension = dimension;
  for (int a = 0; a < 3; ++a) box.lo[a] = kInf, box.hi[a] = -kInf;
  return box;
}

void grow_box(Box* box, const ParticleFrame& f) {
  const int d = f.dimension;
  for (std::size_t p = 0; p < f.count; ++p) {
    // The whole grain, not just its centre, must fit.
    const double r = p < f.volume.size() ? grain_radius(f.volume[p], d) : 0.0;
    for (int a = 0; a < d; ++a) {
      box->lo[a] = std::min(box->lo[a], f.position[d * p + a] - r);
      box->hi[a] = std::max(box->hi[a], f.position[d * p + a] + r);
    }
  }
}

void check_attribute(const ParticleFrame& f, ColorBy c) {
  const std::vector<double>* v = nullptr;
  switch (c) {
    case ColorBy::speed:
      v = &f.velocity;
      break;
    case ColorBy::pressure:
      v = &f.pressure;
      break;
    case ColorBy::phi:
      v = &f.phi;
      break;
    case ColorBy::shear_rate:
      v = &f.shear_rate;
      break;
    case ColorBy::id:
      v = &f.id;
      break;
  }
  const std::size_t per = c == ColorBy::speed ? f.dimension : 1;
  if (v->size() != per * f.count)
    throw IoError("the frame has no " + color_by_label(c) + " values");
  if (f.position.size() != static_cast<std::size_t>(f.dimension) * f.count)
    throw IoError("the frame's positions do not match its particle count");
}

double attribute_value(const ParticleFrame& f, ColorBy c, std::size_t p) {
  switch (c) {
    case ColorBy::speed: {
      const int d = f.dimension;
      double s = 0.0;
      for (int a = 0; a < d; ++a) s += f.velocity[d * p + a] * f.velocity[d * p + a];
      return std::sqrt(s);
    }
    case ColorBy::pressure:
      return f.pressure[p];
    case ColorBy::phi:
      return f.phi[p];
    case ColorBy::shear_rate:
      return f.shear_rate[p];
    case ColorBy::id:
      return f.id[p];
  }
  return 0.0;
}

Range empty_range() { return {kInf, -kInf}; }

void extend_range(const ParticleFrame& f, ColorBy c, Range* range) {
  check_attribute(f, c);
  for (std::size_t p = 0; p < f.count; ++p) {
    const double v = attribute_value(f, c, p);
    if (!std::isfinite(v)) continue;  // a bad value must not blank the whole map
    range->lo = std::min(range->lo, v), range->hi = std::max(range->hi, v);
  }
}

Range finish_range(Range r, ColorBy c) {
  if (r.lo > r.hi) r = {0.0, 0.0};  // no finite value at all
  // Pressure, speed and shear rate are read against zero (a colour means
  // the same in every picture of a series); phi and id use their own span.
  if (c != ColorBy::phi && c != ColorBy::id) r.lo = 0.0, r.hi = std::max(r.hi, 0.0);
  if (r.hi > r.lo) return r;
  // One value everywhere: zero (a bed at rest) maps to the bottom of the map,
  // anything else to its middle.
  if (r.lo == 0.0) return {0.0, 1.0};
  const double w = 0.05 * std::abs(r.lo);
  return {r.lo - w, r.hi + w};
}

int auto_height(const Box& box, View view, int width) {
  double right[3], up[3], back[3], smin, smax, tmin, tmax;
  screen_axes(box, view, right, up, back);
  projected_extent(box, right, up, &smin, &smax, &tmin, &tmax);
  const int s = text_scale(width);
  int top, rgt, bottom, left;
  margins(s, &top, &rgt, &bottom, &left);
  const double aspect = smax > smin ? (tmax - tmin) / (smax - smin) : 1.0;
  const int plot = static_cast<int>(std::lround((width - left - rgt) * aspect));
  // Tall enough for the colour bar's two labels, never absurdly tall.
  return std::clamp(top + bottom + plot, top + bottom + 6 * kGlyphHeight * s, 3 * width);
}

Camera::Camera(const Box& box, View view, int width, int height) : dimension_(box.dimension) {
  screen_axes(box, view, right_, up_, back_);
  double smin, smax, tmin, tmax;
  projected_extent(box, right_, up_, &smin, &smax, &tmin, &tmax);
  const Layout l = layout(width, height);
  // A flat or point-like box still gets a finite scale.
  const double ext_s = std::max(smax - smin, 1e-12), ext_t = std::max(tmax - tmin, 1e-12);
  scale_ = std::min((l.x1 - l.x0) / ext_s, (l.y1 - l.y0) / ext_t);
  // Centred in the plot area; the colour bar then follows the box, so the
  // whole group is centred when the box is narrower than the picture.
  x0_ = l.x0 + 0.5 * ((l.x1 - l.x0) - scale_ * ext_s) - scale_ * smin;
  y0_ = l.y1 - 0.5 * ((l.y1 - l.y0) - scale_ * ext_t) + scale_ * tmin;
  content_ = {x0_ + scale_ * smin, y0_ - scale_ * tmax, x0_ + scale_ * smax, y0_ - scale_ * tmin};
}

Camera::Point Camera::project(const double* position) const {
  const int d = dimension_;
  return {x0_ + scale_ * dot(position, right_, d), y0_ - scale_ * dot(position, up_, d),
          d == 3 ? -dot(position, back_, d) : 0.0};
}

void Camera::unproject(double x, double y, double depth, double* position) const {
  const double s = (x - x0_) / scale_, t = (y0_ - y) / scale_;
  if (dimension_ == 2) depth = 0.0;
  for (int a = 0; a < dimension_; ++a) position[a] = s * right_[a] + t * up_[a] - depth * back_[a];
}

void Camera::to_screen(const double* vector, double out[3]) const {
  out[0] = dot(vector, right_, dimension_);
  out[1] = dot(vector, up_, dimension_);
  out[2] = dot(vector, back_, dimension_);
}

namespace {

double value_fraction(double v, const Range& r) { return (v - r.lo) / (r.hi - r.lo); }

void draw_discs(Canvas& canvas, const ParticleFrame& f, const Camera& cam, const Range& range,
                ColorBy color) {
  for (std::size_t p = 0; p < f.count; ++p) {
    const Camera::Point c = cam.project(&f.position[2 * p]);
    const double r = std::max(1.0, grain_radius(f.volume[p], 2) * cam.pixels_per_metre());
    canvas.disc(c.x, c.y, r, viridis(value_fraction(attribute_value(f, color, p), range)));
  }
}

// A sphere impostor: per pixel, the depth and normal of the sphere's front
// surface, depth-tested, Lambert-shaded under a light from the upper left.
void splat_sphere(Canvas& canvas, std::vector<float>& zbuf, const Camera::Point& c, double r_px,
                  double r_world, Rgb base) {
  const int w = canvas.width(), h = canvas.height();
  const int x0 = std::max(0, static_cast<int>(std::floor(c.x - r_px)));
  const int x1 = std::min(w - 1, static_cast<int>(std::ceil(c.x + r_px)));
  const int y0 = std::max(0, static_cast<int>(std::floor(c.y - r_px)));
  const int y1 = std::min(h - 1, static_cast<int>(std::ceil(c.y + r_px)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double u = (x + 0.5 - c.x) / r_px, v = (c.y - (y + 0.5)) / r_px;
      const double q = u * u + v * v;
      if (q > 1.0) continue;
      const double n = std::sqrt(1.0 - q);
      const float depth = static_cast<float>(c.depth - n * r_world);
      float& z = zbuf[static_cast<std::size_t>(y) * w + x];
      if (depth >= z) continue;
      z = depth;
      const double normal[3] = {u, v, n};
      canvas.set(x, y, shade(base, 0.35 + 0.65 * lambert(normal)));
    }
  }
}

// A line drawn only where nothing nearer was drawn: box edges behind the
// sand stay hidden.
void depth_line(Canvas& canvas, const std::vector<float>& zbuf, const Camera::Point& a,
                const Camera::Point& b, Rgb color, int width) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const int steps = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(dx), std::abs(dy)))));
  const int lo = -(width - 1) / 2, hi = width / 2;
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    const int x = static_cast<int>(std::floor(a.x + t * dx));
    const int y = static_cast<int>(std::floor(a.y + t * dy));
    const double depth = a.depth + t * (b.depth - a.depth);
    for (int oy = lo; oy <= hi; ++oy) {
      for (int ox = lo; ox <= hi; ++ox) {
        const int px = x + ox, py = y + oy;
        if (px < 0 || py < 0 || px >= canvas.width() || py >= canvas.height()) continue;
        if (depth <= zbuf[static_cast<std::size_t>(py) * canvas.width() + px] + 1e-9)
          canvas.set(px, py, color);
      }
    }
  }
}

// The grains as spheres and the box's edges, depth-tested against `zbuf`
// (which may already hold the obstacles).
void draw_spheres(Canvas& canvas, std::vector<float>& zbuf, const ParticleFrame& f, const Box& box,
                  const Camera& cam, const Range& range, ColorBy color, int line_width,
                  const Box& shown) {
  for (std::size_t p = 0; p < f.count; ++p) {
    bool in = true;
    for (int a = 0; a < 3; ++a)
      in = in && f.position[3 * p + a] >= shown.lo[a] && f.position[3 * p + a] <= shown.hi[a];
    if (!in) continue;
    const double r = grain_radius(f.volume[p], 3);
    const double r_px = std::max(1.0, r * cam.pixels_per_metre());
    const Rgb base = viridis(value_fraction(attribute_value(f, color, p), range));
    splat_sphere(canvas, zbuf, cam.project(&f.position[3 * p]), r_px, r, base);
  }
  // The 12 edges join corners that differ on one axis.
  for (int c = 0; c < 8; ++c) {
    for (int a = 0; a < 3; ++a) {
      if ((c >> a) & 1) continue;
      double p[3], q[3];
      for (int k = 0; k < 3; ++k) p[k] = (c >> k) & 1 ? box.hi[k] : box.lo[k];
      for (int k = 0; k < 3; ++k) q[k] = p[k];
      q[a] = box.hi[a];
      depth_line(canvas, zbuf, cam.project(p), cam.project(q), kInk, line_width);
    }
  }
}

void draw_outline_2d(Canvas& canvas, const Box& box, const Camera& cam, int width) {
  const double lo[2] = {box.lo[0], box.lo[1]}, hi[2] = {box.hi[0], box.hi[1]};
  const double ul[2] = {box.lo[0], box.hi[1]}, lr[2] = {box.hi[0], box.lo[1]};
  const Camera::Point a = cam.project(lo), b = cam.project(lr), c = cam.project(hi),
                      d = cam.project(ul);
  canvas.line(a.x, a.y, b.x, b.y, kInk, width);
  canvas.line(b.x, b.y, c.x, c.y, kInk, width);
  canvas.line(c.x, c.y, d.x, d.y, kInk, width);
  canvas.line(d.x, d.y, a.x, a.y, kInk, width);
}

// The colour bar right of the box and as tall as it (but tall enough for its
// labels), its caption above it, the time above the box's left corner.
void draw_legend(Canvas& canvas, const Layout& l, const Camera::Rect& box, const Range& range,
                 ColorBy color, double time) {
  const int s = l.scale, pad = 6 * s;
  const int x0 = static_cast<int>(std::lround(box.x1)) + 2 * pad, x1 = x0 + 6 * s;
  const int min_h = 5 * kGlyphHeight * s;
  int y0 = static_cast<int>(std::lround(box.y0)), y1 = static_cast<int>(std::lround(box.y1));
  if (y1 - y0 < min_h) y0 = std::max(l.y0, (y0 + y1 - min_h) / 2), y1 = y0 + min_h;
  const int span = std::max(1, y1 - 1 - y0);
  for (int y = y0; y < y1; ++y)  // maximum at the top
    canvas.fill_rect(x0, y, x1, y + 1, viridis(1.0 - static_cast<double>(y - y0) / span));
  canvas.rect(x0 - 1, y0 - 1, x1, y1, kInk);
  // Labels longer than the room kept for them slide left rather than off the picture.
  const auto label = [&](int y, const std::string& text) {
    canvas.text(std::min(x1 + 4 * s, canvas.width() - s - text_width(text, s)), y, text, kInk, s);
  };
  label(y0, format_number(range.hi));
  label(y1 - kGlyphHeight * s, format_number(range.lo));
  const int text_y =
      std::max(0, std::min(y0, static_cast<int>(std::lround(box.y0))) - pad - kGlyphHeight * s);
  const std::string caption = color_by_label(color);
  canvas.text(std::min(x0, canvas.width() - pad - text_width(caption, s)), text_y, caption, kInk,
              s);
  char t[48];
  std::snprintf(t, sizeof t, "t = %.3f s", time);
  canvas.text(static_cast<int>(std::lround(box.x0)), text_y, t, kInk, s);
}

// The obstacles as at time t: the rigid bodies moved to their track's last
// row at or before t (their scene position before the first row).
std::vector<ObstacleConfig> obstacles_at_frame(const RenderOptions& opt, double t, int dimension) {
  std::vector<ObstacleConfig> out = opt.obstacles;
  const double until = t + 1e-9 * std::max(1.0, std::abs(t));
  for (const BodyRow& b : opt.bodies) {
    if (b.time > until) continue;
    if (b.obstacle < 0 || static_cast<std::size_t>(b.obstacle) >= out.size()) continue;
    ObstacleConfig& o = out[b.obstacle];
    if (!o.dynamic()) continue;
    o = posed_body(opt.obstacles[b.obstacle], b.centre, b.angle, b.quaternion, dimension);
  }
  return out;
}

}  // namespace

Box cut_box(const Box& box, View view) {
  if (box.dimension != 3) return box;
  double right[3], up[3], back[3];
  view_axes(view, right, up, back);
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(back[a]) > std::abs(back[axis])) axis = a;
  Box half = box;
  const double mid = 0.5 * (box.lo[axis] + box.hi[axis]);
  // `back` points towards the viewer: keep the other side.
  (back[axis] > 0.0 ? half.hi : half.lo)[axis] = mid;
  return half;
}

Canvas render_frame(const ParticleFrame& f, const Box& box, const Range& range,
                    const RenderOptions& opt) {
  const std::vector<ObstacleConfig> obstacles = obstacles_at_frame(opt, f.time, f.dimension);
  if (f.dimension != box.dimension) throw IoError("the frame and the box differ in dimension");
  check_attribute(f, opt.color);
  if (f.volume.size() != f.count) throw IoError("the frame has no particle volumes");
  const int height = opt.height > 0 ? opt.height : auto_height(box, opt.view, opt.width);
  Canvas canvas(opt.width, height, kBackground);
  const Camera cam(box, opt.view, opt.width, height);
  const Layout l = layout(opt.width, height);
  if (f.dimension == 2) {
    fill_obstacles_2d(canvas, obstacles, f.time, box, cam, l.scale);
    draw_discs(canvas, f, cam, range, opt.color);
    draw_outline_2d(canvas, box, cam, l.scale);
  } else {
    std::vector<float> zbuf(static_cast<std::size_t>(canvas.width()) * canvas.height(),
                            std::numeric_limits<float>::infinity());
    // A cutaway keeps the grains of the far half, and the solids clipped to
    // it (their cut faces show); without one, every grain (those a run left
    // outside the box included).
    Box shown = box;
    if (opt.cut) {
      shown = cut_box(box, opt.view);
    } else {
      for (int a = 0; a < 3; ++a) shown.lo[a] = -HUGE_VAL, shown.hi[a] = HUGE_VAL;
    }
    draw_obstacles_3d(canvas, zbuf, obstacles, f.time, opt.cut ? shown : box, cam, l.scale);
    draw_spheres(canvas, zbuf, f, box, cam, range, opt.color, l.scale, shown);
  }
  draw_legend(canvas, l, cam.content(), range, opt.color, f.time);
  return canvas;
}

}  // namespace sablier
