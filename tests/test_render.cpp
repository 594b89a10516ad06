// Pictures of runs: PNG encoding round-trips through libpng's own decoder,
// particles land where the camera says in the colour the map gives, 3D
// frames show the box, obstacles are grey behind (2D) or among (3D) the
// grains, and `sablier render` / `sablier plot` write decodable pictures or
// fail with one line and exit code 2.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "io/image.hpp"
#include "io/plot.hpp"
#include "io/render.hpp"
#include "io/writers.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;

struct Decoded {
  bool ok = false;
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  Rgb at(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

// libpng's simplified reader: independent of the encoder's code path.
Decoded decode_png(const std::string& bytes) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  Decoded d;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) return d;
  image.format = PNG_FORMAT_RGB;
  d.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, d.rgb.data(), 0, nullptr)) {
    png_image_free(&image);
    return d;
  }
  d.ok = true;
  d.width = static_cast<int>(image.width);
  d.height = static_cast<int>(image.height);
  return d;
}

Decoded decode_file(const fs::path& path) { return decode_png(read_file(path.string())); }

TEST(Render, PngRoundTripsThroughLibpng) {
  Canvas c(7, 5, {10, 20, 30});
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x)
      c.set(x, y, {static_cast<std::uint8_t>(x * 36), static_cast<std::uint8_t>(y * 60), 200});
  const std::string png = encode_png(c);
  ASSERT_EQ(png.compare(1, 3, "PNG"), 0);
  const Decoded d = decode_png(png);
  ASSERT_TRUE(d.ok);
  ASSERT_EQ(d.width, 7);
  ASSERT_EQ(d.height, 5);
  EXPECT_EQ(d.rgb, c.pixels());
}

TEST(Render, ViridisMatchesMatplotlib) {
  // Entries 0, 128 and 255 of matplotlib's table as 8-bit colours.
  EXPECT_EQ(viridis(0.0), (Rgb{68, 1, 84}));
  EXPECT_EQ(viridis(128.0 / 255.0), (Rgb{33, 145, 140}));
  EXPECT_EQ(viridis(1.0), (Rgb{253, 231, 37}));
  EXPECT_EQ(viridis(-3.0), viridis(0.0));
  EXPECT_EQ(viridis(7.0), viridis(1.0));
  EXPECT_EQ(viridis(std::nan("")), viridis(0.0));
}

TEST(Render, NumberLabelsAreShort) {
  EXPECT_EQ(format_number(0.0), "0");
  EXPECT_EQ(format_number(1000.0), "1000");
  EXPECT_EQ(format_number(0.25), "0.25");
  EXPECT_EQ(format_number(2.0123e-4), "2.01e-4");
  EXPECT_EQ(format_number(1.5e6), "1.5e6");
  EXPECT_EQ(text_width("t = 0.500 s", 1), 11 * 6 - 1);
}

TEST(Render, RangesStartFromZeroForMagnitudes) {
  ParticleFrame f;
  f.dimension = 2, f.count = 2;
  f.position = {0.1, 0.1, 0.2, 0.2};
  f.velocity = {3.0, 4.0, 1.0, 0.0};
  f.pressure = {100.0, 50.0};
  f.phi = {0.5, 0.6};
  Range speed = empty_range();
  extend_range(f, ColorBy::speed, &speed);
  speed = finish_range(speed, ColorBy::speed);
  EXPECT_EQ(speed.lo, 0.0);
  EXPECT_EQ(speed.hi, 5.0);
  Range pressure = empty_range();
  extend_range(f, ColorBy::pressure, &pressure);
  EXPECT_EQ(finish_range(pressure, ColorBy::pressure).lo, 0.0);
  Range phi = empty_range();
  extend_range(f, ColorBy::phi, &phi);
  phi = finish_range(phi, ColorBy::phi);
  EXPECT_DOUBLE_EQ(phi.lo, 0.5);
  EXPECT_DOUBLE_EQ(phi.hi, 0.6);
  // A bed at rest: one value maps without dividing by zero.
  const Range rest = finish_range({0.0, 0.0}, ColorBy::speed);
  EXPECT_LT(rest.lo, rest.hi);
  EXPECT_THROW(extend_range(f, ColorBy::shear_rate, &phi), IoError);  // no such values
}

