// Rows of a solid's corners at another solid's edges and corners
// (transfer.cpp; docs/method.md, "Frictional obstacles"): where a corner of
// a box, polygon or mesh sits at (or within kCornerSlack cells of) an edge
// or corner of a box, polygon or mesh, several of that solid's faces are
// about as near, and the contact normal is taken from the corner's own
// direction instead of from round-off.
#pragma once

#include <algorithm>
#include <cmath>

#include "physics/obstacle.hpp"

namespace sablier {

// A corner of another solid meeting a box at (or within `slack` of) one of
// its edges or corners: box_distance's nearest face is then a matter of
// round-off (a crate set flush on another: its corners on the other's top
// edges, a side face as near as the top), and a side face's normal lets
// the corner sink. The contact normal belongs in both solids' normal cones;
// here it is the one of the box's cone there (its faces within `slack` of
// the nearest) that best follows `towards`, the corner's own direction into
// its solid: for faces with orthogonal normals n_k the maximiser of n .
// towards is the sum of w_k n_k, w_k = max(0, n_k . towards), normalised (a
// corner on a corner of the same orientation: the one face facing it; a
// beam's edge along a box's edge: the edge's bisector). The distance is
// the same sum of the faces' plane distances (that of the plane through the
// edge or corner across the normal). Returns false, with nothing written,
// where the point is over `slack` outside any face, or only the nearest
// face faces the corner, or none does: box_distance's answer then holds.
template <int D>
inline bool box_face_towards(const Vec<D>& lo, const Vec<D>& hi, const Vec<D>& x,
                             const Vec<D>& towards, double slack, double* distance,
                             Vec<D>* normal) {
  const Vec<D> centre = 0.5 * (lo + hi);
  const Vec<D> q = (x - centre).cwiseAbs() - 0.5 * (hi - lo);
  if (!(q.maxCoeff() <= slack)) return false;
  int nearest = 0;
  for (int k = 1; k < D; ++k)
    if (q[k] > q[nearest]) nearest = k;
  Vec<D> n = Vec<D>::Zero();
  double wq = 0.0;
  int faces = 0;
  for (int k = 0; k < D; ++k) {
    const double side = x[k] < centre[k] ? -1.0 : 1.0, w = side * towards[k];
    if (q[k] >= q[nearest] - slack && w > 0.0) {
      n[k] = side * w;
      wq += w * q[k];
      ++faces;
    }
  }
  const double len = n.norm();
  if (!(len > 0.0) || (faces == 1 && n[nearest] != 0.0)) return false;
  *normal = n / len;
  *distance = wq / len;
  return true;
}

// The direction from corner c of solid o into it, where o has corners:
// a box's (bit k of c set: the upper side on axis k, as body_points and the
// fixed corners number them) or a polygon's (in the order of its corners),
// minus the sum of the outward normals of its faces there; a mesh's vertex
// c, minus its vertex normal. False for other shapes.
template <int D>
inline bool corner_inward(const Obstacle<D>& o, int c, Vec<D>* inward) {
  Vec<D> s;
  if (o.shape == ObstacleShape::Box) {
    for (int k = 0; k < D; ++k) s[k] = (c >> k & 1) ? -1.0 : 1.0;
  } else if constexpr (D == 2) {
    if (o.shape != ObstacleShape::Polygon) return false;
    const auto m = o.polygon->corner_inward(static_cast<std::size_t>(c));
    s = Vec<D>(m[0], m[1]);
  } else {
    if (o.shape != ObstacleShape::Mesh || !o.vertex_normals) return false;
    const Point3& m = (*o.vertex_normals)[static_cast<std::size_t>(c)];
    s = -Vec<D>(m[0], m[1], m[2]);
  }
  *inward = o.posed ? Vec<D>(o.rotation * s) : s;
  return true;
}

// How near (in cells) a corner must come to a solid's edge or corner for
// corner_distance to choose the face: far beyond round-off, and
// small enough that a corner overhanging a box's edge by less is held as if
// it were on the face (a support wider by at most this).
inline constexpr double kCornerSlack = 0.005;

// A point and a direction in the frame signed_distance reads polygon or
// mesh o in (a turned solid's own, about its reference point b; else the
// scene's, less a), and a direction found there back in the world's.
template <int D>
inline Vec<D> solid_frame_point(const Obstacle<D>& o, const Vec<D>& x) {
  return o.posed ? Vec<D>(o.b + o.rotation.transpose() * (x - o.a)) : Vec<D>(x - o.a);
}
template <int D>
inline Vec<D> solid_frame_direction(const Obstacle<D>& o, const Vec<D>& v) {
  return o.posed ? Vec<D>(o.rotation.transpose() * v) : v;
}
template <int D>
inline Vec<D> world_direction(const Obstacle<D>& o, const Vec<D>& v) {
  return o.posed ? Vec<D>(o.rotation * v) : v;
}

// signed_distance for a corner of a box, polygon or mesh, `towards` its
// inward direction (corner_inward), against solid o: where o is a box, a
// polygon or a mesh, the face chosen by box_face_towards, SolidPolygon::
// face_towards or SolidMesh::face_towards (exact, where the sampled
// distance rounds the mesh's edges) within kCornerSlack cells (h the
// cell size) of its edges and corners, and for a mesh its exact distance
// within a cell; else, and elsewhere, signed_distance.
template <int D>
inline double corner_distance(const Obstacle<D>& o, const Vec<D>& x, const Vec<D>& towards,
                              double h, Vec<D>* normal) {
  const double slack = kCornerSlack * h;
  if (o.gone) return signed_distance(o, x, normal);
  // x and `towards` in the frame signed_distance reads the solid in, and
  // the normal found there back in the world's.
  const Vec<D> t = solid_frame_direction(o, towards);
  Vec<D> n;
  double d;
  bool found = false;
  if (o.shape == ObstacleShape::Box) {
    found = o.posed
                ? box_face_towards<D>(Vec<D>(-o.b), o.b, Vec<D>(o.rotation.transpose() * (x - o.a)),
                                      t, slack, &d, &n)
                : box_face_towards<D>(o.a, o.b, x, t, slack, &d, &n);
  } else if constexpr (D == 3) {
    // Exact within a cell (the rows' reach): the sampled distance rounds
    // the mesh's corners over about a sample, and a corner landing on one
    // would find it nearer than its gap said (DistanceGrid).
    if (o.shape == ObstacleShape::Mesh && o.distance) {
      const Vec<D> p = solid_frame_point(o, x);
      Point3 m{};
      found =
          o.distance->mesh().face_towards({p[0], p[1], p[2]}, {t[0], t[1], t[2]}, slack, h, &d, &m);
      n = Vec<D>(m[0], m[1], m[2]);
    }
  } else {
    if (o.shape == ObstacleShape::Polygon) {
      const Vec<D> p = solid_frame_point(o, x);
      found = o.polygon->face_towards(p[0], p[1], t[0], t[1], slack, &d, &n[0], &n[1]);
    }
  }
  if (found) {
    *normal = world_direction(o, n);
    return d;
  }
  return signed_distance(o, x, normal);
}

// Where a polygon or mesh folds inward (a V-groove's bottom, a step's
// inner corner), the solid near the fold is the union of its two faces'
// half-spaces, and a point near it must stay outside both planes: one row
// on the nearest face lets it slip across the fold into the other face
// within a step (a cube dropped into a V-groove ended a third of a
// millimetre into one slope). The faces of solid o that lie under x, the
// point projecting onto them, within `reach` in front of them (or
// kCornerSlack cells of size h behind), and, within that slack of their
// plane, facing `towards` (the point's direction into its own solid, as
// corner_inward gives it; zero for a point that has none): their normals
// (world frame, out of o) and signed distances, at most `max`, one per
// distinct normal. Near a convex fold the point lies behind the other
// face's plane (or on it, facing away) and only the one face counts, which
// the row of the nearest face already holds. Boxes, balls and cylinders
// are convex: none.
template <int D>
inline int faces_over(const Obstacle<D>& o, const Vec<D>& x, const Vec<D>& towards, double reach,
                      double h, Vec<D>* normals, double* distances, int max) {
  if (o.gone) return 0;
  const Vec<D> p = solid_frame_point(o, x), t = solid_frame_direction(o, towards);
  constexpr int kMax = 8;
  max = std::min(max, kMax);
  int count = 0;
  if constexpr (D == 2) {
    if (o.shape != ObstacleShape::Polygon) return 0;
    double nx[kMax], ny[kMax];
    count = o.polygon->faces_over(p[0], p[1], t[0], t[1], reach, kCornerSlack * h, nx, ny,
                                  distances, max);
    for (int f = 0; f < count; ++f) normals[f] = Vec<D>(nx[f], ny[f]);
  } else {
    if (o.shape != ObstacleShape::Mesh || !o.distance) return 0;
    Point3 m[kMax];
    count = o.distance->mesh().faces_over({p[0], p[1], p[2]}, {t[0], t[1], t[2]}, reach,
                                          kCornerSlack * h, m, distances, max);
    for (int f = 0; f < count; ++f) normals[f] = Vec<D>(m[f][0], m[f][1], m[f][2]);
  }
  for (int f = 0; f < count; ++f) normals[f] = world_direction(o, normals[f]);
  return count;
}

}  // namespace sablier
