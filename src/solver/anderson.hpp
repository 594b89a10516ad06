// The Gauss-Seidel solver's reductions and its Anderson acceleration
// (cone_problem.cpp): sums whose floating-point result does not depend on the
// thread count, and the mixing of the last sweeps (docs/method.md).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/tensor.hpp"
#include "solver/cone_problem.hpp"
#include "solver/slide_batch.hpp"
#include "solver/stencil.hpp"
#include "solver/team.hpp"

namespace sablier {
namespace solver_detail {

// The free nodes' blocks: block b is the free nodes [start[b], start[b+1]),
// of at most kSumBlock nodes, fixed by the problem alone (not by the team).
// Sums over the free nodes go block by block and then add the block sums
// in order, so their floating-point result does not depend on the thread
// count. Thread `rank` owns blocks [first[rank], first[rank + 1]): every loop
// over the free nodes takes the same ones, so that a thread reads back what
// it wrote in another, and the solver chooses them to hold the velocities
// its sweeps write (cone_problem.cpp).
constexpr std::int64_t kSumBlock = 1024;

struct SumBlocks {
  std::vector<std::int64_t> start{0};  // first free node of each block, then the count
  std::vector<int> first;              // first block of each thread, then the block count

  int count() const { return static_cast<int>(start.size()) - 1; }
  // Blocks for the free nodes [begin, end) (after the previous ones).
  void add_segment(std::int64_t end) {
    for (std::int64_t b = start.back(); b < end;) start.push_back(b = std::min(end, b + kSumBlock));
  }
  std::pair<std::int64_t, std::int64_t> share(const Team& team) const {
    return {start[first[team.rank]], start[first[team.rank + 1]]};
  }
};

// K sums at once over the free nodes, g(i0, i1, acc) adding the terms of the
// block [i0, i1) to acc[0..K). Called by every thread of the team (each
// fills its blocks; the barrier publishes the block sums, which every thread
// then adds up itself in the same order, so all threads hold the same `out`
// without a further barrier). `partial` is the caller's buffer of
// K blocks.count() doubles; the caller must not refill it before a barrier
// (every thread reads it here). `out` is the calling thread's own.
template <class G>
void deterministic_block_sums(const Team& team, const SumBlocks& blocks, int K,
                              std::vector<double>& partial, double* out, const G& g) {
  for (int b = blocks.first[team.rank]; b < blocks.first[team.rank + 1]; ++b) {
    double* acc = partial.data() + std::int64_t(b) * K;
    std::fill(acc, acc + K, 0.0);
    g(blocks.start[b], blocks.start[b + 1], acc);
  }
  team.sync();
  std::fill(out, out + K, 0.0);
  for (int b = 0; b < blocks.count(); ++b)
    for (int k = 0; k < K; ++k) out[k] += partial[std::int64_t(b) * K + k];
}

// The same with f(i, acc) adding the terms of free node i.
template <class F>
void deterministic_sums(const Team& team, const SumBlocks& blocks, int K,
                        std::vector<double>& partial, double* out, const F& f) {
  deterministic_block_sums(team, blocks, K, partial, out,
                           [&](std::int64_t i0, std::int64_t i1, double* acc) {
                             for (std::int64_t i = i0; i < i1; ++i) f(i, acc);
                           });
}

// Lane sums of sum_i w_i x_a,i y_i and sum_i w_i x_a,i z_i for a < k over
// the doubles [i0, i1), a whole number of quads: sy[a] and sz[a] hold four
// partial sums each, lane l taking the doubles i = l mod 4. Called on
// consecutive ranges, it adds every quad in the same order as one call over
// their union, so the result depends only on where the whole range starts
// and ends (weighted_dot_finish).
inline void weighted_dot_lanes(const double* w, const double* const* x, int k, const double* y,
                               const double* z, std::int64_t i0, std::int64_t i1, simd::Vd* sy,
                               simd::Vd* sz) {
  using simd::Vd;
  for (std::int64_t i = i0; i < i1; i += 4) {
    const Vd wi = detail::load4(w + i), yi = detail::load4(y + i), zi = detail::load4(z + i);
    for (int a = 0; a < k; ++a) {
      const Vd wx = wi * detail::load4(x[a] + i);
      sy[a] += wx * yi;
      sz[a] += wx * zi;
    }
  }
}

// Adds lanes sy[a] and sz[a] (pairwise), then the scalar terms of the
// doubles [i0, i1) past the last quad, to acc[2a] and acc[2a + 1].
inline void weighted_dot_finish(const double* w, const double* const* x, int k, const double* y,
                                const double* z, std::int64_t i0, std::int64_t i1,
                                const simd::Vd* sy, const simd::Vd* sz, double* acc) {
  for (int a = 0; a < k; ++a) {
    double ty = (sy[a][0] + sy[a][1]) + (sy[a][2] + sy[a][3]);
    double tz = (sz[a][0] + sz[a][1]) + (sz[a][2] + sz[a][3]);
    for (std::int64_t i = i0; i < i1; ++i) {
      ty += w[i] * x[a][i] * y[i];
      tz += w[i] * x[a][i] * z[i];
    }
    acc[2 * a] += ty;
    acc[2 * a + 1] += tz;
  }
}

// The doubles of a vector of fixed-size Eigen vectors (stored contiguously).
template <class V>
inline double* flat(std::vector<V>& v) {
  return v.data()->data();
}
template <class V>
inline const double* flat(const std::vector<V>& v) {
  return v.data()->data();
}

// Anderson acceleration (Walker & Ni 2011, "type II") of the Gauss-Seidel
// map G: lambda -> lambda after one sweep. After the sweep from x_k the rows
// hold G(x_k) and the velocities u(G(x_k)); the residual is the velocity
// change of the sweep, f_k = u(G(x_k)) - u(x_k). With the differences of the
// last m residuals dF and sweep outputs dG, gamma minimises
// |f_k - dF gamma|_M (kinetic-energy norm) and the next iterate is
// x_{k+1} = G(x_k) - dG gamma. Velocities are affine in lambda
// (u = u_f + M^{-1} H^T lambda), so u(x_{k+1}) is the same combination of the
// stored velocities and stays consistent without a rescatter. x_{k+1} may
// leave the cones; the next sweep maps every row back into its cone, and the
// solver only stops after a plain sweep, so its answer is always feasible.
// The history restarts when the residual grows by more than kGrowth (the
// accelerated iterate was worse than the last one) or the least-squares
// system is singular.
// Velocity vectors are stored compactly over the free nodes `free[q]`.
//
// Threads. The history (the vectors) is shared, each thread writing its
// share (its blocks of free nodes, SumBlocks, and its rows); the scalar
// bookkeeping (which slot, how many differences, gamma) is kept by every
// thread in its own `State` and updated identically from the same shared
// sums, so the threads agree without a barrier. Loops over the free nodes
// and over the rows split the same ranges as the solver's, so a thread reads
// back what it wrote itself.
template <int D>
class AndersonMixer {
 public:
  static constexpr int kMaxDepth = 16;
  static constexpr int kMaxSums = 2 + 2 * kMaxDepth;  // measure()'s

