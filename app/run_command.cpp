// `sablier run`: a scene from its start, or (`--resume DIR`) from the
// checkpoint of an interrupted run.
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iterator>

#include "checkpoint_state.hpp"
#include "commands.hpp"
#include "io/hash.hpp"
#include "io/obstacle_geometry.hpp"
#include "io/stats_writer.hpp"
#include "io/writers.hpp"
#include "physics/simulation.hpp"
#include "progress.hpp"
#include "run_folder.hpp"
#include "run_record.hpp"
#include "scene/memory_estimate.hpp"
#include "scene/scene.hpp"
#include "scene/scene_obstacles.hpp"

namespace sablier {

const char* const kParticleFormats[3] = {"vtp", "csv", "ply"};

std::string parse_formats(const std::string& list, std::vector<std::string>& formats) {
  formats.clear();
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    const std::string f = list.substr(start, comma == std::string::npos ? comma : comma - start);
    if (std::find(std::begin(kParticleFormats), std::end(kParticleFormats), f) ==
        std::end(kParticleFormats))
      return f.empty() ? "(empty)" : f;
    formats.push_back(f);
    if (comma == std::string::npos) return "";
    start = comma + 1;
  }
}

namespace {

namespace fs = std::filesystem;
volatile std::sig_atomic_t g_interrupted = 0;
void on_signal(int) { g_interrupted = 1; }

std::size_t count_bodies(const SceneConfig& scene) {
  std::size_t n = 0;
  for (const ObstacleConfig& o : scene.obstacles) n += o.dynamic() ? 1 : 0;
  return n;
}

bool has_bodies(const SceneConfig& scene) { return count_bodies(scene) > 0; }

// Whether frames/bodies_NNNNN.vtp are written: the scene has rigid bodies or
// solids driven into the sand.
bool has_moving_solids(const SceneConfig& scene) {
  for (const ObstacleConfig& o : scene.obstacles)
    if (o.dynamic() || moves_into_sand(o, scene.dimension)) return true;
  return false;
}

std::string frame_name(int frame, const char* ext) {
  return fmt::format("frames/particles_{:05d}.{}", frame, ext);
}
std::string grid_name(int frame) { return fmt::format("frames/grid_{:05d}.vti", frame); }
std::string bodies_name(int frame) { return fmt::format("frames/bodies_{:05d}.vtp", frame); }

// What a Runner needs besides the scene and the simulation.
struct RunSettings {
  fs::path dir;
  std::vector<std::string> formats;
  bool quiet = false;
  int stop_after_frame = 0;
  std::string scene_text;  // scene.toml as written
  bool compress = false, grid = false;
  long long interrupt_after_step = 0;  // for tests: as if Ctrl-C came in this step
};

// The checkpoint's formats text: the particle formats, then the output
// options ("grid", "compress"), comma-separated, so that --resume writes
// the same files as the run it continues.
std::string outputs_text(const RunSettings& s) {
  std::string text;
  for (const std::string& f : s.formats) text += (text.empty() ? "" : ",") + f;
  if (s.grid) text += ",grid";
  if (s.compress) text += ",compress";
  return text;
}

// Sets the formats and output options from outputs_text's text; returns
// the first unknown name, or "" if all are known.
std::string parse_outputs_text(const std::string& text, RunSettings& s) {
  std::string formats;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    if (item == "grid")
      s.grid = true;
    else if (item == "compress")
      s.compress = true;
    else
      formats += (formats.empty() ? "" : ",") + item;
    start = comma + 1;
  }
  return parse_formats(formats, s.formats);
}

template <int D>
class Runner {
 public:
  Runner(const SceneConfig& scene, RunSettings settings, Simulation<D> sim)
      : scene_(scene), set_(std::move(settings)), sim_(std::move(sim)) {
    record_.scene_text = set_.scene_text;
    record_.scene_hash = fnv1a64(set_.scene_text);
    record_.formats = set_.formats;
    record_.compress = set_.compress;
    record_.grid = set_.grid;
    record_.threads = omp_get_max_threads();
    record_.started = utc_now();
    record_.frames = scene_.time.frames;
  }

