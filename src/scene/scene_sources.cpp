// Scene parsing of spheres, polygons, triangle meshes and [[spout]] blocks
// (docs/scenes.md), and the check that every source yields particles
// (outside the obstacles).
#include "scene/scene_sources.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <utility>

#include "core/mesh.hpp"
#include "physics/emission.hpp"
#include "physics/seeding.hpp"

namespace sablier {
namespace {

using Names = std::vector<std::string>;
constexpr double kInf = std::numeric_limits<double>::infinity();

Range positive() { return Range{0.0, kInf, true, false}; }
Range non_negative() { return Range{0.0, kInf, false, false}; }
Range closed(double lo, double hi) { return Range{lo, hi, false, false}; }

char axis_name(int a) { return "xyz"[a]; }

// The geometric keys each shape takes.
const std::map<std::string, Names>& shape_keys() {
  static const std::map<std::string, Names> keys{
      {"box", {"min", "max"}},
      {"disk", {"center", "radius"}},
      {"cylinder", {"center", "radius", "height"}},
      {"sphere", {"center", "radius"}},
      {"polygon", {"vertices"}},
      {"mesh", {"file", "scale", "translate"}},
  };
  return keys;
}
const Names kNewKeys{"vertices", "file", "scale", "translate"};
// Every key a [[spout]] block takes: read by read_spout, named by
// source_scene_keys() and listed when a key is unknown.
const Names kSpoutKeys{"center", "radius", "velocity", "start", "stop", "particles_per_cell",
                       "jitter"};
const Names kOldKeys{"min", "max", "center", "radius", "height"};

std::string joined(const Names& words) {
  std::string s;
  for (const std::string& w : words) s += (s.empty() ? "" : ", ") + w;
  return s;
}

void read_sphere(TableReader& t, SandConfig& c, const SceneConfig& s) {
  c.shape = SandShape::Sphere;
  c.center = t.vector("center", 3, std::nullopt, Range());
  c.radius = t.number("radius", std::nullopt, positive());
  for (int a = 0; a < 3; ++a)
    check_inside(t, s, "center", c.center[a] - c.radius, c.center[a] + c.radius, a,
                 {t.full("center"), t.full("radius")});
}

// One corner [x, y] of a polygon.
Vec3d polygon_vertex(TableReader& t, const toml::node& n, std::size_t k) {
  const toml::array* xy = n.as_array();
  Vec3d v{0, 0, 0};
  bool ok = xy && xy->size() == 2;
  for (std::size_t a = 0; ok && a < 2; ++a) {
    const toml::node* x = xy->get(a);
    ok = x->is_number();
    if (ok) v[a] = x->is_integer() ? double(x->as_integer()->get()) : x->as_floating_point()->get();
    ok = ok && std::isfinite(v[a]);
  }
  if (!ok)
    t.fail_at(&n, "vertices",
              fmt::format("vertex {} is not a point [x, y] of finite numbers; allowed: an array of "
                          "at least 3 points [x, y]",
                          k));
  return v;
}

// Twice the signed area (shoelace formula).
double twice_area(const std::vector<Vec3d>& v) {
  double a = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3d &p = v[i], &q = v[(i + 1) % v.size()];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return a;
}

void read_polygon(TableReader& t, SandConfig& c, const SceneConfig& s) {
  c.shape = SandShape::Polygon;
  c.vertices = read_polygon_vertices(t);
  Vec3d lo = c.vertices[0], hi = c.vertices[0];
  for (const Vec3d& v : c.vertices)
    for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], v[a]), hi[a] = std::max(hi[a], v[a]);
  for (int a = 0; a < 2; ++a) check_inside(t, s, "vertices", lo[a], hi[a], a, {});
}

// The mesh file's path: relative paths are relative to the scene file's folder.
std::string mesh_path(const std::string& file, const SceneConfig& s) {
  namespace fs = std::filesystem;
  fs::path p(file);
  if (p.is_relative()) p = fs::path(s.source).parent_path() / p;
  return fs::absolute(p).lexically_normal().string();
}

void read_mesh(TableReader& t, SandConfig& c, const SceneConfig& s) {
  c.shape = SandShape::Mesh;
  MeshKeys m = read_mesh_keys(t, s);
  c.file = std::move(m.file);
  c.file_path = std::move(m.file_path);
  c.scale = m.scale;
  c.translate = m.translate;
  c.mesh = std::move(m.mesh);
  for (int a = 0; a < 3; ++a)
    check_inside(t, s, t.has("translate") ? "translate" : "file", c.mesh->lower()[a],
                 c.mesh->upper()[a], a, {t.full("file"), t.full("scale"), t.full("translate")});
}

