// The slide case of the local Drucker-Prager solve (drucker_prager.hpp, step
// 3) for up to eight rows at once. A scalar slide solve is a chain of
// dependent divisions broken by unpredictable branches (how many Newton
// steps, bisect or not): on the 2D collapse at 1 cm it took 84-88 ns, 44% of
// the sweep time, for 2.4 evaluations of x(beta). Rows of one colour are
// independent, so the sweep queues the rows that need a slide solve and
// solves them here together: each row is a SIMD lane (GCC vector extensions,
// four doubles wide), its branches become selects, and two groups of four
// are interleaved so that their latencies overlap (a micro-benchmark on
// 345,000 slide problems recorded from that collapse: 25 ns per row, against
// 38 with one group of four and 84-88 for the scalar solve).
//
// Each lane runs the scalar solve's iteration: safeguarded Newton on
// f = |z|^2 - (aperture x_N)^2 from the row's guess, bracketed, bisecting or
// quadrupling beta when the Newton step leaves the bracket, and finishing
// with a first-order step below kLastNewtonStep beta. The one difference is
// where x_N <= 0 (beta below the root): there the scalar solve takes a
// Newton step of |z| - aperture x_N, which needs a square root; here beta
// grows without one. A lane stops changing once it has converged, so its
// result depends on its own row alone, not on which rows share its batch
// (results stay independent of the thread count). Solutions agree with the
// scalar solve to round-off (tests/test_slide_batch.cpp).
#pragma once

#include <cmath>
#include <limits>

#include "solver/drucker_prager.hpp"

namespace sablier {

namespace simd {
typedef double Vd __attribute__((vector_size(32)));     // four doubles
typedef long long Vm __attribute__((vector_size(32)));  // four lane masks (all bits set: true)
inline Vd splat(double x) { return Vd{x, x, x, x}; }
inline Vd select(Vm m, Vd a, Vd b) { return m ? a : b; }
inline Vd abs(Vd a) { return a < 0.0 ? -a : a; }
inline bool all(Vm m) { return (m[0] & m[1] & m[2] & m[3]) != 0; }
}  // namespace simd

template <int S>
struct SlideBatch {
  static constexpr int T = S - 1;
  static constexpr int kGroups = 2;
  static constexpr int kCapacity = 4 * kGroups;
  using VecS = Eigen::Matrix<double, S, 1>;
  using VecT = Eigen::Matrix<double, T, 1>;

  // Inputs per lane (the rotated local problem, drucker_prager.hpp) and, after
  // solve(), the solution x = (x_N, z) and its plastic multiplier.
  alignas(32) double w_nn[kCapacity], b_n[kCapacity], aperture[kCapacity], beta[kCapacity];
  alignas(32) double c[T][kCapacity], ev[T][kCapacity], d[T][kCapacity];
  alignas(32) double x_n[kCapacity], z[T][kCapacity];
  int size = 0;

  bool full() const { return size == kCapacity; }

  // Queues the slide problem of a row whose separation and stick candidates
  // failed (solve_without_slide returned false); `guess` as for the scalar
  // solve (0: none). Returns its lane.
  int add(const LocalDelassus<S>& W, const VecS& b, double aperture_, double guess) {
    const int l = size++;
    w_nn[l] = W.w_nn;
    b_n[l] = b[0];
    aperture[l] = aperture_;
    beta[l] = slide_start<S>(W, guess);
    for (int k = 0; k < T; ++k) {
      c[k][l] = W.c[k];
      ev[k][l] = W.ev[k];
      d[k][l] = b[1 + k];
    }
    return l;
  }

  // Lane l's solution in rotated coordinates.
  VecS solution(int l) const {
    VecS x;
    x[0] = x_n[l];
    for (int k = 0; k < T; ++k) x[1 + k] = z[k][l];
    return x;
  }

