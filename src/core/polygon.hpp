// A closed polygon as a 2D solid: its exact signed distance and outward
// normal, for polygonal obstacles (physics/obstacle.hpp). Inside by the
// nonzero winding rule, so either orientation fills the same.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace sablier {

// One edge's share of the winding number around a point at height y (Sunday's
// crossing rule): the edge runs from height ay to by, and `side` is the cross
// product of the edge with the vector from its start to the point.
inline int winding_crossing(double ay, double by, double y, double side) {
  if (ay <= y) return by > y && side > 0.0 ? 1 : 0;  // upward, the point left of the edge
  return by <= y && side < 0.0 ? -1 : 0;             // downward, the point right of it
}

// Winding number of the closed polygon with corners `v` (any points p with
// p[0], p[1]) around (x, y): nonzero inside, for either orientation
// (Sunday's crossing rule; no trigonometry).
template <class Points>
int winding_number(const Points& v, double x, double y) {
  int w = 0;
  for (std::size_t i = 0, n = v.size(); i < n; ++i) {
    const auto& a = v[i];
    const auto& b = v[(i + 1) % n];
    const double side = (b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1]);
    w += winding_crossing(a[1], b[1], y, side);
  }
  return w;
}

class SolidPolygon {
 public:
  using Point2 = std::array<double, 2>;

  explicit SolidPolygon(std::vector<Point2> corners) : v_(std::move(corners)) {
    lo_ = hi_ = v_.front();
    for (const Point2& p : v_)
      for (int a = 0; a < 2; ++a) lo_[a] = std::min(lo_[a], p[a]), hi_[a] = std::max(hi_[a], p[a]);
    // Each edge's start, its end's y, direction and squared length, computed
    // once as signed_distance computed them per call (the same bits): the
    // grains ask for their distance to the polygons several times per step.
    for (std::size_t i = 0, n = v_.size(); i < n; ++i) {
      const Point2& a = v_[i];
      const Point2& b = v_[(i + 1) % n];
      const double ex = b[0] - a[0], ey = b[1] - a[1];
      edges_.push_back({a[0], a[1], b[1], ex, ey, ex * ex + ey * ey});
    }
    outward_ = orientation() > 0.0 ? 1.0 : -1.0;
    // A concave corner turns against the orientation (the two edges' cross
    // product of the other sign, beyond a part in 1e9 of their lengths).
    for (std::size_t i = 0, n = edges_.size(); i < n; ++i) {
      const Edge &e = edges_[i], &f = edges_[(i + 1) % n];
      const double turn = outward_ * (e.ex * f.ey - e.ey * f.ex);
      concave_ = concave_ || turn < -1e-9 * std::sqrt(e.len2 * f.len2);
    }
  }

  // Winding number around (x, y): nonzero inside.
  int winding(double x, double y) const { return winding_number(v_, x, y); }

  // Signed distance of (x, y) to the boundary (m; negative inside) and the
  // outward unit normal there: from the nearest boundary point towards
  // (x, y) outside, away from (x, y) inside. On the boundary itself, the
  // nearest edge's outward normal. O(corners); allocates nothing.
  double signed_distance(double x, double y, double* nx, double* ny) const {
    double best = 1e300, qx = x, qy = y;
    std::size_t edge = 0;
    int wind = 0;  // winding_number's, edge by edge
    for (std::size_t i = 0, n = edges_.size(); i < n; ++i) {
      const Edge& e = edges_[i];
      const double ex = e.ex, ey = e.ey, len2 = e.len2;
      wind += winding_crossing(e.ay, e.by, y, ex * (y - e.ay) - (x - e.ax) * ey);
      // A repeated corner: its point is the neighbouring edges' end too,
      // and it has no normal of its own.
      if (!(len2 > 0.0)) continue;
      const double t = std::clamp(((x - e.ax) * ex + (y - e.ay) * ey) / len2, 0.0, 1.0);
      const double px = e.ax + t * ex, py = e.ay + t * ey;
      const double d2 = (x - px) * (x - px) + (y - py) * (y - py);
      if (d2 < best) best = d2, qx = px, qy = py, edge = i;
    }
    const bool in = wind != 0;
    const double dist = std::sqrt(best);
    if (dist > 0.0) {
      const double s = in ? -1.0 : 1.0;
      *nx = s * (x - qx) / dist;
      *ny = s * (y - qy) / dist;
    } else {
      const Point2& a = v_[edge];
      const Point2& b = v_[(edge + 1) % v_.size()];
      const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
      // The edge's right-hand normal points out of a counter-clockwise
      // polygon (outward_, the orientation's sign, kept at construction).
      *nx = outward_ * ey / len;
      *ny = -outward_ * ex / len;
    }
    return in ? -dist : dist;
  }

  // Edge i's outward unit normal (the corners' orientation decides which
  // side is out; zero for an edge of zero length).
  Point2 edge_normal(std::size_t i) const {
    const Edge& e = edges_[i];
    if (!(e.len2 > 0.0)) return {0.0, 0.0};
    const double len = std::sqrt(e.len2);
    return {outward_ * e.ey / len, -outward_ * e.ex / len};
  }

  // Corner i's direction into the solid: minus the sum of the outward
  // normals of the two edges that meet there.
  Point2 corner_inward(std::size_t i) const {
    const std::size_t n = edges_.size();
    const Point2 a = edge_normal((i + n - 1) % n), b = edge_normal(i);
    return {-(a[0] + b[0]), -(a[1] + b[1])};
  }