double speed_squared(const SpoutConfig& sp) {
  return sp.velocity[0] * sp.velocity[0] + sp.velocity[1] * sp.velocity[1] +
         sp.velocity[2] * sp.velocity[2];
}

// The cross-section (segment or disk perpendicular to the velocity) must
// lie in the box.
void check_spout_inside(TableReader& t, const SpoutConfig& sp, const SceneConfig& s) {
  const double v2 = speed_squared(sp);
  for (int a = 0; a < s.dimension; ++a) {
    const double reach =
        sp.radius * std::sqrt(std::max(0.0, 1.0 - sp.velocity[a] * sp.velocity[a] / v2));
    const bool centre_out = sp.center[a] < 0.0 || sp.center[a] > s.size[a];
    check_inside(t, s, centre_out ? "center" : "radius", sp.center[a] - reach, sp.center[a] + reach,
                 a, {t.full("center"), t.full("radius"), t.full("velocity")},
                 "the spout's cross-section");
  }
}

// A spout must emit at least one particle in the run, and its particle ids
// must stay unique (emission.hpp): fewer than 2^20 points per layer and
// layers.
void check_spout_output(TableReader& t, const SpoutConfig& sp, const SceneConfig& s) {
  const double spacing = s.cell_size() / sp.particles_per_cell;
  const double speed = std::sqrt(speed_squared(sp));
  const Names lattice{"grid", t.full("particles_per_cell")};
  const std::size_t points = spout_layer_size(s.dimension, sp.radius, spacing);
  if (points == 0)
    t.fail_at(t.node("radius"), "radius",
              fmt::format("the cross-section holds no particle at the spacing {} m (the cell "
                          "size / particles_per_cell); allowed: radius > {} m",
                          spacing, s.dimension == 2 ? spacing / 4 : spacing / std::sqrt(2.0)),
              lattice);
  if (points >= std::size_t(kSpoutIdLimit))
    t.fail_at(t.node("radius"), "radius",
              fmt::format("{} particles per layer; allowed: fewer than {} (particle ids)", points,
                          kSpoutIdLimit),
              lattice);
  Names flow = lattice;
  for (const char* k : {"start", "stop", "velocity"}) flow.push_back(t.full(k));
  if (std::isfinite(sp.stop) && spout_layers(sp, spacing, sp.stop) < 1)
    t.fail_at(t.node("stop"), "stop",
              fmt::format("the spout closes before one layer of particles ({} m) has passed, so "
                          "it emits nothing; allowed: stop >= {} s (start + spacing / |velocity|)",
                          spacing, sp.start + spacing / speed),
              flow);
  flow.push_back("time");
  const double end = s.time.frames / s.time.fps;
  if (spout_layers(sp, spacing, end) < 1) {
    const double latest = end - spacing / speed;  // the last start that emits a layer
    t.fail_at(t.node("start"), "start",
              fmt::format("the spout opens at {} s, too late for one layer of particles ({} m) "
                          "to pass before the run ends at {} s (time.frames / time.fps), so it "
                          "emits nothing; allowed: {}",
                          sp.start, spacing, end,
                          latest >= 0.0 ? fmt::format("start <= {} s, or a longer run", latest)
                                        : fmt::format("a run longer than {} s", spacing / speed)),
              flow);
  }
  const std::int64_t layers = spout_layers(sp, spacing, end);
  if (layers >= kSpoutIdLimit)
    t.fail_at(t.node(t.has("stop") ? "stop" : "velocity"), t.has("stop") ? "stop" : "velocity",
              fmt::format("the spout emits {} layers of particles by the end of the run; allowed: "
                          "fewer than {} (particle ids): a slower or shorter flow, or fewer "
                          "particles_per_cell",
                          layers, kSpoutIdLimit),
              flow);
}

