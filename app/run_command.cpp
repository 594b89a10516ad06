// `sablier run`, `sablier check` and `sablier info`.
#include <omp.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>

#include "commands.hpp"
#include "io/stats_writer.hpp"
#include "io/writers.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;
volatile std::sig_atomic_t g_interrupted = 0;
void on_signal(int) { g_interrupted = 1; }

// Files a run writes at the top of its folder: their presence means the
// folder holds a run's outputs.
const char* const kRunFiles[] = {"stats.csv", "series.pvd", "scene.toml"};

bool holds_run_outputs(const fs::path& dir) {
  for (const char* f : kRunFiles)
    if (fs::exists(dir / f)) return true;
  return fs::exists(dir / "frames");
}

void remove_run_outputs(const fs::path& dir) {
  for (const char* f : kRunFiles) fs::remove(dir / f);
  fs::remove_all(dir / "frames");
}

std::string frame_name(int frame, const char* ext) {
  return fmt::format("frames/particles_{:05d}.{}", frame, ext);
}

template <int D>
class Runner {
 public:
  Runner(const SceneConfig& scene, const RunOptions& opt)
      : scene_(scene), opt_(opt), dir_(opt.out_dir), sim_(scene) {}

  int run() {
    write_frame(0);
    const double frame_dt = 1.0 / scene_.time.fps;
    const auto start = std::chrono::steady_clock::now();
    for (int f = 1; f <= scene_.time.frames; ++f) {
      const double t_end = f * frame_dt;
      int sub = 0;
      while (sim_.time() < t_end - 1e-9 * frame_dt) {
        const double remaining = t_end - sim_.time();
        const double dt = scene_.time.substeps > 0 ? remaining / (scene_.time.substeps - sub)
                                                   : sim_.adaptive_dt(remaining);
        ++sub;
        record(sim_.step(dt));
        if (g_interrupted) return interrupted(f - 1);
      }
      write_frame(f);
      log_frame(f, start);
    }
    if (!opt_.quiet)
      std::fprintf(stderr, "done: %d frames, %lld steps, outputs in %s\n", scene_.time.frames,
                   static_cast<long long>(sim_.steps()), opt_.out_dir.c_str());
    return 0;
  }

 private:
  void record(const StepInfo& info) {
    StepStats s{};
    s.step = sim_.steps();
    s.time = sim_.time();
    s.dt = info.dt;
    s.particles = static_cast<long>(sim_.particles().size());
    s.active_nodes = info.active_nodes;
    s.iterations = info.solve.iterations;
    s.residual = info.solve.residual;
    s.kinetic_energy = sim_.kinetic_energy();
    s.potential_energy = sim_.potential_energy();
    s.max_speed = sim_.max_speed();
    s.wall_seconds = info.timings.total();
    s.hit_cap = info.solve.hit_cap;
    s.transfer_seconds = info.timings.transfer;
    s.assembly_seconds = info.timings.assembly;
    s.solve_seconds = info.timings.solve;
    s.advection_seconds = info.timings.advection;
    stats_.add(s);
    iterations_since_log_ += info.solve.iterations;
    capped_since_log_ += info.solve.hit_cap ? 1 : 0;
  }

  void write_frame(int f) {
    const ParticleFrame frame = sim_.frame();
    for (const std::string& fmt_name : opt_.formats) {
      if (fmt_name == "vtp") {
        write_file_atomic((dir_ / frame_name(f, "vtp")).string(), format_vtp(frame));
        series_.push_back({frame.time, frame_name(f, "vtp")});
      } else if (fmt_name == "csv") {
        write_file_atomic((dir_ / frame_name(f, "csv")).string(), format_particle_csv(frame));
      }
    }
    if (!series_.empty()) write_file_atomic((dir_ / "series.pvd").string(), format_pvd(series_));
    write_file_atomic((dir_ / "stats.csv").string(), stats_.csv());
  }

  void log_frame(int f, std::chrono::steady_clock::time_point start) {
    if (opt_.quiet) return;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double eta = wall / f * (scene_.time.frames - f);
    std::fprintf(stderr,
                 "frame %d/%d  t=%.4g s  steps=%lld  particles=%zu  GS sweeps=%ld%s  wall=%.1f s  "
                 "eta=%.1f s\n",
                 f, scene_.time.frames, sim_.time(), static_cast<long long>(sim_.steps()),
                 sim_.particles().size(), iterations_since_log_,
                 capped_since_log_ ? fmt::format(" ({} capped)", capped_since_log_).c_str() : "",
                 wall, eta);
    iterations_since_log_ = 0;
    capped_since_log_ = 0;
  }

  int interrupted(int last_frame) {
    write_file_atomic((dir_ / "stats.csv").string(), stats_.csv());
    std::fprintf(stderr,
                 "interrupted at t=%.6g s (step %lld); frames 0..%d in %s are complete\n",
                 sim_.time(), static_cast<long long>(sim_.steps()), last_frame,
                 opt_.out_dir.c_str());
    return 130;
  }

  const SceneConfig& scene_;
  const RunOptions& opt_;
  fs::path dir_;
  Simulation<D> sim_;
  StatsTable stats_;
  std::vector<SeriesEntry> series_;
  long iterations_since_log_ = 0;
  int capped_since_log_ = 0;
};

}  // namespace

int run_command(const RunOptions& opt) {
  SceneConfig scene;
  try {
    scene = load_scene(opt.scene_path, opt.overrides);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  const fs::path dir(opt.out_dir);
  try {
    if (fs::exists(dir) && !fs::is_directory(dir)) {
      std::fprintf(stderr, "error: --out %s: exists and is not a folder\n", opt.out_dir.c_str());
      return 2;
    }
    if (holds_run_outputs(dir)) {
      if (!opt.overwrite) {
        std::fprintf(stderr,
                     "error: --out %s: the folder holds another run's outputs; pass --overwrite "
                     "to replace them, or choose another folder\n",
                     opt.out_dir.c_str());
        return 2;
      }
      remove_run_outputs(dir);
    }
    ensure_directory((dir / "frames").string());
    write_file_atomic((dir / "scene.toml").string(), scene_to_toml(scene));
    if (opt.threads > 0) omp_set_num_threads(opt.threads);
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    if (scene.dimension == 2) return Runner<2>(scene, opt).run();
    return Runner<3>(scene, opt).run();
  } catch (const IoError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: simulation failed: %s\n", e.what());
    return 4;
  }
}

}  // namespace sablier