  struct State {
    int next = 0, count = 0;
    bool have_prev = false;
    double fnorm2_prev = 0.0;
    int idx[kMaxDepth] = {};
    double sums[kMaxSums] = {};
    double gram[kMaxDepth][kMaxDepth] = {};  // <dF_s, dF_t>_M by history slots s, t
    double gamma[kMaxDepth] = {};
  };

  AndersonMixer(int depth, int rows, const SumBlocks& blocks, int cells = 0)
      : m_(std::min(depth, kMaxDepth)), blocks_(&blocks) {
    if (m_ <= 0) return;
    const std::int64_t nfree = blocks.start.back();
    dF_.assign(m_, std::vector<Vec<D>>(nfree, Vec<D>::Zero()));
    dGu_.assign(m_, std::vector<Vec<D>>(nfree, Vec<D>::Zero()));
    dGl_.assign(m_, std::vector<SymVec<D>>(rows, SymVec<D>::Zero()));
    f_prev_.assign(nfree, Vec<D>::Zero());
    gu_prev_.assign(nfree, Vec<D>::Zero());
    gl_prev_.assign(rows, SymVec<D>::Zero());
    dGc_.assign(m_, std::vector<SymVec<D>>(cells, SymVec<D>::Zero()));
    gc_prev_.assign(cells, SymVec<D>::Zero());
    partial_.assign(std::int64_t(blocks.count()) * kMaxSums, 0.0);
  }

