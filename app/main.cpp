// sablier: run, check and inspect granular-flow scenes. See README.md.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "commands.hpp"
#include "core/heap.hpp"

namespace {

// --threads: a whole number of threads, 0 for all cores (OpenMP's default).
// The solver never spins more threads than there are processors
// (solver/team.hpp); the bound only catches typing slips.
constexpr int kMaxThreads = 1024;
const CLI::Validator kThreadCount(
    [](std::string& text) -> std::string {
      char* end = nullptr;
      const long n = std::strtol(text.c_str(), &end, 10);
      if (text.empty() || *end != '\0' || n < 0 || n > kMaxThreads)
        return "\"" + text + "\" is not a whole number from 0 (all cores) to " +
               std::to_string(kMaxThreads);
      return "";
    },
    "0..1024");

// The command line's own errors as the tool's others: one line on stderr
// and exit code 2 (CLI11 would exit with its own codes, 105-109).
int usage_error(const char* program, const CLI::ParseError& e) {
  std::fprintf(stderr, "error: %s (see %s --help)\n", e.what(), program);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  sablier::keep_freed_memory_in_heap();
  CLI::App app{"Sablier: semi-implicit MPM for dry granular materials"};
  app.require_subcommand(1);

  sablier::RunOptions run;
  std::string formats = "vtp";
  CLI::App* run_cmd = app.add_subcommand("run", "Run a scene and write its outputs");
  CLI::Option* scene_opt = run_cmd->add_option("scene", run.scene_path, "Scene file (TOML)");
  CLI::Option* out_opt = run_cmd->add_option("--out,-o", run.out_dir, "Output folder");
  // One KEY=VALUE per --set: a scene file after it stays the scene.
  CLI::Option* set_opt =
      run_cmd->add_option("--set", run.overrides, "Override a scene key: --set material.mu=0.3")
          ->allow_extra_args(false);
  CLI::Option* format_opt =
      run_cmd->add_option("--format", formats,
                          "Particle formats, comma-separated: vtp,csv,ply (vtp is always written)");
  CLI::Option* compress_opt =
      run_cmd->add_flag("--compress", run.compress,
                        "Compress the VTK files (.vtp, .vti) with zlib, as VTK reads them");
  CLI::Option* grid_opt = run_cmd->add_flag(
      "--grid", run.grid,
      "Also write the grid's phi, velocity, pressure and active nodes: frames/grid_NNNNN.vti, "
      "grid_series.pvd");
  run_cmd
      ->add_option("--threads", run.threads,
                   "OpenMP threads, 0 for all cores (the default); the solver uses at most one "
                   "per processor")
      ->check(kThreadCount);
  run_cmd->add_flag("--quiet,-q", run.quiet, "No progress output");
  CLI::Option* overwrite_opt = run_cmd->add_flag("--overwrite", run.overwrite,
                                                 "Replace another run's outputs in the folder");
  run_cmd
      ->add_option("--resume", run.resume_dir,
                   "Continue the interrupted run in this folder from its checkpoint")
      ->excludes(scene_opt)
      ->excludes(out_opt)
      ->excludes(set_opt)
      ->excludes(format_opt)
      ->excludes(compress_opt)
      ->excludes(grid_opt)
      ->excludes(overwrite_opt);
  // For tests of --resume: stop as an interrupt would, after writing frame N.
  run_cmd->add_option("--stop-after-frame", run.stop_after_frame)
      ->check(CLI::NonNegativeNumber)
      ->group("");
  // For tests of --resume: an interrupt at a chosen step, which a real
  // signal only hits by chance (the last step of a frame, say).
  run_cmd->add_option("--interrupt-after-step", run.interrupt_after_step)
      ->check(CLI::NonNegativeNumber)
      ->group("");

  std::string check_path;
  std::vector<std::string> check_overrides;
  CLI::App* check_cmd = app.add_subcommand("check", "Validate a scene and print a summary");
  check_cmd->add_option("scene", check_path, "Scene file (TOML)")->required();
  check_cmd->add_option("--set", check_overrides, "Override a scene key")->allow_extra_args(false);

  sablier::RenderCommandOptions render;
  CLI::App* render_cmd = app.add_subcommand("render", "Draw a run's frames as PNG pictures");
  render_cmd->add_option("dir", render.dir, "Output folder of a run")->required();
  render_cmd->add_option("--color", render.color, "speed | pressure | phi | shear_rate | id");
  render_cmd->add_option("--view", render.view,
                         "3D view: front | side | top | iso | AZIMUTH,ELEVATION (degrees)");
  render_cmd->add_flag("--cut", render.cut,
                       "3D: show only the far half of the box (grains and solids), cut through "
                       "its middle across the axis nearest the view");
  render_cmd->add_option("--width", render.width, "Picture width in pixels (default 800)");
  render_cmd->add_option("--height", render.height, "Picture height (default: fits the domain)");
  render_cmd->add_option("--frames", render.frames, "all | last | a frame number");
  render_cmd->add_option("--out,-o", render.out_dir, "Picture folder (default DIR/images)");
  render_cmd->add_flag("--gif", render.gif, "Also write animation.gif (needs ImageMagick)");
  render_cmd->add_flag("--mp4", render.mp4, "Also write animation.mp4 (needs ffmpeg)");

  sablier::PlotCommandOptions plot;
  CLI::App* plot_cmd = app.add_subcommand("plot", "Plot a run's stats.csv as a PNG");
  plot_cmd->add_option("dir", plot.dir, "Output folder of a run")->required();
  plot_cmd->add_option("--out,-o", plot.out, "PNG file (default DIR/stats.png)");
  plot_cmd->add_option("--width", plot.width, "Picture width in pixels (default 800)");
  plot_cmd->add_option("--height", plot.height, "Picture height in pixels (default 900)");

  CLI::App* info_cmd = app.add_subcommand("info", "Version, build and OpenMP information");

  if (argc == 1) {
    std::fprintf(stderr,
                 "error: give a command: run, check, render, plot or info (see %s --help)\n",
                 argv[0]);
    return 2;
  }
  if (argv[1][0] != '-') {
    bool known = true;
    try {
      app.get_subcommand(argv[1]);
    } catch (const CLI::OptionNotFound&) {
      known = false;
    }
    if (!known) {
      std::fprintf(stderr,
                   "error: unknown command \"%s\"; allowed: run, check, render, plot, info\n",
                   argv[1]);
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return usage_error(argv[0], e);
  }
  if (*run_cmd) {
    if (run.resume_dir.empty() && (run.scene_path.empty() || run.out_dir.empty())) {
      std::fprintf(stderr, "error: run: give SCENE.toml and --out DIR, or --resume DIR\n");
      return 2;
    }
    const std::string bad = sablier::parse_formats(formats, run.formats);
    if (!bad.empty()) {
      std::fprintf(stderr, "error: --format: unknown format \"%s\"; allowed: vtp, csv, ply\n",
                   bad.c_str());
      return 2;
    }
    // The VTK files are the run's frames for ParaView, `render` and the series
    // file; other formats come beside them (the README's "also").
    if (std::find(run.formats.begin(), run.formats.end(), "vtp") == run.formats.end())
      run.formats.insert(run.formats.begin(), "vtp");
    return sablier::run_command(run);
  }
  if (*check_cmd) return sablier::check_command(check_path, check_overrides);
  if (*render_cmd) return sablier::render_command(render);
  if (*plot_cmd) return sablier::plot_command(plot);
  if (*info_cmd) return sablier::info_command();
  return 2;
}
