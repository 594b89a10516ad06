// Edge-on-edge contacts in 3D (docs/method.md, "Frictional obstacles"): a
// rigid box or mesh meets the other solids by its corners or vertices
// (transfer.cpp), which miss two edges crossing with no corner in contact
// (a box lying across a ridge, a plank across a beam). Where an edge of
// such a body crosses an edge of a fixed box or mesh or of another such
// body, the two edges' closest points get a contact row like a corner's.
// A fixed cylinder has no edges: its rims' points and axis balls meet a
// body's faces (cylinder_points), and a body's edges meet it where they
// come nearest it (edges_against_cylinder).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "core/mesh.hpp"
#include "physics/obstacle.hpp"

namespace sablier {

// The closest points p = p0 + s (p1 - p0) and q = q0 + t (q1 - q0) of two
// segments, s and t in [0, 1] (Ericson, Real-Time Collision Detection,
// 2005, 5.1.9): the lines' closest points, clamped to one segment and then
// to the other. Parallel segments get one closest pair of the many (s = 0
// where it can be).
struct SegmentPair {
  double s = 0.0, t = 0.0;
  Vec<3> p, q;
};

inline SegmentPair closest_points(const Vec<3>& p0, const Vec<3>& p1, const Vec<3>& q0,
                                  const Vec<3>& q1) {
  const Vec<3> d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  SegmentPair out;
  if (a > 0.0 && e > 0.0) {
    const double b = d1.dot(d2), c = d1.dot(r);
    const double denom = a * e - b * b;  // |d1 x d2|^2: zero when parallel
    out.s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
    out.t = (b * out.s + f) / e;
    if (out.t < 0.0) {
      out.t = 0.0;
      out.s = std::clamp(-c / a, 0.0, 1.0);
    } else if (out.t > 1.0) {
      out.t = 1.0;
      out.s = std::clamp((b - c) / a, 0.0, 1.0);
    }
  } else if (a > 0.0) {  // q is a point
    out.s = std::clamp(-d1.dot(r) / a, 0.0, 1.0);
  } else if (e > 0.0) {  // p is a point
    out.t = std::clamp(f / e, 0.0, 1.0);
  }
  out.p = p0 + out.s * d1;
  out.q = q0 + out.t * d2;
  return out;
}

// Where a solid's distance along a segment stays within kFlatReach cells
// of its least (and its normal the same), the segment lies along the
// solid's face: contacts go at both ends of that stretch (least_stretch).
inline constexpr double kFlatReach = 1e-4;

// An edge of a solid where it stands, with its normal cone: the outward
// normals of its two faces span the arc about `bisector` (unit, across the
// edge) of half-angle acos(cos_half). `index` numbers it among the solid's
// edges (for the row's warm start).
struct SolidEdge {
  Vec<3> from, to, bisector;
  double cos_half;
  int index;
};

// How many edges a box (12) or a mesh (its convex ones) has; 0 otherwise.
inline int edge_count(const Obstacle<3>& o) {
  if (o.shape == ObstacleShape::Box) return 12;
  if (o.shape == ObstacleShape::Mesh && o.edges) return static_cast<int>(o.edges->size());
  return 0;
}

// Corner c of a box (bit k set: the upper side on axis k, as body_points
// numbers them), fixed (axis-aligned, from `a` to `b`) or posed (a body, or
// a turned fixed box).
inline Vec<3> box_corner(const Obstacle<3>& o, int c) {
  Vec<3> x;
  if (!o.posed) {
    for (int k = 0; k < 3; ++k) x[k] = (c >> k & 1) ? o.b[k] : o.a[k];
    return x;
  }
  for (int k = 0; k < 3; ++k) x[k] = (c >> k & 1) ? o.b[k] : -o.b[k];
  return o.a + o.rotation * x;
}

// The edges of o (a box's 12, a mesh's convex ones) that come within
// `reach` of `centre`, into `out` (emptied first).
inline void solid_edges(const Obstacle<3>& o, const Vec<3>& centre, double reach,
                        std::vector<SolidEdge>& out) {
  out.clear();
  const auto keep = [&](const SolidEdge& e) {
    const SegmentPair c = closest_points(e.from, e.to, centre, centre);
    if ((c.p - centre).squaredNorm() < reach * reach) out.push_back(e);
  };
  if (o.shape == ObstacleShape::Box) {
    // Edge k * 4 + i along axis k joins corner c (bit k clear) to c + 2^k;
    // its faces are the sides of the other two axes that c's bits give.
    const double half = std::sqrt(0.5);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 4; ++i) {
        const int low = i & ((1 << k) - 1), high = (i >> k) << (k + 1);
        const int c = high | low;
        Vec<3> out_dir = Vec<3>::Zero();
        for (int j = 0; j < 3; ++j)
          if (j != k) out_dir[j] = (c >> j & 1) ? half : -half;
        keep({box_corner(o, c), box_corner(o, c | 1 << k), o.rotation * out_dir, half, k * 4 + i});
      }
  } else if (o.shape == ObstacleShape::Mesh && o.edges) {
    const auto place = [&o](const Point3& p) {
      const Vec<3> x(p[0], p[1], p[2]);
      return o.posed ? Vec<3>(o.a + o.rotation * (x - o.b)) : Vec<3>(x + o.a);
    };
    const auto& edges = *o.edges;
    for (std::size_t k = 0; k < edges.size(); ++k) {
      const FeatureEdge& e = edges[k];
      const Vec<3> b(e.bisector[0], e.bisector[1], e.bisector[2]);
      keep({place(e.from), place(e.to), o.rotation * b, e.cos_half, static_cast<int>(k)});
    }
  }
}