  // Where (x, y) lies within `slack` of the boundary near a corner, the
  // normal of the polygon's cone there (its edges within `slack` of the
  // point) that follows (tx, ty), as physics/corners.hpp's
  // box_face_towards finds it: the sum of the edges' normals weighted by
  // max(0, n . t), normalised, and the same sum of their lines' signed
  // distances (negative on the inner side). True with those; false where
  // the point is farther, only the nearest edge faces t, or none does
  // (signed_distance's answer then holding).
  bool face_towards(double x, double y, double tx, double ty, double slack, double* distance,
                    double* nx, double* ny) const {
    double nearest2 = 1e300;
    std::size_t nearest = 0;
    for (std::size_t i = 0; i < edges_.size(); ++i) {
      if (!(edges_[i].len2 > 0.0)) continue;  // a repeated corner: no normal of its own
      const double d2 = segment_distance2(i, x, y);
      if (d2 < nearest2) nearest2 = d2, nearest = i;
    }
    if (!(nearest2 <= slack * slack)) return false;
    double sx = 0.0, sy = 0.0, wd = 0.0;
    int faces = 0;
    bool nearest_faces = false;
    for (std::size_t i = 0; i < edges_.size(); ++i) {
      if (!(edges_[i].len2 > 0.0) || !(segment_distance2(i, x, y) <= slack * slack)) continue;
      const Point2 m = edge_normal(i);
      const double w = m[0] * tx + m[1] * ty;
      if (!(w > 0.0)) continue;
      sx += w * m[0];
      sy += w * m[1];
      wd += w * (m[0] * (x - edges_[i].ax) + m[1] * (y - edges_[i].ay));
      ++faces;
      nearest_faces = nearest_faces || i == nearest;
    }
    const double len = std::hypot(sx, sy);
    if (!(len > 0.0) || (faces == 1 && nearest_faces)) return false;
    *nx = sx / len;
    *ny = sy / len;
    *distance = wd / len;
    return true;
  }

  // The edges that lie under (x, y): those onto whose segment the point
  // projects (within a part in 1e9 of its ends), facing it within `reach`
  // (the signed distance to their line in [-slack, reach)), and, where the
  // point lies within `slack` of their line, facing (tx, ty), the
  // direction into the solid the point is a corner of (a corner at a
  // convex corner lies on the line of the edge beyond it too, which faces
  // away from it). Their outward normals (nx, ny) and distances (d), at
  // most `max` of them, one per distinct normal (the nearest line of
  // parallel edges). Near a concave corner both its edges lie under a
  // point, and the point must stay outside both lines (physics/corners.hpp,
  // faces_over); near a convex corner the point lies behind the other
  // edge's line and only one counts. Returns their count.
  int faces_over(double x, double y, double tx, double ty, double reach, double slack, double* nx,
                 double* ny, double* d, int max) const {
    // Outside a convex polygon a point lies over one edge at most, the nearest.
    if (!concave_) return 0;
    int count = 0;
    for (std::size_t i = 0; i < edges_.size(); ++i) {
      const Edge& e = edges_[i];
      if (!(e.len2 > 0.0)) continue;
      const double t = ((x - e.ax) * e.ex + (y - e.ay) * e.ey) / e.len2;
      if (!(t >= -1e-9 && t <= 1.0 + 1e-9)) continue;
      const Point2 m = edge_normal(i);
      const double dist = m[0] * (x - e.ax) + m[1] * (y - e.ay);
      if (!(dist >= -slack && dist < reach)) continue;
      if (std::abs(dist) <= slack && !(m[0] * tx + m[1] * ty > 0.0)) continue;
      int f = 0;
      while (f < count && !(std::abs(nx[f] - m[0]) + std::abs(ny[f] - m[1]) < 1e-9)) ++f;
      if (f < count) {
        d[f] = std::min(d[f], dist);
      } else if (count < max) {
        nx[count] = m[0], ny[count] = m[1], d[count++] = dist;
      }
    }
    return count;
  }

  // Twice the signed area: positive for counter-clockwise corners.
  double orientation() const {
    double a = 0.0;
    for (std::size_t i = 0, n = v_.size(); i < n; ++i)
      a += v_[i][0] * v_[(i + 1) % n][1] - v_[(i + 1) % n][0] * v_[i][1];
    return a;
  }

  const std::vector<Point2>& corners() const { return v_; }
  const Point2& lower() const { return lo_; }
  const Point2& upper() const { return hi_; }

 private:
  // Squared distance from (x, y) to edge i (of nonzero length).
  double segment_distance2(std::size_t i, double x, double y) const {
    const Edge& e = edges_[i];
    const double t = std::clamp(((x - e.ax) * e.ex + (y - e.ay) * e.ey) / e.len2, 0.0, 1.0);
    const double px = e.ax + t * e.ex - x, py = e.ay + t * e.ey - y;
    return px * px + py * py;
  }

  struct Edge {
    double ax, ay, by, ex, ey, len2;  // start corner, end's y, corner to corner, squared length
  };
  std::vector<Point2> v_;
  std::vector<Edge> edges_;
  Point2 lo_{}, hi_{};
  bool concave_ = false;  // some corner is concave: faces_over has something to find
  double outward_ = 1.0;  // +1 for counter-clockwise corners: an edge's right-hand normal is out
};

}  // namespace sablier
