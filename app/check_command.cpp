// `sablier check` (validate and summarise a scene) and `sablier info`.
#include <fmt/format.h>
#include <omp.h>
#include <png.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>

#include "commands.hpp"
#include "physics/emission.hpp"
#include "physics/obstacle.hpp"
#include "physics/simulation.hpp"
#include "scene/memory_estimate.hpp"
#include "scene/scene.hpp"
#include "scene/scene_obstacles.hpp"

namespace sablier {
namespace {

const char* shape_name(SandShape shape, int d) {
  switch (shape) {
    case SandShape::Box:
      return "box";
    case SandShape::Cylinder:
      return d == 2 ? "disk" : "cylinder";
    case SandShape::Sphere:
      return "sphere";
    case SandShape::Polygon:
      return "polygon";
    case SandShape::Mesh:
      return "mesh";
  }
  return "";
}

// Particles per [[sand]] block, and each spout's rate (emission.hpp).
void print_sources(const SceneConfig& s, const std::vector<std::size_t>& counts) {
  for (std::size_t k = 0; k < counts.size(); ++k)
    std::printf("  sand[%zu]  %s, %zu particles\n", k, shape_name(s.sand[k].shape, s.dimension),
                counts[k]);
  const double end = s.time.frames / s.time.fps;
  const char* unit = s.dimension == 2 ? "kg/s per m of depth" : "kg/s";
  for (std::size_t k = 0; k < s.spouts.size(); ++k) {
    const SpoutConfig& sp = s.spouts[k];
    const double spacing = spout_spacing(s, sp);
    const std::size_t layer = spout_layer_size(s.dimension, sp.radius, spacing);
    std::printf(
        "  spout[%zu] rate %.6g %s (rho phi_max |v| A; %.6g as emitted, %zu particles "
        "per layer), from t = %g s to %s: %lld particles by the end\n",
        k, spout_nominal_rate(s, sp), unit, spout_lattice_rate(s, sp), layer, sp.start,
        std::isfinite(sp.stop) ? fmt::format("{} s", sp.stop).c_str() : "the end",
        static_cast<long long>(spout_particles(s, sp, end)));
  }
}

std::string point(const Vec3d& v, int d) {
  std::string s = "(";
  for (int a = 0; a < d; ++a) s += fmt::format("{}{:.6g}", a ? ", " : "", v[a]);
  return s + ")";
}

// One line per [[obstacle]]: its shape, where it is, its friction, and for a
// rigid body its density and initial velocity.
void print_obstacles(const SceneConfig& s) {
  const int d = s.dimension;
  for (std::size_t k = 0; k < s.obstacles.size(); ++k) {
    const ObstacleConfig& o = s.obstacles[k];
    std::string where;
    switch (o.shape) {
      case ObstacleShape::Plane:
        where = fmt::format("through {}, normal {}", point(o.point, d), point(o.normal, d));
        break;
      case ObstacleShape::Box:
        where = fmt::format("from {} to {}", point(o.min, d), point(o.max, d));
        break;
      case ObstacleShape::Ball:
        where = fmt::format("centre {}, radius {:.6g} m", point(o.center, d), o.radius);
        break;
      case ObstacleShape::Cylinder:
        where = fmt::format("base centre {}, radius {:.6g} m, height {:.6g} m", point(o.center, d),
                            o.radius, o.height);
        break;
      case ObstacleShape::Polygon:
        where = fmt::format("{} corners within {} to {}", o.vertices.size(), point(o.extent_min, d),
                            point(o.extent_max, d));
        break;
      case ObstacleShape::Mesh:
        where = fmt::format("from \"{}\", within {} to {}", o.file_path, point(o.extent_min, d),
                            point(o.extent_max, d));
        break;
    }
    if (o.angle_degrees != 0.0)  // a body's, or a fixed box's, polygon's or mesh's
      where += d == 2 ? fmt::format(" turned {:.6g} degrees", o.angle_degrees)
                      : fmt::format(" turned {:.6g} degrees about {}", o.angle_degrees,
                                    point(o.axis, 3));
    const double mass = !o.dynamic() ? 0.0
                        : d == 2     ? make_obstacle<2>(o).mass
                                     : make_obstacle<3>(o).mass;
    const std::string body =
        o.dynamic() ? fmt::format(
                          ", rigid body of density {:.6g} kg/m^3 ({:.6g} {}) starting at "
                          "{} m/s",
                          o.density, mass, d == 2 ? "kg/m" : "kg", point(o.velocity, d))
                    : "";
    std::string motion;  // a fixed solid's: translating, turning
    const auto nonzero = [](const Vec3d& v) { return v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0; };
    if (!o.dynamic()) {
      if (moves_into_sand(o, d)) motion += ", driven into the sand";
      if (nonzero(o.velocity)) motion += fmt::format(", moving at {} m/s", point(o.velocity, d));
      if (nonzero(o.spin))
        motion += d == 2 ? fmt::format(", turning at {:.6g} rad/s about its centre", o.spin[2])
                         : fmt::format(", turning at {} rad/s about its centre", point(o.spin, 3));
    }
    const std::string gone =
        std::isfinite(o.until) ? fmt::format(", taken away at {:.6g} s", o.until) : "";
    std::printf("  obstacle[%zu] %s %s, mu %g%s%s%s\n", k, obstacle_shape_name(o.shape, d),
                where.c_str(), o.mu, body.c_str(), motion.c_str(), gone.c_str());
  }
}

// For each cohesive material, the height of a free vertical face its
// cohesion holds by the lower bound of limit analysis: the weight's
// uniaxial stress fits the cone while c >= rho g H f, with f = (1 - mu) / 2
// in 2D and 1 / sqrt(3) - mu / 3 in 3D (docs/scenes.md, "How much cohesion
// a structure needs"); narrow columns stand somewhat higher.
template <int D>
void print_cohesion(const SceneConfig& s, const std::vector<Material>& materials) {
  const double g = std::sqrt(s.gravity[0] * s.gravity[0] + s.gravity[1] * s.gravity[1] +
                             s.gravity[2] * s.gravity[2]);
  for (std::size_t k = 0; k < materials.size(); ++k) {
    const Material& m = materials[k];
    if (m.cohesion <= 0.0 || g <= 0.0) continue;
    const std::string who = k < s.sand.size() ? fmt::format("sand[{}]", k) : "spouts";
    const double f = D == 2 ? (1.0 - m.mu) / 2.0 : 1.0 / std::sqrt(3.0) - m.mu / 3.0;
    if (f <= 0.0) {
      std::printf("cohesion   %s: %g Pa; with mu %g a free vertical face of any height stands\n",
                  who.c_str(), m.cohesion, m.mu);
    } else {
      std::printf(
          "cohesion   %s: %g Pa holds a free vertical face up to %.3g m high (limit "
          "analysis's lower bound)%s\n",
          who.c_str(), m.cohesion, m.cohesion / (m.density * g * f),
          m.cohesion_decay > 0.0 ? "; it decays where the sand yields" : "");
    }
  }
}

template <int D>
void print_summary(const SceneConfig& s) {
  std::vector<std::size_t> counts;
  const Particles<D> p = seed_particles<D>(s, &counts);
  const std::size_t grains = grains_by_end(s, p.size());
  refuse_if_too_big(s, grains);
  std::string cells = std::to_string(s.resolution[0]);
  std::string size = fmt::format("{}", s.size[0]);
  long long ncells = s.resolution[0];
  for (int a = 1; a < D; ++a) {
    cells += fmt::format(" x {}", s.resolution[a]);
    size += fmt::format(" x {}", s.size[a]);
    ncells *= s.resolution[a];
  }
  const std::vector<Material> materials = material_table(s);
  double mass = 0.0;  // each [[sand]] block with its own density
  for (std::size_t k = 0; k < p.size(); ++k) mass += materials[p.material[k]].density * p.volume[k];
  std::printf("scene      %s (%dD)\n", s.source.c_str(), D);
  std::printf("domain     %s m, %s cells of %.4g m (%lld cells)\n", size.c_str(), cells.c_str(),
              s.cell_size(), ncells);
  // In 2D a particle's volume is an area (m^2), so its mass is per metre of depth.
  std::printf("particles  %zu in %zu region(s), grain mass %.6g %s\n", p.size(), s.sand.size(),
              mass, D == 2 ? "kg per metre of depth" : "kg");
  print_sources(s, counts);
  print_cohesion<D>(s, materials);
  print_obstacles(s);
  std::printf("time       %d frames at %g fps (%g s), %s\n", s.time.frames, s.time.fps,
              s.time.frames / s.time.fps,
              s.time.substeps > 0 ? fmt::format("{} sub-steps per frame", s.time.substeps).c_str()
                                  : fmt::format("adaptive sub-steps (cfl {})", s.time.cfl).c_str());
  const SolverConfig& v = s.solver;
  const std::string rule =
      v.decompaction == Decompaction::Move
          ? fmt::format("grains of over-full nodes moved apart {} times per step",
                        v.decompaction_moves)
      : v.decompaction == Decompaction::Push ? std::string("over-full nodes pushed apart")
      : v.decompaction == Decompaction::Project
          ? fmt::format(
                "grains of over-full nodes moved apart {0} times, then projected in at "
                "most {0} rounds per step",
                v.decompaction_moves)
          : std::string("over-full nodes clamped only");
  std::printf("solver     tolerance %g, at most %d sweeps, Anderson depth %d; %s\n", v.tolerance,
              v.max_iterations, v.anderson, rule.c_str());
  std::printf("memory     about %.1f MB (%.1f GB available)\n",
              run_memory_bytes(D, double(ncells), double(grains)) / 1e6,
              machine_memory_bytes() / 1e9);
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
    for (const SceneMessage& m : thin_solid_messages(s))
      std::fprintf(stderr, "%s\n", m.line().c_str());
    std::printf("ok\n");
    return 0;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: %s: out of memory while seeding the scene's grains\n",
                 path.c_str());
    return 4;
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
#if defined(__AVX2__) && defined(__FMA__)
  std::printf("simd       AVX2, FMA\n");
#elif defined(__SSE2__)
  std::printf("simd       SSE2\n");
#endif
  std::printf(
      "outputs    vtp (zlib %s with --compress), csv, ply, vti (--grid), series.pvd, obj "
      "(obstacles)\n",
      ZLIB_VERSION);
  std::printf("pictures   png (libpng %s)\n", PNG_LIBPNG_VER_STRING);
  const bool gif = tool_present("convert"), mp4 = tool_present("ffmpeg");
  std::printf("animations gif %s, mp4 %s\n",
              gif ? "(ImageMagick convert)" : "unavailable (apt-get install imagemagick)",
              mp4 ? "(ffmpeg)" : "unavailable (apt-get install ffmpeg)");
  return 0;
}

}  // namespace sablier