// How far direction n (unit, across the edge) lies within the edge's
// normal cone widened by kConeSlack: n . bisector - cos(half + slack),
// negative outside. The slack keeps the rows of a face resting flat on
// another (n on the cones' rims) when round-off or a slight tilt puts n
// just outside.
inline double cone_margin(const SolidEdge& e, const Vec<3>& n) {
  constexpr double kConeSlack = 0.01;  // rad
  const double sin_half = std::sqrt(std::max(0.0, 1.0 - e.cos_half * e.cos_half));
  return n.dot(e.bisector) - (e.cos_half * std::cos(kConeSlack) - sin_half * std::sin(kConeSlack));
}

// An edge of a body crossing an edge of another solid: the closest points,
// the unit normal from the body to the solid, the separation along it (m,
// negative where they overlap), and the pair's number (the body's edge
// index times the solid's edge count, plus the solid's edge index).
struct EdgeContact {
  Vec<3> on_body, on_solid, normal;
  double separation;
  std::int64_t pair;
};

// The pair of edges as a contact, when it is one: the closest points
// strictly inside both edges (an end is a corner, which has its own rows),
// the edges not parallel, and the separation along the normal n = +-(e1 x
// e2) within a cell either way (further inside is not a contact to
// resolve). The sign: the one for which n leaves the body's edge within
// its normal cone and -n leaves the solid's within its own, when one does
// (the edges can touch there: the plane across both separates the solids
// near them; a negative separation is then an overlap to stop). When
// neither does, the edges cross only where a face of one passes the
// other's edge (the far lower edge of a plank rolling onto a beam, not yet
// down): passing through each other would still bring the solids into each
// other, so n keeps the edges on the sides they are on.
inline bool edge_contact(const SolidEdge& body, const SolidEdge& solid, double h,
                         EdgeContact* out) {
  constexpr double kInside = 1e-6;    // of the edge's length, from either end
  constexpr double kParallel = 1e-3;  // sine of the angle between the edges
  const SegmentPair c = closest_points(body.from, body.to, solid.from, solid.to);
  const auto inside = [](double s) { return s > kInside && s < 1.0 - kInside; };
  if (!inside(c.s) || !inside(c.t)) return false;
  const Vec<3> e1 = body.to - body.from, e2 = solid.to - solid.from;
  const Vec<3> axis = e1.cross(e2);
  const double len = axis.norm();
  if (!(len > kParallel * e1.norm() * e2.norm())) return false;
  Vec<3> n = axis / len;
  const double plus = std::min(cone_margin(body, n), cone_margin(solid, -n));
  const double minus = std::min(cone_margin(body, -n), cone_margin(solid, n));
  if (plus >= 0.0 || minus >= 0.0) {
    if (minus > plus) n = -n;
  } else {
    const double along = (c.q - c.p).dot(n);
    if (along == 0.0) return false;
    if (along < 0.0) n = -n;
  }
  const double separation = (c.q - c.p).dot(n);
  if (!(std::abs(separation) < h)) return false;
  *out = {c.p, c.q, n, separation, 0};
  return true;
}

