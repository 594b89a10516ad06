// The resolved scene as TOML: every key, defaults filled in. Numbers use the
// shortest representation that reads back to the same double.
#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <utility>

#include "scene/scene.hpp"
#include "scene/scene_obstacles.hpp"

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

std::string mu_i_line(const MuIConfig& m) {
  return fmt::format("mu_i = {{ delta_mu = {}, I0 = {}, grain_diameter = {} }}\n", num(m.delta_mu),
                     num(m.I0), num(m.grain_diameter));
}

// Only the keys the block sets: an absent key inherits [material], so
// writing the inherited value would change what a later --set of
// [material] does to this block.
std::string sand_material_lines(const SandMaterial& m) {
  std::string out;
  const std::pair<const char*, const std::optional<double>*> keys[] = {
      {"density", &m.density},
      {"mu", &m.mu},
      {"cohesion", &m.cohesion},
      {"cohesion_decay", &m.cohesion_decay}};
  for (const auto& [key, value] : keys)
    if (*value) out += fmt::format("{} = {}\n", key, num(**value));
  if (m.mu_i) out += mu_i_line(*m.mu_i);
  return out;
}

// A TOML basic string.
std::string quoted(const std::string& text) {
  std::string s = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') s += '\\';
    s += c;
  }
  return s + "\"";
}

// A [[sand]] block's shape and geometric keys. A mesh's file is written as
// the absolute path it was read from: the resolved scene lives in the run's
// folder, not beside the scene file.
std::string shape_lines(const SandConfig& c, int d) {
  switch (c.shape) {
    case SandShape::Box:
      return fmt::format("shape = \"box\"\nmin = {}\nmax = {}\n", vecf(c.min, d), vecf(c.max, d));
    case SandShape::Sphere:
      return fmt::format("shape = \"sphere\"\ncenter = {}\nradius = {}\n", vecf(c.center, d),
                         num(c.radius));
    case SandShape::Polygon: {
      std::string v;
      for (const Vec3d& p : c.vertices) v += (v.empty() ? "" : ", ") + vecf(p, 2);
      return fmt::format("shape = \"polygon\"\nvertices = [{}]\n", v);
    }
    case SandShape::Mesh:
      return fmt::format("shape = \"mesh\"\nfile = {}\nscale = {}\ntranslate = {}\n",
                         quoted(c.file_path), num(c.scale), vecf(c.translate, 3));
    case SandShape::Cylinder:
      break;
  }
  std::string out = fmt::format("shape = \"{}\"\ncenter = {}\nradius = {}\n",
                                d == 2 ? "disk" : "cylinder", vecf(c.center, d), num(c.radius));
  if (d == 3) out += fmt::format("height = {}\n", num(c.height));
  return out;
}

std::string spout_lines(const SpoutConfig& p, int d) {
  std::string out =
      fmt::format("\n[[spout]]\ncenter = {}\nradius = {}\nvelocity = {}\nstart = {}\n",
                  vecf(p.center, d), num(p.radius), vecf(p.velocity, d), num(p.start));
  // TOML could say inf, but scene values must be finite: never closing is
  // the key's absence.
  out += std::isfinite(p.stop) ? fmt::format("stop = {}\n", num(p.stop)) : "# stop: never\n";
  return out +
         fmt::format("particles_per_cell = {}\njitter = {}\n", p.particles_per_cell, num(p.jitter));
}

