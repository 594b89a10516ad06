// `sablier render` (PNG pictures of a run's frames, optionally a GIF or MP4)
// and `sablier plot` (a PNG of the run's stats.csv).
#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>

#include "commands.hpp"
#include "io/plot.hpp"
#include "io/render.hpp"
#include "io/writers.hpp"
#include "scene/scene.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;

// Bad input: the command prints it as one line and exits with code 2.
struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct FrameFile {
  int number;  // NNNNN of particles_NNNNN.vtp
  fs::path path;
};

// The frame number in a name like "particles_00012.vtp"; -1 if none.
int frame_number(const std::string& name) {
  const std::size_t dot = name.rfind('.');
  std::size_t start = dot == std::string::npos ? name.size() : dot;
  while (start > 0 && std::isdigit(static_cast<unsigned char>(name[start - 1]))) --start;
  if (start == dot || dot == std::string::npos || dot - start > 9) return -1;
  return std::stoi(name.substr(start, dot - start));
}

// Frames in the order series.pvd lists them (the run's own index), or the
// particles_*.vtp files of frames/ when the run wrote no series.
std::vector<FrameFile> list_frames(const fs::path& dir) {
  std::vector<FrameFile> frames;
  if (fs::exists(dir / "series.pvd")) {
    const std::string pvd = read_file((dir / "series.pvd").string());
    const std::string key = "file=\"";
    for (std::size_t k = pvd.find(key); k != std::string::npos; k = pvd.find(key, k + 1)) {
      const std::size_t start = k + key.size();
      const std::string file = pvd.substr(start, pvd.find('"', start) - start);
      const int n = frame_number(fs::path(file).filename().string());
      frames.push_back({n >= 0 ? n : static_cast<int>(frames.size()), dir / file});
    }
  } else if (fs::is_directory(dir / "frames")) {
    for (const fs::directory_entry& e : fs::directory_iterator(dir / "frames")) {
      const std::string name = e.path().filename().string();
      const int n = frame_number(name);
      if (name.rfind("particles_", 0) == 0 && e.path().extension() == ".vtp" && n >= 0)
        frames.push_back({n, e.path()});
    }
    std::sort(frames.begin(), frames.end(),
              [](const FrameFile& a, const FrameFile& b) { return a.number < b.number; });
  }
  return frames;
}

std::vector<FrameFile> select_frames(const std::vector<FrameFile>& all, const std::string& which) {
  if (which == "all") return all;
  if (which == "last") return {all.back()};
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  if (which.empty() || which.size() > 9 || !std::all_of(which.begin(), which.end(), digit))
    throw BadInput("--frames: \"" + which + "\" is not all, last or a frame number");
  const int n = std::stoi(which);
  for (const FrameFile& f : all)
    if (f.number == n) return {f};
  throw BadInput(fmt::format("--frames: no frame {} (the run has frames {} to {})", n,
                             all.front().number, all.back().number));
}

ParticleFrame load_frame(const FrameFile& f) {
  return parse_vtp(read_file(f.path.string()), f.path.string());
}

// What all pictures of one call share: the colour range (fixed, so an
// animation does not flicker), the box and the picture size.
struct Scene {
  Range range;
  Box box;
  RenderOptions options;
  double first_time = 0.0, last_time = 0.0;
};

// The run's [[obstacle]] blocks, from its resolved scene. None when
// scene.toml is missing, does not load or is of another dimension: the
// pictures then show the sand alone (with a warning if the file names
// obstacles), never an error.
std::vector<ObstacleConfig> read_obstacles(const fs::path& dir, int dimension) {
  const fs::path path = dir / "scene.toml";
  try {
    if (!fs::exists(path)) return {};
    const SceneConfig scene = load_scene(path.string());
    if (scene.dimension == dimension) return scene.obstacles;
  } catch (const std::exception& e) {
    try {
      if (read_file(path.string()).find("[[obstacle]]") != std::string::npos)
        std::fprintf(stderr, "warning: render: obstacles not drawn: %s\n", e.what());
    } catch (const std::exception&) {  // unreadable: nothing to say about obstacles
    }
  }
  return {};
}

