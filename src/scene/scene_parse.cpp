// Scene files (docs/scenes.md): parsing, --set overrides and validation.
// Every key's default is the member initialiser in scene.hpp; the ranges are
// in the field tables below, which also give known_scene_keys().
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include "scene/memory_estimate.hpp"
#include "scene/scene.hpp"
#include "scene/scene_obstacles.hpp"
#include "scene/scene_reader.hpp"
#include "scene/scene_sources.hpp"

namespace sablier {
namespace {

using Origins = TableReader::Origins;
using Names = std::vector<std::string>;

const Names kFaces{"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
const Names kBoundaryTypes{"stick", "slip", "free"};
const Names kDecompactions{"move", "push", "clamp", "project"};
const Names kShapes2D{"box", "disk", "polygon"};
const Names kShapes3D{"box", "cylinder", "sphere", "mesh"};
constexpr double kInf = std::numeric_limits<double>::infinity();

Range positive() { return Range{0.0, kInf, true, false}; }
Range non_negative() { return Range{0.0, kInf, false, false}; }
Range closed(double lo, double hi) { return Range{lo, hi, false, false}; }
Range open_closed(double lo, double hi) { return Range{lo, hi, true, false}; }
Range open(double lo, double hi) { return Range{lo, hi, true, true}; }

// A scalar key of the struct S: a double or an int member, with its range.
template <class S>
struct Field {
  const char* key;
  double S::*real;
  int S::*whole;
  Range range;
};
template <class S>
Field<S> real(const char* key, double S::*member, Range range) {
  return {key, member, nullptr, range};
}
template <class S>
Field<S> whole(const char* key, int S::*member, Range range) {
  return {key, nullptr, member, range};
}

const std::vector<Field<TimeConfig>> kTimeFields{
    real("fps", &TimeConfig::fps, positive()),
    whole("frames", &TimeConfig::frames, non_negative()),
    whole("substeps", &TimeConfig::substeps, non_negative()),
    real("cfl", &TimeConfig::cfl, open_closed(0, 4)),
};
const std::vector<Field<MaterialConfig>> kMaterialFields{
    real("density", &MaterialConfig::density, positive()),
    real("mu", &MaterialConfig::mu, closed(0, 5)),
    real("phi_max", &MaterialConfig::phi_max, open_closed(0, 1)),
    real("viscosity", &MaterialConfig::viscosity, non_negative()),
    real("cohesion", &MaterialConfig::cohesion, non_negative()),
    real("cohesion_decay", &MaterialConfig::cohesion_decay, non_negative()),
};
const std::vector<Field<MuIConfig>> kMuIFields{
    real("delta_mu", &MuIConfig::delta_mu, non_negative()),
    real("I0", &MuIConfig::I0, positive()),
    real("grain_diameter", &MuIConfig::grain_diameter, positive()),
};
// The [material] keys a [[sand]] block may override (SandMaterial); their
// ranges are those of kMaterialFields.
struct BlockField {
  const char* key;
  std::optional<double> SandMaterial::*member;
};
const std::vector<BlockField> kSandMaterialFields{
    {"density", &SandMaterial::density},
    {"mu", &SandMaterial::mu},
    {"cohesion", &SandMaterial::cohesion},
    {"cohesion_decay", &SandMaterial::cohesion_decay},
};
const std::vector<Field<SolverConfig>> kSolverFields{
    real("tolerance", &SolverConfig::tolerance, open(0, 1)),
    whole("max_iterations", &SolverConfig::max_iterations, closed(1, kInf)),
    whole("anderson", &SolverConfig::anderson, closed(0, 16)),
    real("relaxation", &SolverConfig::relaxation, open_closed(0, 1)),
    whole("zone_rows", &SolverConfig::zone_rows, closed(0, kInf)),
    whole("decompaction_moves", &SolverConfig::decompaction_moves, closed(1, 16)),
    real("stabilization", &SolverConfig::stabilization, closed(0, 1000)),
};
const std::vector<Field<SandConfig>> kSandFields{
    whole("particles_per_cell", &SandConfig::particles_per_cell, closed(1, 8)),
    real("jitter", &SandConfig::jitter, closed(0, 1)),
};

// Reads the fields into `s`; absent keys keep the value already in `s` (the
// default), unless `required`.
template <class S>
void read_fields(TableReader& t, S& s, const std::vector<Field<S>>& fields, bool required) {
  for (const Field<S>& f : fields) {
    if (f.real) {
      const std::optional<double> fallback = required ? std::nullopt : std::optional(s.*f.real);
      s.*f.real = t.number(f.key, fallback, f.range);
    } else {
      const std::optional<int> fallback = required ? std::nullopt : std::optional(s.*f.whole);
      s.*f.whole = t.int_value(f.key, fallback, f.range);
    }
  }
}

// A table of scalar keys only.
template <class S>
void read_table(TableReader t, S& s, const std::vector<Field<S>>& fields) {
  read_fields(t, s, fields, false);
  t.reject_unknown();
}

template <class S>
void add_keys(Names& keys, const std::string& prefix, const std::vector<Field<S>>& fields) {
  for (const Field<S>& f : fields) keys.push_back(prefix + f.key);
}

void read_solver(TableReader t, SolverConfig& s) {
  const std::string rule = t.choice("decompaction", "project", kDecompactions);
  s.decompaction = rule == "push"      ? Decompaction::Push
                   : rule == "clamp"   ? Decompaction::Clamp
                   : rule == "project" ? Decompaction::Project
                                       : Decompaction::Move;
  read_table(std::move(t), s, kSolverFields);
}

BoundaryType boundary_type(const std::string& s) {
  return s == "stick" ? BoundaryType::Stick : s == "slip" ? BoundaryType::Slip : BoundaryType::Free;
}

char axis_name(int a) { return "xyz"[a]; }

void read_grid(TableReader g, SceneConfig& s) {
  const int d = s.dimension;
  s.size = g.vector("size", d, std::nullopt, positive());
  s.resolution = g.integers("resolution", d, std::nullopt, closed(1, 1e5));
  for (int a = d; a < 3; ++a) s.size[a] = 0.0, s.resolution[a] = 1;
  const double h = s.size[0] / s.resolution[0];
  for (int a = 1; a < d; ++a) {
    const double ha = s.size[a] / s.resolution[a];
    if (std::abs(ha - h) > 1e-9 * h)
      g.fail_at(g.node("resolution"), "resolution",
                fmt::format("cells are not cubic: grid.size / grid.resolution is {} on x but {} "
                            "on {}; allowed: grid.size / grid.resolution equal on every axis",
                            h, ha, axis_name(a)),
                {"grid.size"});
  }
  // The grid alone must fit before obstacles' distances are sampled over it
  // and grains seeded on it (check_regions_seed seeds every block).
  if (const std::string what = memory_shortfall(s, 0.0, ""); !what.empty())
    g.fail_at(g.node("resolution"), "resolution", what);
  g.reject_unknown();
}

// The mu_i table of [material] or of a [[sand]] block: all three keys.
std::optional<MuIConfig> read_mu_i(TableReader& t) {
  t.node("mu_i");  // known even when absent: suggested for misspellings
  if (!t.has("mu_i")) return std::nullopt;
  TableReader mi = t.child("mu_i");
  MuIConfig c;
  read_fields(mi, c, kMuIFields, true);
  mi.reject_unknown();
  return c;
}

// `mu`: the dotted keys the friction came from.
void fail_cohesion_without_friction(TableReader& t, double cohesion, const Names& mu) {
  t.fail_at(t.node("cohesion"), "cohesion",
            fmt::format("{} needs friction (the yield cone's apex is at -cohesion/mu); "
                        "allowed: cohesion = 0 when mu = 0",
                        cohesion),
            mu);
}

void read_material(TableReader m, SceneConfig& s) {
  MaterialConfig& mat = s.material;
  read_fields(m, mat, kMaterialFields, false);
  if (mat.cohesion > 0.0 && mat.mu <= 0.0)
    fail_cohesion_without_friction(m, mat.cohesion, {m.full("mu")});
  mat.mu_i = read_mu_i(m);
  m.reject_unknown();
}

Range material_range(const char* key) {
  for (const Field<MaterialConfig>& f : kMaterialFields)
    if (std::strcmp(f.key, key) == 0) return f.range;
  throw std::logic_error(std::string("no [material] key ") + key);
}

// A block's overrides of [material], checked like [material]'s own keys;
// cohesion needs friction here too, whichever of the two the block sets.
// [material] is read before [[sand]] (read_scene), so the inherited values
// are known.
SandMaterial read_sand_material(TableReader& t, const SceneConfig& s) {
  reject_keys(t, {"phi_max", "viscosity"},
              "scene-wide, not per block (docs/scenes.md); allowed: in [material]");
  SandMaterial sm;
  for (const BlockField& f : kSandMaterialFields) {
    t.node(f.key);  // known even when absent: suggested for misspellings
    if (t.has(f.key)) sm.*f.member = t.number(f.key, std::nullopt, material_range(f.key));
  }
  sm.mu_i = read_mu_i(t);
  const double cohesion = sm.cohesion.value_or(s.material.cohesion);
  const double mu = sm.mu.value_or(s.material.mu);
  if (cohesion > 0.0 && mu <= 0.0) {
    if (sm.cohesion) fail_cohesion_without_friction(t, cohesion, {t.full("mu"), "material.mu"});
    t.fail_at(t.node("mu"), "mu",
              fmt::format("{} leaves no friction for the cohesion {} of [material] (the yield "
                          "cone's apex is at -cohesion/mu); allowed: mu > 0, or cohesion = 0 in "
                          "this block",
                          mu, cohesion),
              {"material.cohesion"});
  }
  return sm;
}

// The opening's tangential extent must lie on its face.
void check_opening(TableReader& o, const Opening& op, const SceneConfig& s) {
  const Names with{o.full("min"), o.full("max"), o.full("face"), "grid.size"};
  for (int a = 0; a < s.dimension; ++a) {
    if (a == op.face / 2) continue;
    if (op.min[a] > op.max[a])
      o.fail_at(o.node("max"), "max",
                fmt::format("{} on {} is below min = {}; allowed: min <= max", op.max[a],
                            axis_name(a), op.min[a]),
                with);
    if (op.min[a] < 0.0 || op.max[a] > s.size[a])
      o.fail_at(o.node(op.min[a] < 0.0 ? "min" : "max"), op.min[a] < 0.0 ? "min" : "max",
                fmt::format("[{}, {}] on {} leaves the face; allowed: within [0, {}]", op.min[a],
                            op.max[a], axis_name(a), s.size[a]),
                with);
  }
}

Opening read_opening(TableReader o, const SceneConfig& s) {
  const int d = s.dimension;
  const Names here(kFaces.begin(), kFaces.begin() + 2 * d);
  const Names elsewhere(kFaces.begin() + 2 * d, kFaces.end());
  Opening op;
  const std::string face = dimension_choice(o, "face", here, elsewhere, d);
  op.face = static_cast<int>(std::find(kFaces.begin(), kFaces.end(), face) - kFaces.begin());
  op.min = o.vector("min", d, std::nullopt, Range());
  op.max = o.vector("max", d, std::nullopt, Range());
  check_opening(o, op, s);
  o.reject_unknown();
  return op;
}

void read_boundary(TableReader b, SceneConfig& s) {
  const int d = s.dimension;
  const Names faces(kFaces.begin(), kFaces.begin() + 2 * d);
  if (d == 2)
    reject_keys(b, {"zmin", "zmax"},
                "only valid in 3D scenes; allowed in 2D: xmin, xmax, ymin, ymax", {"dimension"});
  const std::string fallback = b.choice("default", "slip", kBoundaryTypes);
  // In 2D, zmin and zmax keep the struct's value: the scene has no such faces.
  for (std::size_t f = 0; f < faces.size(); ++f)
    s.boundary.faces[f] = boundary_type(b.choice(faces[f], fallback, kBoundaryTypes));
  s.boundary.openings.clear();
  if (const toml::array* list = b.array_of_tables("opening"))
    b.for_each_table(*list, "boundary.opening", [&](TableReader t) {
      s.boundary.openings.push_back(read_opening(std::move(t), s));
    });
  b.reject_unknown();
}

void read_box(TableReader& t, SandConfig& c, const SceneConfig& s) {
  const int d = s.dimension;
  reject_keys(t, {"center", "radius", "height"}, "not used by shape \"box\"; allowed: min, max",
              {t.full("shape")});
  const Names with{t.full("min"), t.full("max")};
  c.shape = SandShape::Box;
  c.min = t.vector("min", d, std::nullopt, Range());
  c.max = t.vector("max", d, std::nullopt, Range());
  for (int a = 0; a < d; ++a) {
    if (!(c.min[a] < c.max[a]))
      t.fail_at(t.node("max"), "max",
                fmt::format("empty box: max = {} on {} is not above min = {}; allowed: min < max",
                            c.max[a], axis_name(a), c.min[a]),
                with);
    check_inside(t, s, c.min[a] < 0.0 ? "min" : "max", c.min[a], c.max[a], a, with);
  }
}

// A disk (2D) or a cylinder along z standing on its base centre (3D).
void read_round(TableReader& t, SandConfig& c, const SceneConfig& s) {
  const int d = s.dimension;
  reject_keys(t, {"min", "max"},
              d == 2 ? "not used by shape \"disk\"; allowed: center, radius"
                     : "not used by shape \"cylinder\"; allowed: center, radius, height",
              {t.full("shape")});
  if (d == 2)
    reject_keys(t, {"height"}, "only used by 3D cylinders; allowed: center, radius", {"dimension"});
  const Names with{t.full("center"), t.full("radius"), t.full("height")};
  c.shape = SandShape::Cylinder;
  c.center = t.vector("center", d, std::nullopt, Range());
  c.radius = t.number("radius", std::nullopt, positive());
  if (d == 3) c.height = t.number("height", std::nullopt, positive());
  for (int a = 0; a < 2; ++a)
    check_inside(t, s, "center", c.center[a] - c.radius, c.center[a] + c.radius, a, with);
  if (d == 3)
    check_inside(t, s, c.center[2] < 0.0 ? "center" : "height", c.center[2], c.center[2] + c.height,
                 2, with);
}

SandConfig read_sand(TableReader t, const SceneConfig& s) {
  const int d = s.dimension;
  SandConfig c;
  c.particles_per_cell = default_particles_per_cell(d);
  const std::string shape =
      dimension_choice(t, "shape", d == 2 ? kShapes2D : kShapes3D, shapes_of_other_dimension(d), d);
  reject_other_shape_keys(t, shape);
  if (shape == "box") {
    read_box(t, c, s);
  } else if (shape == "disk" || shape == "cylinder") {
    read_round(t, c, s);
  } else {
    read_source_shape(t, shape, c, s);  // scene_sources.cpp
  }
  read_fields(t, c, kSandFields, false);
  c.velocity = t.vector("velocity", d, c.velocity, Range());
  c.material = read_sand_material(t, s);
  t.reject_unknown();
  return c;
}

void read_all_sand(TableReader& root, SceneConfig& s) {
  const toml::array* list = root.array_of_tables("sand");
  const std::string required = "at least one [[sand]] block (or a [[spout]])";
  if ((!list || list->empty()) && !s.spouts.empty()) return;  // all sand poured in
  if (!list) root.fail_missing("sand", required);
  if (list->empty()) root.fail_at(root.node("sand"), "sand", "empty; required: " + required);
  root.for_each_table(*list, "sand",
                      [&](TableReader t) { s.sand.push_back(read_sand(std::move(t), s)); });
}

SceneConfig read_scene(const toml::table& doc, const std::string& file, const Origins& origins) {
  SceneConfig s;
  s.source = file;
  TableReader root(&doc, "", file, &origins);
  const int d = root.int_value("dimension", std::nullopt, closed(2, 3));
  s.dimension = d;
  s.seed = static_cast<std::uint64_t>(root.integer("seed", 0, non_negative()));
  s.gravity = root.vector("gravity", d, d == 2 ? Vec3d{0, -9.81, 0} : Vec3d{0, 0, -9.81}, Range());
  read_grid(root.child("grid"), s);
  read_table(root.child("time"), s.time, kTimeFields);
  read_material(root.child("material"), s);
  read_solver(root.child("solver"), s.solver);
  read_boundary(root.child("boundary"), s);
  read_all_obstacles(root, s);  // before [[sand]]: seeding skips their insides
  read_all_spouts(root, s);
  read_all_sand(root, s);
  double grains = double(grains_by_end(s, 0));
  for (const SandConfig& b : s.sand) grains += block_grains(s, b);
  if (const std::string what = memory_shortfall(s, grains, "about "); !what.empty())
    root.fail_at(root.node("sand"), "sand", what);
  check_regions_seed(root, s);
  root.reject_unknown();
  return s;
}

// --- --set overrides: "dotted.path=value", the value TOML or a bare word ---

[[noreturn]] void bad_override(const std::string& text, const std::string& what) {
  throw SceneError(fmt::format(
      "--set {}: {}; allowed: KEY=VALUE with a dotted KEY and a TOML VALUE or a bare word, e.g. "
      "material.mu=0.3, grid.resolution=[80,40], boundary.xmin=stick, sand.0.jitter=0.1",
      text, what));
}

Names split_key(const std::string& text, const std::string& key) {
  Names keys;
  std::stringstream ss(key + ".");
  for (std::string k; std::getline(ss, k, '.');) {
    if (k.empty()) bad_override(text, fmt::format("empty name in the key \"{}\"", key));
    keys.push_back(k);
  }
  return keys;
}

bool bare_word(const std::string& v) {
  return !v.empty() && std::all_of(v.begin(), v.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-' || c == '.' || c == '+';
  });
}

bool parses(const std::string& toml_text) {
  try {
    static_cast<void>(toml::parse(toml_text));  // only whether it parses
    return true;
  } catch (const toml::parse_error&) {
    return false;
  }
}

// The value as a one-key TOML table {v = value}.
toml::table parse_value(const std::string& text, const std::string& value) {
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value, std::string_view("--set"));
  } catch (const toml::parse_error&) {
    if (bare_word(value)) {
      parsed.insert("v", value);
    } else if (value.empty() || std::strchr("[{\"'", value[0]) ||
               !parses("v = \"" + value + "\"")) {
      bad_override(text, fmt::format("\"{}\" is not a TOML value", value));
    } else {  // a file name, words: only bare words go unquoted
      const std::string key = text.substr(0, text.find('='));
      bad_override(text, fmt::format("\"{0}\" is not a TOML value (a string other than a bare "
                                     "word needs quotes: --set '{1}=\"{0}\"')",
                                     value, key));
    }
  }
  if (parsed.size() != 1) bad_override(text, fmt::format("\"{}\" is not one value", value));
  return parsed;
}