// Only the keys of the obstacle's shape (the others are errors).
std::string obstacle_lines(const ObstacleConfig& o, int d) {
  std::string out =
      fmt::format("\n[[obstacle]]\nshape = \"{}\"\n", obstacle_shape_name(o.shape, d));
  switch (o.shape) {
    case ObstacleShape::Plane:
      out += fmt::format("point = {}\nnormal = {}\n", vecf(o.point, d), vecf(o.normal, d));
      break;
    case ObstacleShape::Box:
      out += fmt::format("min = {}\nmax = {}\n", vecf(o.min, d), vecf(o.max, d));
      break;
    case ObstacleShape::Ball:
    case ObstacleShape::Cylinder:
      out += fmt::format("center = {}\nradius = {}\n", vecf(o.center, d), num(o.radius));
      if (o.shape == ObstacleShape::Cylinder) out += fmt::format("height = {}\n", num(o.height));
      break;
    case ObstacleShape::Polygon: {
      std::string v;
      for (const Vec3d& p : o.vertices) v += (v.empty() ? "" : ", ") + vecf(p, 2);
      out += fmt::format("vertices = [{}]\n", v);
      break;
    }
    case ObstacleShape::Mesh:
      out += fmt::format("file = {}\nscale = {}\ntranslate = {}\n", quoted(o.file_path),
                         num(o.scale), vecf(o.translate, 3));
      break;
  }
  out += fmt::format("mu = {}\nvelocity = {}\n", num(o.mu), vecf(o.velocity, d));
  if (o.dynamic()) out += fmt::format("density = {}\n", num(o.density));
  if (o.angle_degrees != 0.0) {
    out += fmt::format("angle = {}\n", num(o.angle_degrees));
    if (d == 3) out += fmt::format("axis = {}\n", vecf(o.axis, 3));
  }
  if (o.spin[0] != 0.0 || o.spin[1] != 0.0 || o.spin[2] != 0.0)
    out += d == 2 ? fmt::format("spin = {}\n", num(o.spin[2]))
                  : fmt::format("spin = {}\n", vecf(o.spin, 3));
  if (std::isfinite(o.until)) out += fmt::format("until = {}\n", num(o.until));
  return out;
}

const char* boundary_name(BoundaryType t) {
  return t == BoundaryType::Stick ? "stick" : t == BoundaryType::Slip ? "slip" : "free";
}

const char* decompaction_name(Decompaction r) {
  switch (r) {
    case Decompaction::Push:
      return "push";
    case Decompaction::Clamp:
      return "clamp";
    case Decompaction::Project:
      return "project";
    default:
      return "move";
  }
}

}  // namespace

std::string scene_to_toml(const SceneConfig& s) {
  const int d = s.dimension;
  const char* faces[] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  std::string out = fmt::format(
      "# Resolved scene (every key, defaults filled in)\ndimension = {}\nseed = {}\ngravity = "
      "{}\n\n",
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
  if (m.mu_i) out += mu_i_line(*m.mu_i);
  out += fmt::format(
      "\n[solver]\ntolerance = {}\nmax_iterations = {}\nanderson = {}\nrelaxation = {}\n"
      "zone_rows = {}\n",
      num(s.solver.tolerance), s.solver.max_iterations, s.solver.anderson, num(s.solver.relaxation),
      s.solver.zone_rows);
  out += fmt::format("decompaction = \"{}\"\ndecompaction_moves = {}\nstabilization = {}\n",
                     decompaction_name(s.solver.decompaction), s.solver.decompaction_moves,
                     num(s.solver.stabilization));
  out += "\n[boundary]\n";
  for (int f = 0; f < 2 * d; ++f)
    out += fmt::format("{} = \"{}\"\n", faces[f], boundary_name(s.boundary.faces[f]));
  for (const Opening& o : s.boundary.openings)
    out += fmt::format("\n[[boundary.opening]]\nface = \"{}\"\nmin = {}\nmax = {}\n", faces[o.face],
                       vecf(o.min, d), vecf(o.max, d));
  for (const SandConfig& c : s.sand) {
    out += "\n[[sand]]\n";
    out += shape_lines(c, d);
    out += fmt::format("particles_per_cell = {}\njitter = {}\nvelocity = {}\n",
                       c.particles_per_cell, num(c.jitter), vecf(c.velocity, d));
    out += sand_material_lines(c.material);
  }
  for (const SpoutConfig& p : s.spouts) out += spout_lines(p, d);
  for (const ObstacleConfig& o : s.obstacles) out += obstacle_lines(o, d);
  return out;
}

}  // namespace sablier