// A 2D frame of three well-separated particles, speeds 0, 1 and 2.
ParticleFrame three_particles() {
  ParticleFrame f;
  f.dimension = 2, f.count = 3, f.time = 0.5;
  f.position = {0.2, 0.1, 0.5, 0.25, 0.8, 0.4};
  f.velocity = {0.0, 0.0, 1.0, 0.0, 0.0, -2.0};
  f.volume.assign(3, 3.14159e-4);  // radius 1 cm
  f.pressure.assign(3, 0.0);
  f.phi.assign(3, 0.6);
  return f;
}

Box unit_box(int d, double x, double y, double z = 0.0) {
  Box b;
  b.dimension = d;
  b.hi[0] = x, b.hi[1] = y, b.hi[2] = z;
  return b;
}

TEST(Render, TwoDParticlesHaveTheirMapColour) {
  const ParticleFrame f = three_particles();
  const Box box = unit_box(2, 1.0, 0.5);
  const Range range{0.0, 2.0};
  RenderOptions opt;
  opt.width = 400, opt.height = 240;
  const Canvas c = render_frame(f, box, range, opt);
  ASSERT_EQ(c.width(), 400);
  ASSERT_EQ(c.height(), 240);
  const Camera cam(box, opt.view, opt.width, opt.height);
  EXPECT_GT(0.01 * cam.pixels_per_metre(), 2.0);  // discs several pixels wide
  for (std::size_t p = 0; p < f.count; ++p) {
    const Camera::Point q = cam.project(&f.position[2 * p]);
    const double speed = std::hypot(f.velocity[2 * p], f.velocity[2 * p + 1]);
    EXPECT_EQ(c.at(static_cast<int>(q.x), static_cast<int>(q.y)), viridis(speed / 2.0))
        << "particle " << p;
  }
  // Between the particles: background; the floor: the box outline.
  const double empty[2] = {0.35, 0.4}, floor[2] = {0.5, 0.0};
  const Camera::Point e = cam.project(empty), w = cam.project(floor);
  EXPECT_EQ(c.at(static_cast<int>(e.x), static_cast<int>(e.y)), kBackground);
  EXPECT_EQ(c.at(static_cast<int>(w.x), static_cast<int>(w.y)), kInk);
  // The box keeps its aspect ratio (2:1).
  const Camera::Rect& r = cam.content();
  EXPECT_NEAR((r.x1 - r.x0) / (r.y1 - r.y0), 2.0, 0.02);
}

ParticleFrame small_3d_block() {
  ParticleFrame f;
  f.dimension = 3, f.count = 8, f.time = 0.25;
  for (int k = 0; k < 8; ++k) {
    f.position.push_back(0.4 + 0.05 * (k & 1));
    f.position.push_back(0.04 + 0.02 * ((k >> 1) & 1));
    f.position.push_back(0.05 + 0.05 * ((k >> 2) & 1));
    for (int a = 0; a < 3; ++a) f.velocity.push_back(a == 2 ? -0.1 * k : 0.0);
  }
  f.volume.assign(8, 4.19e-6);  // radius 1 cm
  f.pressure.assign(8, 1.0);
  f.phi.assign(8, 0.6);
  f.shear_rate.assign(8, 0.0);
  f.id = {0, 1, 2, 3, 4, 5, 6, 7};
  return f;
}

bool ink_near(const Canvas& c, const Camera::Point& p) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (c.at(static_cast<int>(p.x) + dx, static_cast<int>(p.y) + dy) == kInk) return true;
  return false;
}

