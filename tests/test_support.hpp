// Helpers shared by the test programs: the command-line runner, temp folders
// of this process, the shipped scenes, and a stepping loop that checks the
// solver. Each test program is its own process, and ctest runs them side by
// side, so every temp name carries the process id.
#pragma once

#include <gtest/gtest.h>
#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "io/writers.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"

namespace sablier::test {

inline constexpr double kPi = 3.14159265358979323846;

// One OpenMP thread for a whole test program: results do not depend on the
// thread count (tests check it where it matters), and ctest may run test
// programs side by side on few cores, where OpenMP's spinning threads slow
// each other down many times over (measured: 10 s to 206 s for the energy
// test under `ctest -j2`). Register once per program:
//   const auto* const kOneThread = testing::AddGlobalTestEnvironment(new test::OneThread);
struct OneThread : testing::Environment {
  void SetUp() override { omp_set_num_threads(1); }
};

// The temp paths this process has named, removed when it exits: the
// folders of runs and the files that tests write would otherwise stay
// behind, about 13 MB for each pass of the suite.
inline std::vector<std::filesystem::path>& temp_paths() {
  struct Registry {
    std::vector<std::filesystem::path> paths;
    ~Registry() {
      std::error_code ignored;  // a path never made, or already gone
      for (const std::filesystem::path& p : paths) std::filesystem::remove_all(p, ignored);
    }
  };
  static Registry registry;
  return registry.paths;
}

// A temp path of this process, <tmp>/sablier_<name>_<pid><extension>,
// removed when the process exits.
inline std::filesystem::path temp_path(const std::string& name, const std::string& extension = "") {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("sablier_" + name + "_" + std::to_string(::getpid()) + extension);
  std::vector<std::filesystem::path>& known = temp_paths();
  if (std::find(known.begin(), known.end(), path) == known.end()) known.push_back(path);
  return path;
}

// temp_path(name), emptied: removed, not created (a run creates it).
inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = temp_path(name);
  std::filesystem::remove_all(dir);
  return dir;
}

// fresh_dir(name), created.
inline std::filesystem::path temp_dir(const std::string& name) {
  const std::filesystem::path dir = fresh_dir(name);
  std::filesystem::create_directories(dir);
  return dir;
}

// What a command did: its exit code and its stdout and stderr together.
struct Result {
  int code;
  std::string output;
};

// Runs a shell command line, `{bin}` in it standing for the sablier binary;
// the output goes through a log file of this process.
inline Result shell(std::string line) {
  const std::string bin = SABLIER_BINARY;
  for (std::size_t at = line.find("{bin}"); at != std::string::npos;
       at = line.find("{bin}", at + bin.size()))
    line.replace(at, 5, bin);
  const std::filesystem::path log = temp_path("log");
  const int status = std::system(("(" + line + ") > " + log.string() + " 2>&1").c_str());
  Result r{WEXITSTATUS(status), read_file(log.string())};
  std::filesystem::remove(log);
  return r;
}

// Runs the sablier binary with these arguments.
inline Result sablier(const std::string& args) {
  return shell(std::string(SABLIER_BINARY) + " " + args);
}

// The path of a shipped scene, scenes/<name>.
inline std::string scene_file(const std::string& name) {
  return std::string(SABLIER_SOURCE_DIR) + "/scenes/" + name;
}

// A shipped scene, loaded with `--set`-style overrides.
inline SceneConfig scene(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return load_scene(scene_file(name), overrides);
}

// A 2D layer 10 cm deep across a 1 m channel (collapse2d at 80 x 20 cells)
// on a rough floor, under gravity tilted by theta_deg, with friction mu and
// its downhill end free or a slip wall.
inline SceneConfig tilted_layer(double theta_deg, double mu, bool free_end) {
  const double th = theta_deg * kPi / 180.0;
  const std::string gravity = "gravity=[" + std::to_string(9.81 * std::sin(th)) + "," +
                              std::to_string(-9.81 * std::cos(th)) + "]";
  return scene("collapse2d.toml",
               {"grid.resolution=[80,20]", "sand.0.max=[1.0,0.1]", gravity,
                "material.mu=" + std::to_string(mu),
                std::string("boundary.xmax=") + (free_end ? "\"free\"" : "\"slip\"")});
}

// The scene with its sand replaced by one small block (5 cm on a side) at
// `corner` (its lowest corner), and no obstacles or spouts: for tests of
// rigid bodies that must never meet the sand.
template <int D>
SceneConfig small_block_only(SceneConfig s, const Vec3d& corner) {
  s.sand.resize(1);
  s.sand[0].shape = SandShape::Box;
  s.sand[0].min = corner;
  s.sand[0].max = Vec3d{corner[0] + 0.05, corner[1] + 0.05, D == 3 ? corner[2] + 0.05 : 0.0};
  s.spouts.clear();
  s.obstacles.clear();
  return s;
}

