// The sablier command-line tool's commands.
#pragma once

#include <string>
#include <vector>

namespace sablier {

struct RunOptions {
  std::string scene_path;
  std::string out_dir;
  std::vector<std::string> overrides;  // --set KEY=VALUE
  std::vector<std::string> formats{"vtp"};
  bool compress = false;  // zlib-compressed VTK files (.vtp, .vti)
  bool grid = false;      // also frames/grid_NNNNN.vti and grid_series.pvd
  int threads = 0;        // 0 = OpenMP default
  bool quiet = false;
  bool overwrite = false;
  // `run --resume DIR`: continue the run in DIR from its checkpoint (the
  // scene, formats, output options and folder are the run's own; only
  // threads and quiet apply).
  std::string resume_dir;
  // For tests: after writing this frame, stop as an interrupt would (0: never).
  int stop_after_frame = 0;
  // For tests: after step N, go on as if Ctrl-C had come during it (0: never).
  long long interrupt_after_step = 0;
};

// The particle formats `--format` accepts.
extern const char* const kParticleFormats[3];
// Splits "vtp,csv" into its names; returns the first unknown one, or "" if
// all are known.
std::string parse_formats(const std::string& list, std::vector<std::string>& formats);

// True when the program `tool` is on PATH and answers `tool -version`
// (ImageMagick's convert, ffmpeg).
bool tool_present(const char* tool);

// `sablier render DIR`: PNG pictures of a run's frames.
struct RenderCommandOptions {
  std::string dir;
  std::string color = "speed";  // speed | pressure | phi | shear_rate | id
  std::string view = "front";   // front | side | top | iso (3D)
  std::string frames = "all";   // all | last | a frame number
  std::string out_dir;          // default DIR/images
  int width = 800;
  int height = 0;  // 0: from the domain's aspect ratio
  bool gif = false, mp4 = false;
  bool cut = false;  // 3D: only the far half of the box, cut across the view
};

// `sablier plot DIR`: a PNG of the run's stats.csv.
struct PlotCommandOptions {
  std::string dir;
  std::string out;  // default DIR/stats.png
  int width = 800, height = 900;
};

// Runs a scene; returns the process exit code.
int run_command(const RunOptions& options);
// Validates a scene and prints a summary; returns the exit code.
int check_command(const std::string& scene_path, const std::vector<std::string>& overrides);
// Draw pictures of a run; return the exit code (2 for bad input).
int render_command(const RenderCommandOptions& options);
int plot_command(const PlotCommandOptions& options);
// Prints version, build and OpenMP information.
int info_command();

}  // namespace sablier
