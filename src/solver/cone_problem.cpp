#include "solver/cone_problem.hpp"

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "solver/anderson.hpp"
#include "solver/cell_rows.hpp"
#include "solver/contact_rows.hpp"
#include "solver/relaxation.hpp"
#include "solver/slide_batch.hpp"
#include "solver/stencil.hpp"
#include "solver/sweep_order.hpp"
#include "solver/team.hpp"

namespace sablier {

using solver_detail::AndersonMixer;
using solver_detail::apply_B;
using solver_detail::contact_force;
using solver_detail::deterministic_sums;
using solver_detail::free_velocities;
using solver_detail::local_delassus;
using solver_detail::move_contact_node;
using solver_detail::pack_coupling_lines;
using solver_detail::push_body;
using solver_detail::scatter_stress;
using solver_detail::set_velocity_at;
using solver_detail::SumBlocks;
using solver_detail::SweepOrder;
using solver_detail::team_size;
using solver_detail::update_contact_row;
using solver_detail::velocities_from_axes;
using solver_detail::velocities_to_axes;
using solver_detail::velocity_at;

template <int D>
void ConeProblem<D>::resize_rows(int n) {
  node.resize(n);
  coupling.resize(n);
  volume.resize(n);
  k.resize(n);
  aperture.resize(n);
  cohesion.resize(n);
  lambda.resize(n);
  delassus.resize(n);
  state.resize(n);
  beta.resize(n);
}

namespace {

// Row j's stress change dl: to its velocities and its stress (none if zero).
template <int D>
inline void apply_change(ConeProblem<D>& p, int j, const SymVec<D>& dl) {
  if (dl.squaredNorm() == 0.0) return;
  scatter_stress<D>(p, j, dl);
  p.lambda[j] += dl;
}

// Rows of a thread's share of a colour that wait for their slide solve, which
// slide_batch.hpp does eight at a time. Rows of one colour have disjoint
// stencils, so deferring their updates to the end of the batch changes
// nothing.
template <int D>
struct SlideQueue {
  static constexpr int SD = sym_size(D);
  static constexpr int kCapacity = SlideBatch<SD>::kCapacity;
  SlideBatch<SD> batch;
  int row[kCapacity];
  SymVec<D> x_old[kCapacity];
  double shift[kCapacity];