bool is_index(const std::string& name) {
  return !name.empty() && name.size() < 9 &&
         std::all_of(name.begin(), name.end(), [](unsigned char c) { return std::isdigit(c); });
}

// Steps from `cur` into its entry `name` (a key, or an index into [[blocks]]),
// creating missing tables (not blocks: `next` is the name after this one);
// `dotted` is the path so far, as messages name it.
toml::node* step_into(toml::node* cur, const std::string& name, const std::string& next,
                      std::string& dotted, const std::string& text, Origins& origins) {
  if (toml::array* blocks = cur->as_array()) {
    const std::size_t k = is_index(name) ? std::stoul(name) : blocks->size();
    if (k >= blocks->size())
      bad_override(text, fmt::format("\"{}\" is not an index of the {} [[{}]] blocks", name,
                                     blocks->size(), dotted));
    dotted += "[" + name + "]";
    return blocks->get(k);
  }
  toml::table& t = *cur->as_table();
  dotted += (dotted.empty() ? "" : ".") + name;
  if (!t.contains(name)) {
    if (is_index(next))
      bad_override(text, fmt::format("the scene has no [[{}]] blocks; --set changes blocks but "
                                     "cannot add them",
                                     dotted));
    t.insert(name, toml::table{});
    origins[dotted] = {text, true};
  }
  return t.get(name);
}

