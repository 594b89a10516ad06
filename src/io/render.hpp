// Pictures of particle frames (`sablier render`): 2D frames as coloured
// discs, 3D frames as shaded spheres seen along one of four views, with the
// scene's obstacles in grey, the domain's outline, a colour bar and the time.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/image.hpp"
#include "io/particle_frame.hpp"
#include "io/stats_writer.hpp"
#include "scene/scene.hpp"

namespace sablier {

enum class ColorBy { speed, pressure, phi, shear_rate, id };
// A 3D view: orthographic, looking along the direction with `azimuth`
// degrees about +z (0 looks along +y, from the front; -90 along -x, from the
// +x side) and `elevation` degrees down from the horizontal (90 looks
// straight down). The named views are front (0, 0), side (-90, 0), top
// (0, 90) and iso (30, 30).
struct View {
  double azimuth = 0.0;
  double elevation = 0.0;
  static View front() { return {0.0, 0.0}; }
  static View side() { return {-90.0, 0.0}; }
  static View top() { return {0.0, 90.0}; }
  static View iso() { return {30.0, 30.0}; }
};

// Names as the command line spells them; false when unknown.
bool parse_color_by(const std::string& name, ColorBy* out);
// A view's name, or "AZIMUTH,ELEVATION" in degrees (finite, elevation in
// [-90, 90]).
bool parse_view(const std::string& name, View* out);
// The colour bar's caption, with the unit: "speed m/s".
std::string color_by_label(ColorBy c);

// The domain drawn around the particles: [lo, hi] per axis.
struct Box {
  int dimension = 2;
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
};

// The box [0, grid.size] of a run's scene.toml; nothing when the file is
// missing or has no usable grid.size. Never throws.
std::optional<Box> read_scene_box(const std::string& path);
// Grows `box` (set box->dimension first; an empty box has lo > hi) to hold
// the frame's particles.
void grow_box(Box* box, const ParticleFrame& frame);
Box empty_box(int dimension);

// Colour range; values outside are clamped to the ends of the map.
struct Range {
  double lo = 0.0, hi = 1.0;
};
// Throws IoError if the frame lacks the attribute.
void check_attribute(const ParticleFrame& frame, ColorBy c);
double attribute_value(const ParticleFrame& frame, ColorBy c, std::size_t p);
// An empty range, to grow with extend_range over the frames, then finish.
Range empty_range();
void extend_range(const ParticleFrame& frame, ColorBy c, Range* range);
// Speed, pressure and shear rate start from 0 (phi and id from their
// minimum); a degenerate range is widened so that it maps.
Range finish_range(Range range, ColorBy c);

struct RenderOptions {
  ColorBy color = ColorBy::speed;
  View view = View::front();
  int width = 800;
  int height = 0;  // 0: from the box's aspect ratio (auto_height)
  // The scene's [[obstacle]] blocks (of the frame's dimension), drawn in
  // grey where they were at the frame's time, clipped to the box.
  std::vector<ObstacleConfig> obstacles;
  // The rigid bodies' track (bodies.csv): each body is drawn where its
  // last row at or before the frame's time puts it.
  std::vector<BodyRow> bodies;
  // 3D: a cutaway. The box is cut in two through its middle across the
  // axis nearest the view direction, and only the half away from the
  // viewer is drawn: its grains, and the solids clipped to it, whose cut
  // faces show. The picture keeps the whole box's framing and outline.
  bool cut = false;
};

// The part of `box` a cutaway seen along `view` keeps (cut_box(box, view)
// = box when the box is 2D).
Box cut_box(const Box& box, View view);

// Picture height that fits the box at `width` with no empty bands.
int auto_height(const Box& box, View view, int width);

// World-to-picture mapping: orthographic projection along the view (2D
// frames ignore it), scaled to fit the box in the picture's plot area.
class Camera {
 public:
  Camera(const Box& box, View view, int width, int height);
  struct Point {
    double x, y;   // pixels, y down
    double depth;  // metres along the view direction (larger is farther)
  };
  // `position` has box.dimension components.
  Point project(const double* position) const;
  // The inverse: the world point drawn at pixel coordinates (x, y) at
  // `depth` (ignored in 2D); writes box.dimension components.
  void unproject(double x, double y, double depth, double* position) const;
  // A world vector (box.dimension components) in screen coordinates:
  // along right, up and towards the viewer.
  void to_screen(const double* vector, double out[3]) const;
  double pixels_per_metre() const { return scale_; }
  // The box's projection in pixels: its bounding rectangle.
  struct Rect {
    double x0, y0, x1, y1;
  };
  const Rect& content() const { return content_; }

 private:
  int dimension_;
  double right_[3], up_[3], back_[3];
  double scale_ = 1.0, x0_ = 0.0, y0_ = 0.0;  // pixel = x0 + scale*s, y0 - scale*t
  Rect content_{};
};

// One picture of the frame. Throws IoError if the frame lacks the colour
// attribute or the particle volumes.
Canvas render_frame(const ParticleFrame& frame, const Box& box, const Range& range,
                    const RenderOptions& options);

// Background and ink of the pictures (tests look for them).
constexpr Rgb kBackground{255, 255, 255};
constexpr Rgb kInk{40, 40, 40};
// Obstacles: the fill of 2D solids and the unshaded colour of 3D ones
// (shaded 3D surfaces stay grey, r = g = b), and their outlines.
constexpr Rgb kObstacle{160, 160, 160};
constexpr Rgb kObstacleEdge{90, 90, 90};

}  // namespace sablier
