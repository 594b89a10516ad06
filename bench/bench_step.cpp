// Step timings on the shipped scenes (docs/benchmarks.md). Run:
//   OMP_NUM_THREADS=2 build/bench/bench_step
// Counters: per step, the split into transfer / assembly / solve / advection
// (seconds), Gauss-Seidel sweeps, nanoseconds per particle per step and per
// stress row per sweep; for whole runs, wall seconds per simulated second.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "physics/simulation.hpp"
#include "scene/scene.hpp"

namespace sablier {
namespace {

// The benchmark's argument is the Anderson depth (solver.anderson; 0 = plain
// Gauss-Seidel), so each case is timed with and without acceleration.
SceneConfig scene(const benchmark::State& st, const char* name, std::vector<std::string> overrides) {
  overrides.push_back("solver.anderson=" + std::to_string(st.range(0)));
  return load_scene(std::string(SABLIER_SOURCE_DIR) + "/scenes/" + name, overrides);
}

// Steps of a scene after `warmup` simulated seconds (so a collapse is flowing).
template <int D>
void time_steps(benchmark::State& state, const SceneConfig& s, double warmup) {
  Simulation<D> sim(s);
  const double frame_dt = 1.0 / s.time.fps;
  while (sim.time() < warmup) sim.step(sim.adaptive_dt(frame_dt));
  StepTimings sum;
  double sweeps = 0.0, row_sweeps = 0.0, particle_steps = 0.0, steps = 0.0;
  for (auto _ : state) {
    const StepInfo info = sim.step(sim.adaptive_dt(frame_dt));
    sum.transfer += info.timings.transfer;
    sum.assembly += info.timings.assembly;
    sum.solve += info.timings.solve;
    sum.advection += info.timings.advection;
    sweeps += info.solve.iterations;
    row_sweeps += double(info.solve.iterations) * info.active_nodes;
    particle_steps += double(sim.particles().size());
    steps += 1.0;
  }
  state.counters["particles"] = double(sim.particles().size());
  state.counters["rows"] = double(sim.problem().rows());
  state.counters["sweeps_per_step"] = sweeps / steps;
  state.counters["transfer_ms"] = 1e3 * sum.transfer / steps;
  state.counters["assembly_ms"] = 1e3 * sum.assembly / steps;
  state.counters["solve_ms"] = 1e3 * sum.solve / steps;
  state.counters["advection_ms"] = 1e3 * sum.advection / steps;
  state.counters["ns_per_particle_step"] = 1e9 * sum.total() / particle_steps;
  state.counters["ns_per_row_sweep"] = 1e9 * sum.solve / row_sweeps;
}

// One simulated second of a scene, start to end.
template <int D>
void time_simulated_second(benchmark::State& state, const SceneConfig& s) {
  for (auto _ : state) {
    Simulation<D> sim(s);
    double wall = 0.0, sweeps = 0.0;
    long steps = 0;
    const double frame_dt = 1.0 / s.time.fps;
    while (sim.time() < 1.0 - 1e-9) {
      const double t_end = std::min(1.0, (std::floor(sim.time() / frame_dt + 1e-9) + 1) * frame_dt);
      const StepInfo info = sim.step(sim.adaptive_dt(t_end - sim.time()));
      wall += info.timings.total();
      sweeps += info.solve.iterations;
      ++steps;
    }
    state.counters["particles"] = double(sim.particles().size());
    state.counters["steps"] = double(steps);
    state.counters["sweeps_per_step"] = sweeps / steps;
    state.counters["wall_per_simulated_s"] = wall;
  }
}

void Collapse3D(benchmark::State& st) { time_steps<3>(st, scene(st, "collapse3d.toml", {}), 0.2); }
void Collapse3DFine(benchmark::State& st) {
  time_steps<3>(st, scene(st, "collapse3d.toml", {"grid.resolution=[120,12,30]"}), 0.2);
}
// The paper's bed at rest: 1.25 x 0.25 x 0.35 m box at ~3 cm cells, 64,000 particles.
void Bed3DPaperSize(benchmark::State& st) {
  time_steps<3>(st,
                scene(st, "bed3d.toml", {"grid.size=[1.25,0.25,0.3125]", "grid.resolution=[40,8,10]",
                                     "sand.0.max=[1.25,0.25,0.3125]"}),
                0.1);
}
void Collapse2DSecond10mm(benchmark::State& st) {
  time_simulated_second<2>(
      st, scene(st, "collapse2d.toml", {"grid.resolution=[100,25]", "sand.0.particles_per_cell=2"}));
}
void Collapse2DSecond5mm(benchmark::State& st) {
  time_simulated_second<2>(
      st, scene(st, "collapse2d.toml", {"grid.resolution=[200,50]", "sand.0.particles_per_cell=2"}));
}
void Collapse2DSecond12mm(benchmark::State& st) {
  time_simulated_second<2>(st, scene(st, "collapse2d.toml", {}));
}
void Silo2D(benchmark::State& st) { time_steps<2>(st, scene(st, "silo2d.toml", {}), 0.3); }

BENCHMARK(Collapse3D)->Unit(benchmark::kMillisecond)->Iterations(20)->Arg(0)->Arg(5);
BENCHMARK(Collapse3DFine)->Unit(benchmark::kMillisecond)->Iterations(10)->Arg(0)->Arg(5);
BENCHMARK(Bed3DPaperSize)->Unit(benchmark::kMillisecond)->Iterations(10)->Arg(0)->Arg(5);
BENCHMARK(Silo2D)->Unit(benchmark::kMillisecond)->Iterations(30)->Arg(0)->Arg(5);
BENCHMARK(Collapse2DSecond12mm)->Unit(benchmark::kSecond)->Iterations(1)->Arg(0)->Arg(5);
BENCHMARK(Collapse2DSecond10mm)->Unit(benchmark::kSecond)->Iterations(1)->Arg(0)->Arg(5);
BENCHMARK(Collapse2DSecond5mm)->Unit(benchmark::kSecond)->Iterations(1)->Arg(0)->Arg(5);

}  // namespace
}  // namespace sablier

BENCHMARK_MAIN();