SpoutConfig read_spout(TableReader t, const SceneConfig& s) {
  const int d = s.dimension;
  SpoutConfig sp;
  sp.center = t.vector("center", d, std::nullopt, Range());
  sp.radius = t.number("radius", std::nullopt, positive());
  sp.velocity = t.vector("velocity", d, std::nullopt, Range());
  if (speed_squared(sp) <= 0.0)
    t.fail_at(t.node("velocity"), "velocity",
              "zero; allowed: a nonzero vector, the direction and speed of the grains leaving "
              "the spout");
  sp.start = t.number("start", 0.0, non_negative());
  sp.stop = t.number("stop", sp.stop, positive());
  if (!(sp.stop > sp.start))
    t.fail_at(t.node("stop"), "stop",
              fmt::format("{} is out of range; allowed: stop > {} (start)", sp.stop, sp.start),
              {t.full("start")});
  sp.particles_per_cell =
      t.int_value("particles_per_cell", default_particles_per_cell(s.dimension), closed(1, 8));
  sp.jitter = t.number("jitter", 0.0, closed(0, 1));
  t.reject_unknown(kSpoutKeys);
  check_spout_inside(t, sp, s);
  check_spout_output(t, sp, s);
  return sp;
}

// Whether [[sand]] block k would seed particles but for the obstacles.
bool seeds_without_obstacles(const SceneConfig& s, std::size_t k) {
  if (s.obstacles.empty()) return false;
  SceneConfig bare = s;
  bare.obstacles.clear();
  return seeded_per_region(bare)[k] > 0;
}

}  // namespace

void check_inside(TableReader& t, const SceneConfig& s, const std::string& key, double lo,
                  double hi, int axis, std::vector<std::string> with, const char* what) {
  const double eps = 1e-12 * s.size[axis];
  with.push_back("grid.size");
  if (lo < -eps || hi > s.size[axis] + eps)
    t.fail_at(t.node(key), key,
              fmt::format("{} [{}, {}] on {} leaves the box; allowed: within [0, {}] (grid.size)",
                          what, lo, hi, axis_name(axis), s.size[axis]),
              with);
}

bool polygon_edges_meet(const std::vector<Vec3d>& v, std::size_t* first, std::size_t* second) {
  const std::size_t n = v.size();
  const auto cross = [](const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // neighbours share a corner
      const Vec3d &a = v[i], &b = v[(i + 1) % n], &c = v[j], &e = v[(j + 1) % n];
      const double d1 = cross(a, b, c), d2 = cross(a, b, e), d3 = cross(c, e, a),
                   d4 = cross(c, e, b);
      bool overlap = true;  // the edges' bounding boxes (for collinear edges)
      for (int k = 0; k < 2; ++k)
        overlap = overlap && std::max(std::min(a[k], b[k]), std::min(c[k], e[k])) <=
                                 std::min(std::max(a[k], b[k]), std::max(c[k], e[k]));
      if (d1 * d2 <= 0.0 && d3 * d4 <= 0.0 && overlap) {
        *first = i, *second = j;
        return true;
      }
    }
  return false;
}

std::vector<Vec3d> read_polygon_vertices(TableReader& t) {
  const std::string allowed = "an array of at least 3 points [x, y] (a simple polygon)";
  const toml::node* n = t.node("vertices");
  if (!n) t.fail_missing("vertices", allowed);
  const toml::array* list = n->as_array();
  if (!list) t.fail_at(n, "vertices", "expected an array of points; allowed: " + allowed);
  if (list->size() < 3)
    t.fail_at(n, "vertices", fmt::format("{} vertices; allowed: {}", list->size(), allowed));
  std::vector<Vec3d> vertices;
  for (std::size_t k = 0; k < list->size(); ++k)
    vertices.push_back(polygon_vertex(t, *list->get(k), k));
  Vec3d lo = vertices[0], hi = vertices[0];
  for (const Vec3d& v : vertices)
    for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], v[a]), hi[a] = std::max(hi[a], v[a]);
  if (std::abs(twice_area(vertices)) <=
      1e-12 * (hi[0] - lo[0] + hi[1] - lo[1]) * (hi[0] - lo[0] + hi[1] - lo[1])) {
    // A figure eight's two loops cancel out: its edges cross.
    std::size_t i = 0, j = 0;
    if (polygon_edges_meet(vertices, &i, &j))
      t.fail_at(n, "vertices",
                fmt::format("the polygon crosses itself (edges {} and {} meet) and has zero area; "
                            "allowed: a simple polygon of positive area",
                            i, j));
    t.fail_at(n, "vertices",
              "the polygon has zero area (its vertices are collinear or repeated); allowed: a "
              "simple polygon of positive area");
  }
  return vertices;
}