  int run() {
    write_run_json("running");
    write_frame(0);
    return advance(0, 0);
  }

  // Continues after the checkpoint's frame and substep, with the stats rows
  // of the steps it covers.
  int resume(const Checkpoint& c, std::vector<StepStats> rows, std::vector<ObstacleForceRow> forces,
             std::vector<BodyRow> bodies) {
    for (StepStats& s : rows) stats_.add(s);
    forces_ = std::move(forces);
    bodies_ = std::move(bodies);
    frame_times_ = c.frame_times;
    if (writes("vtp"))
      for (std::size_t f = 0; f < frame_times_.size(); ++f) {
        series_.push_back({frame_times_[f], frame_name(static_cast<int>(f), "vtp")});
        if (has_moving_solids(scene_))
          bodies_series_.push_back({frame_times_[f], bodies_name(static_cast<int>(f))});
      }
    if (set_.grid)
      for (std::size_t f = 0; f < frame_times_.size(); ++f)
        grid_series_.push_back({frame_times_[f], grid_name(static_cast<int>(f))});
    record_.resumed_from_step = c.steps;
    record_.frames_written = c.frame + 1;
    write_run_json("running");
    return advance(c.frame, c.substep);
  }

 private:
  // Runs from after frame `frame`, `sub` steps into the next one, to the
  // last frame or an interrupt.
  int advance(int frame, int sub) {
    const double frame_dt = 1.0 / scene_.time.fps;
    Progress progress(set_.quiet, scene_.time.frames, scene_.time.frames * frame_dt, frame,
                      sim_.time(), sim_.steps());
    for (int f = frame + 1; f <= scene_.time.frames; ++f) {
      const double t_end = f * frame_dt;
      while (sim_.time() < t_end - 1e-9 * frame_dt) {
        const double remaining = t_end - sim_.time();
        const double dt = scene_.time.substeps > 0 ? remaining / (scene_.time.substeps - sub)
                                                   : sim_.adaptive_dt(remaining);
        ++sub;
        const StepInfo info = sim_.step(dt);
        record(info);
        if (info.crowding > kCrowded) {
          ++crowded_steps_;
          most_crowded_ = std::max(most_crowded_, info.crowding);
        }
        progress.step(sim_.time(), sim_.steps(), info.solve.iterations, info.solve.hit_cap);
        if (sim_.steps() == set_.interrupt_after_step) g_interrupted = 1;
        // An interrupt in the frame's last step stops after the frame is
        // written: its outputs are the state before the next step's sort
        // (the particles' order) and the last solve (the grid's fields),
        // which a resumed run would not have.
        if (g_interrupted && sim_.time() < t_end - 1e-9 * frame_dt)
          return stop(progress, f - 1, sub);
      }
      sub = 0;
      write_frame(f);
      progress.frame(f, sim_.time(), sim_.steps());
      if ((g_interrupted || f == set_.stop_after_frame) && f < scene_.time.frames)
        return stop(progress, f, 0);
    }
    write_run_json("finished");
    progress.finish();
    if (!set_.quiet) {
      std::fprintf(stderr, "done: %d frames, %lld steps, outputs in %s\n", scene_.time.frames,
                   static_cast<long long>(sim_.steps()), set_.dir.c_str());
      // Said once more at the end, where it is read: a capped step's
      // stresses are the best iterate, not a solution to the tolerance.
      if (progress.capped_steps() > 0)
        std::fprintf(stderr,
                     "note: %lld steps stopped at solver.max_iterations above "
                     "solver.tolerance (column hit_cap of stats.csv)\n",
                     progress.capped_steps());
      // Grains crowded beyond phi_max that the decompaction did not spread
      // (stats.csv's overfill, over the whole run, a resumed one's earlier
      // rows included; NaN in a file of an older build fails the test).
      const StepStats* most = nullptr;
      for (const StepStats& r : stats_.rows())
        if (r.overfill > kOverfillNote && (!most || r.overfill > most->overfill)) most = &r;
      if (most)
        std::fprintf(stderr,
                     "note: grains crowded beyond phi_max by up to %.1f%% of their volume (step "
                     "%ld, t = %.4g s; column overfill of stats.csv): the decompaction did not "
                     "keep up; solver.decompaction = \"project\" holds phi_max, a draining "
                     "bin's too (docs/scenes.md, \"Over-full sand\")\n",
                     100.0 * most->overfill, most->step, most->time);
      // Sand a solid drives where it cannot escape (a piston in a closed
      // box) stays over-full: its force grows without bound. Next to a
      // solid thinner than the cells, a few percent can stay too.
      if (crowded_steps_ > 0)
        std::fprintf(stderr,
                     "note: %lld steps left sand over-full after the projection, by up to %.0f%% "
                     "of phi_max, where it could not escape (a solid moving into it, or one "
                     "thinner than the cells)\n",
                     crowded_steps_, 100.0 * most_crowded_);
    }
    return 0;
  }