// The rigid bodies' track (bodies.csv) when the run has bodies. Without a
// readable one the bodies are drawn where the scene starts them, with a
// warning.
std::vector<BodyRow> read_bodies(const fs::path& dir, const std::vector<ObstacleConfig>& obstacles,
                                 int dimension) {
  bool any = false;
  for (const ObstacleConfig& o : obstacles) any = any || o.dynamic();
  if (!any) return {};
  const fs::path path = dir / "bodies.csv";
  try {
    return parse_bodies_until(read_file(path.string()), dimension,
                              std::numeric_limits<long>::max());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "warning: render: %s: %s; bodies drawn where they start\n",
                 path.string().c_str(), e.what());
  }
  return {};
}

Scene survey(const std::vector<FrameFile>& frames, const fs::path& dir, RenderOptions opt) {
  Scene s;
  s.range = empty_range();
  int dimension = 0;
  Box bbox;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const ParticleFrame f = load_frame(frames[k]);
    if (k == 0) dimension = f.dimension, bbox = empty_box(dimension), s.first_time = f.time;
    if (f.dimension != dimension) throw BadInput(frames[k].path.string() + ": dimension changes");
    extend_range(f, opt.color, &s.range);
    grow_box(&bbox, f);
    s.last_time = f.time;
  }
  s.range = finish_range(s.range, opt.color);
  const std::optional<Box> scene_box = read_scene_box((dir / "scene.toml").string());
  s.box = scene_box && scene_box->dimension == dimension ? *scene_box : bbox;
  if (s.box.lo[0] > s.box.hi[0]) throw BadInput("the frames hold no particles");
  if (opt.height == 0) opt.height = auto_height(s.box, opt.view, opt.width);
  opt.obstacles = read_obstacles(dir, dimension);
  opt.bodies = read_bodies(dir, opt.obstacles, dimension);
  s.options = opt;
  return s;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void check_tools(const RenderCommandOptions& o) {
  if (o.gif && !tool_present("convert"))
    throw BadInput(
        "--gif needs ImageMagick's convert, which is not installed: "
        "apt-get install imagemagick");
  if (o.mp4 && !tool_present("ffmpeg"))
    throw BadInput("--mp4 needs ffmpeg, which is not installed: apt-get install ffmpeg");
}

fs::path picture_path(const fs::path& out, int number) {
  return out / fmt::format("frame_{:05d}.png", number);
}

// Assembles the pictures into out/animation.{gif,mp4} at the run's frame rate.
int make_animations(const RenderCommandOptions& o, const std::vector<FrameFile>& frames,
                    const fs::path& out, const Scene& s) {
  const double span = s.last_time - s.first_time;
  const double fps = frames.size() > 1 && span > 0 ? (frames.size() - 1) / span : 30.0;
  if (o.gif) {
    std::string cmd =
        fmt::format("convert -delay {} -loop 0", std::max(1L, std::lround(100 / fps)));
    for (const FrameFile& f : frames)
      cmd += " " + shell_quote(picture_path(out, f.number).string());
    cmd += " " + shell_quote((out / "animation.gif").string());
    if (std::system(cmd.c_str()) != 0) return std::fprintf(stderr, "error: convert failed\n"), 3;
    std::printf("wrote %s\n", (out / "animation.gif").c_str());
  }
  if (o.mp4) {
    // yuv420p for players' sake, which needs even sides.
    const std::string cmd = fmt::format(
        "ffmpeg -y -loglevel error -framerate {:.6g} -start_number {} -i {} -frames:v {} "
        "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p {}",
        fps, frames.front().number, shell_quote((out / "frame_%05d.png").string()), frames.size(),
        shell_quote((out / "animation.mp4").string()));
    if (std::system(cmd.c_str()) != 0) return std::fprintf(stderr, "error: ffmpeg failed\n"), 3;
    std::printf("wrote %s\n", (out / "animation.mp4").c_str());
  }
  return 0;
}

