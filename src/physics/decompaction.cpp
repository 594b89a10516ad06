// Grains crowded beyond phi_max moved apart after advection (the default,
// `solver.decompaction = "move"`; docs/method.md, "What the decompaction
// costs"). The MPM transfer lets grains crowd into a node beyond
// phi_max V_j; pushing them apart through the cone problem (k_j < 0,
// `"push"`) adds kinetic energy at every step, so much that the 2D collapse
// does not converge under grid refinement (docs/validation.md, "Known
// limits"). Here the cone problem only clamps (METHOD.md step 5) and the
// grains are moved instead, velocities untouched: each move takes the nodes'
// relative excess e_i = max(0, Phi_i / (phi_max V_i) - 1) and displaces every
// grain by -kMoveRate h^2 grad e (x_p), e interpolated by the Q1 shape
// functions, less any component against the grain's velocity; a grain whose
// move would leave the box or enter an obstacle stays. kMoveRate = 0.3: at
// 0.5 and above the moves overshoot and the grains clump below the grid's
// scale (measured, docs/method.md).
#include <omp.h>

#include <algorithm>

#include "physics/simulation.hpp"

namespace sablier {

namespace {
constexpr double kMoveRate = 0.3;
}  // namespace

template <int D>
double Simulation<D>::move_grains_apart(int moves, double dt) {
  constexpr int NC = ipow(2, D);
  const auto corner = grid_.corner_offsets();
  const double h = grid_.h();
  const std::int64_t n = static_cast<std::int64_t>(particles_.size());
  const std::int64_t nodes = grid_.node_count();
  const std::vector<Obstacle<D>> obstacles_end = obstacles_at(time_ + dt);
  Vec<D> upper;
  for (int a = 0; a < D; ++a) upper[a] = grid_.cells()[a] * h;
  const auto inside = [&upper](const Vec<D>& x) {
    for (int a = 0; a < D; ++a)
      if (!(x[a] > 0.0 && x[a] < upper[a])) return false;
    return true;
  };
  move_lift_.assign(n, 0.0);
  move_excess_.resize(nodes);
  move_base_.resize(n);
  // Node index / top_stride: the node's layer along the last axis (+1).
  const std::int64_t top_stride = grid_.node_stride(D - 1), layers = nodes / top_stride;
  for (int move = 0; move < moves; ++move) {
    // Phi_i at the grains' present positions. Each node adds up its grains in
    // particle order, as one thread scattering them would, so the bits do not
    // depend on the thread count: the grains' cells in parallel, then each
    // thread scans the grains in order and adds only to the nodes of its own
    // layers along the last axis.
#pragma omp parallel for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      const Vec<D>& x = particles_.position[p];  // leaving through a free face: -1
      move_base_[p] = inside(x) ? grid_.cell_base_node(grid_.cell_of(x)) : -1;
    }
    std::fill(move_excess_.begin(), move_excess_.end(), 0.0);
#pragma omp parallel
    {
      const std::int64_t team = omp_get_num_threads(), me = omp_get_thread_num();
      const std::int64_t lo = layers * me / team, hi = layers * (me + 1) / team;
      for (std::int64_t p = 0; p < n; ++p) {
        const std::int64_t base = move_base_[p];
        const std::int64_t layer = base / top_stride;  // the cell's nodes: this layer and the next
        if (base < 0 || layer + 1 < lo || layer >= hi) continue;
        std::int64_t again = 0;  // == base
        const Q1Stencil<D> s = stencil_at(particles_.position[p], &again);
        for (int a = 0; a < NC; ++a) {
          const std::int64_t l = layer + ((a >> (D - 1)) & 1);
          if (l >= lo && l < hi) move_excess_[base + corner[a]] += particles_.volume[p] * s.w[a];
        }
      }
    }
    bool crowded = false;
#pragma omp parallel for schedule(static) reduction(|| : crowded)
    for (std::int64_t i = 0; i < nodes; ++i) {
      if (!(move_excess_[i] > 0.0)) continue;
      const double full = phi_max_ * grid_.node_volume(grid_.node_coords(i));
      move_excess_[i] = std::max(0.0, move_excess_[i] / full - 1.0);
      crowded = crowded || move_excess_[i] > 0.0;
    }
    if (!crowded) break;  // no node over-full: every move would be zero
#pragma omp parallel for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      const std::int64_t base = move_base_[p];
      if (base < 0) continue;  // outside
      bool near = false;       // a corner of its cell is over-full (else the move is zero)
      for (int a = 0; a < NC; ++a) near = near || move_excess_[base + corner[a]] > 0.0;
      if (!near) continue;
      Vec<D>& x = particles_.position[p];
      std::int64_t again = 0;  // == base
      const Q1Stencil<D> s = stencil_at(x, &again);
      Vec<D> grad = Vec<D>::Zero();
      for (int a = 0; a < NC; ++a) grad += move_excess_[base + corner[a]] * s.grad[a];
      if (grad.squaredNorm() == 0.0) continue;
      Vec<D> d = -kMoveRate * h * h * grad;
      // Never against the grain's own velocity: where the flow converges
      // (above an orifice) the excess peaks downstream, and moving grains
      // back up its gradient held the flow back (3D silo, 3 x 3 node
      // orifice: 0.44 kg/s against 0.80 under the pure clamp; with the
      // opposing component removed, 0.79; docs/method.md).
      const Vec<D>& u = particles_.velocity[p];
      const double du = d.dot(u);
      if (du < 0.0) d -= (du / u.squaredNorm()) * u;
      const Vec<D> y = x + d;
      if (!inside(y)) continue;
      if (!obstacles_end.empty()) {
        Vec<D> normal;
        if (obstacle_distance(obstacles_end, y, &normal) < 0.0) continue;
      }
      x = y;
      // Work against gravity: a grain lifted gains m g height.
      move_lift_[p] += std::max(0.0, -rho0_ * mass_volume(p) * gravity_.dot(d));
    }
  }
  double lift = 0.0;  // in particle order
  for (double w : move_lift_) lift += w;
  return lift;
}

template double Simulation<2>::move_grains_apart(int, double);
template double Simulation<3>::move_grains_apart(int, double);

}  // namespace sablier
