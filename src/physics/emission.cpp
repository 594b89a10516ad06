// Spouts: stateless emission of particle layers (see emission.hpp for the
// scheme and why it is stateless).
#include "physics/emission.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "physics/obstacle.hpp"

namespace sablier {
namespace {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64's finaliser: a counter-based generator, so that a particle's
// jitter depends on its (spout, layer, point) and on nothing emitted before.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Uniform in [0, 1) from 53 bits of the hash of the counters.
double hash_unit(std::uint64_t seed, std::uint64_t spout, std::uint64_t layer, std::uint64_t point,
                 std::uint64_t axis) {
  std::uint64_t h = mix(seed);
  for (const std::uint64_t c : {spout, layer, point, axis}) h = mix(h ^ c);
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

double speed(const SpoutConfig& s) {
  return std::sqrt(s.velocity[0] * s.velocity[0] + s.velocity[1] * s.velocity[1] +
                   s.velocity[2] * s.velocity[2]);
}

// The flow direction and an orthonormal basis (e1, e2) of the cross-section
// (2D: e1 only, the direction turned a quarter counter-clockwise).
struct SectionFrame {
  Vec3d dir, e1, e2;
};

SectionFrame section_frame(const SpoutConfig& s, int dimension) {
  const double v = speed(s);
  SectionFrame f{{s.velocity[0] / v, s.velocity[1] / v, s.velocity[2] / v}, {}, {}};
  const Vec3d& n = f.dir;
  if (dimension == 2) {
    f.e1 = {-n[1], n[0], 0.0};
    f.e2 = {0.0, 0.0, 0.0};
    return f;
  }
  // e1 = n x (the axis least aligned with n), normalised; e2 = n x e1.
  int a = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[a])) a = k;
  Vec3d axis{0, 0, 0};
  axis[a] = 1.0;
  Vec3d e1{n[1] * axis[2] - n[2] * axis[1], n[2] * axis[0] - n[0] * axis[2],
           n[0] * axis[1] - n[1] * axis[0]};
  const double len = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (double& x : e1) x /= len;
  f.e1 = e1;
  f.e2 = {n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]};
  return f;
}

// Calls f(u, w) for the in-plane offsets of a layer's points, in a fixed
// order (the point index k of the particle ids).
template <class F>
void for_each_layer_point(int dimension, double radius, double spacing, F&& f) {
  if (dimension == 2) {
    const long count = std::lround(2.0 * radius / spacing);
    for (long k = 0; k < count; ++k) f((k - 0.5 * (count - 1)) * spacing, 0.0);
    return;
  }
  const long m = static_cast<long>(std::ceil(radius / spacing));
  for (long j = -m; j < m; ++j)
    for (long i = -m; i < m; ++i) {
      const double u = (i + 0.5) * spacing, w = (j + 0.5) * spacing;
      if (u * u + w * w < radius * radius) f(u, w);
    }
}

// Appends layer `layer` of spout `index`, its centre `distance` downstream,
// but for the points that would lie outside the box or inside an obstacle.
template <int D>
void emit_layer(const SceneConfig& scene, std::size_t index, std::int64_t layer, double distance,
                const SectionFrame& frame, const std::vector<Obstacle<D>>& obstacles,
                Particles<D>& p) {
  const SpoutConfig& sp = scene.spouts[index];
  const double s = spout_spacing(scene, sp);
  const double phi_max = scene.material.phi_max;
  const double volume = phi_max * std::pow(s, D);
  const std::int32_t material = spout_material_index(scene);
  const std::int64_t id_base =
      (static_cast<std::int64_t>(index) + 1) << (2 * kSpoutIdBits) | layer << kSpoutIdBits;
  std::int64_t point = 0;
  for_each_layer_point(D, sp.radius, s, [&](double u, double w) {
    const std::int64_t k = point++;
    Vec<D> x;
    bool inside = true;
    for (int a = 0; a < D; ++a) {
      x[a] = sp.center[a] + distance * frame.dir[a] + u * frame.e1[a] + w * frame.e2[a];
      if (sp.jitter > 0.0)
        x[a] += (hash_unit(scene.seed, index, layer, k, a) - 0.5) * sp.jitter * s;
      inside &= x[a] >= 0.0 && x[a] <= scene.size[a];
    }
    if (!inside) return;  // the box cannot hold it (the sort would drop it)
    Vec<D> normal;
    if (obstacle_distance(obstacles, x, &normal) < 0.0) return;  // nor can a solid
    const std::size_t n = p.size();
    p.resize(n + 1);
    p.position[n] = x;
    for (int a = 0; a < D; ++a) p.velocity[n][a] = sp.velocity[a];
    p.affine[n].setZero();
    p.volume[n] = volume;
    p.cohesion[n] = scene.material.cohesion;
    p.material[n] = material;
    p.inertial[n] = 0.0;
    p.id[n] = id_base | k;
    p.stress[n].setZero();
    p.phi[n] = phi_max;
    p.shear_rate[n] = 0.0;
  });
}

}  // namespace

