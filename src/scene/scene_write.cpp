// The resolved scene as TOML: every key, defaults filled in. Numbers use the
// shortest representation that reads back to the same double.
#include <fmt/format.h>

#include "scene/scene.hpp"

namespace sablier {
namespace {

std::string vec(const Vec3d& v, int d) {
  std::string s = "[";
  for (int a = 0; a < d; ++a) s += fmt::format("{}{}", a ? ", " : "", v[a]);
  return s + "]";
}

// TOML floats must carry a '.' or exponent; fmt's shortest form may not.
std::string num(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string vecf(const Vec3d& v, int d) {
  std::string s = "[";
  for (int a = 0; a < d; ++a) s += (a ? ", " : "") + num(v[a]);
  return s + "]";
}

const char* boundary_name(BoundaryType t) {
  return t == BoundaryType::Stick ? "stick" : t == BoundaryType::Slip ? "slip" : "free";
}

}  // namespace

std::string scene_to_toml(const SceneConfig& s) {
  const int d = s.dimension;
  const char* faces[] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  std::string out = fmt::format("# Resolved scene (every key, defaults filled in)\ndimension = {}\nseed = {}\ngravity = {}\n\n",
                                d, s.seed, vecf(s.gravity, d));
  Vec3d res{double(s.resolution[0]), double(s.resolution[1]), double(s.resolution[2])};
  out += fmt::format("[grid]\nsize = {}\nresolution = {}\n\n", vecf(s.size, d), vec(res, d));
  out += fmt::format("[time]\nfps = {}\nframes = {}\nsubsteps = {}\ncfl = {}\n\n", num(s.time.fps),
                     s.time.frames, s.time.substeps, num(s.time.cfl));
  const MaterialConfig& m = s.material;
  out += fmt::format(
      "[material]\ndensity = {}\nmu = {}\nphi_max = {}\nviscosity = {}\ncohesion = {}\n"
      "cohesion_decay = {}\n",
      num(m.density), num(m.mu), num(m.phi_max), num(m.viscosity), num(m.cohesion),
      num(m.cohesion_decay));
  if (m.mu_i)
    out += fmt::format("mu_i = {{ delta_mu = {}, I0 = {}, grain_diameter = {} }}\n",
                       num(m.mu_i->delta_mu), num(m.mu_i->I0), num(m.mu_i->grain_diameter));
  out += fmt::format("\n[solver]\ntolerance = {}\nmax_iterations = {}\nanderson = {}\n\n[boundary]\n",
                     num(s.solver.tolerance), s.solver.max_iterations, s.solver.anderson);
  for (int f = 0; f < 2 * d; ++f)
    out += fmt::format("{} = \"{}\"\n", faces[f], boundary_name(s.boundary.faces[f]));
  for (const Opening& o : s.boundary.openings)
    out += fmt::format("\n[[boundary.opening]]\nface = \"{}\"\nmin = {}\nmax = {}\n", faces[o.face],
                       vecf(o.min, d), vecf(o.max, d));
  for (const SandConfig& c : s.sand) {
    out += "\n[[sand]]\n";
    if (c.shape == SandShape::Box) {
      out += fmt::format("shape = \"box\"\nmin = {}\nmax = {}\n", vecf(c.min, d), vecf(c.max, d));
    } else {
      out += fmt::format("shape = \"{}\"\ncenter = {}\nradius = {}\n", d == 2 ? "disk" : "cylinder",
                         vecf(c.center, d), num(c.radius));
      if (d == 3) out += fmt::format("height = {}\n", num(c.height));
    }
    out += fmt::format("particles_per_cell = {}\njitter = {}\nvelocity = {}\n",
                       c.particles_per_cell, num(c.jitter), vecf(c.velocity, d));
  }
  return out;
}

}  // namespace sablier
