// Step timings on the shipped scenes (docs/benchmarks.md). Run:
//   OMP_NUM_THREADS=2 build/bench/bench_step
// Counters: per step, the split into transfer / assembly / solve / advection
// (seconds), Gauss-Seidel sweeps, nanoseconds per particle per step and per
// stress row per sweep; for whole runs, wall seconds per simulated second.
// CoreRoundTrip and SpinBarrier2 time what two threads pay to share data on
// the machine, which sets how much a second thread helps the solve.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "core/heap.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "solver/team.hpp"

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
// The bed at rest of sand6's figures (the issue): a 1.25 x 0.25 x 0.35 m
// box full of sand. sand6 used 40 x 10 x 20 cells (64,000 particles, about
// 8,500 active nodes); our cells are cubic, so 2.5 cm cells, 50 x 10 x 14:
// 8,415 nodes (rows) and 56,000 particles (2 per cell and axis). Second
// argument: 0 for the scene's tolerance (about 5 sweeps per step, so the
// solve's setup weighs on the time per sweep), or a number of sweeps that
// every step makes (a tolerance no sweep reaches), as in sand6's capped
// solves, for the time per sweep alone.
void Bed3DPaperSize(benchmark::State& st) {
  std::vector<std::string> o{"grid.size=[1.25,0.25,0.35]", "grid.resolution=[50,10,14]",
                             "sand.0.max=[1.25,0.25,0.35]"};
  if (st.range(1) > 0) {
    o.push_back("solver.tolerance=1e-300");
    o.push_back("solver.max_iterations=" + std::to_string(st.range(1)));
  }
  time_steps<3>(st, scene(st, "bed3d.toml", o), 0.1);
}
// The 2D collapse at the resolutions, with 3 grains per cell and
// axis (the 2D default: with 2 the deposit over-compacts to phi 0.89 at 5 mm,
// docs/benchmarks.md). Second argument: the seeding, 0 the regular lattice
// and k > 0 grains jittered by 0.3 with seed k (the sweep count depends on
// it).
std::vector<std::string> seeding(const benchmark::State& st, std::vector<std::string> overrides) {
  if (st.range(1) > 0) {
    overrides.push_back("sand.0.jitter=0.3");
    overrides.push_back("seed=" + std::to_string(st.range(1)));
  }
  return overrides;
}
void Collapse2DSecond10mm(benchmark::State& st) {
  time_simulated_second<2>(
      st, scene(st, "collapse2d.toml",
                seeding(st, {"grid.resolution=[100,25]", "sand.0.particles_per_cell=3"})));
}
void Collapse2DSecond5mm(benchmark::State& st) {
  time_simulated_second<2>(
      st, scene(st, "collapse2d.toml",
                seeding(st, {"grid.resolution=[200,50]", "sand.0.particles_per_cell=3"})));
}
void Collapse2DSecond12mm(benchmark::State& st) {
  time_simulated_second<2>(st, scene(st, "collapse2d.toml", seeding(st, {})));
}

// The two benchmarks below spin while they wait: with one core to share
// they would take minutes, so they skip.
bool two_cores(benchmark::State& state) {
  if (omp_get_num_procs() >= 2) return true;
  state.SkipWithError("needs two cores (the threads spin)");
  return false;
}

// Two threads handing a flag back and forth: the time for a cache line
// written by one core to be read by the other and answered.
void CoreRoundTrip(benchmark::State& state) {
  if (!two_cores(state)) return;
  constexpr int kTrips = 100000;
  alignas(64) std::atomic<int> flag{0};
  for (auto _ : state) {
    flag.store(0);
    std::thread other([&] {
      for (int i = 0; i < kTrips; ++i) {
        while (flag.load(std::memory_order_acquire) != 2 * i + 1) {
        }
        flag.store(2 * i + 2, std::memory_order_release);
      }
    });
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < kTrips; ++i) {
      flag.store(2 * i + 1, std::memory_order_release);
      while (flag.load(std::memory_order_acquire) != 2 * i + 2) {
      }
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    other.join();
    state.counters["round_trip_ns"] = 1e9 * s / kTrips;
  }
}

// The solver's spin barrier (solver/team.hpp) with two threads.
void SpinBarrier2(benchmark::State& state) {
  if (!two_cores(state)) return;
  constexpr int kWaits = 100000;
  for (auto _ : state) {
    SpinBarrier barrier(2);
    std::thread other([&] {
      for (int i = 0; i < kWaits; ++i) barrier.wait();
    });
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < kWaits; ++i) barrier.wait();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    other.join();
    state.counters["barrier_ns"] = 1e9 * s / kWaits;
  }
}
void Silo2D(benchmark::State& st) { time_steps<2>(st, scene(st, "silo2d.toml", {}), 0.3); }

BENCHMARK(Collapse3D)->Unit(benchmark::kMillisecond)->Iterations(20)->Arg(0)->Arg(5);
BENCHMARK(Collapse3DFine)->Unit(benchmark::kMillisecond)->Iterations(10)->Arg(0)->Arg(5);
BENCHMARK(Bed3DPaperSize)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10)
    ->Args({0, 0})
    ->Args({5, 0})
    ->Args({0, 100})
    ->Args({5, 100});
BENCHMARK(Silo2D)->Unit(benchmark::kMillisecond)->Iterations(30)->Arg(0)->Arg(5);
// {Anderson depth, seeding}: plain and accelerated on the lattice, then the
// three jittered seedings of docs/benchmarks.md.
void seedings(benchmark::internal::Benchmark* b) {
  b->Args({0, 0})->Args({5, 0})->Args({5, 1})->Args({5, 2})->Args({5, 3});
}
BENCHMARK(Collapse2DSecond12mm)->Unit(benchmark::kSecond)->Iterations(1)->Apply(seedings);
BENCHMARK(Collapse2DSecond10mm)->Unit(benchmark::kSecond)->Iterations(1)->Apply(seedings);
BENCHMARK(Collapse2DSecond5mm)->Unit(benchmark::kSecond)->Iterations(1)->Apply(seedings);
BENCHMARK(CoreRoundTrip)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(SpinBarrier2)->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace
}  // namespace sablier

// Google Benchmark's main, after the tool's allocator settings (the steps
// are timed as `sablier run` takes them).
int main(int argc, char** argv) {
  sablier::keep_freed_memory_in_heap();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