double spout_spacing(const SceneConfig& scene, const SpoutConfig& spout) {
  return scene.cell_size() / spout.particles_per_cell;
}

std::size_t spout_layer_size(int dimension, double radius, double spacing) {
  std::size_t n = 0;
  for_each_layer_point(dimension, radius, spacing, [&](double, double) { ++n; });
  return n;
}

std::int64_t spout_layers(const SpoutConfig& spout, double spacing, double t) {
  if (!(t > spout.start)) return 0;
  const double layers =
      std::floor(speed(spout) * (std::min(t, spout.stop) - spout.start) / spacing);
  // Saturates rather than overflow (the parser caps the layers of a run).
  return layers < 0x1.0p62 ? static_cast<std::int64_t>(layers) : std::int64_t(1) << 62;
}

std::int64_t spout_particles(const SceneConfig& scene, const SpoutConfig& spout, double t) {
  const double spacing = spout_spacing(scene, spout);
  return spout_layers(spout, spacing, t) *
         static_cast<std::int64_t>(spout_layer_size(scene.dimension, spout.radius, spacing));
}

double spout_nominal_rate(const SceneConfig& scene, const SpoutConfig& spout) {
  const double area = scene.dimension == 2 ? 2.0 * spout.radius : kPi * spout.radius * spout.radius;
  return scene.material.density * scene.material.phi_max * speed(spout) * area;
}

double spout_lattice_rate(const SceneConfig& scene, const SpoutConfig& spout) {
  const double s = spout_spacing(scene, spout);
  const double area = static_cast<double>(spout_layer_size(scene.dimension, spout.radius, s)) *
                      std::pow(s, scene.dimension - 1);
  return scene.material.density * scene.material.phi_max * speed(spout) * area;
}

double open_spout_speed(const SceneConfig& scene, double t) {
  double v = 0.0;
  for (const SpoutConfig& s : scene.spouts)
    if (t < s.stop) v = std::max(v, speed(s));
  return v;
}

std::int32_t spout_material_index(const SceneConfig& scene) {
  return static_cast<std::int32_t>(scene.sand.size());
}

template <int D>
void emit_spout_particles(const SceneConfig& scene, double t0, double t1, Particles<D>& p,
                          const std::vector<Obstacle<D>>* bodies) {
  if (scene.spouts.empty()) return;
  // No grain inside a solid: the fixed obstacles as the scene places them
  // at t1, the rigid bodies where the run has taken them.
  std::vector<Obstacle<D>> obstacles = make_obstacles<D>(scene, t1);
  obstacles.erase(std::remove_if(obstacles.begin(), obstacles.end(),
                                 [](const Obstacle<D>& o) { return o.dynamic; }),
                  obstacles.end());
  if (bodies)
    for (const Obstacle<D>& o : *bodies)
      if (o.dynamic) obstacles.push_back(o);
  for (std::size_t i = 0; i < scene.spouts.size(); ++i) {
    const SpoutConfig& sp = scene.spouts[i];
    const double s = spout_spacing(scene, sp);
    const std::int64_t from = spout_layers(sp, s, t0), to = spout_layers(sp, s, t1);
    if (from >= to) continue;
    const SectionFrame frame = section_frame(sp, D);
    const double front = speed(sp) * (t1 - sp.start);  // how far the first grains went
    for (std::int64_t j = from; j < to; ++j)
      emit_layer<D>(scene, i, j, front - (j + 0.5) * s, frame, obstacles, p);
  }
}

template void emit_spout_particles<2>(const SceneConfig&, double, double, Particles<2>&,
                                      const std::vector<Obstacle<2>>*);
template void emit_spout_particles<3>(const SceneConfig&, double, double, Particles<3>&,
                                      const std::vector<Obstacle<3>>*);

}  // namespace sablier
