// What a run's memory comes to, for `check`'s summary and for refusing a
// scene this machine cannot hold before anything is allocated or written.
#pragma once

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <string>

#include "core/mesh.hpp"
#include "physics/emission.hpp"
#include "scene/scene.hpp"

namespace sablier {

// Bytes per cell and per grain, fitted to the largest resident size of
// `sablier run` (one frame, one thread, g++ 12 Release; 2026-12-07): 2D
// collapse at 400 x 100 and 800 x 200 cells with 72,000 and 288,000 grains
// (95, 308 and 360 MB), 3D collapse at 80 x 8 x 20 and 160 x 16 x 40 cells
// with 20,480 to 552,960 grains (113-870 MB). A grain costs far more than
// its own arrays (about 240 bytes in 3D): sorting keeps a second copy, and a
// frame's files and the checkpoint are encoded in memory before they are
// written. The fit overestimates each of those eight runs by 2-11%.
inline double run_memory_bytes(int dimension, double cells, double grains) {
  const double per_cell = dimension == 2 ? 450.0 : 1450.0;
  const double per_grain = dimension == 2 ? 1000.0 : 1350.0;
  return 8e6 + per_cell * cells + per_grain * grains;
}

// The memory a run may take, in bytes (0 when unknown): the environment's
// SABLIER_MEMORY_LIMIT when set (to leave room for other work, or to test
// the check), else the machine's physical memory, or the control group's
// limit when lower (a container's or a cluster job's).
inline double machine_memory_bytes() {
  if (const char* limit = std::getenv("SABLIER_MEMORY_LIMIT"); limit && *limit)
    return std::strtod(limit, nullptr);
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  double bytes = pages > 0 && page > 0 ? double(pages) * double(page) : 0.0;
  std::ifstream cgroup("/sys/fs/cgroup/memory.max");  // cgroup v2; "max" when unlimited
  double group = 0.0;
  if (cgroup >> group && group > 0.0 && (bytes <= 0.0 || group < bytes)) bytes = group;
  return bytes;
}

inline double scene_cells(const SceneConfig& s) {
  double cells = 1.0;
  for (int a = 0; a < s.dimension; ++a) cells *= s.resolution[a];
  return cells;
}

// About how many grains [[sand]] block b seeds, from its volume (area in
// 2D) and its particles per cell and axis, before seeding tries: a block that
// fills a large box can ask for more grains than the machine holds. Blocks
// that overlap or reach past the box count twice here.
inline double block_grains(const SceneConfig& s, const SandConfig& b) {
  const int d = s.dimension;
  const double pi = 3.14159265358979323846;
  double volume = 0.0;
  switch (b.shape) {
    case SandShape::Box:
      volume = 1.0;
      for (int a = 0; a < d; ++a) volume *= std::max(0.0, b.max[a] - b.min[a]);
      break;
    case SandShape::Cylinder:
      volume = pi * b.radius * b.radius * (d == 3 ? b.height : 1.0);
      break;
    case SandShape::Sphere:
      volume = 4.0 / 3.0 * pi * b.radius * b.radius * b.radius;
      break;
    case SandShape::Polygon:  // the shoelace formula
      for (std::size_t k = 0; k < b.vertices.size(); ++k) {
        const Vec3d& p = b.vertices[k];
        const Vec3d& q = b.vertices[(k + 1) % b.vertices.size()];
        volume += 0.5 * (p[0] * q[1] - q[0] * p[1]);
      }
      volume = std::abs(volume);
      break;
    case SandShape::Mesh:
      volume = b.mesh ? b.mesh->volume() : 0.0;
      break;
  }
  return volume * std::pow(b.particles_per_cell / s.cell_size(), d);
}

// The grains a run holds at its end at most: those seeded and those its
// spouts emit (some may leave through free faces before then).
inline std::size_t grains_by_end(const SceneConfig& s, std::size_t seeded) {
  const double end = s.time.frames / s.time.fps;
  std::size_t n = seeded;
  for (const SpoutConfig& sp : s.spouts) n += std::size_t(spout_particles(s, sp, end));
  return n;
}

// What is wrong when `grains` grains on the scene's grid need more memory
// than the machine has ("" when they fit): the reader asks with the grid
// alone and then with the blocks' grains (block_grains), before any
// seeding; run and check with the grains seeded.
inline std::string memory_shortfall(const SceneConfig& s, double grains, const char* up_to) {
  const double need = run_memory_bytes(s.dimension, scene_cells(s), grains);
  const double have = machine_memory_bytes();
  if (have <= 0.0 || need <= have) return "";
  const std::string of_grains =
      grains > 0.0 ? fmt::format(" and {}{:.4g} grains", up_to, grains) : std::string();
  return fmt::format(
      "{:.0f} cells{} need about {:.1f} GB, more than the {:.1f} GB available; allowed: fewer "
      "cells or fewer particles per cell",
      scene_cells(s), of_grains, need / 1e9, have / 1e9);
}

// The same as a SceneError naming the file, once the grains are seeded.
inline void refuse_if_too_big(const SceneConfig& s, std::size_t grains) {
  const std::string what = memory_shortfall(s, double(grains), "");
  if (!what.empty()) throw SceneError(s.source + ": grid.resolution: " + what);
}

}  // namespace sablier