RenderOptions parse_render_options(const RenderCommandOptions& o) {
  RenderOptions opt;
  if (!parse_color_by(o.color, &opt.color))
    throw BadInput("--color: unknown attribute \"" + o.color +
                   "\"; allowed: speed, pressure, phi, shear_rate, id");
  if (!parse_view(o.view, &opt.view))
    throw BadInput("--view: unknown view \"" + o.view +
                   "\"; allowed: front, side, top, iso, or AZIMUTH,ELEVATION in degrees "
                   "(elevation from -90 to 90)");
  if (o.width < 16 || o.width > 8192) throw BadInput("--width: must be 16 to 8192 pixels");
  if (o.height != 0 && (o.height < 16 || o.height > 8192))
    throw BadInput("--height: must be 16 to 8192 pixels");
  opt.width = o.width;
  opt.height = o.height;
  opt.cut = o.cut;
  return opt;
}

void require_folder(const std::string& dir) {
  if (dir.empty() || !fs::is_directory(dir)) throw BadInput("no folder " + dir);
}

}  // namespace

int render_command(const RenderCommandOptions& o) {
  std::vector<FrameFile> frames;
  Scene scene;
  try {
    const RenderOptions opt = parse_render_options(o);
    require_folder(o.dir);
    const std::vector<FrameFile> all = list_frames(o.dir);
    if (all.empty())
      throw BadInput("no frames in " + o.dir +
                     " (expected series.pvd or frames/particles_NNNNN.vtp)");
    frames = select_frames(all, o.frames);
    check_tools(o);
    scene = survey(frames, o.dir, opt);
  } catch (const std::exception& e) {  // BadInput, IoError (unreadable frame), filesystem
    std::fprintf(stderr, "error: render: %s\n", e.what());
    return 2;
  }
  const fs::path out = o.out_dir.empty() ? fs::path(o.dir) / "images" : fs::path(o.out_dir);
  try {
    ensure_directory(out.string());
    for (const FrameFile& f : frames) {
      const Canvas picture = render_frame(load_frame(f), scene.box, scene.range, scene.options);
      write_file_atomic(picture_path(out, f.number).string(), encode_png(picture));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: render: %s\n", e.what());
    return 3;
  }
  std::printf("wrote %zu picture(s) of %dx%d to %s (%s from %s to %s)\n", frames.size(),
              scene.options.width, scene.options.height, out.c_str(), o.color.c_str(),
              format_number(scene.range.lo).c_str(), format_number(scene.range.hi).c_str());
  return make_animations(o, frames, out, scene);
}

int plot_command(const PlotCommandOptions& o) {
  StatsSeries stats;
  try {
    require_folder(o.dir);
    const fs::path csv = fs::path(o.dir) / "stats.csv";
    if (!fs::exists(csv))
      throw BadInput("no " + csv.string() + " (is " + o.dir + " a run's folder?)");
    stats = parse_stats_series(read_file(csv.string()), csv.string());
    // The dimension from the run's resolved scene; without it (no scene.toml,
    // or one that is not TOML) the energy panel says J.
    const fs::path scene = fs::path(o.dir) / "scene.toml";
    if (fs::exists(scene)) {
      try {
        const toml::table t = toml::parse(read_file(scene.string()), scene.string());
        const std::optional<int> d = t["dimension"].value<int>();
        if (d && (*d == 2 || *d == 3)) stats.dimension = *d;
      } catch (const toml::parse_error&) {
      }
    }
    if (stats.time.empty()) throw BadInput(csv.string() + " has no steps yet");
    if (o.width < 200 || o.width > 8192 || o.height < 200 || o.height > 8192)
      throw BadInput("--width and --height must be 200 to 8192 pixels");
    if (!o.out.empty() && fs::path(o.out).extension() != ".png")
      throw BadInput("--out " + o.out +
                     ": the picture is a PNG; allowed: a file name ending in .png");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: plot: %s\n", e.what());
    return 2;
  }
  const fs::path out = o.out.empty() ? fs::path(o.dir) / "stats.png" : fs::path(o.out);
  try {
    if (out.has_parent_path()) ensure_directory(out.parent_path().string());
    write_file_atomic(out.string(), encode_png(plot_stats(stats, o.width, o.height)));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: plot: %s\n", e.what());
    return 3;
  }
  std::printf("wrote %s (%zu steps)\n", out.c_str(), stats.time.size());
  return 0;
}

// `-version` exits 0 only for the real program (a stand-in that merely
// shares the name must not count).
bool tool_present(const char* tool) {
  return std::system(fmt::format("{} -version >/dev/null 2>&1", tool).c_str()) == 0;
}

}  // namespace sablier