TEST(Render, ThreeDFramesShowTheBoxAndShadedGrains) {
  const ParticleFrame f = small_3d_block();
  const Box box = unit_box(3, 1.0, 0.1, 0.25);
  for (View view : {View::front(), View::side(), View::top(), View::iso(), View{-120.0, 55.0}}) {
    RenderOptions opt;
    opt.view = view, opt.color = ColorBy::id, opt.width = 500;
    opt.height = auto_height(box, view, opt.width);
    const Canvas c = render_frame(f, box, {0.0, 7.0}, opt);
    const Camera cam(box, view, opt.width, opt.height);
    // Every corner of the box is on a drawn edge (no grain hides them here).
    for (int corner = 0; corner < 8; ++corner) {
      const double p[3] = {corner & 1 ? 1.0 : 0.0, corner & 2 ? 0.1 : 0.0, corner & 4 ? 0.25 : 0.0};
      EXPECT_TRUE(ink_near(c, cam.project(p)))
          << "view " << view.azimuth << "," << view.elevation << " corner " << corner;
    }
    // The grains are drawn, shaded: not background at the first grain's centre.
    const Camera::Point g = cam.project(&f.position[0]);
    EXPECT_NE(c.at(static_cast<int>(g.x), static_cast<int>(g.y)), kBackground);
  }
}

// Unprojecting a pixel and projecting it back gives the pixel (and the
// depth in 3D).
TEST(Render, CameraUnprojectInvertsProject) {
  const Box flat = unit_box(2, 1.0, 0.5), deep = unit_box(3, 1.0, 0.3, 0.25);
  for (View view : {View::front(), View::iso(), View{-120.0, 55.0}}) {
    for (const Box& box : {flat, deep}) {
      const Camera cam(box, view, 400, 300);
      double p[3];
      cam.unproject(123.5, 77.25, 0.4, p);
      const Camera::Point q = cam.project(p);
      EXPECT_NEAR(q.x, 123.5, 1e-9);
      EXPECT_NEAR(q.y, 77.25, 1e-9);
      EXPECT_NEAR(q.depth, box.dimension == 3 ? 0.4 : 0.0, 1e-12);
    }
  }
}

bool is_grey(Rgb c) { return c.r == c.g && c.g == c.b && c != kBackground && c != kInk; }

Rgb pixel_at(const Canvas& c, double x, double y) {
  return c.at(static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y)));
}

ObstacleConfig ball(double x, double y, double z, double radius) {
  ObstacleConfig o;
  o.shape = ObstacleShape::Ball;
  o.center = {x, y, z};
  o.radius = radius;
  return o;
}

// A disk obstacle is filled grey, outlined, clipped to the box, and drawn
// behind the grains: one grain on its rim keeps its colour.
TEST(Render, TwoDObstaclesAreGreyBehindTheGrains) {
  ParticleFrame f = three_particles();
  f.count = 4;
  f.position.insert(f.position.end(), {0.4, 0.1});  // on the first disk's rim
  f.velocity.insert(f.velocity.end(), {1.0, 0.0});
  f.volume.push_back(f.volume[0]);
  f.pressure.push_back(0.0);
  f.phi.push_back(0.6);
  const Box box = unit_box(2, 1.0, 0.5);
  RenderOptions opt;
  opt.width = 400, opt.height = 240;
  opt.obstacles = {ball(0.35, 0.1, 0.0, 0.05), ball(1.0, 0.5, 0.0, 0.1)};  // the second in a corner
  const Canvas c = render_frame(f, box, {0.0, 2.0}, opt);
  const Camera cam(box, opt.view, opt.width, opt.height);
  const auto at = [&](double x, double y) {
    const double p[2] = {x, y};
    const Camera::Point q = cam.project(p);
    return pixel_at(c, q.x, q.y);
  };
  EXPECT_EQ(at(0.35, 0.1), kObstacle);
  EXPECT_EQ(at(0.35, 0.13), kObstacle);
  EXPECT_EQ(at(0.4, 0.1), viridis(0.5));  // the grain on the rim
  EXPECT_EQ(at(0.35, 0.2), kBackground);
  EXPECT_EQ(at(0.25, 0.1), kBackground);
  // The outline: along the row through the centre, the fill is edged.
  const double centre[2] = {0.35, 0.1};
  const Camera::Point q = cam.project(centre);
  int edge = 0;
  for (int x = static_cast<int>(q.x) - 30; x < static_cast<int>(q.x); ++x)
    edge += c.at(x, static_cast<int>(q.y)) == kObstacleEdge;
  EXPECT_GE(edge, 1);
  // The corner disk: grey inside the box, nothing beyond it.
  EXPECT_EQ(at(0.95, 0.45), kObstacle);
  EXPECT_EQ(at(1.02, 0.45), kBackground);
  EXPECT_EQ(at(0.95, 0.52), kBackground);
}

