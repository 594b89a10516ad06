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
  Vec<D> b = Vec<D>::Zero();  // plane: unit normal; box: max
  double radius = 0.0;
  double height = 0.0;
  std::shared_ptr<const SolidPolygon> polygon;   // 2D polygons
  std::shared_ptr<const DistanceGrid> distance;  // 3D meshes
  double mu = 0.5;  // Coulomb coefficient (scene convention, METHOD.md section 4)
  Vec<D> velocity = Vec<D>::Zero();  // m/s: kinematic translation, or a body's velocity
  double until = 1e300;              // s: taken away from this time on (scene's obstacle[].until)
  bool gone = false;                 // taken away: no longer there at all
  // A rigid body (a ball or a box with a density): its state is advanced by
  // the simulation, not by at_time. Mass in kg (kg/m in 2D), moments of
  // inertia about its centre along its own axes in kg m^2 (2D: inertia[0],
  // kg m, about z), angular velocity in rad/s about world axes (2D:
  // spin[0]), and its orientation: in 2D the angle it has turned through
  // (rad, counter-clockwise), in 3D a unit quaternion (w, x, y, z). A box
  // body keeps its centre in `a` (as a ball does) and its half sides in `b`:
  // it spans a + rotation [-b, b]; `rotation` follows the orientation
  // (set_orientation).
  bool dynamic = false;
  double mass = 0.0;
  Vec<D> inertia = Vec<D>::Zero();
  Vec<D> spin = Vec<D>::Zero();
  double angle = 0.0;
  std::array<double, 4> quaternion{1.0, 0.0, 0.0, 0.0};
  Mat<D> rotation = Mat<D>::Identity();
};

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
  return o.shape == ObstacleShape::Box ? o.b.norm() : o.radius;
}

// A box body's corners in world coordinates (2^D of them, corner c taking
// the upper side on axis k when bit k of c is set).
template <int D>
inline std::array<Vec<D>, ipow(2, D)> box_corners(const Obstacle<D>& o) {
  std::array<Vec<D>, ipow(2, D)> out;
  for (int c = 0; c < ipow(2, D); ++c) {
    Vec<D> local;
    for (int k = 0; k < D; ++k) local[k] = (c >> k & 1) ? o.b[k] : -o.b[k];
    out[c] = o.a + o.rotation * local;
  }
  return out;
}

// dt times a body's inverse inertia tensor about world axes, R J^-1 R^T
// (2D: entry (0, 0) only, about z).
template <int D>
inline Mat<D> spin_inverse(const Obstacle<D>& o, double dt) {
  if constexpr (D == 2) {
    Mat<D> m = Mat<D>::Zero();
    m(0, 0) = dt / o.inertia[0];
    return m;
  } else {
    if (o.shape != ObstacleShape::Box) return Mat<D>::Identity() * (dt / o.inertia[0]);  // a ball
    return o.rotation * (dt * o.inertia.cwiseInverse()).asDiagonal() * o.rotation.transpose();
  }
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
  o.until = c.until;
  if (c.shape == ObstacleShape::Plane) o.b.normalize();
  o.radius = c.radius;
  o.height = c.height;
  o.mu = c.mu;
  for (int k = 0; k < D; ++k) o.velocity[k] = c.velocity[k];
  if (c.dynamic()) {
    constexpr double pi = 3.14159265358979323846;
    o.dynamic = true;
    if (c.shape == ObstacleShape::Box) {
      const Vec<D> size = o.b - o.a;
      o.a = 0.5 * (o.a + o.b);  // the centre
      o.b = 0.5 * size;         // the half sides
      o.mass = c.density * size.prod();
      // A uniform box: J_k = m (sum of the other sides squared) / 12; in 2D
      // about z, m (w^2 + h^2) / 12.
      const double sq = size.squaredNorm();
      if constexpr (D == 2) {
        o.inertia[0] = o.mass * sq / 12.0;
      } else {
        for (int k = 0; k < D; ++k) o.inertia[k] = o.mass * (sq - size[k] * size[k]) / 12.0;
      }
    } else {
      const double r = c.radius;
      o.mass = c.density * (D == 2 ? pi * r * r : 4.0 / 3.0 * pi * r * r * r);
      o.inertia.setConstant((D == 2 ? 0.5 : 0.4) * o.mass * r * r);  // disk, solid sphere
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
  if (o.shape == ObstacleShape::Box) o.b += shift;
  return o;
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
      if (!o.dynamic) return box_distance<D>(o.a, o.b, x, normal);
      // A box body: the distance in its own frame, the normal turned back.
      const Vec<D> local = o.rotation.transpose() * (x - o.a);
      const double s = box_distance<D>(-o.b, o.b, local, normal);
      *normal = o.rotation * *normal;
      return s;
    }
    case ObstacleShape::Polygon: {
      if constexpr (D == 2) {
        double nx = 0.0, ny = 0.0;
        const double s = o.polygon->signed_distance(x[0] - o.a[0], x[1] - o.a[1], &nx, &ny);
        *normal = Vec<D>(nx, ny);
        return s;
      }
      break;
    }
    case ObstacleShape::Mesh: {
      if constexpr (D == 3) {
        Point3 n{};
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