void apply_override(toml::table& doc, const std::string& text, Origins& origins) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) bad_override(text, "no '='");
  if (eq == 0) bad_override(text, "empty key");
  const Names keys = split_key(text, text.substr(0, eq));
  toml::table value = parse_value(text, text.substr(eq + 1));
  toml::node* cur = &doc;
  std::string dotted;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    cur = step_into(cur, keys[i], keys[i + 1], dotted, text, origins);
    if (!cur->is_table() && !cur->is_array_of_tables())
      bad_override(text, fmt::format("{} is a value, not a table", dotted));
  }
  if (!cur->is_table() && is_index(keys.back()))
    bad_override(text, fmt::format("a whole [[{0}]] block cannot be set; set its keys one by one, "
                                   "e.g. --set {0}.{1}.KEY=VALUE",
                                   dotted, keys.back()));
  if (!cur->is_table())
    bad_override(text, fmt::format("{} holds [[blocks]]: give an index, e.g. {}.0.{}", dotted,
                                   dotted, keys.back()));
  cur->as_table()->insert_or_assign(keys.back(), std::move(*value.get("v")));
  origins[(dotted.empty() ? "" : dotted + ".") + keys.back()] = {text, false};
}

}  // namespace

std::vector<std::string> known_scene_keys() {
  Names keys{"dimension", "seed", "gravity", "grid.size", "grid.resolution"};
  add_keys(keys, "time.", kTimeFields);
  add_keys(keys, "material.", kMaterialFields);
  add_keys(keys, "material.mu_i.", kMuIFields);
  add_keys(keys, "solver.", kSolverFields);
  keys.push_back("solver.decompaction");
  keys.push_back("boundary.default");
  for (const std::string& f : kFaces) keys.push_back("boundary." + f);
  for (const char* k : {"face", "min", "max"})
    keys.push_back(std::string("boundary.opening[].") + k);
  for (const char* k : {"shape", "min", "max", "center", "radius", "height", "velocity"})
    keys.push_back(std::string("sand[].") + k);
  add_keys(keys, "sand[].", kSandFields);
  for (const std::string& k : source_scene_keys()) keys.push_back(k);
  for (const BlockField& f : kSandMaterialFields) keys.push_back(std::string("sand[].") + f.key);
  add_keys(keys, "sand[].mu_i.", kMuIFields);
  for (const std::string& k : obstacle_scene_keys()) keys.push_back(k);
  return keys;
}

MaterialConfig sand_material(const SceneConfig& scene, std::size_t block) {
  MaterialConfig m = scene.material;
  const SandMaterial& o = scene.sand.at(block).material;
  m.density = o.density.value_or(m.density);
  m.mu = o.mu.value_or(m.mu);
  m.cohesion = o.cohesion.value_or(m.cohesion);
  m.cohesion_decay = o.cohesion_decay.value_or(m.cohesion_decay);
  if (o.mu_i) m.mu_i = o.mu_i;
  return m;
}

SceneConfig parse_scene(const std::string& text, const std::string& source,
                        const std::vector<std::string>& overrides) {
  toml::table doc;
  try {
    doc = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw SceneError(fmt::format("{}:{}: TOML syntax error: {}; allowed: TOML 1.0 (toml.io)",
                                 source, e.source().begin.line, e.description()));
  }
  Origins origins;
  for (const std::string& o : overrides) apply_override(doc, o, origins);
  return read_scene(doc, source, origins);
}

SceneConfig load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError(path + ": is a directory; expected a scene file (.toml)");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw SceneError(
        fmt::format("{}: cannot open the scene file ({})", path, std::strerror(errno)));
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), path, overrides);
}

}  // namespace sablier