// A 3D grain at `position` (radius 1 cm), its speed `speed`.
void add_grain(ParticleFrame* f, const double* position, double speed) {
  ++f->count;
  f->position.insert(f->position.end(), position, position + 3);
  f->velocity.insert(f->velocity.end(), {speed, 0.0, 0.0});
  f->volume.push_back(4.19e-6);
  f->pressure.push_back(0.0);
  f->phi.push_back(0.6);
}

// A sphere obstacle is a shaded grey surface in the grains' depth buffer:
// a grain in front of it keeps its colour, one behind it is hidden, and
// the rest of its disc is grey, in every view.
TEST(Render, ThreeDObstaclesAreShadedAmongTheGrains) {
  const Box box = unit_box(3, 1.0, 0.3, 0.25);
  const double centre[3] = {0.5, 0.15, 0.12}, radius = 0.06;
  for (View view : {View::front(), View::side(), View::top(), View::iso(), View{-120.0, 55.0}}) {
    RenderOptions opt;
    opt.view = view, opt.width = 500;
    opt.height = auto_height(box, view, opt.width);
    opt.obstacles = {ball(centre[0], centre[1], centre[2], radius)};
    const Camera cam(box, view, opt.width, opt.height);
    const Camera::Point c = cam.project(centre);
    const double ppm = cam.pixels_per_metre();
    ParticleFrame f;
    f.dimension = 3, f.time = 0.25;
    double in_front[3], behind[3];
    cam.unproject(c.x, c.y, c.depth - radius - 0.015, in_front);
    cam.unproject(c.x + 0.035 * ppm, c.y, c.depth + radius + 0.02, behind);
    add_grain(&f, in_front, 1.0);
    add_grain(&f, behind, 2.0);
    const Canvas pic = render_frame(f, box, {0.0, 2.0}, opt);
    const std::string where =
        "view " + std::to_string(view.azimuth) + "," + std::to_string(view.elevation);
    const Rgb front = pixel_at(pic, c.x, c.y);
    EXPECT_FALSE(is_grey(front)) << where;
    EXPECT_NE(front, kBackground) << where;
    EXPECT_TRUE(is_grey(pixel_at(pic, c.x + 0.035 * ppm, c.y))) << where;  // hides the far grain
    int grey = 0, total = 0;
    for (int y = static_cast<int>(c.y - radius * ppm); y <= c.y + radius * ppm; ++y)
      for (int x = static_cast<int>(c.x - radius * ppm); x <= c.x + radius * ppm; ++x)
        if (std::hypot(x + 0.5 - c.x, y + 0.5 - c.y) < 0.9 * radius * ppm)
          ++total, grey += is_grey(pic.at(x, y));
    EXPECT_GT(grey, 0.8 * total) << where;
  }
}

// A cutaway (`--cut`) keeps the half of the box away from the viewer,
// across the axis nearest the view: front (looking along +y) keeps
// y >= mid, side (from +x) x <= mid, top (from +z) z <= mid. A grain in the
// near half is not drawn, and a solid straddling the cut shows its cut
// face, lit flat, where the grain stood in front of it.
TEST(Render, CutawayShowsTheFarHalf) {
  const Box box = unit_box(3, 1.0, 0.3, 0.25);
  const Box front = cut_box(box, View::front()), side = cut_box(box, View::side()),
            top = cut_box(box, View::top());
  EXPECT_EQ(front.lo[1], 0.15);
  EXPECT_EQ(front.hi[1], 0.3);
  EXPECT_EQ(side.lo[0], 0.0);
  EXPECT_EQ(side.hi[0], 0.5);
  EXPECT_EQ(top.lo[2], 0.0);
  EXPECT_EQ(top.hi[2], 0.125);
  const double centre[3] = {0.5, 0.15, 0.12}, radius = 0.06;
  RenderOptions opt;
  opt.view = View::front(), opt.width = 500;
  opt.height = auto_height(box, opt.view, opt.width);
  opt.obstacles = {ball(centre[0], centre[1], centre[2], radius)};
  const Camera cam(box, opt.view, opt.width, opt.height);
  const Camera::Point c = cam.project(centre);
  ParticleFrame f;
  f.dimension = 3, f.time = 0.25;
  double in_front[3];
  cam.unproject(c.x, c.y, c.depth - radius - 0.015, in_front);
  add_grain(&f, in_front, 1.0);
  const Rgb whole = pixel_at(render_frame(f, box, {0.0, 2.0}, opt), c.x, c.y);
  opt.cut = true;
  const Canvas pic = render_frame(f, box, {0.0, 2.0}, opt);
  EXPECT_FALSE(is_grey(whole));                   // the grain, in front of the ball
  EXPECT_TRUE(is_grey(pixel_at(pic, c.x, c.y)));  // the ball's cut face
  // Lit flat: the same grey across the cut face's middle.
  const double ppm = cam.pixels_per_metre();
  EXPECT_EQ(pixel_at(pic, c.x, c.y), pixel_at(pic, c.x + 0.02 * ppm, c.y - 0.02 * ppm));
}

