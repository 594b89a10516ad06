// Filling [[sand]] regions with particles (METHOD.md section 2, step 1),
// except inside [[obstacle]] blocks.
#include "physics/seeding.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/mesh.hpp"
#include "core/polygon.hpp"
#include "physics/obstacle.hpp"
#include "physics/simulation.hpp"

namespace sablier {
namespace {

// Uniform double in [0, 1) from 53 random bits: portable across standard
// libraries (std::uniform_real_distribution is not), so seeds reproduce.
inline double unit_random(std::mt19937_64& rng) { return (rng() >> 11) * 0x1.0p-53; }

template <int D>
bool inside(const SandConfig& s, const Vec<D>& x) {
  double r2 = 0.0;
  switch (s.shape) {
    case SandShape::Box:
      for (int a = 0; a < D; ++a)
        if (x[a] < s.min[a] || x[a] >= s.max[a]) return false;
      return true;
    case SandShape::Sphere:
      for (int a = 0; a < D; ++a) r2 += (x[a] - s.center[a]) * (x[a] - s.center[a]);
      return r2 < s.radius * s.radius;
    case SandShape::Polygon:
      return winding_number(s.vertices, x[0], x[1]) != 0;
    case SandShape::Mesh:
      if constexpr (D == 3) return s.mesh->contains({x[0], x[1], x[2]});
      return false;
    case SandShape::Cylinder:
      break;
  }
  // Disk (2D) or vertical cylinder (3D, axis along z from center[2] to + height).
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
    } else if (s.shape == SandShape::Polygon) {
      lo[a] = hi[a] = s.vertices[0][a];
      for (const Vec3d& v : s.vertices) {
        lo[a] = std::min(lo[a], v[a]);
        hi[a] = std::max(hi[a], v[a]);
      }
    } else if (s.shape == SandShape::Mesh) {
      lo[a] = s.mesh->lower()[a];
      hi[a] = s.mesh->upper()[a];
    } else if (a < 2 || s.shape == SandShape::Sphere) {
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
Particles<D> seed_particles(const SceneConfig& scene, std::vector<std::size_t>* region_counts) {
  if (region_counts) region_counts->assign(scene.sand.size(), 0);
  const double h = scene.cell_size();
  const double phi_max = scene.material.phi_max;
  std::mt19937_64 rng(scene.seed);
  const std::vector<Obstacle<D>> obstacles = make_obstacles<D>(scene);
  Particles<D> p;
  for (std::size_t r = 0; r < scene.sand.size(); ++r) {
    const SandConfig& s = scene.sand[r];
    const int n = s.particles_per_cell;
    const double spacing = h / n;
    const double vp = phi_max * std::pow(spacing, D);
    // Material index r: the block's entry of the material table (material.hpp).
    const double cohesion = sand_material(scene, r).cohesion;
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
      // Sand cannot be inside a solid. After the jitter: the random stream,
      // hence every other particle, is the same with or without obstacles.
      Vec<D> normal;
      if (obstacle_distance(obstacles, x, &normal) < 0.0) continue;
      const std::size_t k = p.size();
      p.resize(k + 1);
      p.position[k] = x;
      for (int a = 0; a < D; ++a) p.velocity[k][a] = s.velocity[a];
      p.affine[k].setZero();
      p.volume[k] = vp;
      p.cohesion[k] = cohesion;
      p.material[k] = static_cast<std::int32_t>(r);
      p.inertial[k] = 0.0;
      p.id[k] = static_cast<std::int64_t>(k);
      p.stress[k].setZero();
      p.phi[k] = phi_max;
      p.shear_rate[k] = 0.0;
      if (region_counts) ++(*region_counts)[r];
    }
  }
  return p;
}

template Particles<2> seed_particles<2>(const SceneConfig&, std::vector<std::size_t>*);
template Particles<3> seed_particles<3>(const SceneConfig&, std::vector<std::size_t>*);

std::vector<std::size_t> seeded_per_region(const SceneConfig& scene) {
  std::vector<std::size_t> counts;
  if (scene.dimension == 2) {
    seed_particles<2>(scene, &counts);
  } else {
    seed_particles<3>(scene, &counts);
  }
  return counts;
}

}  // namespace sablier
