// Scene parsing of [[obstacle]] blocks (docs/scenes.md, "[[obstacle]]").
#include "scene/scene_obstacles.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "core/distance_grid.hpp"
#include "core/mesh.hpp"
#include "core/polygon.hpp"
#include "physics/obstacle.hpp"
#include "scene/scene_sources.hpp"

namespace sablier {

bool moves_into_sand(const ObstacleConfig& o, int d) {
  if (o.dynamic()) return false;
  if (o.posed() && (o.spin[0] != 0.0 || o.spin[1] != 0.0 || o.spin[2] != 0.0)) return true;
  double speed = 0.0, normal = 0.0;
  for (int a = 0; a < d; ++a) {
    speed += o.velocity[a] * o.velocity[a];
    normal += o.velocity[a] * o.normal[a];
  }
  if (speed == 0.0) return false;
  // A plane sliding along itself keeps its solid in place (a conveyor belt).
  return o.shape != ObstacleShape::Plane || std::abs(normal) > 1e-12 * std::sqrt(speed);
}

namespace {

using Names = std::vector<std::string>;
constexpr double kInf = std::numeric_limits<double>::infinity();
const Range kPositive{0.0, kInf, true, false};
const Range kMuRange{0.0, kMaxObstacleMu, false, false};
const Range kDensityRange{0.0, 1e5, true, false};  // kg/m^3: above 0, up to 100 t/m^3

const Names kShapes2D{"plane", "box", "disk", "polygon"};
const Names kShapes3D{"plane", "box", "sphere", "cylinder", "mesh"};
const Names kGeometryKeys{"point",  "normal",   "min",  "max",   "center",   "radius",
                          "height", "vertices", "file", "scale", "translate"};

char axis_name(int a) { return "xyz"[a]; }

// The geometric keys each shape takes.
Names shape_keys(const std::string& shape) {
  if (shape == "plane") return {"point", "normal"};
  if (shape == "box") return {"min", "max"};
  if (shape == "cylinder") return {"center", "radius", "height"};
  if (shape == "polygon") return {"vertices"};
  if (shape == "mesh") return {"file", "scale", "translate"};
  return {"center", "radius"};  // disk, sphere
}

// Keys of another shape are errors, as in [[sand]] blocks.
void reject_other_obstacle_keys(TableReader& t, const std::string& shape) {
  const Names mine = shape_keys(shape);
  for (const std::string& k : kGeometryKeys)
    if (std::find(mine.begin(), mine.end(), k) == mine.end())
      reject_keys(
          t, {k},
          fmt::format("not used by shape \"{}\"; allowed: {}", shape, fmt::join(mine, ", ")),
          {t.full("shape")});
}

// The keys beyond the geometry, and which obstacles take them (takes()):
// the one rule for refusing them and for listing the keys a block takes.
const Names kMotionKeys{"mu", "velocity", "density", "angle", "axis", "spin", "until"};

// A box, polygon or mesh, or a rigid body, turns: angle, spin (axis in 3D).
bool turns(const ObstacleConfig& o) {
  return o.dynamic() || o.shape == ObstacleShape::Box || o.shape == ObstacleShape::Polygon ||
         o.shape == ObstacleShape::Mesh;
}

// Whether `o` takes `key` of kMotionKeys; density and the keys that depend on
// it as far as they are read (rigid bodies turn, and cannot be taken away).
bool takes(const std::string& key, const ObstacleConfig& o, int d) {
  if (key == "density")
    return o.shape != ObstacleShape::Plane && o.shape != ObstacleShape::Cylinder;
  if (key == "angle") return turns(o);
  if (key == "axis") return turns(o) && d == 3;
  if (key == "spin") return turns(o) || o.shape == ObstacleShape::Ball;  // a roller
  if (key == "until") return !o.dynamic();
  return true;
}

// Every key the block of `o` takes, for the list an unknown key gets.
Names obstacle_keys(const ObstacleConfig& o, int d) {
  Names keys{"shape"};
  for (const std::string& k : shape_keys(obstacle_shape_name(o.shape, d))) keys.push_back(k);
  for (const std::string& k : kMotionKeys)
    if (takes(k, o, d)) keys.push_back(k);
  return keys;
}

double length(const Vec3d& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// The plane's normal, normalised. One already of unit length (within
// rounding) is kept as given: normalising it again could move its last bits,
// and the resolved scene must read back to the same normal.
Vec3d unit_normal(TableReader& t, int d) {
  Vec3d n = t.vector("normal", d, std::nullopt, Range());
  if (std::abs(length(n) - 1.0) <= 1e-14) return n;
  // Scaled by the largest component first, so that tiny or huge vectors
  // neither underflow nor overflow.
  const double largest = std::max({std::abs(n[0]), std::abs(n[1]), std::abs(n[2])});
  if (largest == 0.0)
    t.fail_at(t.node("normal"), "normal",
              "zero; allowed: a nonzero vector, pointing from the solid into the sand");
  for (double& x : n) x /= largest;
  const double len = length(n);
  for (double& x : n) x /= len;
  return n;
}

// The dotted keys that place `o` in the box: its geometry, its pose and
// grid.size (for the checks against the box).
Names placing_keys(const TableReader& t, const ObstacleConfig& o, int d) {
  Names keys{"grid.size", t.full("angle"), t.full("axis")};
  for (const std::string& k : shape_keys(obstacle_shape_name(o.shape, d)))
    keys.push_back(t.full(k));
  return keys;
}

// 0 <= mu <= kMaxObstacleMu.
double read_mu(TableReader& t) { return t.number("mu", ObstacleConfig{}.mu, kMuRange); }

// A plane must cut or touch the box and leave some of it to the sand: some
// corner of the box on the solid side or on the plane, some strictly on the
// sand side.
void check_plane_reaches_box(TableReader& t, const ObstacleConfig& o, const SceneConfig& s) {
  const int d = s.dimension;
  double lowest = kInf, highest = -kInf;
  for (int corner = 0; corner < (1 << d); ++corner) {
    double dist = 0.0;
    for (int a = 0; a < d; ++a)
      dist += ((corner >> a & 1 ? s.size[a] : 0.0) - o.point[a]) * o.normal[a];
    lowest = std::min(lowest, dist);
    highest = std::max(highest, dist);
  }
  const double eps = 1e-12 * length(s.size);
  if (highest <= eps)
    t.fail_at(t.node("normal"), "normal",
              "the whole box is on the plane's solid side (the normal points from the solid into "
              "the sand), so no room is left for sand; allowed: a plane with part of the box on "
              "the side its normal points to",
              placing_keys(t, o, d));
  if (lowest > eps)
    t.fail_at(t.node("point"), "point",
              fmt::format("the plane misses the box: the box lies {} m or more on its sand side; "
                          "allowed: a plane that cuts or touches the box [0, grid.size]",
                          lowest),
              placing_keys(t, o, d));
}

// Other shapes: their bounding box must overlap or touch the box on every axis.
void check_bounds_reach_box(TableReader& t, const ObstacleConfig& o, const SceneConfig& s) {
  for (int a = 0; a < s.dimension; ++a) {
    double lo = o.min[a], hi = o.max[a];
    if (o.shape == ObstacleShape::Polygon || o.shape == ObstacleShape::Mesh) {
      lo = o.extent_min[a];
      hi = o.extent_max[a];
    } else if (o.shape != ObstacleShape::Box) {
      const bool axial = o.shape == ObstacleShape::Cylinder && a == 2;
      lo = axial ? o.center[a] : o.center[a] - o.radius;
      hi = axial ? o.center[a] + o.height : o.center[a] + o.radius;
    }
    const double eps = 1e-12 * s.size[a];
    if (hi >= -eps && lo <= s.size[a] + eps) continue;
    const std::string key = o.shape == ObstacleShape::Polygon ? "vertices"
                            : o.shape == ObstacleShape::Mesh
                                ? (t.has("translate") ? "translate" : "file")
                            : o.shape != ObstacleShape::Box ? "center"
                            : hi < 0.0                      ? "max"
                                                            : "min";
    t.fail_at(t.node(key), key,
              fmt::format("the obstacle spans [{}, {}] on {}, outside the box [0, {}] "
                          "(grid.size); allowed: an obstacle that reaches into or touches the "
                          "box (its bounding box overlapping [0, grid.size] on every axis)",
                          lo, hi, axis_name(a), s.size[a]),
              placing_keys(t, o, s.dimension));
  }
}

// A solid driven into the sand (a fixed obstacle given a velocity, other
// than a plane sliding along itself) needs the projection: the grains'
// moves do not keep up with it (docs/method.md, "Solids driven into the
// sand"), the default since 0.3.0.
void check_motion(TableReader& t, const ObstacleConfig& o, const SceneConfig& s) {
  if (!moves_into_sand(o, s.dimension) || s.solver.decompaction == Decompaction::Project) return;
  const char* key = t.has("velocity") ? "velocity" : "spin";  // a solid may turn in place
  t.fail_at(t.node(key), key,
            fmt::format("a {} moving into the sand needs solver.decompaction = \"project\" (the "
                        "default); allowed: that, or no velocity, or a plane "
                        "moving along itself (velocity . normal = 0, a conveyor belt)",
                        obstacle_shape_name(o.shape, s.dimension)),
            {"solver.decompaction", t.full("velocity"), t.full("spin"), t.full("normal")});
}

// A rigid polygon must not cross itself (its mass properties are those of
// a simple polygon): no two edges that are not neighbours meet.
void check_simple_polygon(TableReader& t, const ObstacleConfig& o) {
  std::size_t i = 0, j = 0;
  if (polygon_edges_meet(o.vertices, &i, &j))
    t.fail_at(t.node("vertices"), "vertices",
              fmt::format("edges {} and {} of the rigid polygon meet; allowed: a polygon that "
                          "does not cross or touch itself",
                          i, j));
}

// A rigid body's initial orientation: `angle` (degrees, counter-clockwise
// about its centre) and in 3D `axis` (normalised when read; z by default);
// its initial `spin`. A fixed box, polygon or mesh takes them too (turned,
// turning at a constant rate), a fixed disk or sphere a spin (a roller).
void read_orientation(TableReader& t, ObstacleConfig& o, int d) {
  for (const char* key : {"angle", "axis", "spin"}) {
    if (!t.has(key) || takes(key, o, d)) continue;
    if (turns(o))  // the axis, in 2D
      t.fail_at(t.node(key), key, "2D bodies turn about z; allowed: axis in 3D scenes only",
                {"dimension"});
    t.fail_at(t.node(key), key,
              fmt::format("a {} does not turn; allowed: angle, spin (and axis in 3D) on a box, "
                          "{}, or a rigid body; spin on a {} (a roller)",
                          obstacle_shape_name(o.shape, d), d == 2 ? "polygon" : "mesh",
                          d == 2 ? "disk" : "sphere"),
              {t.full("shape"), t.full("density")});
  }
  if (takes("spin", o, d)) {
    if (d == 2) {
      o.spin[2] = t.number("spin", 0.0, Range());
    } else {
      o.spin = t.vector("spin", 3, Vec3d{0, 0, 0}, Range());
    }
  }
  if (takes("angle", o, d))
    o.angle_degrees = t.number("angle", 0.0, Range{-360.0, 360.0, false, false});
  if (!t.has("axis")) return;
  Vec3d a = t.vector("axis", 3, std::nullopt, Range());
  const double len = length(a);
  if (!(len > 0.0) || !std::isfinite(len))
    t.fail_at(t.node("axis"), "axis",
              "zero or too long; allowed: a nonzero vector of finite numbers");
  if (std::abs(len - 1.0) > 1e-14)
    for (double& x : a) x /= len;
  o.axis = a;
}

void read_geometry(TableReader& t, const std::string& shape, ObstacleConfig& o,
                   const SceneConfig& s) {
  const int d = s.dimension;
  if (shape == "plane") {
    o.shape = ObstacleShape::Plane;
    o.point = t.vector("point", d, std::nullopt, Range());
    o.normal = unit_normal(t, d);
  } else if (shape == "box") {
    o.shape = ObstacleShape::Box;
    o.min = t.vector("min", d, std::nullopt, Range());
    o.max = t.vector("max", d, std::nullopt, Range());
    for (int a = 0; a < d; ++a)
      if (!(o.min[a] < o.max[a]))
        t.fail_at(t.node("max"), "max",
                  fmt::format("empty box: max = {} on {} is not above min = {}; allowed: min < "
                              "max on every axis",
                              o.max[a], axis_name(a), o.min[a]),
                  {t.full("min")});
  } else if (shape == "polygon") {
    o.shape = ObstacleShape::Polygon;
    o.vertices = read_polygon_vertices(t);
    std::vector<SolidPolygon::Point2> corners;
    for (const Vec3d& v : o.vertices) corners.push_back({v[0], v[1]});
    o.polygon = std::make_shared<const SolidPolygon>(std::move(corners));
    for (int a = 0; a < 2; ++a) {
      o.extent_min[a] = o.polygon->lower()[a];
      o.extent_max[a] = o.polygon->upper()[a];
    }
  } else if (shape == "mesh") {
    o.shape = ObstacleShape::Mesh;
    MeshKeys m = read_mesh_keys(t, s);
    o.file = std::move(m.file);
    o.file_path = std::move(m.file_path);
    o.scale = m.scale;
    o.translate = m.translate;
    o.surface = std::move(m.surface);
    o.edges = std::make_shared<const std::vector<FeatureEdge>>(feature_edges(*o.surface));
    o.vertex_normals = std::make_shared<const std::vector<Point3>>(vertex_normals(*o.surface));
    for (int a = 0; a < 3; ++a) {
      o.extent_min[a] = m.mesh->lower()[a];
      o.extent_max[a] = m.mesh->upper()[a];
    }
    o.solid = std::move(m.mesh);
  } else {
    o.shape = shape == "cylinder" ? ObstacleShape::Cylinder : ObstacleShape::Ball;
    o.center = t.vector("center", d, std::nullopt, Range());
    o.radius = t.number("radius", std::nullopt, kPositive);
    if (shape == "cylinder") o.height = t.number("height", std::nullopt, kPositive);
  }
}

// The box a mesh's signed distance is sampled over: its bounds within 3
// cells, cut to the box within 3 cells (the contact rows look one cell out
// from the box's nodes, the grains and the moves no further than the box),
// and `reach` further (a rigid ball's radius: its contacts are measured
// from its centre).
void sample_region(const ObstacleConfig& o, const SceneConfig& s, Point3& lo, Point3& hi,
                   double reach = 0.0) {
  const double margin = 3.0 * s.cell_size() + reach;
  for (int a = 0; a < 3; ++a) {
    lo[a] = o.extent_min[a] - margin;
    hi[a] = o.extent_max[a] + margin;
    // A body goes anywhere, a moving solid through the box, a posed one is
    // sampled in its own frame: sampled whole.
    if (o.dynamic() || o.posed() || moves_into_sand(o, s.dimension)) continue;
    lo[a] = std::max(lo[a], -margin);
    hi[a] = std::min(hi[a], s.size[a] + margin);
  }
}

// At half the cell size: at most kMaxSamples points.
void check_sample_count(TableReader& t, const ObstacleConfig& o, const SceneConfig& s) {
  Point3 lo{}, hi{};
  sample_region(o, s, lo, hi);
  double samples = 1.0;
  for (int a = 0; a < 3; ++a) samples *= std::ceil((hi[a] - lo[a]) / (0.5 * s.cell_size())) + 1.0;
  constexpr double kMaxSamples = 5e7;  // 400 MB of doubles
  if (samples > kMaxSamples)
    t.fail_at(t.node("file"), "file",
              fmt::format("the mesh's distance would be sampled at {:.3g} points (half the cell "
                          "size over its bounds in the box); allowed: at most {:.0e} (a coarser "
                          "grid or a smaller mesh)",
                          samples, kMaxSamples),
              {t.full("scale"), t.full("translate"), "grid"});
}

// Every mesh obstacle's signed distance, sampled at half the cell size
// (physics/obstacle.hpp) and exact to 3.5 cells from its surface, or
// further where a rigid ball could touch it: a ball's contact is measured
// from its centre (physics/transfer.cpp), so the band and the sampled
// region reach one radius beyond that.
void sample_mesh_distances(SceneConfig& s) {
  double radius = 0.0;
  for (const ObstacleConfig& o : s.obstacles)
    if (o.dynamic()) radius = std::max(radius, o.radius);
  const double h = s.cell_size();
  for (ObstacleConfig& o : s.obstacles) {
    if (o.shape != ObstacleShape::Mesh) continue;
    Point3 lo{}, hi{};
    sample_region(o, s, lo, hi, radius);
    o.distance = std::make_shared<const DistanceGrid>(o.solid, lo, hi, 0.5 * h, 4.0 * h + radius);
  }
}

// Signed distance of x to the solid `o`: exact for meshes, whose distance
// is not sampled yet.
template <int D>
double config_distance(const ObstacleConfig& o, const Vec<D>& x) {
  if constexpr (D == 3)
    if (o.shape == ObstacleShape::Mesh) {
      Vec<D> p = x;
      if (o.dynamic() || o.posed()) {  // where x is on the solid as the file gives it
        const Obstacle<D> body = make_obstacle<D>(o);
        p = body.b + body.rotation.transpose() * (x - body.a);
      }
      const Point3 c{p[0], p[1], p[2]};
      const double d = o.solid->distance(c);
      return o.solid->contains(c) ? -d : d;
    }
  Vec<D> n;
  return signed_distance(make_obstacle<D>(o), x, &n);
}

// The points by which a solid meets a rigid body (docs/scenes.md, "Rigid
// bodies"): a ball's centre, reaching `reach` = its radius further; a body's
// corners or vertices, a fixed box's or polygon's corners (reach 0). Other
// shapes have none.
template <int D>
std::vector<Vec<D>> contact_points(const ObstacleConfig& c, double* reach) {
  const Obstacle<D> o = make_obstacle<D>(c);
  *reach = 0.0;
  if (c.shape == ObstacleShape::Ball) {
    *reach = o.radius;
    return {o.a};
  }
  if (c.dynamic()) return body_points(o);
  std::vector<Vec<D>> out;
  if (c.shape == ObstacleShape::Box) {
    for (int k = 0; k < ipow(2, D); ++k) {
      Vec<D> x;
      for (int a = 0; a < D; ++a) x[a] = (k >> a & 1) ? c.max[a] : c.min[a];
      out.push_back(x);
    }
  } else if (c.shape == ObstacleShape::Polygon) {
    for (const Vec3d& v : c.vertices) {
      Vec<D> x = Vec<D>::Zero();
      for (int a = 0; a < 2; ++a) x[a] = v[a];
      out.push_back(x);
    }
  }
  return out;
}

// How far the rigid body `b` and the solid `o` reach into each other (m;
// <= 0 when clear or touching): over the points each meets the other by.
template <int D>
double overlap(const ObstacleConfig& b, const ObstacleConfig& o) {
  double depth = -kInf, reach = 0.0;
  for (const Vec<D>& x : contact_points<D>(b, &reach))
    depth = std::max(depth, reach - config_distance<D>(o, x));
  for (const Vec<D>& x : contact_points<D>(o, &reach))
    depth = std::max(depth, reach - config_distance<D>(b, x));
  return depth;
}

// The extent of a rigid body on axis a.
template <int D>
std::pair<double, double> body_extent(const ObstacleConfig& c, int a) {
  double reach = 0.0, lo = kInf, hi = -kInf;
  for (const Vec<D>& x : contact_points<D>(c, &reach)) {
    lo = std::min(lo, x[a] - reach);
    hi = std::max(hi, x[a] + reach);
  }
  return {lo, hi};
}

// A rigid body must start inside the box and clear of every solid read
// before it, and a solid read after a body clear of that body: the contact
// rows stop solids from moving into each other, not pull them apart
// (docs/method.md, "Frictional obstacles").
void check_bodies_clear(TableReader& t, const ObstacleConfig& o, const SceneConfig& s) {
  const int d = s.dimension;
  if (o.dynamic())
    for (int a = 0; a < d; ++a) {
      const auto [lo, hi] = d == 2 ? body_extent<2>(o, a) : body_extent<3>(o, a);
      const double eps = 1e-12 * s.size[a];
      if (lo >= -eps && hi <= s.size[a] + eps) continue;
      const char* key = o.shape == ObstacleShape::Box ? "min" : "center";
      t.fail_at(t.node(key), key,
                fmt::format("the rigid body spans [{}, {}] on {}, not inside the box [0, {}] "
                            "(grid.size); allowed: a body that starts inside the box",
                            lo, hi, axis_name(a), s.size[a]),
                placing_keys(t, o, d));
    }
  for (std::size_t k = 0; k < s.obstacles.size(); ++k) {
    const ObstacleConfig& p = s.obstacles[k];
    if (!o.dynamic() && !p.dynamic()) continue;
    const ObstacleConfig& body = o.dynamic() ? o : p;
    const ObstacleConfig& other = o.dynamic() ? p : o;
    const double depth = d == 2 ? overlap<2>(body, other) : overlap<3>(body, other);
    if (depth <= 1e-9 * length(s.size)) continue;
    const std::string key = o.shape == ObstacleShape::Plane     ? "point"
                            : o.shape == ObstacleShape::Box     ? "min"
                            : o.shape == ObstacleShape::Polygon ? "vertices"
                            : o.shape == ObstacleShape::Mesh    ? "file"
                                                                : "center";
    Names with = placing_keys(t, o, d);
    with.push_back(fmt::format("obstacle[{}]", k));
    t.fail_at(t.node(key), key,
              fmt::format("overlaps obstacle[{}] (a {}{}) by {} m at the start; allowed: rigid "
                          "bodies clear of the other obstacles and bodies (touching is clear)",
                          k, p.dynamic() ? "rigid " : "", obstacle_shape_name(p.shape, d), depth),
              with);
  }
}

ObstacleConfig read_obstacle(TableReader t, SceneConfig& s) {
  const int d = s.dimension;
  const std::string shape =
      dimension_choice(t, "shape", d == 2 ? kShapes2D : kShapes3D,
                       d == 2 ? Names{"sphere", "cylinder", "mesh"} : Names{"disk", "polygon"}, d);
  reject_other_obstacle_keys(t, shape);
  ObstacleConfig o;
  read_geometry(t, shape, o, s);
  o.mu = read_mu(t);
  o.velocity = t.vector("velocity", d, Vec3d{0, 0, 0}, Range());
  if (t.has("density")) {
    if (!takes("density", o, d))
      t.fail_at(t.node("density"), "density",
                fmt::format("a {} cannot be a rigid body; allowed: density on a {}",
                            obstacle_shape_name(o.shape, d),
                            d == 2 ? "disk, box or polygon" : "sphere, box or mesh"),
                {t.full("shape")});
    o.density = t.number("density", std::nullopt, kDensityRange);
    if (o.shape == ObstacleShape::Polygon || o.shape == ObstacleShape::Mesh) {
      if (o.shape == ObstacleShape::Polygon) check_simple_polygon(t, o);
      o.centroid = body_mass_properties(o).centroid;
      o.center = o.centroid;
    }
  }
  read_orientation(t, o, d);
  if (o.posed() && (o.shape == ObstacleShape::Polygon || o.shape == ObstacleShape::Mesh)) {
    // Turned about its centroid, as a body.
    if (o.shape == ObstacleShape::Polygon) check_simple_polygon(t, o);
    o.centroid = body_mass_properties(o).centroid;
    o.center = o.centroid;
  }
  if (t.has("until")) {
    if (!takes("until", o, d))
      t.fail_at(t.node("until"), "until",
                "a rigid body cannot be taken away; allowed: until on fixed obstacles only",
                {t.full("density")});
    o.until = t.number("until", std::nullopt, kPositive);
  }
  check_motion(t, o, s);
  t.reject_unknown(obstacle_keys(o, d));
  if (o.shape == ObstacleShape::Plane) {
    check_plane_reaches_box(t, o, s);
  } else {
    check_bounds_reach_box(t, o, s);
  }
  if (o.shape == ObstacleShape::Mesh) check_sample_count(t, o, s);
  check_bodies_clear(t, o, s);
  return o;
}

}  // namespace

void read_all_obstacles(TableReader& root, SceneConfig& s) {
  s.obstacles.clear();
  if (const toml::array* list = root.array_of_tables("obstacle"))
    root.for_each_table(*list, "obstacle", [&](TableReader t) {
      s.obstacles.push_back(read_obstacle(std::move(t), s));
    });
  sample_mesh_distances(s);
  measure_thin_solids(s);
}

const char* obstacle_shape_name(ObstacleShape shape, int dimension) {
  switch (shape) {
    case ObstacleShape::Plane:
      return "plane";
    case ObstacleShape::Box:
      return "box";
    case ObstacleShape::Ball:
      return dimension == 2 ? "disk" : "sphere";
    case ObstacleShape::Cylinder:
      return "cylinder";
    case ObstacleShape::Polygon:
      return "polygon";
    case ObstacleShape::Mesh:
      return "mesh";
  }
  return "";
}

std::vector<std::string> obstacle_scene_keys() {
  Names keys{"obstacle[].shape"};
  for (const std::string& k : kGeometryKeys) keys.push_back("obstacle[]." + k);
  for (const std::string& k : kMotionKeys) keys.push_back("obstacle[]." + k);
  return keys;
}

}  // namespace sablier