// Views by name or by explicit angles; malformed angles and elevations
// beyond the poles are refused.
TEST(Render, ViewsByNameOrAngles) {
  View v;
  ASSERT_TRUE(parse_view("-37.5,12", &v));
  EXPECT_EQ(v.azimuth, -37.5);
  EXPECT_EQ(v.elevation, 12.0);
  for (const char* bad :
       {"", "30", "30,", ",30", "a,b", "0,91", "0,-90.5", "nan,0", "0,inf", "1,2,3"})
    EXPECT_FALSE(parse_view(bad, &v)) << '"' << bad << '"';
  // Each name is the camera its documented angles give (docs/render.md).
  for (const auto& [name, angles] : {std::pair<const char*, const char*>{"front", "0,0"},
                                     {"side", "-90,0"},
                                     {"top", "0,90"},
                                     {"iso", "30,30"}}) {
    View a, b;
    ASSERT_TRUE(parse_view(name, &a));
    ASSERT_TRUE(parse_view(angles, &b));
    EXPECT_EQ(a.azimuth, b.azimuth) << name;
    EXPECT_EQ(a.elevation, b.elevation) << name;
  }
}

// ---- the command line ----

using test::Result;
using test::sablier;
using test::shell;

fs::path temp(const std::string& name) { return test::temp_path("render_" + name); }

// A finished 2-frame run of the bed scene (frames 0, 1, 2).
fs::path tiny_run(const std::string& name) {
  const fs::path dir = temp(name);
  fs::remove_all(dir);
  const Result r = sablier("run " + std::string(SABLIER_SOURCE_DIR) + "/scenes/bed2d.toml --out " +
                           dir.string() + " --set time.frames=2 --quiet");
  EXPECT_EQ(r.code, 0) << r.output;
  return dir;
}

// One line, starting with "error:", that mentions `what`.
void expect_one_line_error(const Result& r, const std::string& what) {
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_EQ(r.output.rfind("error: ", 0), 0u) << r.output;
  EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << r.output;
  EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
}

TEST(RenderCli, WritesOnePictureAFrameAtTheRequestedSize) {
  const fs::path dir = tiny_run("frames");
  const Result r = sablier("render " + dir.string() + " --width 320 --height 200");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* name : {"frame_00000.png", "frame_00001.png", "frame_00002.png"}) {
    const Decoded d = decode_file(dir / "images" / name);
    ASSERT_TRUE(d.ok) << name;
    EXPECT_EQ(d.width, 320) << name;
    EXPECT_EQ(d.height, 200) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "images" / "frame_00003.png"));
  // --frames last, another folder, another attribute, default size.
  const fs::path out = temp("frames_last");
  fs::remove_all(out);
  const Result last =
      sablier("render " + dir.string() + " --frames last --color pressure --out " + out.string());
  ASSERT_EQ(last.code, 0) << last.output;
  EXPECT_FALSE(fs::exists(out / "frame_00001.png"));
  const Decoded d = decode_file(out / "frame_00002.png");
  ASSERT_TRUE(d.ok);
  EXPECT_EQ(d.width, 800);
  EXPECT_GT(d.height, 100);
  fs::remove_all(out);
  fs::remove_all(dir);
}