  // The history's depth (0: plain Gauss-Seidel, whose sweeps the solver
  // neither measures nor mixes here).
  int depth() const { return m_; }

  // The sweep's sums and the history's new entries, in one pass over the
  // free nodes. p holds G(x_k) and u(G(x_k)); u_before[q] = u(x_k) at free
  // node q, u_free[q] the velocity without stresses; w the kinetic-energy
  // weights per free node. residual[0] = |f_k|_M^2 (f_k = u(G(x_k)) -
  // u(x_k), the sweep's velocity change) and residual[1] = |u(G(x_k)) -
  // u_free|_M^2, the solver's residual and its scale, summed as the plain
  // sweeps sum them (the same bits). The pass also stores this sweep's f
  // and u(G) and their differences from the last sweep's, and accumulates
  // r_a = <dF_a, f>_M and the Gram matrix's new row A_a0 = <dF_a, dF_0>_M
  // (dF_0 the difference just stored) into st.sums: all as if the history
  // records this sweep, which mix() decides from residual[0] afterwards
  // (when it does not, the history restarts, and what was stored goes
  // unread: the next recorded difference takes the same slot). Computing
  // them before the decision saves the pass and the barrier that the
  // residual's sums took of their own (docs/benchmarks.md, twenty-fifth
  // session). Called by every thread of the solver's parallel region, each
  // with its own state; ends with the sums' barrier. depth() > 0.
  void measure(const Team& team, const ConeProblem<D>& p, const std::vector<std::int64_t>& free,
               const std::vector<Vec<D>>& u_before, const std::vector<Vec<D>>& u_free,
               const std::vector<Vec<D>>& w, double* residual, State& st) const {
    // The history as it will be if this sweep is recorded (mix()).
    const int slot = st.next % m_;
    const bool record = st.have_prev;
    const int k = record ? std::min(st.count + 1, m_) : 0;
    const double* x[kMaxDepth] = {};
    for (int a = 0; a < k; ++a) x[a] = flat(dF_[((st.next - a) % m_ + m_) % m_]);
    // Each block goes by chunks of kChunk nodes, the dot products right
    // after the differences, while they are in the first-level cache.
    const auto block = [&](std::int64_t b0, std::int64_t b1, double* acc) {
      simd::Vd sy[kMaxDepth], sz[kMaxDepth];
      for (int a = 0; a < k; ++a) sy[a] = sz[a] = simd::splat(0.0);
      // The doubles [b0 D, quads) go by quads, the rest one by one.
      const std::int64_t quads = b0 * D + ((b1 - b0) * D / 4) * 4;
      // The residual's two sums in registers (acc may alias the arrays), in
      // the same order as into acc.
      double r0 = acc[0], r1 = acc[1];
      Vec<D>* const new_df = dF_[slot].data();
      Vec<D>* const new_dgu = dGu_[slot].data();
      for (std::int64_t c0 = b0; c0 < b1; c0 += kChunk) {
        const std::int64_t c1 = std::min(b1, c0 + kChunk);
        for (std::int64_t q = c0; q < c1; ++q) {
          const Vec<D> u = velocity_at<D>(p, free[q]);
          const Vec<D> f = u - u_before[q], b = u - u_free[q];
          r0 += f.dot(w[q].cwiseProduct(f));
          r1 += b.dot(w[q].cwiseProduct(b));
          if (record) {
            new_df[q] = f - f_prev_[q];
            new_dgu[q] = u - gu_prev_[q];
          }
          f_prev_[q] = f;
          gu_prev_[q] = u;
        }
        if (k > 0)
          weighted_dot_lanes(flat(w), x, k, flat(f_prev_), x[0], c0 * D, std::min(c1 * D, quads),
                             sy, sz);
      }
      acc[0] = r0;
      acc[1] = r1;
      if (k > 0)
        weighted_dot_finish(flat(w), x, k, flat(f_prev_), x[0], quads, b1 * D, sy, sz, acc + 2);
    };
    deterministic_block_sums(team, *blocks_, 2 + 2 * k, partial_, st.sums, block);
    residual[0] = st.sums[0];
    residual[1] = st.sums[1];
  }

