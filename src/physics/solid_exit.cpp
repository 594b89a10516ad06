// Grains put back out of solids (docs/method.md, "Frictional obstacles",
// "Volume"): after advection (grid_to_particles.cpp) and the decompaction's moves
// (decompaction.cpp), a grain inside a solid goes back outside it, the
// box's walls permitting and on the side it came from.
#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/simulation.hpp"

namespace sablier {

// Whether a grain beyond the box's face (axis, side) at x leaves: the face
// is free, or x is within one of its openings.
template <int D>
bool Simulation<D>::leaves_through_free_face(int axis, int side, const Vec<D>& x) const {
  const int face = 2 * axis + side;
  if (scene_.boundary.faces[face] == BoundaryType::Free) return true;
  for (const Opening& o : scene_.boundary.openings) {
    if (o.face != face) continue;
    bool within = true;
    for (int a = 0; a < D; ++a)
      if (a != axis) within &= x[a] >= o.min[a] && x[a] <= o.max[a];
    if (within) return true;
  }
  return false;
}

// A point the domain keeps: inside the box, or beyond a free face or an
// opening (where grains leave).
template <int D>
bool Simulation<D>::kept_by_walls(const Vec<D>& x) const {
  const auto& cells = grid_.cells();
  for (int a = 0; a < D; ++a) {
    if (x[a] < 0.0 && !leaves_through_free_face(a, 0, x)) return false;
    if (x[a] > cells[a] * grid_.h() && !leaves_through_free_face(a, 1, x)) return false;
  }
  return true;
}

// A grain inside a solid goes back just outside it, along the nearest
// surface's normal; where that is beyond a wall of the box (a solid whose
// face lies on the wall: a blade sliding on the floor would push the grains
// it meets out through the floor), along the shortest of the exits in the
// directions of the box's axes and of the solid's own, that the walls keep.
// Each exit is found by doubling a step from the distance to the surface
// until outside every solid, then bisecting. Without any, the grain stays
// where the normal puts it, inside the box. Given where the grain came from
// this step (`from`, outside the solids), a grain whose path crossed a part
// thinner than its step (the tip of a wedge) goes back to where the path
// entered: one that ended inside with its nearest face turned away from
// where it came from (the normals there and at `from` opposed), or beyond
// the part, on its far side; from there it slides on along the surface
// (below). For a solid that moves, `from` is the grain's
// start carried along with it (transfer_to_particles), so that the path is
// the grain's relative to the solid.
template <int D>
bool Simulation<D>::put_outside_solids(const std::vector<Obstacle<D>>& solids, Vec<D>& x,
                                       const Vec<D>* from, Vec<D>* held, double* clearance) const {
  if (clearance) *clearance = solids.empty() ? std::numeric_limits<double>::infinity() : 0.0;
  if (solids.empty()) return false;
  const double h = grid_.h();
  const auto& cells = grid_.cells();
  const auto inside = [&](const Vec<D>& y) {
    Vec<D> n;
    return obstacle_distance(solids, y, &n) < 0.0;
  };
  Vec<D> normal;
  int which = 0;
  const double depth = -obstacle_distance(solids, x, &normal, &which);
  // Outside, no crossing: no solid within the step's reach.
  if (depth <= 0.0 && (from == nullptr || -depth >= (x - *from).norm())) {
    // x's distance bounds it after a move where every solid's distance is
    // exact (1-Lipschitz); a mesh's is sampled and interpolated.
    bool exact = true;
    for (const Obstacle<D>& o : solids) exact = exact && (o.gone || o.shape != ObstacleShape::Mesh);
    if (clearance && exact) *clearance = -depth;
    return false;
  }
  Vec<D> from_normal = Vec<D>::Zero();
  int from_which = -1;
  const double start = from ? obstacle_distance(solids, *from, &from_normal, &from_which) : -1.0;
  // The last point outside before the first inside on the path from
  // `from`, sampled every h / 64 (a part thinner than that may be missed)
  // and bisected; false when the path stays outside.
  const auto entry = [&](Vec<D>& at) {
    const Vec<D> a = *from;
    const double length = (x - a).norm();
    if (start < 0.0 || start - depth >= length) return false;  // no solid within reach
    const int samples = std::min(256, 1 + static_cast<int>(std::ceil(64.0 * length / h)));
    for (int k = 1; k <= samples; ++k) {
      double hi = double(k) / samples;
      if (!inside(a + hi * (x - a))) continue;
      double lo = double(k - 1) / samples;
      for (int i = 0; i < 50 && (hi - lo) * length > 1e-7 * h; ++i) {
        const double mid = 0.5 * (lo + hi);
        (inside(a + mid * (x - a)) ? hi : lo) = mid;
      }
      at = a + lo * (x - a);
      return true;
    }
    return false;
  };
  const bool turned_away = from && start >= 0.0 && from_normal.dot(normal) < 0.0;
  Vec<D> at;
  // Held on the side it came from (through a thin part and out, or into
  // it past its middle): from where its path entered, the rest of its step
  // without the part into the surface there, along the surface as far as
  // the surface goes on flat (its distance unchanged, sampled every h / 64)
  // and no further: a grain going round a sharp convex edge (the chord of
  // its step cuts the edge) reaches the edge and rounds it at the next
  // step; stopped where its path entered, it stayed there step after step
  // and the sand clumped at the edge (docs/method.md). Its velocity loses
  // the part into that surface (`held`, its normal).
  if (turned_away && entry(at) && kept_by_walls(at)) {
    Vec<D> n_at;
    int w_at = 0;
    const double d_at = obstacle_distance(solids, at, &n_at, &w_at);
    Vec<D> rest = x - at;
    rest -= rest.dot(n_at) * n_at;
    // Only round one solid's edge: between two solids (the path from one
    // to the other, their tips meeting as in a closed V) the grain stays
    // where its path entered.
    const double length = from_which == which ? rest.norm() : 0.0;
    double t_end = 0.0;  // the slide's end, as a fraction of rest
    if (length > 0.0) {
      const int samples = std::min(256, 1 + static_cast<int>(std::ceil(64.0 * length / h)));
      for (int k = 1; k <= samples; ++k) {
        const Vec<D> y = at + (double(k) / samples) * rest;
        Vec<D> n;
        const double d = obstacle_distance(solids, y, &n);
        if (d < 0.0 || d > d_at + 1e-6 * h || !kept_by_walls(y)) break;
        t_end = double(k) / samples;
      }
      // If another solid lies within h / 8 of the slide's end (two solids'
      // tips that meet, as in a closed V, or a slit narrower than that),
      // the grain stops h / 4 short of it: from there its next step would
      // pass between them.
      {
        const Vec<D> e = at + t_end * rest;
        double gap = 1e300;
        for (std::size_t o = 0; o < solids.size(); ++o) {
          if (static_cast<int>(o) == w_at) continue;
          Vec<D> n;
          gap = std::min(gap, signed_distance(solids[o], e, &n));
        }
        if (gap < 0.125 * h) t_end = std::max(0.0, t_end - 0.25 * h / length);
      }
    }
    x = at + t_end * rest;
    if (held) *held = n_at;
    return true;
  }
  if (depth <= 0.0) return false;
  const Vec<D> out = x + (depth + 1e-6 * h) * normal;
  if (kept_by_walls(out)) {
    x = out;
    return false;
  }
  double reach = 0.0;  // no exit is further than the box's diagonal
  for (int a = 0; a < D; ++a) reach += (cells[a] * h) * (cells[a] * h);
  reach = std::sqrt(reach);
  const auto outside = [&](double t, const Vec<D>& d) { return !inside(x + t * d); };
  double best = reach;
  Vec<D> exit = out;
  bool found = false;
  const auto try_direction = [&](const Vec<D>& d) {
    double in = 0.0, t = depth;
    while (!outside(t, d)) {
      in = t;
      t *= 2.0;
      if (t >= best) return;
    }
    for (int i = 0; i < 40 && t - in > 1e-7 * h; ++i) {
      const double mid = 0.5 * (in + t);
      (outside(mid, d) ? t : in) = mid;
    }
    const Vec<D> z = x + (t + 1e-6 * h) * d;
    if (t < best && kept_by_walls(z) && outside(t + 1e-6 * h, d)) {
      best = t;
      exit = z;
      found = true;
    }
  };
  const Obstacle<D>& solid = solids[which];
  for (int a = 0; a < D; ++a)
    for (const double sign : {1.0, -1.0}) {
      try_direction(sign * Vec<D>::Unit(a));
      if (solid.posed || solid.dynamic) try_direction(sign * solid.rotation.col(a));
    }
  if (!found)
    for (int a = 0; a < D; ++a) exit[a] = std::clamp(exit[a], 1e-6 * h, cells[a] * h - 1e-6 * h);
  x = exit;
  return false;
}

// A grain's clearance after advection bounds its distance to the solids
// after its moves, each taking its length off: a signed distance that is
// exact changes by no more than the point moves. Where the bound left at y
// exceeds the move, put_outside_solids would find y outside every solid
// and no solid within the move's reach, and leave it: the query is
// skipped. The slack (a billionth of a cell) covers the distances'
// rounding, so that the answer is the query's, bit for bit. hourglass2d,
// whose two polygons every grain queried about seven times per step (at
// advection and at each move), spent a fifth of its samples on them.
template <int D>
void Simulation<D>::move_outside_solids(const std::vector<Obstacle<D>>& solids, std::int64_t p,
                                        const Vec<D>& x, Vec<D>& y, double* clearance_at_y) const {
  const double step = (y - x).norm();
  if (clear_of_solids(p, step)) {
    *clearance_at_y = clearance_[p] - step;
    return;
  }
  put_outside_solids(solids, y, &x, nullptr, clearance_at_y);
}

#define SABLIER_INSTANTIATE(D)                                                                    \
  template bool Simulation<D>::kept_by_walls(const Vec<D>&) const;                                \
  template bool Simulation<D>::leaves_through_free_face(int, int, const Vec<D>&) const;           \
  template bool Simulation<D>::put_outside_solids(const std::vector<Obstacle<D>>&, Vec<D>&,       \
                                                  const Vec<D>*, Vec<D>*, double*) const;         \
  template void Simulation<D>::move_outside_solids(const std::vector<Obstacle<D>>&, std::int64_t, \
                                                   const Vec<D>&, Vec<D>&, double*) const;
SABLIER_INSTANTIATE(2)
SABLIER_INSTANTIATE(3)
#undef SABLIER_INSTANTIATE

}  // namespace sablier