TEST(RenderCli, FindsFramesWithoutTheSeriesFile) {
  const fs::path dir = tiny_run("noseries");
  fs::remove(dir / "series.pvd");
  fs::remove(dir / "scene.toml");  // the box then comes from the particles
  const Result r = sablier("render " + dir.string() + " --frames 1 --width 200");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(decode_file(dir / "images" / "frame_00001.png").ok);
  EXPECT_FALSE(fs::exists(dir / "images" / "frame_00000.png"));
  fs::remove_all(dir);
}

// The obstacles come from the run's scene.toml; one that does not load
// leaves them out (with a warning), and the pictures are still written.
TEST(RenderCli, DrawsTheScenesObstacles) {
  const fs::path dir = tiny_run("obstacles");
  std::ofstream(dir / "scene.toml", std::ios::app)
      << "\n[[obstacle]]\nshape = \"disk\"\ncenter = [0.5, 0.42]\nradius = 0.05\n";
  const auto disk_centre = [&] {
    const Decoded d = decode_file(dir / "images" / "frame_00002.png");
    EXPECT_TRUE(d.ok);
    const Camera cam(unit_box(2, 1.0, 0.5), View::front(), d.width, d.height);
    const double centre[2] = {0.5, 0.42};
    const Camera::Point q = cam.project(centre);
    return d.at(static_cast<int>(q.x), static_cast<int>(q.y));
  };
  const Result r = sablier("render " + dir.string() + " --frames last --width 400");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(disk_centre(), kObstacle);
  std::ofstream(dir / "scene.toml", std::ios::app) << "radius = [\n";  // no longer TOML
  const Result bad = sablier("render " + dir.string() + " --frames last --width 400");
  ASSERT_EQ(bad.code, 0) << bad.output;
  EXPECT_NE(bad.output.find("warning: render: obstacles not drawn"), std::string::npos)
      << bad.output;
  EXPECT_NE(disk_centre(), kObstacle);
  fs::remove_all(dir);
}