  void flush(ConeProblem<D>& p) {
    batch.solve();
    for (int l = 0; l < batch.size; ++l) {
      const int j = row[l];
      SymVec<D> dl = p.delassus[j].unrotated_change(batch.solution(l), x_old[l], shift[l]);
      relax<D>(p, j, DPCase::Slide, dl);
      p.state[j] = DPCase::Slide;
      p.beta[j] = batch.beta[l];
      apply_change<D>(p, j, dl);
    }
    batch.size = 0;
  }
};

// Sand row j's strain rate at its current stress (METHOD.md step 5):
// y = (B u + k_j e_0) / V_j, from the row's gather.
template <int D>
inline SymVec<D> row_strain(const ConeProblem<D>& p, int j) {
  SymVec<D> y = apply_B<D>(p, j);
  y[0] += p.k[j];
  y *= p.inv_volume[j];
  return y;
}

// Sand row j's local problem in rotated coordinates from its strain rate y:
// its stress x_old and b, the strain rate with x_j = 0 (shifted by the
// cohesion).
template <int D>
inline void local_problem(const ConeProblem<D>& p, int j, const SymVec<D>& y, SymVec<D>& x_old,
                          SymVec<D>& b) {
  const LocalDelassus<sym_size(D)>& W = p.delassus[j];
  W.rotated_problem(y, p.lambda[j], x_old, b);
  // Cohesion: the cone's apex sits at lambda = -shift e_0; solve for the
  // shifted stress lambda + shift e_0 (METHOD.md section 1).
  const double shift = p.cohesion[j];
  if (shift != 0.0) {
    SymVec<D> e0 = SymVec<D>::Zero();
    e0[0] = shift;
    b -= W.apply_rotated(e0);
  }
}

// Separation and stick for sand row j without rotations
// (separate_or_stick_unrotated), from its strain rate y.
template <int D>
inline bool separate_or_stick(const ConeProblem<D>& p, int j, const SymVec<D>& y, SymVec<D>& dl,
                              DPCase& result) {
  const auto& U = p.unrotated[j];
  return separate_or_stick_unrotated<sym_size(D)>(U.first_row, U.inverse, p.lambda[j], y,
                                                  p.cohesion[j], p.aperture[j], dl, result);
}

// Exact local updates of rows [begin, end), all of one run (rows of one
// colour have disjoint stencils, so their order does not matter). Sand rows
// go eight at a time: first every row's gather, a loop without branches
// whose loads and arithmetic overlap from row to row; then each row's case:
// separation and stick tried without rotations (separate_or_stick) unless
// the row slid in the last sweep (a slide costs the rotated problem anyway,
// and mostly slides again), then, for the rows neither holds or that slid,
// the rotated problem (local_problem), whose separation, stick,
// frictionless or round-off cases are solved at once and whose slides are
// queued for a batched slide solve (slide_batch.hpp), done when the queue
// is full and by the caller at the end of each group of independent rows
// (SweepOrder::walk). In 3D the unrotated candidates of the eight rows come
// in a pass of their own and the scatters in another, after the cases:
// eight independent chains of arithmetic per pass, which the core overlaps
// (4-6% less time per 3D sweep; in 2D, whose rows cost a third as much, it
// cost 3-5%, docs/benchmarks.md, twenty-first session). Either way, the
// same results. Contact rows (own colours) are updated one by one, in
// order, with the queue empty.
template <int D>
inline void update_rows(ConeProblem<D>& p, int begin, int end, SlideQueue<D>& queue,
                        solver_detail::BodyMoves<D>* moves) {
  constexpr int SD = sym_size(D);
  constexpr int kChunk = 8;
  constexpr bool kPasses = D == 3;
  for (int j = begin; j < std::min(end, p.first_contact); j += kChunk) {
    const int n = std::min(kChunk, std::min(end, p.first_contact) - j);
    SymVec<D> y[kChunk], dl[kChunk];
    DPCase result[kChunk];
    bool solved[kChunk];
    for (int r = 0; r < n; ++r) y[r] = row_strain<D>(p, j + r);
    if constexpr (kPasses) {
      for (int r = 0; r < n; ++r)
        solved[r] = p.unrotated[j + r].degenerate ||
                    (p.state[j + r] != DPCase::Slide &&
                     separate_or_stick<D>(p, j + r, y[r], dl[r], result[r]));
    }
    for (int r = 0; r < n; ++r) {
      const int row = j + r;
      if (p.unrotated[row].degenerate) {
        p.state[row] = DPCase::Inactive;
        solved[r] = false;  // no change below
        continue;
      }
      if constexpr (!kPasses)
        solved[r] =
            p.state[row] != DPCase::Slide && separate_or_stick<D>(p, row, y[r], dl[r], result[r]);
      if (!solved[r]) {
        const LocalDelassus<SD>& W = p.delassus[row];
        SymVec<D> x_old, b, x;
        local_problem<D>(p, row, y[r], x_old, b);
        if (!solve_without_slide<SD>(W, b, p.aperture[row], x, result[r])) {
          const int l = queue.batch.add(W, b, p.aperture[row], p.beta[row]);
          queue.row[l] = row;
          queue.x_old[l] = x_old;
          queue.shift[l] = p.cohesion[row];
          if (queue.batch.full()) queue.flush(p);
          continue;
        }
        dl[r] = W.unrotated_change(x, x_old, p.cohesion[row]);
        solved[r] = true;
      }
      relax<D>(p, row, result[r], dl[r]);
      p.state[row] = result[r];
      p.beta[row] = 0.0;
      if constexpr (!kPasses) apply_change<D>(p, row, dl[r]);
    }
    if constexpr (kPasses) {
      for (int r = 0; r < n; ++r) {
        // dl[r] holds the stress change of a row solved above (the queued
        // ones are updated by the flush).
        if (solved[r]) apply_change<D>(p, j + r, dl[r]);
      }
    }
  }
  for (int j = std::max(begin, p.first_contact); j < end; ++j) update_contact_row<D>(p, j, moves);
}

}  // namespace

template <int D>
void assemble_delassus(ConeProblem<D>& p) {
  const int n = p.rows();
  // The sand rows' blocks (contact rows get theirs in assemble_contacts).
  const int sand = std::min(p.first_contact, n);
  p.unrotated.resize(sand);
  // First, as it rounds the 3D couplings to the single precision the sweeps
  // read them in: the blocks below are those of the operator they apply.
  pack_coupling_lines<D>(p, sand);
#pragma omp parallel for schedule(static)
  for (int j = 0; j < sand; ++j) {
    const auto& g = p.coupling[j];
    const Vec<D>* im = p.inv_mass.data() + p.node[j];
    const SymMat<D> W =
        local_delassus<D>(
            ConeProblem<D>::NS,
            [&](int s) { return std::pair<Vec<D>, Vec<D>>(im[p.stencil[s]], g.col(s)); }) /
        p.volume[j];
    p.delassus[j].set(0.5 * (W + W.transpose()));
    p.delassus[j].unrotated(p.unrotated[j].first_row, p.unrotated[j].inverse);
    p.unrotated[j].degenerate = p.delassus[j].degenerate;
  }
  solver_detail::assemble_contacts<D>(p);
  p.inv_volume.resize(sand);
  for (int j = 0; j < sand; ++j) p.inv_volume[j] = 1.0 / p.volume[j];
}

namespace {

// apply_stress_to_velocity on the sweeps' velocities (velocity_at): in 3D
// between velocities_to_axes and velocities_from_axes.
template <int D>
void add_stress_velocities(ConeProblem<D>& p) {
  // In the sweep's order and on its team (SweepOrder), so that each velocity
  // sums its stresses in one order whatever the thread count.
  const auto move = [&p](int j) {
    if (!(p.lambda[j].squaredNorm() > 0.0)) return;
    if (j < p.first_contact) {
      scatter_stress<D>(p, j, p.lambda[j]);
      return;
    }
    const Vec<D> f = contact_force<D>(p, j, p.lambda[j]);
    move_contact_node<D>(p, j, f);
    if (j < p.first_body_row) return;
    const int c = j - p.first_contact;
    if (p.contact_body[c] >= 0) push_body<D>(p, p.contact_body[c], p.contact_arm[c], f);
    if (p.other_body(c) >= 0) push_body<D>(p, p.other_body(c), p.contact_other_arm[c], -f);
  };
  SpinBarrier barrier;
#pragma omp parallel num_threads(team_size(p))
  {
#pragma omp single
    barrier.set_size(omp_get_num_threads());
    const SweepOrder<D> order(p, omp_get_num_threads());
    order.walk(
        omp_get_thread_num(),
        [&](int j0, int j1) {
          for (int j = j0; j < j1; ++j) move(j);
        },
        [] {}, [&] { barrier.wait(); });
    solver_detail::scatter_cell_stresses<D>(
        p, Team{omp_get_thread_num(), omp_get_num_threads(), &barrier});
  }
}

}  // namespace

template <int D>
void apply_stress_to_velocity(ConeProblem<D>& p) {
  velocities_to_axes<D>(p);
  add_stress_velocities<D>(p);
  velocities_from_axes<D>(p);
}

template <int D>
SolveReport solve_gauss_seidel(ConeProblem<D>& p, double tolerance, int max_iterations,
                               int anderson_depth, std::vector<double>* history) {
  SolveReport report;
  const int n = p.rows();
  if (n == 0) return report;
  // The free velocity nodes (some component with inv_mass > 0): the only ones
  // stresses move, in the order of the threads that write them
  // (free_velocities). Their kinetic-energy weights w = 1 / inv_mass per free
  // component (0 on constrained ones) define |a|_M^2 = sum_q a_q . w_q a_q.
  std::vector<std::int64_t> free;
  SumBlocks blocks;
  std::vector<int> segment_block;
  free_velocities(p, free, blocks, segment_block);
  const std::int64_t nf = static_cast<std::int64_t>(free.size());
  std::vector<Vec<D>> weight(nf), u_free(nf), u_prev(nf);
  velocities_to_axes<D>(p);  // the sweeps' copy (3D), copied back at the end
  for (std::int64_t q = 0; q < nf; ++q) {
    const std::int64_t i = free[q];
    for (int c = 0; c < D; ++c)
      weight[q][c] = p.inv_mass[i][c] > 0.0 ? 1.0 / p.inv_mass[i][c] : 0.0;
    u_free[q] = velocity_at<D>(p, i);  // before any stress acts
  }
  std::fill(p.beta.begin(), p.beta.end(), 0.0);
  // The first sweep tries every row without rotations (update_rows): the
  // cases of an earlier step, which a resumed run does not have, must not
  // steer it.
  std::fill(p.state.begin(), p.state.end(), DPCase::Separation);
  p.flips.assign(n, 0);
  p.calm.assign(n, 0);
  const int cells = p.cells();
  if (cells > 0) solver_detail::assemble_cells<D>(p);
  add_stress_velocities<D>(p);  // warm start
  AndersonMixer<D> mixer(anderson_depth, n, blocks, cells);
  const bool plain = mixer.depth() <= 0;
  // One parallel region for the whole solve: a fork and join per colour
  // would cost more than a barrier (measured: about 2 us against 0.4 us on
  // 2 threads), and a 2D sweep of a few hundred rows takes tens of us. The
  // loops split their ranges themselves and synchronise with the team's spin
  // barrier (solver/team.hpp), not libgomp's, which makes a system call per
  // barrier. Barriers are kept to those the data need (one before the
  // colours, after the mixing's writes, one per colour, one per sum): every
  // thread takes the same decisions from the same shared sums, and loops
  // over the free nodes use one split (the blocks of the sums), so a thread
  // reads back its own writes.
  std::vector<double> partial(std::int64_t(blocks.count()) * 2, 0.0);
  int iterations = 0;
  double residual = 0.0;
  if (history) history->clear();
  // The best iterate of the second half (allocated when first needed): its
  // stresses and cases. Its velocities are not copied (a pass over the free
  // nodes at every better sweep of a capped solve):
  // going back to it, they are recomputed from its stresses, as the warm
  // start computes them (the same velocities but for rounding).
  const int keep_from = std::max(1, max_iterations / 2);
  std::vector<SymVec<D>> best_lambda, best_cell_stress;
  std::vector<DPCase> best_state;
  bool went_back = false;
  double bodies_traded = 0.0;
  SpinBarrier barrier;
#pragma omp parallel num_threads(team_size(p))
  {
    const SweepOrder<D> order(p, omp_get_num_threads());
#pragma omp single
    {
      barrier.set_size(order.size);
      // Each thread's free nodes: those of its zones and the separators after them.
      blocks.first.resize(order.size + 1);
      for (int k = 0; k < order.size; ++k) blocks.first[k] = segment_block[order.first_segment(k)];
      blocks.first[order.size] = blocks.count();
    }
    const Team team{omp_get_thread_num(), order.size, &barrier};
    const auto [q0, q1] = blocks.share(team);
    // f(j0, j1, pos) on each range of the rows this thread updates in a
    // sweep. Loops over rows outside the sweep take the same ranges, so that
    // a row stays in its thread's cache; pos numbers the rows so that each
    // thread's are consecutive (the mixer stores its history of the rows in
    // that order, read in one stream per thread).
    const int own_base = order.rows_before(team.rank);
    const auto own_rows = [&](const auto& f) {
      int pos = own_base;
      order.walk(
          team.rank,
          [&](int j0, int j1) {
            f(j0, j1, pos);
            pos += j1 - j0;
          },
          [] {}, [] {});
    };
    // f(c0, c1) on each range of the cell rows this thread updates
    // (update_cells: its share of each colour).
    const auto own_cells = [&](const auto& f) { solver_detail::walk_cells<D>(p, team, f, [] {}); };
    typename AndersonMixer<D>::State mix_state;
    SlideQueue<D> queue;
    int my_iterations = 0;
    double my_residual = 0.0;
    double best = std::numeric_limits<double>::infinity();
    bool allocated = false;
    solver_detail::BodyMoves<D> moves;  // the bodies' rows against solids, on the first thread
    if (team.rank == 0) moves.reset(p);
    // u_prev = the velocities before each sweep (after the first, the
    // mixer leaves them there).
    for (std::int64_t q = q0; q < q1; ++q) u_prev[q] = velocity_at<D>(p, free[q]);
    for (int it = 1; it <= max_iterations; ++it) {
      team.sync();
      order.walk(
          team.rank, [&](int j0, int j1) { update_rows<D>(p, j0, j1, queue, &moves); },
          [&] { queue.flush(p); }, [&] { team.sync(); });
      // The bodies' rows run on the first thread; the others read what they
      // traded after the sums' barrier below.
      if (team.rank == 0) bodies_traded = moves.traded(p);
      // The walk ends at a barrier: the cell rows see every row's update.
      if (cells > 0) solver_detail::update_cells<D>(p, team);
      // |u^k - u^{k-1}|_M^2 and |u^k - u_f|_M^2. Without mixing, u_prev
      // takes u^k here for the next sweep (what the mixer would do in a pass
      // of its own); with it, the mixer's pass sums them (measure).
      double sums[2];
      if (plain) {
        deterministic_sums(team, blocks, 2, partial, sums, [&](std::int64_t q, double* acc) {
          const Vec<D> u = velocity_at<D>(p, free[q]);
          const Vec<D> a = u - u_prev[q], b = u - u_free[q];
          acc[0] += a.dot(weight[q].cwiseProduct(a));
          acc[1] += b.dot(weight[q].cwiseProduct(b));
          u_prev[q] = u;
        });
      } else {
        mixer.measure(team, p, free, u_prev, u_free, weight, sums, mix_state);
      }
      const double r = sums[1] > 0.0 ? std::sqrt((sums[0] + bodies_traded) / sums[1]) : 0.0;
      my_iterations = it;
      my_residual = r;
      if (history) {
#pragma omp master
        history->push_back(r);
      }
      if (r <= tolerance) break;
      if (it >= keep_from && r < best) {
        // Same static splits as the mixer's loops over rows and free nodes,
        // which are the next to write these: no barrier needed.
        best = r;
        if (!allocated) {  // the same decision on every thread
          if (team.rank == 0) {
            best_lambda.resize(n);
            best_state.resize(n);
            best_cell_stress.resize(cells);
          }
          team.sync();
          allocated = true;
        }
        own_rows([&](int j0, int j1, int) {
          for (int j = j0; j < j1; ++j) {
            best_lambda[j] = p.lambda[j];
            best_state[j] = p.state[j];
          }
        });
        own_cells([&](int c0, int c1) {
          for (int c = c0; c < c1; ++c) best_cell_stress[c] = p.cell_stress[c];
        });
      }
      if (it < max_iterations && !plain)
        mixer.mix(team, p, free, u_prev, sums[0], own_rows, own_cells, mix_state);
    }
    const bool restored = my_residual > tolerance && best < my_residual;
    if (restored) {
      // Stopped at the cap on a worse iterate: go back to the best one.
      team.sync();
      own_rows([&](int j0, int j1, int) {
        for (int j = j0; j < j1; ++j) {
          p.lambda[j] = best_lambda[j];
          p.state[j] = best_state[j];
        }
      });
      own_cells([&](int c0, int c1) {
        for (int c = c0; c < c1; ++c) p.cell_stress[c] = best_cell_stress[c];
      });
      for (std::int64_t q = q0; q < q1; ++q) set_velocity_at<D>(p, free[q], u_free[q]);
      my_residual = best;
    }
#pragma omp master
    {
      iterations = my_iterations;
      residual = my_residual;
      went_back = restored;
    }
  }
  if (went_back) add_stress_velocities<D>(p);  // the best iterate's velocities
  velocities_from_axes<D>(p);
  report.iterations = iterations;
  report.residual = residual;
  report.hit_cap = report.residual > tolerance;
  for (int j = 0; j < n; ++j) {
    switch (p.state[j]) {
      case DPCase::Slide:
        ++report.sliding;
        break;
      case DPCase::Stick:
        ++report.sticking;
        break;
      default:
        ++report.separated;
        break;
    }
  }
  return report;
}

#define SABLIER_INSTANTIATE(D)                                                  \
  template struct ConeProblem<D>;                                               \
  template void assemble_delassus<D>(ConeProblem<D>&);                          \
  template void apply_stress_to_velocity<D>(ConeProblem<D>&);                   \
  template SolveReport solve_gauss_seidel<D>(ConeProblem<D>&, double, int, int, \
                                             std::vector<double>*);
SABLIER_INSTANTIATE(2)
SABLIER_INSTANTIATE(3)
#undef SABLIER_INSTANTIATE

}  // namespace sablier