// Reused between calls: the edges near each other.
struct EdgeScratch {
  std::vector<SolidEdge> body, solid;
};

// Where a distance f(s, &normal), convex in s on [0, 1] (a convex solid's
// signed distance along a segment), is least: the ends [s0, s1] of the
// stretch on which it stays within `flat` of its least and its normal stays
// that of the stretch's middle (one point, s0 == s1, unless the segment
// lies along a face). A golden-section search finds the least, bisections
// the stretch's ends (to 1e-12 of the segment): first by the distance,
// then from its middle by the distance and the normal.
template <class F>
inline std::pair<double, double> least_stretch(const F& f, double flat) {
  constexpr double kGolden = 0.6180339887498949;
  constexpr double kSmall = 1e-12;
  Vec<3> n;
  double a = 0.0, b = 1.0;
  double s1 = b - kGolden * (b - a), s2 = a + kGolden * (b - a);
  double f1 = f(s1, &n), f2 = f(s2, &n);
  while (b - a > kSmall) {
    if (f1 <= f2) {
      b = s2;
      s2 = s1;
      f2 = f1;
      s1 = b - kGolden * (b - a);
      f1 = f(s1, &n);
    } else {
      a = s1;
      s1 = s2;
      f1 = f2;
      s2 = a + kGolden * (b - a);
      f2 = f(s2, &n);
    }
  }
  const double best = 0.5 * (a + b);
  const double least = f(best, &n);
  // Going from `from` (where near holds) towards `end`: the farthest s
  // before near fails (bisection; near holds on an interval about `from`).
  const auto end_towards = [&](double from, double end, const auto& near) {
    if (near(end)) return end;
    double in = from, off = end;
    while (std::abs(off - in) > kSmall) {
      const double mid = 0.5 * (in + off);
      (near(mid) ? in : off) = mid;
    }
    return in;
  };
  const auto low = [&](double s) { return f(s, &n) <= least + flat; };
  // The least may sit at the stretch's end, where the normal turns (a
  // face's edge): the normal to keep is the one at the stretch's middle.
  const double mid = 0.5 * (end_towards(best, 0.0, low) + end_towards(best, 1.0, low));
  Vec<3> n_mid;
  f(mid, &n_mid);
  const auto on_face = [&](double s) { return low(s) && n.dot(n_mid) >= 1.0 - 1e-12; };
  return {end_towards(mid, 0.0, on_face), end_towards(mid, 1.0, on_face)};
}

// Where the edges of body o (a box's, a mesh's convex ones) come within a
// cell of a fixed cylinder q away from their ends (a box turned edge-down
// across a post's top disk, its corners beyond the post, which its rim's
// points would let sink between them): the ends of the stretch of the edge
// nearest q (least_stretch on q's distance, convex along the edge as q is
// convex; two points where the edge lies along q's disk or side, else one),
// each strictly inside the edge (an end is a corner, with its own rows).
// Normal from the body to q (q's outward normal reversed), the distance as
// separation, pair = the edge's index times 2 plus which end.
inline void edges_against_cylinder(const Obstacle<3>& o, const Obstacle<3>& q, double h,
                                   EdgeScratch& w, std::vector<EdgeContact>& out) {
  out.clear();
  if (q.gone || q.shape != ObstacleShape::Cylinder || edge_count(o) == 0) return;
  Vec<3> centre = q.a;
  centre[2] += 0.5 * q.height;
  solid_edges(o, centre, std::hypot(q.radius, 0.5 * q.height) + h, w.body);
  constexpr double kInside = 1e-6;  // of the edge's length, from either end
  for (const SolidEdge& e : w.body) {
    const auto distance = [&](double s, Vec<3>* n) {
      return signed_distance(q, Vec<3>(e.from + s * (e.to - e.from)), n);
    };
    const auto [s0, s1] = least_stretch(distance, kFlatReach * h);
    for (int end = 0; end < 2; ++end) {
      const double s = end == 0 ? s0 : s1;
      if (end == 1 && s1 == s0) break;
      if (!(s > kInside && s < 1.0 - kInside)) continue;
      Vec<3> n;
      const double d = distance(s, &n);
      if (!(d < h)) continue;
      const Vec<3> x = e.from + s * (e.to - e.from);
      out.push_back({x, Vec<3>(x - d * n), Vec<3>(-n), d, std::int64_t(e.index) * 2 + end});
    }
  }
}