  bool writes(const char* format) const {
    for (const std::string& f : set_.formats)
      if (f == format) return true;
    return false;
  }

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
    s.decompaction_work = info.restoring_work;
    s.overfill = info.overfill;
    stats_.add(s);
    for (std::size_t k = 0; k < info.obstacle_force.size(); ++k) {
      ObstacleForceRow r;
      r.step = s.step;
      r.time = s.time;
      r.obstacle = static_cast<int>(k);
      for (int a = 0; a < 3; ++a) r.force[a] = info.obstacle_force[k][a];
      forces_.push_back(r);
    }
    const auto& obstacles = sim_.obstacles();
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      if (!obstacles[k].dynamic) continue;
      BodyRow b;
      b.step = s.step;
      b.time = s.time;
      b.obstacle = static_cast<int>(k);
      for (int a = 0; a < D; ++a) {
        b.centre[a] = obstacles[k].a[a];
        b.velocity[a] = obstacles[k].velocity[a];
      }
      for (int a = 0; a < (D == 2 ? 1 : 3); ++a) b.spin[a] = obstacles[k].spin[a];
      b.angle = obstacles[k].angle;
      for (int a = 0; a < 4; ++a) b.quaternion[a] = obstacles[k].quaternion[a];
      bodies_.push_back(b);
    }
  }

  // stats.csv, and obstacles.csv when the scene has obstacles.
  void write_tables() {
    write_file_atomic((set_.dir / "stats.csv").string(), stats_.csv());
    if (!scene_.obstacles.empty())
      write_file_atomic((set_.dir / "obstacles.csv").string(),
                        obstacle_forces_csv(forces_, scene_.dimension));
    if (has_bodies(scene_))
      write_file_atomic((set_.dir / "bodies.csv").string(), bodies_csv(bodies_, scene_.dimension));
  }

  // The frame's files, then stats.csv, then the checkpoint: a run killed
  // anywhere in between resumes from the previous checkpoint and rewrites
  // the same files.
  void write_frame(int f) {
    const ParticleFrame frame = sim_.frame();
    const std::string base = (set_.dir / "frames/particles_").string() + fmt::format("{:05d}.", f);
    if (writes("vtp")) {
      write_file_atomic(base + "vtp", format_vtp(frame, compression()));
      series_.push_back({frame.time, frame_name(f, "vtp")});
      write_file_atomic((set_.dir / "series.pvd").string(), format_pvd(series_));
      if (has_moving_solids(scene_)) write_bodies(f, frame.time);
    }
    if (writes("csv")) write_file_atomic(base + "csv", format_particle_csv(frame));
    if (writes("ply")) write_file_atomic(base + "ply", format_ply(frame));
    if (set_.grid) write_grid(f);
    frame_times_.push_back(frame.time);
    write_tables();
    write_checkpoint(f, 0);
    record_.frames_written = f + 1;
    write_run_json("running");
  }

  VtkCompression compression() const {
    return set_.compress ? VtkCompression::Zlib : VtkCompression::None;
  }

  // The rigid bodies' and moving solids' surfaces where they are
  // (frames/bodies_NNNNN.vtp, a series of its own for ParaView).
  void write_bodies(int f, double time) {
    std::vector<ObstacleConfig> posed = scene_.obstacles;
    const auto bodies = sim_.obstacles_at(time);  // bodies as they are, turning solids at `time`
    for (std::size_t k = 0; k < posed.size(); ++k) {
      if (!bodies[k].dynamic && !(bodies[k].posed && moves_into_sand(bodies[k]))) continue;
      double centre[3] = {0, 0, 0};
      for (int a = 0; a < D; ++a) centre[a] = bodies[k].a[a];
      posed[k] =
          posed_body(scene_.obstacles[k], centre, bodies[k].angle, bodies[k].quaternion.data(), D);
    }
    write_file_atomic((set_.dir / bodies_name(f)).string(), format_bodies_vtp(posed, scene_, time));
    bodies_series_.push_back({time, bodies_name(f)});
    write_file_atomic((set_.dir / "bodies_series.pvd").string(), format_pvd(bodies_series_));
  }

  void write_grid(int f) {
    const GridFrame grid = sim_.grid_frame();
    write_file_atomic((set_.dir / grid_name(f)).string(), format_vti(grid, compression()));
    grid_series_.push_back({grid.time, grid_name(f)});
    write_file_atomic((set_.dir / "grid_series.pvd").string(), format_pvd(grid_series_));
  }

  void write_checkpoint(int frame, int substep) {
    Checkpoint& c = checkpoint_;  // its arrays and bytes reused from frame to frame
    capture_checkpoint(sim_, &c);
    c.scene_hash = record_.scene_hash;
    c.frame = frame;
    c.substep = substep;
    c.formats = outputs_text(set_);
    c.frame_times = frame_times_;
    const std::string path = (set_.dir / "checkpoint.bin").string();
    encode_checkpoint(c, path, &checkpoint_bytes_);
    write_file_atomic(path, checkpoint_bytes_);
  }

  void write_run_json(const char* status) {
    record_.status = status;
    if (record_.status != "running") record_.ended = utc_now();
    record_.steps = sim_.steps();
    record_.time = sim_.time();
    record_.transfer = record_.assembly = record_.solve = record_.advection = 0.0;
    for (const StepStats& s : stats_.rows()) {
      record_.transfer += s.transfer_seconds;
      record_.assembly += s.assembly_seconds;
      record_.solve += s.solve_seconds;
      record_.advection += s.advection_seconds;
    }
    write_file_atomic((set_.dir / "run.json").string(), format_run_json(record_));
  }

  // An interrupt (or --stop-after-frame) after a whole step: everything
  // needed to continue is saved, then exit code 130 as for a shell's Ctrl-C.
  int stop(Progress& progress, int last_frame, int substep) {
    write_tables();
    write_checkpoint(last_frame, substep);
    write_run_json("interrupted");
    progress.finish();
    std::fprintf(stderr,
                 "interrupted at step %lld (t = %.6g s): checkpoint written; frames 0..%d are "
                 "complete; continue with: sablier run --resume %s\n",
                 static_cast<long long>(sim_.steps()), sim_.time(), last_frame, set_.dir.c_str());
    return 130;
  }

  const SceneConfig& scene_;
  RunSettings set_;
  Simulation<D> sim_;
  StatsTable stats_;
  std::vector<ObstacleForceRow> forces_;
  std::vector<BodyRow> bodies_;
  std::vector<SeriesEntry> series_, grid_series_, bodies_series_;
  // Steps whose projection left a node more than kCrowded over phi_max.
  static constexpr double kCrowded = 0.01;
  long long crowded_steps_ = 0;
  // The end note on overfill: above this fraction of the grains' volume
  // (the shipped scenes without draining flows stay below 3.6%; docs/scenes.md).
  static constexpr double kOverfillNote = 0.05;
  double most_crowded_ = 0.0;
  std::vector<double> frame_times_;
  Checkpoint checkpoint_;
  std::string checkpoint_bytes_;
  RunRecord record_;
};

