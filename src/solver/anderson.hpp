// The Gauss-Seidel solver's reductions and its Anderson acceleration
// (cone_problem.cpp): sums whose floating-point result does not depend on the
// thread count, and the mixing of the last sweeps (docs/method.md).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/tensor.hpp"
#include "solver/cone_problem.hpp"
#include "solver/slide_batch.hpp"
#include "solver/team.hpp"

namespace sablier {
namespace solver_detail {

// K sums at once, each over i in [0, n) in fixed blocks of 1024 and then the
// block sums in order: the same floating-point result for any thread count.
// f(i, acc) adds its K terms to acc[0..K). Called by every thread of the
// team (each fills its share of the blocks; the barrier publishes the block
// sums, which every thread then adds up itself in the same order, so all
// threads hold the same `out` without a further barrier). `partial` is the
// caller's buffer; the caller must not refill it before a barrier (every
// thread reads it here). `out` is the calling thread's own.
constexpr std::int64_t kSumBlock = 1024;

inline std::int64_t sum_blocks(std::int64_t n) { return (n + kSumBlock - 1) / kSumBlock; }

// The same with g(i0, i1, acc) adding the terms of a whole block [i0, i1).
template <class G>
void deterministic_block_sums(const Team& team, std::int64_t n, int K, std::vector<double>& partial,
                              double* out, const G& g) {
  const std::int64_t nb = sum_blocks(n);
  const auto [b0, b1] = team.split(nb);
  for (std::int64_t b = b0; b < b1; ++b) {
    double* acc = partial.data() + b * K;
    std::fill(acc, acc + K, 0.0);
    g(b * kSumBlock, std::min(n, (b + 1) * kSumBlock), acc);
  }
  team.sync();
  std::fill(out, out + K, 0.0);
  for (std::int64_t b = 0; b < nb; ++b)
    for (int k = 0; k < K; ++k) out[k] += partial[b * K + k];
}

template <class F>
void deterministic_sums(const Team& team, std::int64_t n, int K, std::vector<double>& partial,
                        double* out, const F& f) {
  deterministic_block_sums(team, n, K, partial, out,
                           [&](std::int64_t i0, std::int64_t i1, double* acc) {
                             for (std::int64_t i = i0; i < i1; ++i) f(i, acc);
                           });
}

// sum_i w_i x_i y_i and sum_i w_i x_i z_i over [i0, i1), four lanes at a
// time in a fixed order (a function of i0 and i1 alone).
inline void weighted_dots(const double* w, const double* x, const double* y, const double* z,
                          std::int64_t i0, std::int64_t i1, double& xy, double& xz) {
  using simd::Vd;
  Vd sy = simd::splat(0.0), sz = simd::splat(0.0);
  std::int64_t i = i0;
  for (; i + 4 <= i1; i += 4) {
    const Vd wx = detail::load4(w + i) * detail::load4(x + i);
    sy += wx * detail::load4(y + i);
    sz += wx * detail::load4(z + i);
  }
  double ty = (sy[0] + sy[1]) + (sy[2] + sy[3]), tz = (sz[0] + sz[1]) + (sz[2] + sz[3]);
  for (; i < i1; ++i) {
    ty += w[i] * x[i] * y[i];
    tz += w[i] * x[i] * z[i];
  }
  xy += ty;
  xz += tz;
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
// share (Team::split); the scalar bookkeeping (which slot, how many
// differences, gamma) is kept by every thread in its own `State` and updated
// identically from the same shared sums, so the threads agree without a
// barrier. Loops over the free nodes and over the rows split the same
// ranges as the solver's, so a thread reads back what it wrote itself.
template <int D>
class AndersonMixer {
 public:
  static constexpr int kMaxDepth = 16;
  static constexpr int kMaxSums = 2 * kMaxDepth;

  struct State {
    int next = 0, count = 0;
    bool have_prev = false;
    double fnorm2_prev = 0.0;
    int idx[kMaxDepth] = {};
    double sums[kMaxSums] = {};
    double gram[kMaxDepth][kMaxDepth] = {};  // <dF_s, dF_t>_M by history slots s, t
    double gamma[kMaxDepth] = {};
  };

  AndersonMixer(int depth, int rows, std::int64_t nfree) : m_(std::min(depth, kMaxDepth)) {
    if (m_ <= 0) return;
    dF_.assign(m_, std::vector<Vec<D>>(nfree, Vec<D>::Zero()));
    dGu_.assign(m_, std::vector<Vec<D>>(nfree, Vec<D>::Zero()));
    dGl_.assign(m_, std::vector<SymVec<D>>(rows, SymVec<D>::Zero()));
    f_prev_.assign(nfree, Vec<D>::Zero());
    gu_prev_.assign(nfree, Vec<D>::Zero());
    gl_prev_.assign(rows, SymVec<D>::Zero());
    partial_.assign(sum_blocks(nfree) * kMaxSums, 0.0);
  }

  // p holds G(x_k) and u(G(x_k)); u_before[q] = u(x_k) at free node q; w the
  // kinetic-energy weights per free node; fnorm2 = |f_k|_M^2. Called by
  // every thread of the solver's parallel region (or serially), each with
  // its own state `st`. Ends without a barrier: the caller's next
  // loops over its share of the free nodes or the rows see this thread's own
  // writes, and anything else must wait for a barrier.
  void mix(const Team& team, ConeProblem<D>& p, const std::vector<std::int64_t>& free,
           const std::vector<Vec<D>>& u_before, const std::vector<Vec<D>>& w, double fnorm2,
           State& st) const {
    if (m_ <= 0) return;
    const std::int64_t nf = static_cast<std::int64_t>(free.size());
    const int rows = p.rows();
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
    const int k = st.count;
    for (int a = 0; a < k; ++a) st.idx[a] = ((st.next - 1 - a) % m_ + m_) % m_;
    const int* idx = st.idx;
    // One pass over the free nodes: store the new differences and this
    // sweep's f and u(G), and accumulate r_a = <dF_a, f>_M and the Gram
    // matrix's new row A_a0 = <dF_a, dF_0>_M (dF_0 = the difference just
    // stored; k > 0 implies one was). The older entries do not change and are
    // kept in st.gram. (The loop's barrier also orders these writes before
    // the combination below, which splits the free nodes differently.)
    deterministic_block_sums(
        team, nf, 2 * k, partial_, st.sums, [&](std::int64_t b0, std::int64_t b1, double* acc) {
          for (std::int64_t q = b0; q < b1; ++q) {
            const Vec<D>& u = p.velocity[free[q]];
            const Vec<D> f = u - u_before[q];
            if (record) {
              dF_[slot][q] = f - f_prev_[q];
              dGu_[slot][q] = u - gu_prev_[q];
            }
            f_prev_[q] = f;
            gu_prev_[q] = u;
          }
          // The sums over the block's doubles (D per free node), vectorised.
          for (int a = 0; a < k; ++a)
            weighted_dots(flat(w), flat(dF_[idx[a]]), flat(f_prev_), flat(dF_[idx[0]]), b0 * D,
                          b1 * D, acc[2 * a], acc[2 * a + 1]);
        });
    for (int a = 0; a < k; ++a)
      st.gram[idx[a]][idx[0]] = st.gram[idx[0]][idx[a]] = st.sums[2 * a + 1];
    // Same row split as the combination below: no barrier needed.
    const auto [j0, j1] = team.split(rows);
    const auto [q0, q1] = team.split(nf);
    for (int j = j0; j < j1; ++j) {
      if (record) dGl_[slot][j] = p.lambda[j] - gl_prev_[j];
      gl_prev_[j] = p.lambda[j];
    }
    if (k == 0) return;
    if (!solve_gram(k, st)) {
      st.count = 0;
      return;
    }
    const double* gamma = st.gamma;
    for (std::int64_t q = q0; q < q1; ++q) {
      Vec<D>& u = p.velocity[free[q]];
      for (int a = 0; a < k; ++a) u -= gamma[a] * dGu_[idx[a]][q];
    }
    constexpr int SD = sym_size(D);
    double* lambda = flat(p.lambda);
    for (int a = 0; a < k; ++a) {
      const double* dl = flat(dGl_[idx[a]]);
      for (std::int64_t i = j0 * SD; i < j1 * SD; ++i) lambda[i] -= gamma[a] * dl[i];
    }
  }

 private:
  // st.gamma = A^{-1} r from st.sums; false when the system is singular.
  static bool solve_gram(int k, State& st) {
    Eigen::MatrixXd A(k, k);
    Eigen::VectorXd r(k);
    for (int a = 0; a < k; ++a) {
      r[a] = st.sums[2 * a];
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
  int m_ = 0;
  // The shared history, written in work-shared loops (mutable: mix is const
  // so that its scalar state can only live in the threads' State).
  mutable std::vector<double> partial_;
  mutable std::vector<std::vector<Vec<D>>> dF_, dGu_;
  mutable std::vector<std::vector<SymVec<D>>> dGl_;
  mutable std::vector<Vec<D>> f_prev_, gu_prev_;
  mutable std::vector<SymVec<D>> gl_prev_;
};

}  // namespace solver_detail
}  // namespace sablier