// Points on each rim circle of a fixed cylinder that meet rigid bodies'
// faces: a body tilted on a post's rim sinks at most r (1 - cos(pi /
// kRimPoints)), 1.9% of the radius, between two of them.
inline constexpr int kRimPoints = 16;

// The points by which a fixed cylinder q (its axis upright) meets the faces
// of body o (a box resting on a post narrower than itself, a box pushed
// against a post's side), appended to `out`: kRimPoints points on each rim
// circle, reaching nothing further, and last the centres of the largest
// balls inside the cylinder on its axis where it comes nearest the body
// (both ends of the stretch along a face parallel to the axis, else one),
// reaching those balls' radius, min(radius, height / 2), further: a ball is
// part of the cylinder, so its row only holds the body off the solid. None
// when the body's centre is farther than its bounding radius and a cell.
inline void cylinder_points(const Obstacle<3>& q, const Obstacle<3>& o, double h,
                            std::vector<Vec<3>>& out) {
  constexpr double kPi = 3.14159265358979323846;
  Vec<3> n;
  if (signed_distance(q, o.a, &n) >= bounding_radius(o) + h) return;  // too far to touch
  for (int rim = 0; rim < 2; ++rim)
    for (int k = 0; k < kRimPoints; ++k) {
      const double angle = 2.0 * kPi * k / kRimPoints;
      Vec<3> x = q.a;
      x[0] += q.radius * std::cos(angle);
      x[1] += q.radius * std::sin(angle);
      x[2] += rim * q.height;
      out.push_back(x);
    }
  // The body's distance is convex along the axis for a convex body (a
  // local nearest for a mesh).
  const double r = std::min(q.radius, 0.5 * q.height);
  const double lo = q.a[2] + r, hi = q.a[2] + q.height - r;
  const auto distance = [&](double t, Vec<3>* normal) {
    Vec<3> x = q.a;
    x[2] = lo + t * (hi - lo);
    return signed_distance(o, x, normal);
  };
  const auto [t0, t1] = least_stretch(distance, kFlatReach * h);
  for (const double t : {t0, t1}) {
    Vec<3> centre = q.a;
    centre[2] = lo + t * (hi - lo);
    out.push_back(centre);
    if (t1 == t0) break;  // one point: no second row on it
  }
}

// The crossings of body o's edges with solid q's within h (q a fixed box
// or mesh or another body; no rows for other shapes), into `out`.
inline void edge_contacts(const Obstacle<3>& o, const Obstacle<3>& q, double h, EdgeScratch& w,
                          std::vector<EdgeContact>& out) {
  out.clear();
  if (q.gone || edge_count(o) == 0 || edge_count(q) == 0) return;
  solid_edges(q, o.a, bounding_radius(o) + h, w.solid);
  if (w.solid.empty()) return;
  // The body's edges near the box around those.
  Vec<3> lo = Vec<3>::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const SolidEdge& e : w.solid) {
    lo = lo.cwiseMin(e.from).cwiseMin(e.to);
    hi = hi.cwiseMax(e.from).cwiseMax(e.to);
  }
  solid_edges(o, 0.5 * (lo + hi), 0.5 * (hi - lo).norm() + h, w.body);
  const std::int64_t count = edge_count(q);
  for (const SolidEdge& b : w.body)
    for (const SolidEdge& s : w.solid) {
      // Segments whose bounding spheres are over a cell apart cannot touch.
      const double r = 0.5 * ((b.to - b.from).norm() + (s.to - s.from).norm()) + h;
      if ((0.5 * (b.from + b.to - s.from - s.to)).squaredNorm() >= r * r) continue;
      EdgeContact c;
      if (!edge_contact(b, s, h, &c)) continue;
      c.pair = b.index * count + s.index;
      out.push_back(c);
    }
}

}  // namespace sablier
