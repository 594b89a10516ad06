#include "io/obstacle_geometry.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/mesh.hpp"
#include "scene/scene_obstacles.hpp"

namespace sablier {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kRound = 48;  // segments around a disk, sphere or cylinder
constexpr int kRings = 24;  // latitude bands of a sphere

using P3 = std::array<double, 3>;

// Vertices and faces of one object; faces index this object's vertices from 0.
struct Shape {
  std::vector<P3> v;
  std::vector<std::vector<int>> faces;  // 3D: polygons; 2D: closed polylines
};

// The box [0, size] cut by a plane: the corners of that polygon, in order
// around the plane's normal (empty when the plane misses the box).
std::vector<P3> plane_cut(const Vec3d& point, const Vec3d& normal, const Vec3d& size, int d) {
  const auto side = [&](const P3& x) {
    double s = 0.0;
    for (int a = 0; a < d; ++a) s += (x[a] - point[a]) * normal[a];
    return s;
  };
  std::vector<P3> cut;
  const int corners = 1 << d;
  for (int i = 0; i < corners; ++i)
    for (int a = 0; a < d; ++a) {
      if (i >> a & 1) continue;  // each edge once, from its lower end along axis a
      const int j = i | 1 << a;
      P3 x{0, 0, 0}, y{0, 0, 0};
      for (int b = 0; b < d; ++b)
        x[b] = (i >> b & 1) ? size[b] : 0.0, y[b] = (j >> b & 1) ? size[b] : 0.0;
      const double sx = side(x), sy = side(y);
      // Both ends on one side: no crossing. Both on the plane: its ends
      // come with the edges that reach them.
      if (sx * sy > 0.0 || (sx == 0.0 && sy == 0.0)) continue;
      const double t = sx / (sx - sy);
      P3 p{0, 0, 0};
      for (int b = 0; b < d; ++b) p[b] = x[b] + t * (y[b] - x[b]);
      if (std::none_of(cut.begin(), cut.end(), [&](const P3& q) {
            return std::abs(q[0] - p[0]) + std::abs(q[1] - p[1]) + std::abs(q[2] - p[2]) <
                   1e-12 * (size[0] + size[1] + size[2]);
          }))
        cut.push_back(p);
    }
  if (d == 3 && cut.size() >= 3) {
    // Order around the centroid, in a frame of the plane.
    P3 c{0, 0, 0};
    for (const P3& p : cut)
      for (int a = 0; a < 3; ++a) c[a] += p[a] / cut.size();
    const Vec3d& n = normal;
    P3 u = std::abs(n[0]) < 0.9 ? P3{0, -n[2], n[1]} : P3{n[2], 0, -n[0]};  // n x e
    const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (double& x : u) x /= lu;
    const P3 w{n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
    const auto angle = [&](const P3& p) {
      const P3 r{p[0] - c[0], p[1] - c[1], p[2] - c[2]};
      return std::atan2(r[0] * w[0] + r[1] * w[1] + r[2] * w[2],
                        r[0] * u[0] + r[1] * u[1] + r[2] * u[2]);
    };
    std::sort(cut.begin(), cut.end(),
              [&](const P3& a, const P3& b) { return angle(a) < angle(b); });
  }
  return cut;
}

Shape shape_of(const ObstacleConfig& o, const SceneConfig& s) {
  const int d = s.dimension;
  Shape g;
  const auto ring = [&](double cx, double cy, double z, double r) {
    const int first = static_cast<int>(g.v.size());
    for (int k = 0; k < kRound; ++k) {
      const double t = 2.0 * kPi * k / kRound;
      g.v.push_back({cx + r * std::cos(t), cy + r * std::sin(t), z});
    }
    return first;
  };
  switch (o.shape) {
    case ObstacleShape::Plane: {
      g.v = plane_cut(o.point, o.normal, s.size, d);
      std::vector<int> f;
      for (int k = 0; k < static_cast<int>(g.v.size()); ++k) f.push_back(k);
      if (g.v.size() >= 2) g.faces.push_back(f);
      break;
    }
    case ObstacleShape::Box:
      if (d == 2) {
        g.v = {{o.min[0], o.min[1], 0},
               {o.max[0], o.min[1], 0},
               {o.max[0], o.max[1], 0},
               {o.min[0], o.max[1], 0}};
        g.faces = {{0, 1, 2, 3}};
      } else {
        for (int k = 0; k < 8; ++k)
          g.v.push_back({k & 1 ? o.max[0] : o.min[0], k & 2 ? o.max[1] : o.min[1],
                         k & 4 ? o.max[2] : o.min[2]});
        g.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                   {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
      }
      break;
    case ObstacleShape::Ball:
      if (d == 2) {
        ring(o.center[0], o.center[1], 0.0, o.radius);
        std::vector<int> f(kRound);
        for (int k = 0; k < kRound; ++k) f[k] = k;
        g.faces.push_back(f);
      } else {
        // Latitude rings between the two poles.
        g.v.push_back({o.center[0], o.center[1], o.center[2] - o.radius});
        for (int i = 1; i < kRings; ++i) {
          const double phi = kPi * i / kRings - kPi / 2;
          ring(o.center[0], o.center[1], o.center[2] + o.radius * std::sin(phi),
               o.radius * std::cos(phi));
        }
        const int top = static_cast<int>(g.v.size());
        g.v.push_back({o.center[0], o.center[1], o.center[2] + o.radius});
        const auto at = [](int ringi, int k) { return 1 + ringi * kRound + (k % kRound); };
        for (int k = 0; k < kRound; ++k) {
          g.faces.push_back({0, at(0, k + 1), at(0, k)});
          g.faces.push_back({top, at(kRings - 2, k), at(kRings - 2, k + 1)});
          for (int i = 0; i + 1 < kRings - 1; ++i)
            g.faces.push_back({at(i, k), at(i, k + 1), at(i + 1, k + 1), at(i + 1, k)});
        }
      }
      break;
    case ObstacleShape::Cylinder: {
      const int bottom = ring(o.center[0], o.center[1], o.center[2], o.radius);
      const int top = ring(o.center[0], o.center[1], o.center[2] + o.height, o.radius);
      std::vector<int> lid, base;
      for (int k = 0; k < kRound; ++k) {
        const int k1 = (k + 1) % kRound;
        g.faces.push_back({bottom + k, bottom + k1, top + k1, top + k});
        lid.push_back(top + k);
        base.push_back(bottom + kRound - 1 - k);
      }
      g.faces.push_back(lid);
      g.faces.push_back(base);
      break;
    }
    case ObstacleShape::Polygon: {
      std::vector<int> f;
      for (const Vec3d& p : o.vertices) {
        f.push_back(static_cast<int>(g.v.size()));
        g.v.push_back({p[0], p[1], 0.0});
      }
      g.faces.push_back(f);
      break;
    }
    case ObstacleShape::Mesh:
      if (o.surface) {
        for (const Point3& p : o.surface->vertices) g.v.push_back(p);
        for (const auto& t : o.surface->triangles) g.faces.push_back({t[0], t[1], t[2]});
      }
      break;
  }
  if (o.dynamic() || o.posed()) {
    // A body (or a turned fixed solid) turned about its centre by `angle` about `axis` (z in 2D); a
    // polygon's or mesh's solid, given where the scene had it, moved from
    // its centroid to the body's centre.
    const Eigen::Vector3d axis =
        d == 2 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(o.axis[0], o.axis[1], o.axis[2]);
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(o.angle_degrees * kPi / 180.0, axis.normalized()).toRotationMatrix();
    Eigen::Vector3d from(0.0, 0.0, 0.0), to(0.0, 0.0, 0.0);
    for (int a = 0; a < d; ++a) {
      const bool solid = o.shape == ObstacleShape::Polygon || o.shape == ObstacleShape::Mesh;
      to[a] = o.shape == ObstacleShape::Box ? 0.5 * (o.min[a] + o.max[a]) : o.center[a];
      from[a] = solid ? o.centroid[a] : to[a];
    }
    for (P3& p : g.v) {
      const Eigen::Vector3d x = to + R * (Eigen::Vector3d(p[0], p[1], p[2]) - from);
      p = {x[0], x[1], d == 2 ? 0.0 : x[2]};
    }
  }
  return g;
}

}  // namespace

std::string format_obstacles_obj(const SceneConfig& scene) {
  std::string out;
  int base = 1;  // OBJ indices count from 1 over the whole file
  for (std::size_t k = 0; k < scene.obstacles.size(); ++k) {
    const ObstacleConfig& o = scene.obstacles[k];
    if (o.dynamic() || moves_into_sand(o, scene.dimension)) continue;  // in bodies_NNNNN.vtp
    const Shape g = shape_of(o, scene);
    if (g.faces.empty()) continue;
    out += fmt::format("o obstacle_{}\n", k);
    for (const P3& p : g.v) out += fmt::format("v {:.10g} {:.10g} {:.10g}\n", p[0], p[1], p[2]);
    for (const std::vector<int>& f : g.faces) {
      out += scene.dimension == 2 ? "l" : "f";
      for (int i : f) out += fmt::format(" {}", base + i);
      if (scene.dimension == 2 && f.size() > 2) out += fmt::format(" {}", base + f.front());
      out += "\n";
    }
    base += static_cast<int>(g.v.size());
  }
  if (out.empty()) return out;
  return "# Sablier: the scene's fixed obstacles, in metres (one object per [[obstacle]]\n"
         "# block, named by its index; rigid bodies are in bodies.csv)\n" +
         out;
}

ObstacleConfig posed_body(const ObstacleConfig& start, const double centre[3], double angle,
                          const double quaternion[4], int dimension) {
  ObstacleConfig o = start;
  constexpr double kDegrees = 180.0 / kPi;
  if (o.shape == ObstacleShape::Box) {
    for (int a = 0; a < 3; ++a) {
      const double half = 0.5 * (start.max[a] - start.min[a]);
      o.min[a] = centre[a] - half;
      o.max[a] = centre[a] + half;
    }
  } else {
    for (int a = 0; a < 3; ++a) o.center[a] = centre[a];
  }
  if (dimension == 2) {
    o.angle_degrees = angle * kDegrees;
  } else {
    const Eigen::AngleAxisd turn(
        Eigen::Quaterniond(quaternion[0], quaternion[1], quaternion[2], quaternion[3])
            .normalized());
    o.angle_degrees = turn.angle() * kDegrees;
    for (int a = 0; a < 3; ++a) o.axis[a] = turn.axis()[a];
  }
  return o;
}

std::string format_bodies_vtp(const std::vector<ObstacleConfig>& obstacles,
                              const SceneConfig& scene, double time) {
  const int d = scene.dimension;
  std::vector<P3> points;
  std::vector<std::vector<int>> cells;  // point indices over the whole file
  std::vector<int> owner;
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const bool moving = moves_into_sand(obstacles[k], d);
    if (!obstacles[k].dynamic() && !moving) continue;
    Shape g = shape_of(obstacles[k], scene);
    if (moving && !obstacles[k].posed())  // where its velocity has taken it (posed: given posed)
      for (P3& p : g.v)
        for (int a = 0; a < d; ++a) p[a] += time * obstacles[k].velocity[a];
    const int base = static_cast<int>(points.size());
    points.insert(points.end(), g.v.begin(), g.v.end());
    for (const std::vector<int>& f : g.faces) {
      std::vector<int> cell;
      for (int i : f) cell.push_back(base + i);
      if (d == 2) cell.push_back(base + f.front());  // a closed outline
      cells.push_back(std::move(cell));
      owner.push_back(static_cast<int>(k));
    }
  }
  fmt::memory_buffer out;
  const auto put = [&](auto&&... args) { fmt::format_to(std::back_inserter(out), args...); };
  const char* kind = d == 2 ? "Lines" : "Polys";
  put("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<PolyData>\n");
  put("<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
      "NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
      points.size(), d == 2 ? cells.size() : 0, d == 2 ? 0 : cells.size());
  put("<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (const P3& p : points) put("{:.17g} {:.17g} {:.17g}\n", p[0], p[1], p[2]);
  put("</DataArray>\n</Points>\n<CellData Scalars=\"obstacle\">\n"
      "<DataArray type=\"Int32\" Name=\"obstacle\" format=\"ascii\">\n");
  for (int k : owner) put("{}\n", k);
  put("</DataArray>\n</CellData>\n<{}>\n"
      "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n",
      kind);
  for (const auto& cell : cells) {
    for (int i : cell) put("{} ", i);
    put("\n");
  }
  put("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  std::size_t end = 0;
  for (const auto& cell : cells) put("{}\n", end += cell.size());
  put("</DataArray>\n</{}>\n</Piece>\n</PolyData>\n</VTKFile>\n", kind);
  return fmt::to_string(out);
}

}  // namespace sablier
