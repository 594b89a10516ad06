// Fixed frictional obstacles (METHOD.md section 3) as signed distance
// functions: negative inside the solid, positive in the sand's space, with
// the outward unit normal (pointing into the sand). Plain structs and
// a switch, no virtual dispatch: they are evaluated per node and per particle.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "core/distance_grid.hpp"
#include "core/mass_properties.hpp"
#include "core/mesh.hpp"
#include "core/polygon.hpp"
#include "core/tensor.hpp"
#include "scene/scene.hpp"

namespace sablier {

template <int D>
struct Obstacle {
  ObstacleShape shape = ObstacleShape::Plane;
  // plane: point; box: min; ball, cylinder: centre (of the base); polygon,
  // mesh: the translation of their solid (zero unless it moves)
  Vec<D> a = Vec<D>::Zero();
  Vec<D> b = Vec<D>::Zero();  // plane: unit normal; box: max (bodies: below)
  double radius = 0.0;
  double height = 0.0;
  std::shared_ptr<const SolidPolygon> polygon;   // 2D polygons
  std::shared_ptr<const DistanceGrid> distance;  // 3D meshes
  // 3D meshes: the convex edges of the solid as the scene gave it (`points`'
  // frame for a body, less `a` for a fixed mesh), for edge contacts (edges.hpp).
  std::shared_ptr<const std::vector<FeatureEdge>> edges;
  // 3D meshes with `points`: each point's outward vertex normal
  // (core/mesh.hpp), in `points`' frame (physics/corners.hpp).
  std::shared_ptr<const std::vector<Point3>> vertex_normals;
  double mu = 0.5;                   // Coulomb coefficient (scene convention, METHOD.md section 4)
  Vec<D> velocity = Vec<D>::Zero();  // m/s: kinematic translation, or a body's velocity
  double until = 1e300;              // s: taken away from this time on (scene's obstacle[].until)
  bool gone = false;                 // taken away: no longer there at all
  // A rigid body (a ball, box, polygon or mesh with a density): its state
  // is advanced by the simulation, not by at_time. Mass in kg (kg/m in 2D),
  // inertia tensor about its centre of mass in the scene's unturned axes,
  // kg m^2 (2D: entry (0, 0), kg m, about z), angular velocity in rad/s
  // about world axes (2D: spin[0]), and its orientation: in 2D the angle it
  // has turned through (rad, counter-clockwise), in 3D a unit quaternion
  // (w, x, y, z); `rotation` follows it (set_orientation). Every body keeps
  // its centre of mass in `a`. A box keeps its half sides in `b`: it spans
  // a + rotation [-b, b]. A polygon or mesh keeps its solid as the scene
  // gave it (unturned) and that solid's centroid in `b`: a point x of the
  // world is b + rotation^T (x - a) of the solid; `points` are its corners
  // or vertices there, and `extent` its largest distance from the centroid.
  bool dynamic = false;
  // Laid out as a body (centre in `a`, `b` and `rotation` as above): every
  // body, and a fixed box, polygon or mesh that is turned or turns (its
  // `spin` constant, its orientation at time t set by at_time).
  bool posed = false;
  double mass = 0.0;
  Mat<D> inertia = Mat<D>::Zero();
  std::shared_ptr<const std::vector<Vec<D>>> points;
  double extent = 0.0;
  Vec<D> spin = Vec<D>::Zero();
  double angle = 0.0;
  std::array<double, 4> quaternion{1.0, 0.0, 0.0, 0.0};
  Mat<D> rotation = Mat<D>::Identity();
};

// Whether a fixed obstacle moves through the box: translates
// (obstacle[].velocity, other than a plane's along itself, which leaves its
// solid in place: a conveyor belt) or turns (a box, polygon or mesh with a
// spin; a spinning disk or sphere stays in place: a roller).
template <int D>
inline bool moves_into_sand(const Obstacle<D>& o) {
  if (o.dynamic) return false;
  if (o.posed && o.spin.squaredNorm() > 0.0) return true;  // a turning box, polygon or mesh
  const double speed = o.velocity.norm();
  if (speed == 0.0) return false;
  return o.shape != ObstacleShape::Plane || std::abs(o.velocity.dot(o.b)) > 1e-12 * speed;
}

// The rotation of a body's orientation (angle in 2D, quaternion in 3D).
template <int D>
inline void set_orientation(Obstacle<D>& o) {
  if constexpr (D == 2) {
    const double c = std::cos(o.angle), s = std::sin(o.angle);
    o.rotation << c, -s, s, c;
  } else {
    const auto& q = o.quaternion;
    o.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  }
}

// The radius of the smallest ball about its centre that holds a body.
template <int D>
inline double bounding_radius(const Obstacle<D>& o) {
  switch (o.shape) {
    case ObstacleShape::Box:
      return o.b.norm();
    case ObstacleShape::Ball:
      return o.radius;
    default:
      return o.extent;
  }
}

// The points by which a box, polygon or mesh body meets other solids, in
// world coordinates: a box's 2^D corners (corner c taking the upper side on
// axis k when bit k of c is set), a polygon's corners, a mesh's vertices.
template <int D>
inline void body_points(const Obstacle<D>& o, std::vector<Vec<D>>& out) {
  out.clear();
  if (o.shape == ObstacleShape::Box) {
    for (int c = 0; c < ipow(2, D); ++c) {
      Vec<D> local;
      for (int k = 0; k < D; ++k) local[k] = (c >> k & 1) ? o.b[k] : -o.b[k];
      out.push_back(o.a + o.rotation * local);
    }
  } else if (o.points) {
    for (const Vec<D>& p : *o.points) out.push_back(o.a + o.rotation * (p - o.b));
  }
}

template <int D>
inline std::vector<Vec<D>> body_points(const Obstacle<D>& o) {
  std::vector<Vec<D>> out;
  body_points(o, out);
  return out;
}

// dt times a body's inverse inertia tensor about world axes, R J^-1 R^T
// (2D: entry (0, 0) only, about z).
template <int D>
inline Mat<D> spin_inverse(const Obstacle<D>& o, double dt) {
  if constexpr (D == 2) {
    Mat<D> m = Mat<D>::Zero();
    m(0, 0) = dt / o.inertia(0, 0);
    return m;
  } else {
    if (o.shape == ObstacleShape::Ball) return Mat<D>::Identity() * (dt / o.inertia(0, 0));
    if (o.inertia.isDiagonal(0.0))  // a box
      return o.rotation * (dt * o.inertia.diagonal().cwiseInverse()).asDiagonal() *
             o.rotation.transpose();
    return o.rotation * (dt * o.inertia.inverse()) * o.rotation.transpose();
  }
}

// A polygon's or mesh's mass properties per unit density.
inline MassProperties body_mass_properties(const ObstacleConfig& c) {
  if (c.shape == ObstacleShape::Polygon) return polygon_mass_properties(c.polygon->corners());
  return mesh_mass_properties(*c.surface);
}

template <int D>
Obstacle<D> make_obstacle(const ObstacleConfig& c) {
  Obstacle<D> o;
  o.shape = c.shape;
  for (int k = 0; k < D; ++k) {
    switch (c.shape) {
      case ObstacleShape::Plane:
        o.a[k] = c.point[k];
        o.b[k] = c.normal[k];
        break;
      case ObstacleShape::Box:
        o.a[k] = c.min[k];
        o.b[k] = c.max[k];
        break;
      case ObstacleShape::Ball:
      case ObstacleShape::Cylinder:
        o.a[k] = c.center[k];
        break;
      case ObstacleShape::Polygon:
      case ObstacleShape::Mesh:
        break;
    }
  }
  o.polygon = c.polygon;
  o.distance = c.distance;
  o.edges = c.edges;
  o.until = c.until;
  if constexpr (D == 3)
    if (c.shape == ObstacleShape::Mesh && c.surface && !c.dynamic() && !c.posed()) {
      // A fixed mesh's vertices where the scene puts them (`a` translates
      // them), which meet rigid bodies' faces (transfer.cpp).
      auto points = std::make_shared<std::vector<Vec<D>>>();
      for (const Point3& p : c.surface->vertices) points->push_back(Vec<D>(p[0], p[1], p[2]));
      o.points = std::move(points);
      o.vertex_normals = c.vertex_normals;
    }
  if (c.shape == ObstacleShape::Plane) o.b.normalize();
  o.radius = c.radius;
  o.height = c.height;
  o.mu = c.mu;
  for (int k = 0; k < D; ++k) o.velocity[k] = c.velocity[k];
  {  // a body's initial spin, a fixed solid's constant one
    if constexpr (D == 2) {
      o.spin[0] = c.spin[2];
    } else {
      for (int k = 0; k < 3; ++k) o.spin[k] = c.spin[k];
    }
  }
  if (c.dynamic() || c.posed()) {
    constexpr double pi = 3.14159265358979323846;
    o.dynamic = c.dynamic();
    o.posed = true;
    if (c.shape == ObstacleShape::Box) {
      const Vec<D> size = o.b - o.a;
      o.a = 0.5 * (o.a + o.b);  // the centre
      o.b = 0.5 * size;         // the half sides
      o.mass = c.density * size.prod();
      // A uniform box: J_k = m (sum of the other sides squared) / 12; in 2D
      // about z, m (w^2 + h^2) / 12.
      const double sq = size.squaredNorm();
      if constexpr (D == 2) {
        o.inertia(0, 0) = o.mass * sq / 12.0;
      } else {
        for (int k = 0; k < D; ++k) o.inertia(k, k) = o.mass * (sq - size[k] * size[k]) / 12.0;
      }
    } else if (c.shape == ObstacleShape::Polygon || c.shape == ObstacleShape::Mesh) {
      // The solid's mass properties (core/mass_properties.hpp), its corners
      // or vertices, and its centroid; it starts at `center` (the parser
      // sets it to the centroid).
      const MassProperties m = body_mass_properties(c);
      o.mass = c.density * m.measure;
      if constexpr (D == 2) {
        o.inertia(0, 0) = c.density * m.inertia[2][2];
      } else {
        for (int r = 0; r < 3; ++r)
          for (int k = 0; k < 3; ++k) o.inertia(r, k) = c.density * m.inertia[r][k];
      }
      auto points = std::make_shared<std::vector<Vec<D>>>();
      if constexpr (D == 2) {
        for (const auto& p : c.polygon->corners()) points->push_back(Vec<D>(p[0], p[1]));
      } else {
        for (const Point3& p : c.surface->vertices) points->push_back(Vec<D>(p[0], p[1], p[2]));
        o.vertex_normals = c.vertex_normals;
      }
      for (int k = 0; k < D; ++k) {
        o.b[k] = c.centroid[k];
        o.a[k] = c.center[k];
      }
      for (const Vec<D>& p : *points) o.extent = std::max(o.extent, (p - o.b).norm());
      o.points = std::move(points);
    } else {
      const double r = c.radius;
      o.mass = c.density * (D == 2 ? pi * r * r : 4.0 / 3.0 * pi * r * r * r);
      // disk, solid sphere
      o.inertia = Mat<D>::Identity() * ((D == 2 ? 0.5 : 0.4) * o.mass * r * r);
    }
    // The initial orientation: `angle` (degrees) about `axis` (3D; z in 2D).
    const double turn = c.angle_degrees * pi / 180.0;
    if constexpr (D == 2) {
      o.angle = turn;
    } else {
      const Eigen::Vector3d axis(c.axis[0], c.axis[1], c.axis[2]);
      const Eigen::Quaterniond q(Eigen::AngleAxisd(turn, axis.normalized()));
      o.quaternion = {q.w(), q.x(), q.y(), q.z()};
    }
    set_orientation(o);
  }
  return o;
}

// The obstacle where its motion has taken it at time t (s). A rigid body
// moves as the sand pushes it: its state is the simulation's, not a
// function of t, and it is returned as it is.
template <int D>
Obstacle<D> at_time(Obstacle<D> o, double t) {
  if (o.dynamic) return o;
  // A step starting within a nanosecond of `until` (frame ends are sums of
  // rounded step lengths) already goes without it.
  o.gone = t >= o.until - 1e-9;
  const Vec<D> shift = t * o.velocity;
  o.a += shift;
  if (o.shape == ObstacleShape::Box && !o.posed) o.b += shift;  // a posed box: half sides
  if (o.posed && o.spin.squaredNorm() > 0.0) {                  // turned by spin t about its centre
    if constexpr (D == 2) {
      o.angle += o.spin[0] * t;
    } else {
      const Eigen::Quaterniond start(o.quaternion[0], o.quaternion[1], o.quaternion[2],
                                     o.quaternion[3]);
      const Eigen::Quaterniond q =
          Eigen::Quaterniond(Eigen::AngleAxisd(o.spin.norm() * t, o.spin.normalized())) * start;
      o.quaternion = {q.w(), q.x(), q.y(), q.z()};
    }
    set_orientation(o);
  }
  return o;
}

// The velocity of a fixed solid's surface at x: its translation plus its
// turn about its centre (a ball's, a posed solid's), velocity + spin x (x -
// a).
template <int D>
inline Vec<D> surface_velocity(const Obstacle<D>& o, const Vec<D>& x) {
  if (o.spin.squaredNorm() == 0.0 || (!o.posed && o.shape != ObstacleShape::Ball))
    return o.velocity;
  const Vec<D> r = x - o.a;
  if constexpr (D == 2) {
    return o.velocity + o.spin[0] * Vec<D>(-r[1], r[0]);
  } else {
    return o.velocity + o.spin.cross(r);
  }
}

// The scene's obstacles at time t (s).
template <int D>
std::vector<Obstacle<D>> make_obstacles(const SceneConfig& scene, double t = 0.0) {
  std::vector<Obstacle<D>> out;
  for (const ObstacleConfig& c : scene.obstacles) out.push_back(at_time(make_obstacle<D>(c), t));
  return out;
}

// Signed distance of x to the axis-aligned box [lo, hi] and the outward
// normal there. Outside: the distance to the box; inside: minus the distance
// to the nearest face, whose normal is the outward one.
template <int D>
inline double box_distance(const Vec<D>& lo, const Vec<D>& hi, const Vec<D>& x, Vec<D>* normal) {
  const Vec<D> centre = 0.5 * (lo + hi);
  const Vec<D> half = 0.5 * (hi - lo);
  const Vec<D> q = (x - centre).cwiseAbs() - half;
  const Vec<D> outside = q.cwiseMax(0.0);
  const double out_len = outside.norm();
  if (out_len > 0.0) {
    for (int k = 0; k < D; ++k)
      (*normal)[k] = (x[k] < centre[k] ? -outside[k] : outside[k]) / out_len;
    return out_len;
  }
  int axis = 0;
  for (int k = 1; k < D; ++k)
    if (q[k] > q[axis]) axis = k;
  *normal = Vec<D>::Zero();
  (*normal)[axis] = x[axis] < centre[axis] ? -1.0 : 1.0;
  return q[axis];
}

// Signed distance of x to the obstacle (m) and the outward normal there.
template <int D>
inline double signed_distance(const Obstacle<D>& o, const Vec<D>& x, Vec<D>* normal) {
  if (o.gone) {
    *normal = Vec<D>::Zero();
    (*normal)[D - 1] = 1.0;
    return 1e300;
  }
  switch (o.shape) {
    case ObstacleShape::Plane: {
      *normal = o.b;
      return (x - o.a).dot(o.b);
    }
    case ObstacleShape::Ball: {
      const Vec<D> r = x - o.a;
      const double len = r.norm();
      if (len > 0.0) {
        *normal = r / len;
      } else {
        *normal = Vec<D>::Zero();
        (*normal)[D - 1] = 1.0;
      }
      return len - o.radius;
    }
    case ObstacleShape::Box: {
      if (!o.posed) return box_distance<D>(o.a, o.b, x, normal);
      // A box body: the distance in its own frame, the normal turned back.
      const Vec<D> local = o.rotation.transpose() * (x - o.a);
      const double s = box_distance<D>(-o.b, o.b, local, normal);
      *normal = o.rotation * *normal;
      return s;
    }
    case ObstacleShape::Polygon: {
      if constexpr (D == 2) {
        double nx = 0.0, ny = 0.0;
        if (o.posed) {  // the solid as the scene gave it, where x is
          const Vec<D> p = o.b + o.rotation.transpose() * (x - o.a);
          const double s = o.polygon->signed_distance(p[0], p[1], &nx, &ny);
          *normal = o.rotation * Vec<D>(nx, ny);
          return s;
        }
        const double s = o.polygon->signed_distance(x[0] - o.a[0], x[1] - o.a[1], &nx, &ny);
        *normal = Vec<D>(nx, ny);
        return s;
      }
      break;
    }
    case ObstacleShape::Mesh: {
      if constexpr (D == 3) {
        Point3 n{};
        if (o.posed) {
          const Vec<D> p = o.b + o.rotation.transpose() * (x - o.a);
          const double s = o.distance->signed_distance({p[0], p[1], p[2]}, &n);
          *normal = o.rotation * Vec<D>(n[0], n[1], n[2]);
          return s;
        }
        const double s =
            o.distance->signed_distance({x[0] - o.a[0], x[1] - o.a[1], x[2] - o.a[2]}, &n);
        *normal = Vec<D>(n[0], n[1], n[2]);
        return s;
      }
      break;
    }
    case ObstacleShape::Cylinder: {
      // 3D only: axis along the last coordinate, from a[D-1] to a[D-1] + height.
      Vec<D> radial = x - o.a;
      radial[D - 1] = 0.0;
      const double rho = radial.norm();
      const double dr = rho - o.radius;
      const double mid = o.a[D - 1] + 0.5 * o.height;
      const double dz = std::abs(x[D - 1] - mid) - 0.5 * o.height;
      Vec<D> nr = rho > 0.0 ? Vec<D>(radial / rho) : Vec<D>::Unit(0);
      Vec<D> nz = Vec<D>::Zero();
      nz[D - 1] = x[D - 1] < mid ? -1.0 : 1.0;
      if (dr > 0.0 && dz > 0.0) {
        const double len = std::hypot(dr, dz);
        *normal = (dr * nr + dz * nz) / len;
        return len;
      }
      if (dr > dz) {
        *normal = nr;
        return dr;
      }
      *normal = nz;
      return dz;
    }
  }
  *normal = Vec<D>::Zero();
  return 1e300;
}

// The nearest obstacle's signed distance at x (1e300 without obstacles).
template <int D>
inline double obstacle_distance(const std::vector<Obstacle<D>>& obstacles, const Vec<D>& x,
                                Vec<D>* normal, int* which = nullptr) {
  double best = 1e300;
  Vec<D> n = Vec<D>::Zero();
  *normal = Vec<D>::Zero();
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    const double s = signed_distance(obstacles[k], x, &n);
    if (s < best) {
      best = s;
      *normal = n;
      if (which) *which = static_cast<int>(k);
    }
  }
  return best;
}

// An orthonormal frame whose first column is the unit normal n.
template <int D>
inline Mat<D> contact_frame(const Vec<D>& n) {
  Mat<D> F;
  F.col(0) = n;
  if constexpr (D == 2) {
    F.col(1) = Vec<D>(-n[1], n[0]);
  } else {
    // The coordinate axis least aligned with n, made orthogonal to it.
    int axis = 0;
    for (int k = 1; k < D; ++k)
      if (std::abs(n[k]) < std::abs(n[axis])) axis = k;
    Vec<D> t = Vec<D>::Unit(axis) - n[axis] * n;
    t.normalize();
    F.col(1) = t;
    F.col(2) = n.cross(t);
  }
  return F;
}

// Fraction of the integral of a node's hat function (support [-h, h] along
// the normal) that lies inside a plane at signed distance s from the node:
// the solid's share of the node's volume V_j, in the plane approximation.
inline double solid_fraction(double s, double h) {
  const double t = s / h;
  if (t >= 1.0) return 0.0;
  if (t <= -1.0) return 1.0;
  return t >= 0.0 ? 0.5 * (1.0 - t) * (1.0 - t) : 1.0 - 0.5 * (1.0 + t) * (1.0 + t);
}

}  // namespace sablier
