// Fixed frictional obstacles (METHOD.md section 3) as signed distance
// functions: negative inside the solid, positive in the sand's space, with
// the outward unit normal (pointing into the sand). Plain structs and
// a switch, no virtual dispatch: they are evaluated per node and per particle.
#pragma once

#include <algorithm>
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
  // A rigid body (a ball with a density): its state is advanced by the
  // simulation, not by at_time. Mass in kg (kg/m in 2D), moment of inertia
  // about its centre in kg m^2 (kg m in 2D), angular velocity in rad/s
  // (2D: spin[0]), and in 2D the angle it has turned through (rad).
  bool dynamic = false;
  double mass = 0.0, inertia = 0.0;
  Vec<D> spin = Vec<D>::Zero();
  double angle = 0.0;
};

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
    const double r = c.radius;
    o.dynamic = true;
    o.mass = c.density * (D == 2 ? pi * r * r : 4.0 / 3.0 * pi * r * r * r);
    o.inertia = (D == 2 ? 0.5 : 0.4) * o.mass * r * r;  // disk, solid sphere
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
      // Outside: distance to the box; inside: minus the distance to the
      // nearest face, whose normal is the outward one.
      const Vec<D> centre = 0.5 * (o.a + o.b);
      const Vec<D> half = 0.5 * (o.b - o.a);
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