  // After measure(), with fnorm2 = residual[0] = |f_k|_M^2: decides whether
  // the history records the sweep, and mixes. own_rows(f) calls f(j0, j1,
  // pos) on each range of rows the thread updates in the sweeps, pos
  // numbering its rows consecutively (the order in which the history of the
  // rows is stored). Leaves p holding x_{k+1} and u(x_{k+1}), and u_before
  // = u(x_{k+1}) at the free nodes, ready for the next sweep. Ends without a
  // barrier: the thread has written its own rows and its share of the free
  // nodes (SumBlocks::share), which is what the caller may read back before
  // its next barrier. depth() > 0.
  template <class OwnRows, class OwnCells>
  void mix(const Team& team, ConeProblem<D>& p, const std::vector<std::int64_t>& free,
           std::vector<Vec<D>>& u_before, double fnorm2, const OwnRows& own_rows,
           const OwnCells& own_cells, State& st) const {
    const auto [q0, q1] = blocks_->share(team);
    // The history bookkeeping, the same on every thread.
    const bool grew = st.have_prev && fnorm2 > kGrowth * kGrowth * st.fnorm2_prev;
    if (grew) st.count = 0;  // restart
    const bool record = st.have_prev && !grew;
    st.have_prev = true;
    st.fnorm2_prev = fnorm2;
    const int slot = st.next % m_;
    if (record) {
      ++st.next;
      st.count = std::min(st.count + 1, m_);
    }
    const int k = st.count;  // measure()'s k when recorded, else 0
    for (int a = 0; a < k; ++a) st.idx[a] = ((st.next - 1 - a) % m_ + m_) % m_;
    const int* idx = st.idx;
    // measure()'s dot products: the Gram matrix's new row (its older
    // entries do not change and are kept in st.gram) and r.
    const double* dots = st.sums + 2;
    for (int a = 0; a < k; ++a) st.gram[idx[a]][idx[0]] = st.gram[idx[0]][idx[a]] = dots[2 * a + 1];
    bool combine = k > 0;
    if (combine && !solve_gram(k, dots, st)) {
      st.count = 0;
      combine = false;
    }
    const double* gamma = st.gamma;
    // The thread's free nodes (the blocks it summed): u(x_{k+1}), also kept as
    // the next sweep's u_before.
    const int kc = combine ? k : 0;  // the differences combined
    const Vec<D>* gu[kMaxDepth];
    for (int a = 0; a < kc; ++a) gu[a] = dGu_[idx[a]].data();
    for (std::int64_t q = q0; q < q1; ++q) {
      Vec<D> u = velocity_at<D>(p, free[q]);
      if (combine) {
        for (int a = 0; a < kc; ++a) u -= gamma[a] * gu[a][q];
        set_velocity_at<D>(p, free[q], u);
      }
      u_before[q] = u;
    }
    // The thread's rows: the new difference of the stresses, then x_{k+1},
    // in one pass over each range.
    constexpr int SD = sym_size(D);
    double* lambda = flat(p.lambda);
    const double* dl[kMaxDepth];
    for (int a = 0; a < kc; ++a) dl[a] = flat(dGl_[idx[a]]);
    double* new_dl = record ? flat(dGl_[slot]) : nullptr;
    double* prev = flat(gl_prev_);
    own_rows([&](int j0, int j1, int pos) {
      const std::int64_t o = std::int64_t(pos) * SD;
      mix_rows(lambda + std::int64_t(j0) * SD, prev + o, new_dl ? new_dl + o : nullptr, dl, o,
               gamma, kc, std::int64_t(j1 - j0) * SD);
    });
    // The cell rows' stresses likewise, stored by cell index; own_cells(f)
    // calls f(c0, c1) on the thread's ranges of cells.
    if (gc_prev_.empty()) return;
    double* stress = flat(p.cell_stress);
    for (int a = 0; a < kc; ++a) dl[a] = flat(dGc_[idx[a]]);
    double* new_dc = record ? flat(dGc_[slot]) : nullptr;
    double* prev_c = flat(gc_prev_);
    own_cells([&](int c0, int c1) {
      const std::int64_t o = std::int64_t(c0) * SD;
      mix_rows(stress + o, prev_c + o, new_dc ? new_dc + o : nullptr, dl, o, gamma, kc,
               std::int64_t(c1 - c0) * SD);
    });
  }

