// Filling [[sand]] regions with particles (METHOD.md section 2, step 1).
#include <cmath>
#include <random>

#include "physics/simulation.hpp"

namespace sablier {
namespace {

// Uniform double in [0, 1) from 53 random bits: portable across standard
// libraries (std::uniform_real_distribution is not), so seeds reproduce.
inline double unit_random(std::mt19937_64& rng) { return (rng() >> 11) * 0x1.0p-53; }

template <int D>
bool inside(const SandConfig& s, const Vec<D>& x) {
  if (s.shape == SandShape::Box) {
    for (int a = 0; a < D; ++a)
      if (x[a] < s.min[a] || x[a] >= s.max[a]) return false;
    return true;
  }
  // Disk (2D) or vertical cylinder (3D, axis along z from center[2] to + height).
  double r2 = 0.0;
  for (int a = 0; a < 2; ++a) r2 += (x[a] - s.center[a]) * (x[a] - s.center[a]);
  if (r2 >= s.radius * s.radius) return false;
  if constexpr (D == 3) return x[2] >= s.center[2] && x[2] < s.center[2] + s.height;
  return true;
}

template <int D>
void region_bounds(const SandConfig& s, Vec<D>& lo, Vec<D>& hi) {
  for (int a = 0; a < D; ++a) {
    if (s.shape == SandShape::Box) {
      lo[a] = s.min[a];
      hi[a] = s.max[a];
    } else if (a < 2) {
      lo[a] = s.center[a] - s.radius;
      hi[a] = s.center[a] + s.radius;
    } else {
      lo[a] = s.center[2];
      hi[a] = s.center[2] + s.height;
    }
  }
}

}  // namespace

template <int D>
Particles<D> seed_particles(const SceneConfig& scene) {
  const double h = scene.cell_size();
  const double phi_max = scene.material.phi_max;
  std::mt19937_64 rng(scene.seed);
  Particles<D> p;
  for (std::size_t r = 0; r < scene.sand.size(); ++r) {
    const SandConfig& s = scene.sand[r];
    const int n = s.particles_per_cell;
    const double spacing = h / n;
    const double vp = phi_max * std::pow(spacing, D);
    Vec<D> lo, hi;
    region_bounds<D>(s, lo, hi);
    // Sub-cell lattice points k spacing + spacing/2 covering the region.
    std::array<long, D> first, count;
    long total = 1;
    for (int a = 0; a < D; ++a) {
      first[a] = static_cast<long>(std::floor(lo[a] / spacing));
      count[a] = static_cast<long>(std::ceil(hi[a] / spacing)) - first[a];
      total *= count[a];
    }
    for (long flat = 0; flat < total; ++flat) {
      Vec<D> x;
      long rest = flat;
      for (int a = 0; a < D; ++a) {
        x[a] = (first[a] + rest % count[a] + 0.5) * spacing;
        rest /= count[a];
      }
      if (s.jitter > 0.0)
        for (int a = 0; a < D; ++a) x[a] += (unit_random(rng) - 0.5) * s.jitter * spacing;
      if (!inside<D>(s, x)) continue;
      bool taken = false;  // overlapping regions: the first region owns the space
      for (std::size_t q = 0; q < r && !taken; ++q) taken = inside<D>(scene.sand[q], x);
      if (taken) continue;
      const std::size_t k = p.size();
      p.resize(k + 1);
      p.position[k] = x;
      for (int a = 0; a < D; ++a) p.velocity[k][a] = s.velocity[a];
      p.affine[k].setZero();
      p.volume[k] = vp;
      p.cohesion[k] = scene.material.cohesion;
      p.inertial[k] = 0.0;
      p.id[k] = static_cast<std::int64_t>(k);
      p.stress[k].setZero();
      p.phi[k] = phi_max;
      p.shear_rate[k] = 0.0;
    }
  }
  return p;
}

template Particles<2> seed_particles<2>(const SceneConfig&);
template Particles<3> seed_particles<3>(const SceneConfig&);

}  // namespace sablier