TEST(RenderCli, PlotWritesADecodablePicture) {
  const fs::path dir = tiny_run("plot");
  const Result r = sablier("plot " + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const Decoded d = decode_file(dir / "stats.png");
  ASSERT_TRUE(d.ok);
  EXPECT_EQ(d.width, 800);
  EXPECT_EQ(d.height, 900);
  const fs::path out = test::temp_path("render_plot_out", ".png");
  ASSERT_EQ(sablier("plot " + dir.string() + " --out " + out.string()).code, 0);
  EXPECT_TRUE(decode_file(out).ok);
  fs::remove(out);
  fs::remove_all(dir);
}

TEST(RenderCli, BadInputsExitTwoWithOneLine) {
  const fs::path missing = temp("missing");
  fs::remove_all(missing);
  expect_one_line_error(sablier("render " + missing.string()), "no folder");
  expect_one_line_error(sablier("plot " + missing.string()), "no folder");
  const fs::path empty = temp("empty");
  fs::create_directories(empty);
  expect_one_line_error(sablier("render " + empty.string()), "no frames");
  expect_one_line_error(sablier("plot " + empty.string()), "stats.csv");
  fs::remove_all(empty);

  const fs::path dir = tiny_run("bad");
  expect_one_line_error(sablier("render " + dir.string() + " --color temperature"),
                        "unknown attribute \"temperature\"");
  expect_one_line_error(sablier("render " + dir.string() + " --view under"), "unknown view");
  expect_one_line_error(sablier("render " + dir.string() + " --view 10,95"),
                        "AZIMUTH,ELEVATION in degrees (elevation from -90 to 90)");
  expect_one_line_error(sablier("render " + dir.string() + " --frames 7"), "no frame 7");
  expect_one_line_error(sablier("render " + dir.string() + " --frames first"), "--frames");
  expect_one_line_error(sablier("render " + dir.string() + " --width 3"), "--width");
  expect_one_line_error(sablier("plot " + dir.string() + " --out " + (dir / "s.jpg").string()),
                        "allowed: a file name ending in .png");
  EXPECT_FALSE(fs::exists(dir / "s.jpg"));
  std::ofstream(dir / "stats.csv") << "step,time\n1,0.1\n";
  expect_one_line_error(sablier("plot " + dir.string()), "no column \"kinetic_energy\"");
  EXPECT_FALSE(fs::exists(dir / "images"));  // nothing written on bad input
  fs::remove_all(dir);
}

TEST(RenderCli, AnimationsNeedTheirToolAndSaySoWhenMissing) {
  const fs::path dir = tiny_run("anim");
  // With no PATH, neither ImageMagick nor ffmpeg can be found.
  const std::string bin = std::string("PATH=/nonexistent ") + SABLIER_BINARY;
  expect_one_line_error(shell(bin + " render " + dir.string() + " --gif"),
                        "apt-get install imagemagick");
  expect_one_line_error(shell(bin + " render " + dir.string() + " --mp4"),
                        "apt-get install ffmpeg");
  EXPECT_FALSE(fs::exists(dir / "images"));
  fs::remove_all(dir);
}

// Stand-ins for convert and ffmpeg that answer -version and write their
// arguments to the output file (their last argument): the commands the
// renderer builds must get through the shell intact.
TEST(RenderCli, AnimationsCallTheirToolWithTheFrames) {
  const fs::path dir = tiny_run("anim_tools");
  const fs::path bin = temp("fake_bin");
  fs::create_directories(bin);
  for (const char* tool : {"convert", "ffmpeg"}) {
    std::ofstream(bin / tool) << "#!/bin/sh\n[ \"$1\" = -version ] && exit 0\n"
                                 "for last; do :; done\necho \"$@\" > \"$last\"\n";
    fs::permissions(bin / tool, fs::perms::owner_all);
  }
  const Result r = shell("PATH=" + bin.string() + ":/usr/bin:/bin " + SABLIER_BINARY + " render " +
                         dir.string() + " --width 64 --height 48 --gif --mp4");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string gif = read_file((dir / "images" / "animation.gif").string());
  EXPECT_NE(gif.find("-loop 0"), std::string::npos) << gif;
  EXPECT_NE(gif.find("frame_00000.png"), std::string::npos) << gif;
  EXPECT_NE(gif.find("frame_00002.png"), std::string::npos) << gif;
  const std::string mp4 = read_file((dir / "images" / "animation.mp4").string());
  EXPECT_NE(mp4.find("-framerate 30 -start_number 0"), std::string::npos) << mp4;
  EXPECT_NE(mp4.find("frame_%05d.png -frames:v 3"), std::string::npos) << mp4;
  EXPECT_NE(mp4.find("pad=ceil(iw/2)*2:ceil(ih/2)*2"), std::string::npos) << mp4;
  fs::remove_all(bin);
  fs::remove_all(dir);
}

// With Debian's ImageMagick and ffmpeg installed (scripts/setup.sh installs
// both), the animations are real files: a GIF with one image per frame and
// an H.264 MP4 with as many video frames, read back by the tools' own
// readers (identify, ffprobe). Skipped, saying why, where they are absent.
TEST(RenderCli, AnimationsAreRealWithDebianTools) {
  for (const char* tool : {"convert", "identify", "ffmpeg", "ffprobe"})
    if (shell(std::string("command -v ") + tool).code != 0)
      GTEST_SKIP() << tool << " is not installed (apt-get install imagemagick ffmpeg)";
  const fs::path dir = tiny_run("anim_real");  // frames 0, 1, 2
  const Result r = sablier("render " + dir.string() + " --width 64 --height 47 --gif --mp4");
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path gif = dir / "images" / "animation.gif";
  const fs::path mp4 = dir / "images" / "animation.mp4";
  EXPECT_EQ(read_file(gif.string()).rfind("GIF89a", 0), 0u);
  const Result frames = shell("identify -format '%wx%h\n' " + gif.string());
  ASSERT_EQ(frames.code, 0) << frames.output;
  EXPECT_EQ(frames.output, "64x47\n64x47\n64x47\n");
  const Result probe = shell(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=codec_name,width,height,nb_read_frames -of csv=p=0 " +
      mp4.string());
  ASSERT_EQ(probe.code, 0) << probe.output;
  // The odd height is padded to an even one, as H.264 requires.
  EXPECT_EQ(probe.output, "h264,64,48,3\n");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sablier