 private:
  // Over the n doubles of a range of rows: nd = l - pr (when nd is not
  // null), pr = l, then l -= g[a] d[a][o + i] for a < k, in that order (the
  // same operations, and so the same bits, as one loop per step).
  static void mix_rows(double* l, double* pr, double* nd, const double* const* d, std::int64_t o,
                       const double* g, int k, std::int64_t n) {
    std::int64_t i = 0;
#ifdef SABLIER_STENCIL_LANES
    for (; i + 4 <= n; i += 4) {
      __m256d v = _mm256_loadu_pd(l + i);
      if (nd) _mm256_storeu_pd(nd + i, _mm256_sub_pd(v, _mm256_loadu_pd(pr + i)));
      _mm256_storeu_pd(pr + i, v);
      for (int a = 0; a < k; ++a)
        v = _mm256_fnmadd_pd(_mm256_set1_pd(g[a]), _mm256_loadu_pd(d[a] + o + i), v);
      _mm256_storeu_pd(l + i, v);
    }
#endif
    for (; i < n; ++i) {
      double v = l[i];
      if (nd) nd[i] = v - pr[i];
      pr[i] = v;
      for (int a = 0; a < k; ++a) v = std::fma(-g[a], d[a][o + i], v);
      l[i] = v;
    }
  }

  // st.gamma = A^{-1} r, r_a = dots[2 a]; false when the system is singular.
  static bool solve_gram(int k, const double* dots, State& st) {
    Eigen::MatrixXd A(k, k);
    Eigen::VectorXd r(k);
    for (int a = 0; a < k; ++a) {
      r[a] = dots[2 * a];
      for (int b = 0; b < k; ++b) A(a, b) = st.gram[st.idx[a]][st.idx[b]];
    }
    const double scale = A.diagonal().maxCoeff();
    if (!(scale > 0.0)) return false;
    A.diagonal().array() += kRegularisation * scale;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
    const Eigen::VectorXd gamma = ldlt.solve(r);
    if (ldlt.info() != Eigen::Success || !gamma.allFinite()) return false;
    for (int a = 0; a < k; ++a) st.gamma[a] = gamma[a];
    return true;
  }

  // Restart when |f| grows by more than 20%. Measured (sweeps per step): 3D
  // collapse (80 x 8 x 20, 0.2-0.26 s) 351 against 441 with a factor 2 and
  // 548 plain; 2D collapse at 1 cm (0.1-0.4 s) 339 against 374. A factor 1
  // (any growth) does as well there but stalls the first step of the 2D
  // collapse at 1.8e-4 (tests/test_solver.cpp).
  static constexpr double kGrowth = 1.2;
  static constexpr double kRegularisation = 1e-10;  // relative Tikhonov shift of A
  // Free nodes per chunk of the first pass: the chunk's differences and the
  // arrays its sums read stay in the first-level cache (a multiple of 4, so
  // that chunks start on a quad).
  static constexpr std::int64_t kChunk = 64;
  int m_ = 0;
  const SumBlocks* blocks_;
  // The shared history, written in work-shared loops (mutable: mix is const
  // so that its scalar state can only live in the threads' State).
  mutable std::vector<double> partial_;
  mutable std::vector<std::vector<Vec<D>>> dF_, dGu_;
  mutable std::vector<std::vector<SymVec<D>>> dGl_;
  mutable std::vector<Vec<D>> f_prev_, gu_prev_;
  mutable std::vector<SymVec<D>> gl_prev_;
  mutable std::vector<std::vector<SymVec<D>>> dGc_;  // the cell rows' (ConeProblem::cell_stress)
  mutable std::vector<SymVec<D>> gc_prev_;
};

}  // namespace solver_detail
}  // namespace sablier