MeshKeys read_mesh_keys(TableReader& t, const SceneConfig& s) {
  const std::string allowed =
      "a closed triangle mesh file, OBJ (v and f lines) or STL (binary or ASCII)";
  const toml::node* n = t.node("file");
  if (!n) t.fail_missing("file", allowed);
  if (!n->is_string()) t.fail_at(n, "file", "expected a file name (a string); allowed: " + allowed);
  MeshKeys m;
  m.file = n->as_string()->get();
  m.file_path = mesh_path(m.file, s);
  m.scale = t.number("scale", 1.0, positive());
  m.translate = t.vector("translate", 3, Vec3d{0, 0, 0}, Range());
  TriangleMesh mesh;
  try {
    mesh = read_mesh_file(m.file_path);
  } catch (const MeshError& e) {
    t.fail_at(n, "file",
              fmt::format("cannot use the mesh file \"{}\": {}; allowed: {}", m.file_path, e.what(),
                          allowed));
  }
  if (const std::size_t open = open_edge_count(mesh))
    t.fail_at(n, "file",
              fmt::format("the mesh in \"{}\" is not closed: {} open edge{} (each edge must be "
                          "shared by exactly two triangles); allowed: {}",
                          m.file_path, open, open == 1 ? "" : "s", allowed));
  for (Point3& v : mesh.vertices)
    for (int a = 0; a < 3; ++a) v[a] = m.scale * v[a] + m.translate[a];
  m.mesh = std::make_shared<const SolidMesh>(mesh);
  m.surface = std::make_shared<const TriangleMesh>(std::move(mesh));
  return m;
}

std::vector<std::string> shapes_of_other_dimension(int dimension) {
  return dimension == 2 ? Names{"cylinder", "sphere", "mesh"} : Names{"disk", "polygon"};
}

void reject_other_shape_keys(TableReader& t, const std::string& shape) {
  const bool old_shape = shape == "box" || shape == "disk" || shape == "cylinder";
  const Names& allowed = shape_keys().at(shape);
  for (const std::string& k : old_shape ? kNewKeys : kOldKeys)
    if (t.has(k) && std::find(allowed.begin(), allowed.end(), k) == allowed.end())
      t.fail_at(t.node(k), k,
                fmt::format("not used by shape \"{}\"; allowed: {}", shape, joined(allowed)),
                {t.full("shape")});
}

void read_source_shape(TableReader& t, const std::string& shape, SandConfig& c,
                       const SceneConfig& s) {
  if (shape == "sphere") {
    read_sphere(t, c, s);
  } else if (shape == "polygon") {
    read_polygon(t, c, s);
  } else {
    read_mesh(t, c, s);
  }
}

void read_all_spouts(TableReader& root, SceneConfig& s) {
  s.spouts.clear();
  if (const toml::array* list = root.array_of_tables("spout"))
    root.for_each_table(*list, "spout",
                        [&](TableReader t) { s.spouts.push_back(read_spout(std::move(t), s)); });
}

void check_regions_seed(TableReader& root, const SceneConfig& s) {
  if (s.sand.empty()) return;
  const std::vector<std::size_t> counts = seeded_per_region(s);
  const toml::array* list = root.array_of_tables("sand");
  for (std::size_t k = 0; k < counts.size(); ++k) {
    if (counts[k] > 0) continue;
    TableReader t = root.sub(list->get(k)->as_table(), fmt::format("sand[{}]", k));
    if (seeds_without_obstacles(s, k))
      t.fail_at(t.node("shape"), "shape",
                "the region holds no particle: it lies inside [[obstacle]] blocks (the seeding "
                "skips their insides); allowed: a region with room for particles outside the "
                "obstacles",
                {t.prefix(), "obstacle"});
    const double spacing = s.cell_size() / s.sand[k].particles_per_cell;
    Names with{t.prefix(), "grid"};  // this block, the grid and the blocks before it
    for (std::size_t e = 0; e < k; ++e) with.push_back(fmt::format("sand[{}]", e));
    t.fail_at(t.node("shape"), "shape",
              fmt::format("the region holds no particle: it is thinner than the particle spacing "
                          "{} m (the cell size / particles_per_cell), or covered by earlier "
                          "[[sand]] blocks; allowed: a region holding at least one particle",
                          spacing),
              with);
  }
}

std::vector<std::string> source_scene_keys() {
  Names keys;
  for (const std::string& k : kNewKeys) keys.push_back("sand[]." + k);
  for (const std::string& k : kSpoutKeys) keys.push_back("spout[]." + k);
  return keys;
}

}  // namespace sablier