  // Solves every queued lane (the unused lanes repeat lane 0's problem) and
  // leaves the batch holding their solutions; size is kept.
  void solve();
};

namespace detail {

// The state of one group of four lanes during the root search.
template <int T>
struct SlideLanes {
  simd::Vd w_nn, b_n, aperture;
  simd::Vd c[T], ev[T], d[T];
  simd::Vd beta, lo, hi;
  simd::Vd out_xn, out_beta, out_z[T];
  simd::Vm done;
};

// One evaluation of x(beta) for the four lanes and one step of the root
// search (drucker_prager.hpp, eval_slide and the Newton loop), lanes that
// finish storing their solution. Returns whether all four are done.
template <int T>
inline bool slide_iteration(SlideLanes<T>& g) {
  using simd::Vd;
  using simd::Vm;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const Vd beta = g.beta;
  // r_k = 1 / (ev_k + beta) and 1 / (w_nn - sum_k c_k^2 r_k) from one
  // division (eval_slide does this in 2D): with e_k = ev_k + beta, their
  // product P, the products E_k of all but e_k and den_P = w_nn P - sum_k
  // c_k^2 E_k (the denominator times P), q = 1 / (P den_P) gives
  // r_k = E_k den_P q and 1 / den = P^2 q.
  Vd e[T], E[T], r[T];
  for (int k = 0; k < T; ++k) e[k] = g.ev[k] + beta;
  Vd prefix = simd::splat(1.0);
  for (int k = 0; k < T; ++k) {
    E[k] = prefix;
    prefix *= e[k];
  }
  const Vd P = prefix;
  Vd suffix = simd::splat(1.0);
  for (int k = T - 1; k >= 0; --k) {
    E[k] *= suffix;
    suffix *= e[k];
  }
  Vd den_p = g.w_nn * P;
  for (int k = 0; k < T; ++k) den_p -= g.c[k] * g.c[k] * E[k];
  const Vd q = 1.0 / (P * den_p);
  const Vd inv_p = den_p * q;
  for (int k = 0; k < T; ++k) r[k] = E[k] * inv_p;
  const Vd inv_den = P * P * q;
  Vd num = -g.b_n, dnum = simd::splat(0.0), dden = simd::splat(0.0), cr[T];
  for (int k = 0; k < T; ++k) {
    cr[k] = g.c[k] * r[k];
    num += cr[k] * g.d[k];
    dnum -= cr[k] * r[k] * g.d[k];
    dden += cr[k] * r[k] * g.c[k];
  }
  const Vd xn = num * inv_den;
  const Vd dxn = (dnum - xn * dden) * inv_den;
  Vd z[T], dz[T], zz = simd::splat(0.0), zdz = simd::splat(0.0);
  for (int k = 0; k < T; ++k) {
    const Vd dc = g.d[k] + g.c[k] * xn;
    z[k] = -dc * r[k];
    dz[k] = -cr[k] * dxn + dc * r[k] * r[k];
    zz += z[k] * z[k];
    zdz += z[k] * dz[k];
  }
  const Vd ax = g.aperture * xn;
  const Vm positive = xn > 0.0;
  // x_N > 0: f = |z|^2 - (a x_N)^2. Otherwise f = |z|^2 + (a x_N)^2 > 0 (beta
  // is below the root) and no Newton step.
  const Vd f = simd::select(positive, zz - ax * ax, zz + ax * ax);
  const Vd df = 2.0 * (zdz - g.aperture * ax * dxn);
  const Vm converged = simd::abs(f) <= 1e-15 * (zz + ax * ax);
  const Vm above = f > 0.0;
  const Vd lo = simd::select(above, beta, g.lo), hi = simd::select(above, g.hi, beta);
  const Vm collapsed = (hi < kInf) & (hi - lo <= 1e-15 * hi);
  const Vd step = -f / df;
  const Vd next = beta + step;
  const Vm newton = positive & (df < 0.0) & (next > lo) & (next < hi);
  const Vm last = newton & (simd::abs(step) <= kLastNewtonStep * beta);
  const Vm here = (converged | collapsed) & ~g.done;
  const Vm first_order = last & ~converged & ~collapsed & ~g.done;
  g.out_xn = simd::select(here, xn, simd::select(first_order, xn + step * dxn, g.out_xn));
  for (int k = 0; k < T; ++k)
    g.out_z[k] =
        simd::select(here, z[k], simd::select(first_order, z[k] + step * dz[k], g.out_z[k]));
  g.out_beta = simd::select(here, beta, simd::select(first_order, next, g.out_beta));
  g.done = g.done | here | first_order;
  const Vd fallback = simd::select(hi == kInf, 4.0 * beta, 0.5 * (lo + hi));
  g.beta = simd::select(g.done, beta, simd::select(newton, next, fallback));
  g.lo = lo;
  g.hi = hi;
  return simd::all(g.done);
}

inline simd::Vd load4(const double* p) {
  simd::Vd v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
inline void store4(double* p, const simd::Vd& v) { __builtin_memcpy(p, &v, sizeof v); }

}  // namespace detail

template <int S>
inline void SlideBatch<S>::solve() {
  using simd::Vd;
  if (size == 0) return;
  for (int l = size; l < kCapacity; ++l) {  // padding: a copy of lane 0
    w_nn[l] = w_nn[0];
    b_n[l] = b_n[0];
    aperture[l] = aperture[0];
    beta[l] = beta[0];
    for (int k = 0; k < T; ++k) {
      c[k][l] = c[k][0];
      ev[k][l] = ev[k][0];
      d[k][l] = d[k][0];
    }
  }
  detail::SlideLanes<T> g[kGroups];
  for (int q = 0; q < kGroups; ++q) {
    const int o = 4 * q;
    g[q].w_nn = detail::load4(w_nn + o);
    g[q].b_n = detail::load4(b_n + o);
    g[q].aperture = detail::load4(aperture + o);
    g[q].beta = detail::load4(beta + o);
    for (int k = 0; k < T; ++k) {
      g[q].c[k] = detail::load4(c[k] + o);
      g[q].ev[k] = detail::load4(ev[k] + o);
      g[q].d[k] = detail::load4(d[k] + o);
      g[q].out_z[k] = simd::splat(0.0);
    }
    g[q].lo = simd::splat(0.0);
    g[q].hi = simd::splat(std::numeric_limits<double>::infinity());
    g[q].out_xn = simd::splat(0.0);
    g[q].out_beta = g[q].beta;
    g[q].done = simd::Vm{0, 0, 0, 0};
  }
  // The scalar solve's cap on root-search iterations.
  for (int it = 0; it < 200; ++it) {
    bool all = true;
    for (int q = 0; q < kGroups; ++q) all = detail::slide_iteration<T>(g[q]) && all;
    if (all) break;
  }
  for (int q = 0; q < kGroups; ++q) {
    // Put x exactly on the cone (the correction is at round-off level).
    Vd zz = simd::splat(0.0);
    for (int k = 0; k < T; ++k) zz += g[q].out_z[k] * g[q].out_z[k];
    Vd zn = zz;
    for (int l = 0; l < 4; ++l) zn[l] = std::sqrt(zz[l]);
    const Vd scale = simd::select(zn > 0.0, g[q].aperture * g[q].out_xn / zn, simd::splat(1.0));
    const int o = 4 * q;
    detail::store4(x_n + o, g[q].out_xn);
    detail::store4(beta + o, g[q].out_beta);
    for (int k = 0; k < T; ++k) detail::store4(z[k] + o, g[q].out_z[k] * scale);
  }
}

}  // namespace sablier