// Every stress row of p lies in its cone, |lambda_T| <= a (lambda_N + c)
// (a the row's aperture, c its cohesion, the apex's shift along e_0), to
// 1e-10 relative; `what` names the problem in failures.
template <int D>
void expect_stresses_in_cones(const ConeProblem<D>& p, const std::string& what) {
  for (int j = 0; j < p.rows(); ++j) {
    SymVec<D> x = p.lambda[j];
    x[0] += p.cohesion[j];
    EXPECT_LE(x.tail(sym_size(D) - 1).norm(), p.aperture[j] * x[0] + 1e-10 * std::abs(x[0]) + 1e-12)
        << what << " row " << j;
  }
}

// Runs to time t with adaptive steps, each within at most `max_dt` (a
// frame, say) of the remaining time; checks every step's solver report
// (the residual is below the tolerance, or the step says it hit the cap).
template <int D>
void run_until(Simulation<D>& sim, double t, double max_dt = 1e300) {
  const double tol = sim.scene().solver.tolerance;
  while (sim.time() < t - 1e-12) {
    const StepInfo info = sim.step(sim.adaptive_dt(std::min(max_dt, t - sim.time())));
    ASSERT_TRUE(info.solve.residual <= tol || info.solve.hit_cap)
        << "step " << sim.steps() << " residual " << info.solve.residual;
  }
}

// Runs body 0 of `sim` (the scene's first [[obstacle]], a rigid body) for
// `duration` s with adaptive steps, checking its momentum balance at every
// step: m (V_n - V_{n-1}) = (F_n + m g) dt_n, F_n the force of the sand's
// rows on it (StepInfo::obstacle_force). `worst` is the largest imbalance
// relative to m |g| dt_n; `mean_force` the force along the last axis over
// the second half of the run, weighted by dt.
struct BodyBalance {
  double worst = 0.0, mean_force = 0.0;
};

template <int D>
BodyBalance run_body_balance(Simulation<D>& sim, double duration) {
  const double m = sim.obstacles()[0].mass;
  Vec<D> g;
  for (int a = 0; a < D; ++a) g[a] = sim.scene().gravity[a];
  Vec<D> v_prev = sim.obstacles()[0].velocity;
  BodyBalance out;
  double impulse = 0.0, span = 0.0;
  while (sim.time() < duration - 1e-12) {
    const double dt = sim.adaptive_dt(duration - sim.time());
    const StepInfo info = sim.step(dt);
    const Obstacle<D>& b = sim.obstacles()[0];
    Vec<D> force;
    for (int a = 0; a < D; ++a) force[a] = info.obstacle_force[0][a];
    const Vec<D> gained = m * (b.velocity - v_prev) - (force + m * g) * dt;
    out.worst = std::max(out.worst, gained.norm() / (m * g.norm() * dt));
    v_prev = b.velocity;
    if (sim.time() > 0.5 * duration) {
      impulse += force[D - 1] * dt;
      span += dt;
    }
  }
  out.mean_force = impulse / span;
  return out;
}

// Steps `scene` on 1 thread and on 2 through the same `steps` adaptive
// steps and expects the same bits: the particles' positions and, if body
// >= 0, that rigid body's state (results must not depend on the thread
// count). Leaves the thread count as it found it.
template <int D>
void expect_same_bits_on_1_and_2_threads(const SceneConfig& scene, int steps, int body = -1) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  Simulation<D> one(scene);
  omp_set_num_threads(2);
  Simulation<D> two(scene);
  for (int i = 0; i < steps; ++i) {
    const double dt = one.adaptive_dt(1.0 / scene.time.fps);
    omp_set_num_threads(1);
    one.step(dt);
    omp_set_num_threads(2);
    two.step(dt);
  }
  omp_set_num_threads(threads);
  if (body >= 0) {
    EXPECT_EQ(one.obstacles()[body].a, two.obstacles()[body].a);
    EXPECT_EQ(one.obstacles()[body].spin, two.obstacles()[body].spin);
    EXPECT_EQ(one.obstacles()[body].quaternion, two.obstacles()[body].quaternion);
  }
  EXPECT_EQ(one.particles().position, two.particles().position);
}

// Least-squares line y = a x + b.
inline void fit_line(const std::vector<double>& x, const std::vector<double>& y, double* a,
                     double* b) {
  const double n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i] / n, my += y[i] / n;
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
    sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
  *a = sxy / sxx;
  *b = my - *a * mx;
}

}  // namespace sablier::test
