// Fixed solids thinner than the grid resolves (docs/scenes.md, "Thin
// solids"): how thin a solid is, its measure when the scene is read, the
// notes and warnings about it.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/distance_grid.hpp"
#include "core/mesh.hpp"
#include "core/polygon.hpp"
#include "scene/scene_obstacles.hpp"

namespace sablier {

void measure_thin_solids(SceneConfig& s) {
  // Each fixed solid is measured once, here. The grid does not resolve the
  // thin ones, so the grains next to them keep to the nodes on their side
  // (the compatible transfer, physics/thin_solids.cpp).
  for (ObstacleConfig& o : s.obstacles) {
    ThinPart thin;
    if (o.dynamic() || !thinnest_part(o, s.dimension, kThinSolidCells * s.cell_size(), &thin))
      continue;
    o.thin = thin.thickness;
    o.thin_at = thin.where;
  }
}

namespace {

// The depth below `below` at which the line from `m` (on a face) along
// `inward` leaves the solid of signed distance sd(x, &normal) again through
// a face turned away from the first one (its normal against `inward` by
// more than kAcross: the other side of a wall, not a face that meets this
// one at an edge), or -1.
template <class Distance>
double depth_across(const Distance& sd, const Vec3d& m, const Vec3d& inward, double below) {
  constexpr double kAcross = 0.9;  // cosine: faces within 25 degrees of opposed
  Vec3d n{};
  const auto at = [&](double t) {
    return sd(Vec3d{m[0] + t * inward[0], m[1] + t * inward[1], m[2] + t * inward[2]}, &n);
  };
  const double step = below / 16.0;
  for (int k = 1; k <= 16; ++k) {
    if (at(k * step) < 0.0) continue;
    double in = (k - 1) * step, out = k * step;
    for (int i = 0; i < 30; ++i) {
      const double mid = 0.5 * (in + out);
      (at(mid) < 0.0 ? in : out) = mid;
    }
    at(out);
    const bool across = n[0] * inward[0] + n[1] * inward[1] + n[2] * inward[2] > kAcross;
    return across ? out : -1.0;
  }
  return -1.0;
}

// The thinnest crossing over faces (middle m, unit normal n of either
// sign): the normal's side where sd is negative just off the face is
// inward.
template <class Distance>
void thinnest_across(const Distance& sd, const Vec3d& m, const Vec3d& n, double below,
                     ThinPart* best) {
  const double eps = 1e-4 * below;
  Vec3d ignored{};
  const double dp = sd(Vec3d{m[0] + eps * n[0], m[1] + eps * n[1], m[2] + eps * n[2]}, &ignored);
  const double dm = sd(Vec3d{m[0] - eps * n[0], m[1] - eps * n[1], m[2] - eps * n[2]}, &ignored);
  if (!(std::min(dp, dm) < 0.0)) return;  // no solid on either side: a degenerate face
  const double sign = dp < dm ? 1.0 : -1.0;
  const double t = depth_across(sd, m, Vec3d{sign * n[0], sign * n[1], sign * n[2]}, below);
  if (t >= 0.0 && t < best->thickness) *best = {t, m};
}

}  // namespace

bool thinnest_part(const ObstacleConfig& o, int dimension, double below, ThinPart* out) {
  ThinPart best{below, {0, 0, 0}};
  switch (o.shape) {
    case ObstacleShape::Plane:
      return false;
    case ObstacleShape::Box:
      for (int a = 0; a < dimension; ++a) {
        const double t = o.max[a] - o.min[a];
        if (t < best.thickness)
          best = {t,
                  {0.5 * (o.min[0] + o.max[0]), 0.5 * (o.min[1] + o.max[1]),
                   0.5 * (o.min[2] + o.max[2])}};
      }
      break;
    case ObstacleShape::Ball:  // small rather than thin: not measured (docs/scenes.md)
      return false;
    case ObstacleShape::Cylinder:  // a disk: thin by its height
      if (o.height < best.thickness) best = {o.height, o.center};
      break;
    case ObstacleShape::Polygon: {
      const SolidPolygon& poly = *o.polygon;
      const auto sd = [&poly](const Vec3d& x, Vec3d* n) {
        (*n)[2] = 0.0;
        return poly.signed_distance(x[0], x[1], &(*n)[0], &(*n)[1]);
      };
      const auto& c = poly.corners();
      for (std::size_t i = 0; i < c.size(); ++i) {
        const auto& a = c[i];
        const auto& b = c[(i + 1) % c.size()];
        const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
        if (!(len > 0.0)) continue;
        thinnest_across(sd, Vec3d{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.0},
                        Vec3d{ey / len, -ex / len, 0.0}, below, &best);
      }
      break;
    }
    case ObstacleShape::Mesh: {
      if (!o.distance) return false;  // sampled once every obstacle is read
      const auto sd = [&o](const Vec3d& x, Vec3d* n) {
        Point3 g;
        const double d = o.distance->signed_distance(Point3{x[0], x[1], x[2]}, &g);
        *n = {g[0], g[1], g[2]};
        return d;
      };
      const TriangleMesh& m = *o.surface;
      const std::size_t count = m.triangles.size();
      constexpr std::size_t kMaxFaces = 5000;
      for (std::size_t k = 0; k < std::min(count, kMaxFaces); ++k) {
        const auto& t = m.triangles[count <= kMaxFaces ? k : k * count / kMaxFaces];
        const Point3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
        const Point3 n = cross(sub(b, a), sub(c, a));
        const double len = std::sqrt(dot(n, n));
        if (!(len > 0.0)) continue;
        thinnest_across(sd,
                        Vec3d{(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0,
                              (a[2] + b[2] + c[2]) / 3.0},
                        Vec3d{n[0] / len, n[1] / len, n[2] / len}, below, &best);
      }
      break;
    }
  }
  if (!(best.thickness < below)) return false;
  *out = best;
  return true;
}

std::vector<SceneMessage> thin_solid_messages(const SceneConfig& s) {
  std::vector<SceneMessage> messages;
  const double h = s.cell_size(), below = kThinSolidCells * h;
  const bool projected = s.solver.decompaction == Decompaction::Project;
  for (std::size_t k = 0; k < s.obstacles.size(); ++k) {
    const ObstacleConfig& o = s.obstacles[k];
    if (!(o.thin > 0.0)) continue;
    const ThinPart thin{o.thin, o.thin_at};
    std::string where = "(";
    for (int a = 0; a < s.dimension; ++a)
      where += fmt::format("{}{:.4g}", a ? ", " : "", thin.where[a]);
    where += ")";
    const std::string what = fmt::format(
        "{}: obstacle[{}] ({}) is {:.3g} mm thick near {}, less than {} cells ({:.3g} mm), "
        "which the grid does not resolve",
        s.source, k, obstacle_shape_name(o.shape, s.dimension), 1e3 * thin.thickness, where,
        kThinSolidCells, 1e3 * below);
    messages.push_back(
        projected ? SceneMessage{false, what + ": the sand next to it is kept at phi_max by "
                                               "solver.decompaction = \"project\" (the default; "
                                               "docs/scenes.md, \"Thin solids\")"}
                  : SceneMessage{
                        true, what + ": under this solver.decompaction the sand flowing along it "
                                     "may pack beyond phi_max; \"project\", the default, keeps "
                                     "it there (docs/scenes.md, \"Thin solids\")"});
  }
  return messages;
}

}  // namespace sablier