// Error classes to exit codes: bad input 2, output trouble 3, the simulation 4.
template <class F>
int guarded(F&& body) {
  try {
    return body();
  } catch (const SceneError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const CheckpointError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const IoError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 3;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: out of memory (`sablier check` gives the scene's size)\n");
    return 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: simulation failed: %s\n", e.what());
    return 4;
  }
}

void start_threads_and_signals(int threads) {
  if (threads > 0) omp_set_num_threads(threads);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

// Seeds the scene's grains, refuses a run this machine cannot hold, then
// writes the run's first files and runs it: nothing is written, and an
// earlier run in the folder is not removed, until the grains are seeded.
template <int D>
int seed_and_run(const SceneConfig& scene, RunSettings set, const RunOptions& opt) {
  Simulation<D> sim(scene);
  refuse_if_too_big(scene, grains_by_end(scene, sim.particles().size()));
  const fs::path& dir = set.dir;
  if (holds_run_outputs(dir)) remove_run_outputs(dir);  // --overwrite, checked by the caller
  ensure_directory((dir / "frames").string());
  write_file_atomic((dir / "scene.toml").string(), set.scene_text);
  if (const std::string obj = format_obstacles_obj(scene); !obj.empty())
    write_file_atomic((dir / "obstacles.obj").string(), obj);
  for (const SceneMessage& m : thin_solid_messages(scene))  // notes unless --quiet
    if (!opt.quiet || m.warning) std::fprintf(stderr, "%s\n", m.line().c_str());
  return Runner<D>(scene, std::move(set), std::move(sim)).run();
}

int start_run(const RunOptions& opt) {
  SceneConfig scene;
  try {
    scene = load_scene(opt.scene_path, opt.overrides);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  const fs::path dir(opt.out_dir);
  return guarded([&] {
    if (fs::exists(dir) && !fs::is_directory(dir)) {
      std::fprintf(stderr, "error: --out %s: exists and is not a folder\n", opt.out_dir.c_str());
      return 2;
    }
    if (holds_run_outputs(dir) && !opt.overwrite) {
      std::fprintf(stderr,
                   "error: --out %s: the folder holds another run's outputs; pass --overwrite "
                   "to replace them, or choose another folder\n",
                   opt.out_dir.c_str());
      return 2;
    }
    RunSettings set{
        dir,          opt.formats, opt.quiet, opt.stop_after_frame, scene_to_toml(scene),
        opt.compress, opt.grid};
    set.interrupt_after_step = opt.interrupt_after_step;
    start_threads_and_signals(opt.threads);
    if (scene.dimension == 2) return seed_and_run<2>(scene, std::move(set), opt);
    return seed_and_run<3>(scene, std::move(set), opt);
  });
}

// The stats rows of the checkpoint's steps; a later tail (written after the
// checkpoint, or torn) is dropped.
std::vector<StepStats> stats_until(const fs::path& dir, std::int64_t steps) {
  const fs::path path = dir / "stats.csv";
  if (!fs::exists(path)) throw CheckpointError(path.string() + ": missing; cannot resume");
  std::vector<StepStats> rows = parse_stats_csv_until(read_file(path.string()), steps);
  if (static_cast<std::int64_t>(rows.size()) != steps)
    throw CheckpointError(
        fmt::format("{}: holds rows for {} of the checkpoint's {} steps; cannot resume",
                    path.string(), rows.size(), steps));
  return rows;
}

template <int D>
int resume_from(const SceneConfig& scene, RunSettings set, const Checkpoint& c,
                const std::string& source, std::vector<StepStats> rows) {
  // Everything is read and checked before the first write.
  Simulation<D> sim = restore_simulation<D>(scene, c, source);
  std::vector<ObstacleForceRow> forces;
  if (!scene.obstacles.empty()) {
    const fs::path path = set.dir / "obstacles.csv";
    if (!fs::exists(path)) throw CheckpointError(path.string() + ": missing; cannot resume");
    forces = parse_obstacle_forces_until(read_file(path.string()), scene.dimension, c.steps);
  }
  // The bodies' state is not in the checkpoint: bodies.csv holds it, to the
  // last bit, for every step.
  std::vector<BodyRow> bodies;
  if (has_bodies(scene)) {
    const fs::path path = set.dir / "bodies.csv";
    if (!fs::exists(path)) throw CheckpointError(path.string() + ": missing; cannot resume");
    bodies = parse_bodies_until(read_file(path.string()), scene.dimension, c.steps);
    std::size_t restored = 0;
    for (const BodyRow& b : bodies) {
      if (b.step != c.steps) continue;
      Vec<D> x, v, w = Vec<D>::Zero();
      for (int a = 0; a < D; ++a) {
        x[a] = b.centre[a];
        v[a] = b.velocity[a];
      }
      for (int a = 0; a < (D == 2 ? 1 : 3); ++a) w[a] = b.spin[a];
      if (b.obstacle < 0 || static_cast<std::size_t>(b.obstacle) >= scene.obstacles.size() ||
          !scene.obstacles[b.obstacle].dynamic())
        throw CheckpointError(path.string() +
                              ": a row names an obstacle that is not a body; cannot resume");
      sim.set_body_state(b.obstacle, x, v, w, b.angle,
                         {b.quaternion[0], b.quaternion[1], b.quaternion[2], b.quaternion[3]});
      ++restored;
    }
    const std::size_t expected = c.steps > 0 ? count_bodies(scene) : 0;
    if (restored != expected)
      throw CheckpointError(
          fmt::format("{}: holds {} body states for step {}, expected {}; cannot resume",
                      path.string(), restored, c.steps, expected));
  }
  return Runner<D>(scene, std::move(set), std::move(sim))
      .resume(c, std::move(rows), std::move(forces), std::move(bodies));
}

int resume_run(const RunOptions& opt) {
  const fs::path dir(opt.resume_dir);
  const fs::path scene_path = dir / "scene.toml", ckpt_path = dir / "checkpoint.bin";
  for (const fs::path& p : {scene_path, ckpt_path})
    if (!fs::exists(p)) {
      std::fprintf(stderr, "error: --resume %s: no %s: not the folder of a sablier run\n",
                   opt.resume_dir.c_str(), p.filename().c_str());
      return 2;
    }
  return guarded([&] {
    RunSettings set{dir, {}, opt.quiet, opt.stop_after_frame, read_file(scene_path.string())};
    set.interrupt_after_step = opt.interrupt_after_step;
    const SceneConfig scene = parse_scene(set.scene_text, scene_path.string());
    const Checkpoint c = decode_checkpoint(read_file(ckpt_path.string()), ckpt_path.string());
    const std::uint64_t hash = fnv1a64(set.scene_text);
    if (c.scene_hash != hash)
      throw CheckpointError(fmt::format(
          "{}: written for another scene (hash {}) than {} (hash {}); cannot resume",
          ckpt_path.string(), hash_hex(c.scene_hash), scene_path.string(), hash_hex(hash)));
    if (c.dimension != scene.dimension)
      throw CheckpointError(ckpt_path.string() +
                            ": dimension differs from the scene's; cannot resume");
    const std::string bad = parse_outputs_text(c.formats, set);
    if (!bad.empty())
      throw CheckpointError(ckpt_path.string() + ": unknown format \"" + bad + "\"; cannot resume");
    if (c.frame >= scene.time.frames) {
      std::fprintf(stderr, "nothing to resume: the run in %s is finished (all %d frames written)\n",
                   opt.resume_dir.c_str(), scene.time.frames);
      return 0;
    }
    std::vector<StepStats> rows = stats_until(dir, c.steps);
    start_threads_and_signals(opt.threads);
    if (!opt.quiet)
      std::fprintf(stderr, "resuming %s at frame %d, step %lld (t = %.6g s)\n",
                   opt.resume_dir.c_str(), c.frame, static_cast<long long>(c.steps), c.time);
    if (scene.dimension == 2) return resume_from<2>(scene, set, c, ckpt_path.string(), rows);
    return resume_from<3>(scene, set, c, ckpt_path.string(), rows);
  });
}

}  // namespace

int run_command(const RunOptions& opt) {
  return opt.resume_dir.empty() ? start_run(opt) : resume_run(opt);
}

}  // namespace sablier
