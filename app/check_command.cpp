// `sablier check` (validate and summarise a scene) and `sablier info`.
#include <omp.h>

#include <cstdio>
#include <fmt/format.h>

#include "commands.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"

namespace sablier {
namespace {

template <int D>
void print_summary(const SceneConfig& s) {
  const Particles<D> p = seed_particles<D>(s);
  std::string cells = std::to_string(s.resolution[0]);
  std::string size = fmt::format("{}", s.size[0]);
  long long ncells = s.resolution[0];
  for (int a = 1; a < D; ++a) {
    cells += fmt::format(" x {}", s.resolution[a]);
    size += fmt::format(" x {}", s.size[a]);
    ncells *= s.resolution[a];
  }
  double volume = 0.0;
  for (double v : p.volume) volume += v;
  std::printf("scene      %s (%dD)\n", s.source.c_str(), D);
  std::printf("domain     %s m, %s cells of %.4g m (%lld cells)\n", size.c_str(), cells.c_str(),
              s.cell_size(), ncells);
  std::printf("particles  %zu in %zu region(s), grain mass %.6g kg\n", p.size(), s.sand.size(),
              s.material.density * volume);
  std::printf("time       %d frames at %g fps (%g s), %s\n", s.time.frames, s.time.fps,
              s.time.frames / s.time.fps,
              s.time.substeps > 0 ? fmt::format("{} sub-steps per frame", s.time.substeps).c_str()
                                  : fmt::format("adaptive sub-steps (cfl {})", s.time.cfl).c_str());
  // Dense node fields (velocity, inverse mass, mask, momentum, warm start, mass,
  // row map) and per-row solver data, plus the particle arrays.
  constexpr int SD = sym_size(D);
  const double nodes = static_cast<double>(ncells) * 1.1 + 1e3;
  const double node_bytes = nodes * 8.0 * (4 * D + SD + 1.5);
  const double row_bytes = nodes * 8.0 * (ipow(3, D) * D + 2 * SD + SD * SD + 8);
  const double particle_bytes = p.size() * 8.0 * (3 * D + D * D + SD + 6);
  std::printf("memory     about %.1f MB\n", (node_bytes + row_bytes + particle_bytes) / 1e6);
}

}  // namespace

int check_command(const std::string& path, const std::vector<std::string>& overrides) {
  try {
    const SceneConfig s = load_scene(path, overrides);
    if (s.dimension == 2) {
      print_summary<2>(s);
    } else {
      print_summary<3>(s);
    }
    std::printf("ok\n");
    return 0;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}

int info_command() {
  std::printf("sablier %s\n", SABLIER_VERSION);
  std::printf("build      %s\n", SABLIER_BUILD_TYPE);
#if defined(__clang__)
  std::printf("compiler   clang %s\n", __clang_version__);
#elif defined(__GNUC__)
  std::printf("compiler   g++ %d.%d.%d\n", __GNUC__, __GNUC_MINOR__, __GNUC_PATCHLEVEL__);
#endif
  std::printf("openmp     %d threads (set OMP_NUM_THREADS or --threads)\n", omp_get_max_threads());
  std::printf("dimensions 2, 3\n");
  return 0;
}

}  // namespace sablier
