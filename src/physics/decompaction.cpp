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
#include <limits>

#include "physics/simulation.hpp"
#include "solver/team.hpp"

namespace sablier {

namespace {
constexpr double kMoveRate = 0.3;

// Calls add(p, mask) for each grain p with a cell (base[p] >= 0) whose
// cell has corners in the calling thread's range of nodes, mask the bits of
// those corners. The ranges split the grains about evenly: the grains are
// sorted by cell at each step's start, and their cells' base nodes rise in
// the same order (the decompaction's moves shuffle them a little, which
// costs balance only), so thread t's range begins at the base node of grain
// n t / team. Splitting the nodes in equal layers instead left one thread
// idle once a collapsing column had spread low. Each thread scans the grains
// in order, so each node adds up its grains in particle order whatever the
// thread count and the split.
template <int D, class Add>
void scatter_by_ranges(const std::vector<std::int64_t>& base,
                       const std::array<std::int64_t, ipow(2, D)>& corner, std::int64_t nodes,
                       Add add) {
  constexpr int NC = ipow(2, D);
  constexpr unsigned kAll = (1u << NC) - 1;
  const std::int64_t n = static_cast<std::int64_t>(base.size());
  const std::int64_t span = corner[NC - 1];  // a cell's last corner from its base node
#pragma omp parallel
  {
    const std::int64_t team = omp_get_num_threads(), me = omp_get_thread_num();
    // The first node of thread t's range (nodes for t = team), rising with t.
    const auto start = [&](std::int64_t t, std::int64_t below) {
      if (t == 0) return std::int64_t(0);
      if (t == team) return nodes;
      std::int64_t k = n * t / team;
      while (k < n && base[k] < 0) ++k;  // grains leaving the box have none
      return std::max(below, k < n ? base[k] : nodes);
    };
    std::int64_t lo = 0;
    for (std::int64_t t = 1; t <= me; ++t) lo = start(t, lo);
    const std::int64_t hi = start(me + 1, lo);
    for (std::int64_t p = 0; p < n; ++p) {
      const std::int64_t b = base[p];
      if (b < 0 || b + span < lo || b >= hi) continue;
      if (b >= lo && b + span < hi) {
        add(p, kAll);
        continue;
      }
      unsigned mask = 0;
      for (int a = 0; a < NC; ++a)
        if (b + corner[a] >= lo && b + corner[a] < hi) mask |= 1u << a;
      add(p, mask);
    }
  }
}

}  // namespace

template <int D>
void Simulation<D>::grain_volume_at_positions() {
  constexpr int NC = ipow(2, D);
  const auto corner = grid_.corner_offsets();
  const double h = grid_.h();
  const std::int64_t n = static_cast<std::int64_t>(particles_.size());
  Vec<D> upper;
  for (int a = 0; a < D; ++a) upper[a] = grid_.cells()[a] * h;
  move_base_.resize(n);
  move_local_.resize(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const Vec<D>& x = particles_.position[p];  // leaving through a free face: -1
    bool inside = true;
    for (int a = 0; a < D; ++a) inside = inside && x[a] > 0.0 && x[a] < upper[a];
    if (!inside) {
      move_base_[p] = -1;
      continue;
    }
    const auto cc = grid_.cell_of(x);  // as stencil_of
    move_base_[p] = grid_.cell_base_node(cc);
    move_local_[p] = place_in_cell(x, cc);
  }
  find_own_sides();  // this round's positions, for its passes
  move_excess_.assign(grid_.node_count(), 0.0);
  scatter_by_ranges<D>(move_base_, corner, grid_.node_count(), [&](std::int64_t p, unsigned mask) {
    const std::int64_t base = move_base_[p];
    const Q1Stencil<D> s = stencil_at_move_base(p);
    for (int a = 0; a < NC; ++a)
      if (mask >> a & 1) move_excess_[base + corner[a]] += particles_.volume[p] * s.w[a];
  });
}

template <int D>
double Simulation<D>::move_grains_apart(int moves, double dt) {
  constexpr int NC = ipow(2, D);
  const auto corner = grid_.corner_offsets();
  const double h = grid_.h();
  const std::int64_t n = static_cast<std::int64_t>(particles_.size());
  const std::int64_t nodes = grid_.node_count();
  const std::vector<Obstacle<D>> obstacles_end = obstacles_at(time_ + dt);
  place_thin_solids(time_ + dt);  // where the step leaves them
  Vec<D> upper;
  for (int a = 0; a < D; ++a) upper[a] = grid_.cells()[a] * h;
  const auto inside = [&upper](const Vec<D>& x) {
    for (int a = 0; a < D; ++a)
      if (!(x[a] > 0.0 && x[a] < upper[a])) return false;
    return true;
  };
  move_lift_.assign(n, 0.0);
  moves_settled_ = false;
  for (int move = 0; move < moves; ++move) {
    grain_volume_at_positions();
    bool crowded = false;
#pragma omp parallel for schedule(static) reduction(|| : crowded)
    for (std::int64_t i = 0; i < nodes; ++i) {
      if (!(move_excess_[i] > 0.0)) continue;
      const double full = phi_max_ * grid_.node_volume(grid_.node_coords(i));
      move_excess_[i] = std::max(0.0, move_excess_[i] / full - 1.0);
      crowded = crowded || move_excess_[i] > 0.0;
    }
    if (!crowded) {  // no node over-full: every move would be zero
      moves_settled_ = true;
      break;
    }
#pragma omp parallel for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      const std::int64_t base = move_base_[p];
      if (base < 0) continue;  // outside
      bool near = false;       // a corner of its cell is over-full (else the move is zero)
      for (int a = 0; a < NC; ++a) near = near || move_excess_[base + corner[a]] > 0.0;
      if (!near) continue;
      Vec<D>& x = particles_.position[p];
      const Q1Stencil<D> s = stencil_at_move_base(p);
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
      if (!obstacles_end.empty()) {  // no move into a solid, or across a thin part of one
        Vec<D> kept = y;
        double clearance = 0.0;
        move_outside_solids(obstacles_end, p, x, kept, &clearance);
        if (kept != y) continue;
        clearance_[p] = clearance;
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

template <int D>
double Simulation<D>::overfill() const {
  double over = 0.0, all = 0.0;  // in node order: the same bits whatever the thread count
  for (std::int64_t i = 0; i < grid_.node_count(); ++i) {
    const double v = move_excess_[i];
    if (!(v > 0.0)) continue;
    all += v;
    over += std::max(0.0, v - phi_max_ * grid_.node_volume(grid_.node_coords(i)));
  }
  return all > 0.0 ? over / all : 0.0;
}

namespace {
constexpr double kProjectSlack = 1e-3;  // of phi_max V_j
constexpr int kProjectSweeps = 200;     // at most, per round
}  // namespace

// The projection (solver.decompaction = "project"): node potentials q >= 0
// such that moving every grain by d_p = -sum_k q_k grad N_k(x_p) takes each
// node's grain volume back to its capacity, to first order: Phi - L q <= C,
// with complementarity, L_jk = sum_p V_p grad N_j(x_p) . grad N_k(x_p) (the
// first-order change of Phi_j when the grains move by -grad q), C_j =
// phi_max V_j (1 - s_j), s_j the share of the node that the solids moving
// into the sand take (project_capacities; nodes where grains leave the box
// are not bounded). Solved by projected Gauss-Seidel over the nodes in 2^d
// colours (coordinate parities: nodes of one colour share no cell, so their
// updates are independent and the result does not depend on the thread
// count). Grains are then moved (as in advection: a grain
// crossing a free face or an opening leaves, one crossing a wall stays
// inside, one entering a solid is put back on its surface), and the part
// of a grain's velocity against its move gives up the kinetic energy the
// move's lift added, at most |d| / dt of speed, so that the moves add no
// energy to moving grains (removing that part whole, up to |d| / dt, as
// until the thirty-first session, dragged sheared flows: docs/method.md);
// a clump of grains touching no wall or solid gets that momentum back
// (restore_braked_momentum). Each round is linearised at the grains'
// positions; up to `rounds` rounds, until no node is more than
// kProjectSlack over its capacity.
template <int D>
double Simulation<D>::project_grains_apart(int rounds, double dt) {
  const std::vector<Obstacle<D>> obstacles_end = obstacles_at(time_ + dt);
  place_thin_solids(time_ + dt);    // where the step leaves them
  std::vector<Obstacle<D>> moving;  // the solids that take a share of a node
  for (const Obstacle<D>& o : obstacles_end)
    if (o.dynamic || moves_into_sand(o)) moving.push_back(o);
  move_lift_.assign(particles_.size(), 0.0);
  brake_velocity_.assign(particles_.size(), Vec<D>::Zero());
  bool moved = false;
  // Rounds, then one more look at where the last one left the grains.
  for (int round = 0; round <= rounds; ++round) {
    grain_volume_at_positions();  // Phi into move_excess_
    project_left_ = project_capacities(moving);
    if (project_left_ <= kProjectSlack || round == rounds) break;
    project_assemble();
    project_potentials();
    project_move(obstacles_end, dt);
    moved = true;
  }
  if (moved) restore_braked_momentum(obstacles_end);
  double lift = 0.0;  // in particle order
  for (double w : move_lift_) lift += w;
  return lift;
}

// Each node's capacity C_j = phi_max V_j (1 - s_j), s_j the share of the
// solids that move (`moving`: bodies, and fixed solids that translate or
// turn, where the step leaves them); the largest excess of Phi_j over it,
// in units of phi_max V_j; potentials reset to zero. A solid that stays in
// place takes no share: the sand's rows already keep it from compacting into
// the solid (build_rows), and the plane estimate of s_j and the grains'
// quadrature of Phi_j disagree by a few percent next to it, which moved the
// grains off sloping walls at every step (hopper3d: 36 of 121 steps at the
// solver's cap and 1,027 sweeps per step, against 0 and 274 without the
// fixed walls' share). Nodes on a free face or an opening are not bounded:
// the grains there are leaving, and bounding them pushed the grains above a
// small orifice back into the bin (silo3d with 3 x 3 free nodes drained 402
// grains over 0.1-0.4 s against 1,166 when they are not, 1,270 under the
// pure clamp).
template <int D>
double Simulation<D>::project_capacities(const std::vector<Obstacle<D>>& moving) {
  const double h = grid_.h();
  const std::int64_t nodes = grid_.node_count();
  project_q_.assign(nodes, 0.0);
  project_capacity_.resize(nodes);
  project_full_.resize(nodes);
  double over = 0.0;
#pragma omp parallel for schedule(static) reduction(max : over)
  for (std::int64_t i = 0; i < nodes; ++i) {
    if (!(move_excess_[i] > 0.0)) continue;
    const auto nc = grid_.node_coords(i);
    const double full = phi_max_ * grid_.node_volume(nc);
    project_full_[i] = full;
    if (open_node_[i]) {
      project_capacity_[i] = std::numeric_limits<double>::infinity();
      continue;
    }
    Vec<D> x, normal;
    for (int a = 0; a < D; ++a) x[a] = nc[a] * h;
    const double solid =
        moving.empty() ? 0.0 : solid_fraction(obstacle_distance(moving, x, &normal), h);
    project_capacity_[i] = full * (1.0 - solid);
    over = std::max(over, (move_excess_[i] - project_capacity_[i]) / full);
  }
  return over;
}

// L_jk = sum_p V_p grad N_j(x_p) . grad N_k(x_p), each node's row of 3^d
// neighbours summed in particle order; the nodes holding grains, by colour
// (coordinate parities), in index order.
template <int D>
void Simulation<D>::project_assemble() {
  constexpr int NC = ipow(2, D), NS = ipow(3, D);
  const auto corner = grid_.corner_offsets();
  const std::int64_t nodes = grid_.node_count();
  // Slot in a node's row of L of corner b seen from corner a of one cell.
  int slot[NC][NC];
  for (int a = 0; a < NC; ++a)
    for (int b = 0; b < NC; ++b) {
      int k = 0, w = 1;
      for (int ax = 0; ax < D; ++ax, w *= 3) k += (((b >> ax) & 1) - ((a >> ax) & 1) + 1) * w;
      slot[a][b] = k;
    }
  project_L_.assign(nodes * NS, 0.0);
  scatter_by_ranges<D>(move_base_, corner, nodes, [&](std::int64_t p, unsigned mask) {
    const std::int64_t base = move_base_[p];
    const Q1Stencil<D> s = stencil_at_move_base(p);
    const double v = particles_.volume[p];
    for (int a = 0; a < NC; ++a) {
      if (!(mask >> a & 1)) continue;
      double* row = project_L_.data() + (base + corner[a]) * NS;
      for (int b = 0; b < NC; ++b) row[slot[a][b]] += v * s.grad[a].dot(s.grad[b]);
    }
  });
  for (auto& list : project_nodes_) list.clear();
  for (std::int64_t i = 0; i < nodes; ++i) {
    if (!(move_excess_[i] > 0.0) || open_node_[i] || !(project_L_[i * NS + NS / 2] > 0.0)) continue;
    const auto nc = grid_.node_coords(i);
    int colour = 0;
    for (int a = 0; a < D; ++a) colour |= (nc[a] & 1) << a;
    project_nodes_[colour].push_back(i);
  }
}

// Projected Gauss-Seidel on Phi - L q <= C, q >= 0, complementarity:
// q_j <- max(0, q_j + (Phi_j - (L q)_j - C_j) / L_jj), colour by colour,
// until no node is more than kProjectSlack off. One parallel region for all
// the sweeps, each thread taking its share of each colour and waiting at a
// spin barrier after it (solver/team.hpp): a work-shared loop per colour and
// sweep forked the team and entered the kernel at every one (the 2D collapse
// at 5 mm: about 117 sweeps per round, 4 colours, 415 rounds, and libgomp's
// barriers took 6.5% of the run). The nodes of one colour share no cell,
// so their updates are independent and any split gives the same bits; each
// thread's largest miss goes to its own slot, and every thread takes the
// largest of them, the same decision on every thread.
template <int D>
void Simulation<D>::project_potentials() {
  constexpr int NS = ipow(3, D);
  const auto neighbour = grid_.stencil_offsets();
  const int most = spinning_team_limit();
  constexpr int kPad = 8;  // a cache line per thread's miss
  std::vector<double> worst_of(static_cast<std::size_t>(most) * kPad, 0.0);
  SpinBarrier barrier;
#pragma omp parallel num_threads(most)
  {
#pragma omp single
    barrier.set_size(omp_get_num_threads());
    const Team team{omp_get_thread_num(), omp_get_num_threads(), &barrier};
    for (int sweep = 0; sweep < kProjectSweeps; ++sweep) {
      double worst = 0.0;  // the largest miss of this sweep's updates, of phi_max V_j
      for (const auto& list : project_nodes_) {
        const auto [k0, k1] = team.split<std::int64_t>(static_cast<std::int64_t>(list.size()));
        for (std::int64_t k = k0; k < k1; ++k) {
          const std::int64_t i = list[k];
          const double* row = project_L_.data() + i * NS;
          double lq = 0.0;
          for (int t = 0; t < NS; ++t) lq += row[t] * project_q_[i + neighbour[t]];
          const double excess = move_excess_[i] - lq - project_capacity_[i];
          const double q = std::max(0.0, project_q_[i] + excess / row[NS / 2]);
          if (q > 0.0 || project_q_[i] > 0.0)
            worst = std::max(worst, std::abs(excess) / project_full_[i]);
          project_q_[i] = q;
        }
        team.sync();
      }
      // Read after the last colour's barrier; written again only after the
      // next sweep's first one, which every thread passes after reading.
      worst_of[static_cast<std::size_t>(team.rank) * kPad] = worst;
      team.sync();
      double all = 0.0;
      for (int r = 0; r < team.size; ++r)
        all = std::max(all, worst_of[static_cast<std::size_t>(r) * kPad]);
      if (all <= kProjectSlack) break;
    }
  }
}

// Each grain moves by d_p = -sum_k q_k grad N_k(x_p), out through a free
// face or an opening, else kept inside the box's walls, and is put back on
// the surface of a solid it would enter (as in advection); the part of its
// velocity against d_p gives up the kinetic energy the move's lift against
// gravity added, at most |d_p| / dt of speed.
template <int D>
void Simulation<D>::project_move(const std::vector<Obstacle<D>>& obstacles_end, double dt) {
  constexpr int NC = ipow(2, D);
  const auto corner = grid_.corner_offsets();
  const std::int64_t n = static_cast<std::int64_t>(particles_.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const std::int64_t base = move_base_[p];
    if (base < 0) continue;
    bool near = false;  // a corner of its cell has a potential (else the move is zero)
    for (int a = 0; a < NC; ++a) near = near || project_q_[base + corner[a]] > 0.0;
    if (!near) continue;
    Vec<D>& x = particles_.position[p];
    const Q1Stencil<D> s = stencil_at_move_base(p);
    Vec<D> d = Vec<D>::Zero();
    for (int a = 0; a < NC; ++a) d -= project_q_[base + corner[a]] * s.grad[a];
    const double len = d.norm();
    if (len == 0.0) continue;
    Vec<D> y = x + d;
    put_inside_walls(y);
    double clearance = 0.0;
    move_outside_solids(obstacles_end, p, x, y, &clearance);
    clearance_[p] = clearance;
    const double lift = std::max(0.0, -gravity_.dot(y - x));  // per unit mass
    move_lift_[p] += rho0_ * mass_volume(p) * lift;
    x = y;
    Vec<D>& u = particles_.velocity[p];
    const Vec<D> dir = d / len;
    const double against = -u.dot(dir);
    if (against > 0.0 && lift > 0.0) {
      // Remove from the part of u against the move the kinetic energy the
      // lift added, a^2/2 - (a - b)^2/2 = lift, no more (at most |d| / dt).
      const double a2 = against * against;
      const double brake = a2 <= 2.0 * lift ? against : against - std::sqrt(a2 - 2.0 * lift);
      const Vec<D> dv = std::min(brake, len / dt) * dir;
      u += dv;
      brake_velocity_[p] += dv;
    }
  }
}

// The braking is an inelastic collision among the grains. Where they touch
// a wall or a solid, through grains whose cells share a node, that wall
// takes the momentum the braking takes (the sand's stresses carry it
// there); a clump that touches none, in flight, keeps its momentum: what
// the braking takes from some grains goes back to the grains round them.
// Each node of such a clump gathers the momentum the braking took from its
// grains and their mass (Q1 weights at their positions, in particle
// order), and every grain gets back its share (momentum over mass,
// interpolated), which conserves the clump's momentum (partition of
// unity). Two blocks colliding head-on far from the walls lost 6.8% of
// their momentum to the braking without this.
template <int D>
void Simulation<D>::restore_braked_momentum(const std::vector<Obstacle<D>>& obstacles_end) {
  constexpr int NC = ipow(2, D), NS = ipow(3, D);
  const auto corner = grid_.corner_offsets();
  const auto neighbour = grid_.stencil_offsets();
  const std::int64_t nodes = grid_.node_count();
  const std::int64_t n = static_cast<std::int64_t>(particles_.size());
  const double h = grid_.h();
  bool braked = false;  // most steps brake some grain; the others need no clumps
  for (std::int64_t p = 0; p < n && !braked; ++p)
    braked = move_base_[p] >= 0 && !brake_velocity_[p].isZero();
  if (!braked) return;
  // Clumps: the cells holding grains (by base node), joined where they share
  // a node, by union-find in index order.
  std::vector<std::int64_t>& root = brake_root_;
  root.assign(nodes, -1);
  for (std::int64_t p = 0; p < n; ++p)
    if (move_base_[p] >= 0) root[move_base_[p]] = move_base_[p];
  const auto find = [&root](std::int64_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  for (std::int64_t c = 0; c < nodes; ++c) {
    if (root[c] < 0) continue;
    for (int t = 0; t < NS / 2; ++t) {  // the neighbours before c in index order
      const std::int64_t o = c + neighbour[t];
      if (root[o] < 0) continue;
      const std::int64_t a = find(c), b = find(o);
      if (a != b) root[std::max(a, b)] = std::min(a, b);
    }
  }
  for (std::int64_t c = 0; c < nodes; ++c)
    if (root[c] >= 0) root[c] = find(c);
  // A clump touches a wall where one of its nodes has a constrained
  // velocity component (a stick or slip face; ghost nodes), a solid where
  // one of its nodes lies within a cell of it. Flags per clump root: kWall
  // (it touches one), kBraked (the braking took velocity from a grain in it).
  constexpr std::uint8_t kWall = 1, kBraked = 2;
  std::vector<std::uint8_t>& flag = brake_flags_;
  flag.assign(nodes, 0);
  for (std::int64_t c = 0; c < nodes; ++c) {
    if (root[c] < 0 || (flag[root[c]] & kWall)) continue;
    for (int a = 0; a < NC; ++a)
      if (free_mask_[c + corner[a]] != Vec<D>::Ones()) flag[root[c]] |= kWall;
  }
  bool any = false;  // a braked grain in a clump in flight
  for (std::int64_t p = 0; p < n; ++p) {
    if (move_base_[p] < 0 || brake_velocity_[p].isZero()) continue;
    std::uint8_t& f = flag[root[move_base_[p]]];
    f |= kBraked;
    any = any || !(f & kWall);
  }
  if (!any) return;
  for (std::int64_t c = 0; c < nodes && !obstacles_end.empty(); ++c) {
    if (root[c] < 0 || flag[root[c]] != kBraked) continue;
    for (int a = 0; a < NC; ++a) {
      const auto nc = grid_.node_coords(c + corner[a]);
      Vec<D> x, normal;
      for (int k = 0; k < D; ++k) x[k] = nc[k] * h;
      if (obstacle_distance(obstacles_end, x, &normal) < h) {
        flag[root[c]] |= kWall;
        break;
      }
    }
  }
  brake_momentum_.assign(nodes, Vec<D>::Zero());
  brake_mass_.assign(nodes, 0.0);
  scatter_by_ranges<D>(move_base_, corner, nodes, [&](std::int64_t p, unsigned mask) {
    // A clump's nodes are its own: the walls' clumps need no sums.
    const std::int64_t base = move_base_[p];
    if (flag[root[base]] != kBraked) return;
    const Q1Stencil<D> s = stencil_at_move_base(p);
    const double m = mass_volume(p);
    for (int a = 0; a < NC; ++a) {
      if (!(mask >> a & 1)) continue;
      brake_momentum_[base + corner[a]] += (m * s.w[a]) * brake_velocity_[p];
      brake_mass_[base + corner[a]] += m * s.w[a];
    }
  });
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nodes; ++i)
    if (brake_mass_[i] > 0.0) brake_momentum_[i] /= brake_mass_[i];
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const std::int64_t c = move_base_[p];
    if (c < 0 || flag[root[c]] != kBraked) continue;
    const Q1Stencil<D> s = stencil_at_move_base(p);
    Vec<D> back = Vec<D>::Zero();
    for (int a = 0; a < NC; ++a) back += s.w[a] * brake_momentum_[c + corner[a]];
    particles_.velocity[p] -= back;
  }
}

template double Simulation<2>::move_grains_apart(int, double);
template double Simulation<3>::move_grains_apart(int, double);
template double Simulation<2>::project_grains_apart(int, double);
template double Simulation<3>::project_grains_apart(int, double);
#define SABLIER_INSTANTIATE(D)                                                           \
  template double Simulation<D>::project_capacities(const std::vector<Obstacle<D>>&);    \
  template void Simulation<D>::project_assemble();                                       \
  template void Simulation<D>::project_potentials();                                     \
  template void Simulation<D>::project_move(const std::vector<Obstacle<D>>&, double);    \
  template void Simulation<D>::restore_braked_momentum(const std::vector<Obstacle<D>>&); \
  template void Simulation<D>::grain_volume_at_positions();                              \
  template double Simulation<D>::overfill() const;
SABLIER_INSTANTIATE(2)
SABLIER_INSTANTIATE(3)
#undef SABLIER_INSTANTIATE

}  // namespace sablier
