// The compatible transfer next to fixed solids thinner than the grid
// resolves (docs/scenes.md, "Thin solids"; docs/method.md).
#include <cmath>

#include "physics/simulation.hpp"

namespace sablier {

template <int D>
void Simulation<D>::find_thin_solids() {
  // Fixed solids thinner than the cells resolve (not rigid bodies): the
  // grains next to them keep to the nodes on their own side (the
  // compatible transfer, corners_across), which needs each node's distance
  // to them and its normal: computed once for solids that stand still, at
  // each new time for solids that move or are taken away.
  for (std::size_t k = 0; k < scene_.obstacles.size(); ++k) {
    const ObstacleConfig& c = scene_.obstacles[k];
    if (!(c.thin > 0.0) || c.dynamic()) continue;
    thin_index_.push_back(k);
    const bool driven = moves_into_sand(obstacles_[k]) || std::isfinite(c.until);
    thin_driven_.push_back(driven ? 1 : 0);
    thin_move_ = thin_move_ || driven;
  }
  if (thin_index_.empty()) return;
  thin_node_distance_.assign(grid_.node_count(), 0.0);
  thin_node_normal_.assign(grid_.node_count(), Vec<D>::Zero());
  thin_node_driven_.assign(grid_.node_count(), 0);
  place_thin_solids(time_);
}

// The thin solids where they are at time t, and the nodes' distances to
// them (kept while t and the solids stay the same).
template <int D>
void Simulation<D>::place_thin_solids(double t) {
  if (thin_index_.empty() || (thin_placed_ && (!thin_move_ || t == thin_time_))) return;
  thin_solids_.clear();
  for (std::size_t k : thin_index_) thin_solids_.push_back(at_time(obstacles_[k], t));
  const std::int64_t nodes = grid_.node_count();
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nodes; ++i) {
    const auto nc = grid_.node_coords(i);
    Vec<D> x;
    for (int a = 0; a < D; ++a) x[a] = nc[a] * grid_.h();
    int which = 0;
    thin_node_distance_[i] = obstacle_distance(thin_solids_, x, &thin_node_normal_[i], &which);
    thin_node_driven_[i] = thin_driven_[static_cast<std::size_t>(which)];
  }
  thin_placed_ = true;
  thin_time_ = t;
}

// The compatible transfer (Hu et al. 2018, CPIC): next to a fixed solid
// thinner than the cells resolve, a grain's shape functions keep only the
// corners of its cell on its own side of the solid, renormalised to a
// partition of unity (N_a / S, and gradients (grad N_a - N_a grad S / S) / S
// over the kept corners, whose sum stays zero), so that its mass, momentum,
// stress couplings and velocity stay on its side: with the nodes beyond
// such a wall in the grain's stencil, the sand on one face felt the other,
// and its grains were carried into the wall and packed on it
// (docs/scenes.md, "Thin solids"). A corner is across when it lies inside
// the solid, or when the nearest faces of the grain and of the corner face
// opposite ways (normals' dot product negative) and the solid-free balls
// about the two (their distances) do not cover the segment between them.
template <int D>
std::uint8_t Simulation<D>::corners_across(const Vec<D>& x, std::int64_t base) const {
  constexpr int NC = ipow(2, D);
  const double h = grid_.h();
  const auto corner = grid_.corner_offsets();
  bool near = false;  // a corner within reach of a thin solid
  for (int a = 0; a < NC; ++a) near = near || thin_node_distance_[base + corner[a]] < 2.0 * h;
  if (!near) return 0;
  Vec<D> n;
  const double d = obstacle_distance(thin_solids_, x, &n);
  if (!(d >= 0.0)) return 0;  // inside: put back after the step
  // As stencil_of has it: x in cells from the base node.
  const Vec<D> local = place_in_cell(x, grid_.node_coords(base));
  const Q1Stencil<D> s = q1_stencil<D>(local, h);
  double S = 0.0;  // the kept corners' weight
  unsigned across = 0;
  for (int a = 0; a < NC; ++a) {
    const std::int64_t node = base + corner[a];
    const double dn = thin_node_distance_[node];
    const auto nc = grid_.node_coords(node);
    Vec<D> xa;
    for (int k = 0; k < D; ++k) xa[k] = nc[k] * h;
    // Across: inside the solid, or beyond it by the normals. A node on the
    // solid's face (a face on a node plane, whose distance rounds either
    // way) is judged by the normals like a node outside. So is one less
    // than half a cell inside a driven solid (deeper, its row is left out,
    // transfer.cpp): on the side of the face nearest to it, it carries the
    // solid's push on the sand that touches it (taken as across, plough3d's
    // blade, one cell thick, pushed with 12.9 and 16.9 N against 13.2 and
    // 17.9 N, and 13.5 and 18.8 N for a blade two cells thick). Not next
    // to a still one: there the sand flowing along a thin wall packed
    // against it under the grains' moves (largest phi 1.02 against 0.94;
    // docs/method.md).
    const double deep = thin_node_driven_[node] ? -0.5 * h : -1e-9 * h;
    if (dn < deep ||
        (thin_node_normal_[node].dot(n) < 0.0 && (xa - x).norm() > d + std::max(dn, 0.0)))
      across |= 1u << a;
    else
      S += s.w[a];
  }
  // Kept corners carrying less than half the weight leave the stencil
  // whole: renormalised, their few nodes' velocities and gradients are
  // magnified by 1 / S (measured on a funnel of a 3 mm shell at 1 cm
  // cells: with 0.05 some grains reached 21.7 m/s, with 0.25 2.7 m/s, with
  // 0.5 at most 1.9 m/s, the free fall's).
  constexpr double kLeastOwnWeight = 0.5;
  if (!(S >= kLeastOwnWeight)) return 0;
  return static_cast<std::uint8_t>(across);
}

// Every grain's corners across at its present position (the grains
// outside the box, which the sort drops and the decompaction leaves alone,
// get 0).
template <int D>
void Simulation<D>::find_own_sides() {
  if (thin_solids_.empty()) return;
  const std::int64_t n = static_cast<std::int64_t>(particles_.size());
  const double h = grid_.h();
  Vec<D> upper;
  for (int a = 0; a < D; ++a) upper[a] = grid_.cells()[a] * h;
  across_.resize(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const Vec<D>& x = particles_.position[p];
    bool inside = true;
    for (int a = 0; a < D; ++a) inside = inside && x[a] >= 0.0 && x[a] <= upper[a];
    across_[p] = inside ? corners_across(x, grid_.cell_base_node(grid_.cell_of(x))) : 0;
  }
}

#define SABLIER_INSTANTIATE(D)                                                            \
  template void Simulation<D>::find_thin_solids();                                        \
  template std::uint8_t Simulation<D>::corners_across(const Vec<D>&, std::int64_t) const; \
  template void Simulation<D>::find_own_sides();                                          \
  template void Simulation<D>::place_thin_solids(double);
SABLIER_INSTANTIATE(2)
SABLIER_INSTANTIATE(3)
#undef SABLIER_INSTANTIATE

}  // namespace sablier
