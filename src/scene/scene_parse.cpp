// Scene files (docs/scenes.md): parsing, --set overrides, validation and the
// resolved scene written back as TOML.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "scene/scene.hpp"
#include "scene/scene_reader.hpp"

namespace sablier {
namespace {

const std::vector<std::string> kFaces{"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
const std::vector<std::string> kBoundaryTypes{"stick", "slip", "free"};

Range positive() { return Range{0.0, Range().hi, true, false}; }
Range non_negative() { return Range{0.0, Range().hi, false, false}; }
Range closed(double lo, double hi) { return Range{lo, hi, false, false}; }

BoundaryType boundary_type(const std::string& s) {
  return s == "stick" ? BoundaryType::Stick : s == "slip" ? BoundaryType::Slip : BoundaryType::Free;
}

std::vector<std::string> faces_for(int dim) {
  return std::vector<std::string>(kFaces.begin(), kFaces.begin() + 2 * dim);
}

void read_grid(TableReader& root, SceneConfig& s) {
  TableReader g = root.sub(root.table("grid"), "grid");
  if (!root.has("grid")) root.fail("grid", "missing; the [grid] table is required");
  const int d = s.dimension;
  s.size = g.vector("size", d, std::nullopt, positive());
  const Vec3d res = g.vector("resolution", d, std::nullopt, closed(1, 1e5));
  for (int a = 0; a < d; ++a) {
    if (res[a] != std::floor(res[a]))
      g.fail_at(g.node("resolution"), "resolution", "expected whole numbers of cells per axis");
    s.resolution[a] = static_cast<int>(res[a]);
  }
  for (int a = d; a < 3; ++a) s.size[a] = 0.0, s.resolution[a] = 1;
  const double h = s.size[0] / s.resolution[0];
  for (int a = 1; a < d; ++a)
    if (std::abs(s.size[a] / s.resolution[a] - h) > 1e-9 * h)
      g.fail_at(g.node("resolution"), "resolution",
                fmt::format("cells must be cubic: size/resolution is {} on x but {} on axis {}", h,
                            s.size[a] / s.resolution[a], a));
  g.reject_unknown({"size", "resolution"});
}

void read_time(TableReader& root, SceneConfig& s) {
  TableReader t = root.sub(root.table("time"), "time");
  s.time.fps = t.number("fps", 30.0, positive());
  s.time.frames = static_cast<int>(t.integer("frames", 30, closed(0, 1e7)));
  s.time.substeps = static_cast<int>(t.integer("substeps", 0, closed(0, 1e6)));
  s.time.cfl = t.number("cfl", 1.0, Range{0.0, 4.0, true, false});
  t.reject_unknown({});
}

void read_material(TableReader& root, SceneConfig& s) {
  TableReader m = root.sub(root.table("material"), "material");
  MaterialConfig& mat = s.material;
  mat.density = m.number("density", 2500.0, positive());
  mat.mu = m.number("mu", 0.5, closed(0, 5));
  mat.phi_max = m.number("phi_max", 0.6, Range{0.0, 1.0, true, false});
  mat.viscosity = m.number("viscosity", 0.0, non_negative());
  mat.cohesion = m.number("cohesion", 0.0, non_negative());
  mat.cohesion_decay = m.number("cohesion_decay", 0.0, non_negative());
  if (mat.cohesion > 0.0 && mat.mu <= 0.0)
    m.fail_at(m.node("cohesion"), "cohesion",
              "cohesion needs friction (the cone's apex is at -cohesion/mu); allowed: mu > 0");
  mat.mu_i.reset();
  if (m.has("mu_i")) {
    TableReader mi = root.sub(m.table("mu_i"), "material.mu_i");
    MuIConfig c;
    c.delta_mu = mi.number("delta_mu", std::nullopt, closed(0, 5));
    c.I0 = mi.number("I0", std::nullopt, positive());
    c.grain_diameter = mi.number("grain_diameter", std::nullopt, positive());
    mi.reject_unknown({});
    mat.mu_i = c;
  }
  m.reject_unknown({});
}

void read_solver(TableReader& root, SceneConfig& s) {
  TableReader t = root.sub(root.table("solver"), "solver");
  s.solver.tolerance = t.number("tolerance", 1e-5, Range{0.0, 1.0, true, true});
  s.solver.max_iterations = static_cast<int>(t.integer("max_iterations", 2000, closed(1, 1e7)));
  t.reject_unknown({});
}

void read_boundary(TableReader& root, SceneConfig& s) {
  TableReader b = root.sub(root.table("boundary"), "boundary");
  const std::vector<std::string> faces = faces_for(s.dimension);
  const BoundaryType def = boundary_type(b.choice("default", "slip", kBoundaryTypes));
  s.boundary.faces.fill(def);
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (b.has(faces[f])) s.boundary.faces[f] = boundary_type(b.choice(faces[f], {}, kBoundaryTypes));
  s.boundary.openings.clear();
  if (const toml::array* list = b.array_of_tables("opening")) {
    for (std::size_t k = 0; k < list->size(); ++k) {
      TableReader o = root.sub(list->get(k)->as_table(), fmt::format("boundary.opening[{}]", k));
      Opening op;
      op.face = static_cast<int>(
          std::find(faces.begin(), faces.end(), o.choice("face", std::nullopt, faces)) -
          faces.begin());
      op.min = o.vector("min", s.dimension, std::nullopt, Range());
      op.max = o.vector("max", s.dimension, std::nullopt, Range());
      const int normal = op.face / 2;
      for (int a = 0; a < s.dimension; ++a) {
        if (a == normal) continue;
        if (op.min[a] > op.max[a])
          o.fail_at(o.node("max"), "max", fmt::format("component {} is below min; allowed: min <= max", a));
        if (op.min[a] < 0.0 || op.max[a] > s.size[a])
          o.fail_at(o.node("min"), "min", fmt::format("the opening leaves the face on axis {}; allowed: 0 <= min <= max <= {}", a, s.size[a]));
      }
      o.reject_unknown({});
      s.boundary.openings.push_back(op);
    }
  }
  b.reject_unknown(faces);
}

void check_inside(TableReader& t, const SceneConfig& s, const std::string& key, double lo,
                  double hi, int axis) {
  const double eps = 1e-12 * s.size[axis];
  if (lo < -eps || hi > s.size[axis] + eps)
    t.fail_at(t.node(key), key,
              fmt::format("the sand region [{}, {}] on axis {} leaves the box; allowed: within "
                          "[0, {}]",
                          lo, hi, axis, s.size[axis]));
}

SandConfig read_sand(TableReader& t, const SceneConfig& s) {
  const int d = s.dimension;
  SandConfig c;
  const std::string shape =
      t.choice("shape", std::nullopt, d == 2 ? std::vector<std::string>{"box", "disk"}
                                             : std::vector<std::string>{"box", "cylinder"});
  c.particles_per_cell = static_cast<int>(t.integer("particles_per_cell", 2, closed(1, 8)));
  c.jitter = t.number("jitter", 0.0, closed(0, 1));
  c.velocity = t.vector("velocity", d, Vec3d{0, 0, 0}, Range());
  if (shape == "box") {
    c.shape = SandShape::Box;
    c.min = t.vector("min", d, std::nullopt, Range());
    c.max = t.vector("max", d, std::nullopt, Range());
    for (int a = 0; a < d; ++a) {
      if (!(c.min[a] < c.max[a]))
        t.fail_at(t.node("max"), "max", fmt::format("empty box on axis {}; allowed: min < max", a));
      check_inside(t, s, "min", c.min[a], c.max[a], a);
    }
    t.reject_unknown({});
    return c;
  }
  c.shape = SandShape::Cylinder;
  c.center = t.vector("center", d, std::nullopt, Range());
  c.radius = t.number("radius", std::nullopt, positive());
  if (d == 3) c.height = t.number("height", std::nullopt, positive());
  for (int a = 0; a < 2; ++a) check_inside(t, s, "center", c.center[a] - c.radius, c.center[a] + c.radius, a);
  if (d == 3) check_inside(t, s, "height", c.center[2], c.center[2] + c.height, 2);
  t.reject_unknown({});
  return c;
}

SceneConfig read_scene(const toml::table& doc, const std::string& file,
                       const TableReader::Origins& origins) {
  SceneConfig s;
  s.source = file;
  TableReader root(&doc, "", file, &origins);
  s.dimension = static_cast<int>(root.integer("dimension", std::nullopt, closed(2, 3)));
  const long seed = root.integer("seed", 0, closed(0, 9.2e18));
  s.seed = static_cast<std::uint64_t>(seed);
  const Vec3d g_default = s.dimension == 2 ? Vec3d{0, -9.81, 0} : Vec3d{0, 0, -9.81};
  s.gravity = root.vector("gravity", s.dimension, g_default, Range());
  read_grid(root, s);
  read_time(root, s);
  read_material(root, s);
  read_solver(root, s);
  read_boundary(root, s);
  const toml::array* sand = root.array_of_tables("sand");
  if (!sand || sand->empty()) root.fail("sand", "missing; at least one [[sand]] block is required");
  for (std::size_t k = 0; k < sand->size(); ++k) {
    TableReader t = root.sub(sand->get(k)->as_table(), fmt::format("sand[{}]", k));
    s.sand.push_back(read_sand(t, s));
  }
  root.reject_unknown({});
  return s;
}

// --set dotted.path=value: the value is TOML (a bare word is a string).
void apply_override(toml::table& doc, const std::string& text, TableReader::Origins& origins) {
  const std::string origin = "--set " + text;
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError(origin + ": expected KEY=VALUE, e.g. --set material.mu=0.3");
  const std::string path = text.substr(0, eq), value = text.substr(eq + 1);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value, origin);
  } catch (const toml::parse_error&) {
    const bool word = !value.empty() && value.find_first_of(" \t\"'[]{}=#,") == std::string::npos;
    if (!word) throw SceneError(origin + ": \"" + value + "\" is not a TOML value");
    parsed = toml::parse("v = \"" + value + "\"", origin);
  }
  std::vector<std::string> keys;
  std::stringstream ss(path);
  for (std::string k; std::getline(ss, k, '.');) {
    if (k.empty()) throw SceneError(origin + ": empty key in \"" + path + "\"");
    keys.push_back(k);
  }
  toml::node* cur = &doc;
  std::string dotted;  // the key as messages name it: sand[0].jitter
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    dotted += cur->is_array() ? "[" + keys[i] + "]" : (dotted.empty() ? "" : ".") + keys[i];
    if (toml::array* arr = cur->as_array()) {
      char* end = nullptr;
      const unsigned long idx = std::strtoul(keys[i].c_str(), &end, 10);
      if (*end != '\0' || idx >= arr->size())
        throw SceneError(fmt::format("{}: \"{}\" is not an index of the {} blocks", origin,
                                     keys[i], keys[i ? i - 1 : 0]));
      cur = arr->get(idx);
    } else if (toml::table* t = cur->as_table()) {
      if (!t->contains(keys[i])) t->insert(keys[i], toml::table{});
      cur = t->get(keys[i]);
    } else {
      throw SceneError(origin + ": \"" + keys[i - 1] + "\" is not a table");
    }
  }
  toml::table* target = cur->as_table();
  if (!target) throw SceneError(origin + ": \"" + path + "\" does not name a table's key");
  target->insert_or_assign(keys.back(), *parsed.get("v"));
  origins[(dotted.empty() ? "" : dotted + ".") + keys.back()] = origin;
}

}  // namespace

SceneConfig parse_scene(const std::string& text, const std::string& source,
                        const std::vector<std::string>& overrides) {
  toml::table doc;
  try {
    doc = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw SceneError(fmt::format("{}:{}: TOML syntax error: {}", source, e.source().begin.line,
                                 e.description()));
  }
  TableReader::Origins origins;
  for (const std::string& o : overrides) apply_override(doc, o, origins);
  return read_scene(doc, source, origins);
}

SceneConfig load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), path, overrides);
}

}  // namespace sablier
