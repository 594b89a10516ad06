// A stress row's gather and scatter over its stencil (cone_problem.cpp):
// (B u)_j from the velocities and the stress force's velocity change, with
// AVX2 paths where Eigen leaves the small vectors' arithmetic scalar. Each
// path does the same fused products and sums, in the same order, as the
// plain loops after it, so results do not depend on which one runs.
#pragma once

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

#include <cstdint>

#include "core/tensor.hpp"
#include "solver/cone_problem.hpp"

namespace sablier {
namespace solver_detail {

#if defined(__AVX2__) && defined(__FMA__)
// 3-vectors in the first three lanes of an AVX register (the fourth zero):
// Eigen leaves 3-vector arithmetic scalar. Loaded and stored as two and one
// doubles, so that nothing past the vector is read or written.
inline __m256d load3(const double* x) {
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(x)), _mm_load_sd(x + 2), 1);
}
inline void store3(double* x, __m256d v) {
  _mm_storeu_pd(x, _mm256_castpd256_pd128(v));
  _mm_store_sd(x + 2, _mm256_extractf128_pd(v, 1));
}
#define SABLIER_LANES3 1
#endif

// (B u)_j: the symmetric part of sum_i u_i g_ji^T, in basis coordinates.
template <int D>
inline SymVec<D> apply_B(const ConeProblem<D>& p, int j) {
  const Vec<D>* u = p.velocity.data() + p.node[j];
  const auto& g = p.coupling[j];
  Mat<D> L = Mat<D>::Zero();
#ifdef SABLIER_LANES3
  if constexpr (D == 3) {
    // Column b of L accumulates u_s g_s[b] over the stencil, in order: the
    // same fused products and sums as the loop below, four lanes at a time
    // (bit-identical results; 2-5% of a 3D sweep, docs/benchmarks.md).
    const double* gs = g.data();
    __m256d c0 = _mm256_setzero_pd(), c1 = c0, c2 = c0;
    for (int s = 0; s < ConeProblem<D>::NS; ++s, gs += 3) {
      const __m256d v = load3(u[p.stencil[s]].data());
      c0 = _mm256_fmadd_pd(v, _mm256_broadcast_sd(gs), c0);
      c1 = _mm256_fmadd_pd(v, _mm256_broadcast_sd(gs + 1), c1);
      c2 = _mm256_fmadd_pd(v, _mm256_broadcast_sd(gs + 2), c2);
    }
    store3(L.col(0).data(), c0);
    store3(L.col(1).data(), c1);
    store3(L.col(2).data(), c2);
    return to_sym<D>(L);
  }
  if constexpr (D == 2) {
    // L = (L00, L10, L01, L11) in one register: u_s = (u0, u1) twice
    // against (g0, g0, g1, g1), in stencil order, the same fused products and
    // sums as the loop below (bit-identical results).
    const double* gs = g.data();
    __m256d c = _mm256_setzero_pd();
    for (int s = 0; s < ConeProblem<D>::NS; ++s, gs += 2) {
      const __m256d v =
          _mm256_broadcast_pd(reinterpret_cast<const __m128d*>(u[p.stencil[s]].data()));
      const __m256d w =
          _mm256_permute_pd(_mm256_broadcast_pd(reinterpret_cast<const __m128d*>(gs)), 0b1100);
      c = _mm256_fmadd_pd(v, w, c);
    }
    _mm256_storeu_pd(L.data(), c);
    return to_sym<D>(L);
  }
#endif
  for (int s = 0; s < ConeProblem<D>::NS; ++s)
    L.noalias() += u[p.stencil[s]] * g.col(s).transpose();
  return to_sym<D>(L);
}

// u_i += M_i^{-1} Lambda g_ji over row j's stencil.
template <int D>
inline void scatter_stress(ConeProblem<D>& p, int j, const SymVec<D>& dlambda) {
  const Mat<D> T = from_sym<D>(dlambda);
  Vec<D>* u = p.velocity.data() + p.node[j];
  const Vec<D>* im = p.inv_mass.data() + p.node[j];
  const auto& g = p.coupling[j];
#ifdef SABLIER_LANES3
  if constexpr (D == 3) {
    // T g_s = T_0 g_s[0] + T_1 g_s[1] + T_2 g_s[2] over T's columns, four
    // lanes at a time (Eigen leaves it scalar; 5-10% of a 3D sweep,
    // docs/benchmarks.md, fifteenth session).
    const __m256d t0 = load3(T.col(0).data()), t1 = load3(T.col(1).data()),
                  t2 = load3(T.col(2).data());
    const double* gs = g.data();
    for (int s = 0; s < ConeProblem<D>::NS; ++s, gs += 3) {
      const std::int64_t o = p.stencil[s];
      __m256d f = _mm256_mul_pd(t0, _mm256_broadcast_sd(gs));
      f = _mm256_fmadd_pd(t1, _mm256_broadcast_sd(gs + 1), f);
      f = _mm256_fmadd_pd(t2, _mm256_broadcast_sd(gs + 2), f);
      store3(u[o].data(), _mm256_fmadd_pd(load3(im[o].data()), f, load3(u[o].data())));
    }
    return;
  }
  if constexpr (D == 2) {
    // Two stencil nodes per register: T g_s = T_0 g_s[0] + T_1 g_s[1] for
    // s and s + 1 at once (the same products and sums as the loop below).
    const __m256d t0 = _mm256_broadcast_pd(reinterpret_cast<const __m128d*>(T.col(0).data())),
                  t1 = _mm256_broadcast_pd(reinterpret_cast<const __m128d*>(T.col(1).data()));
    const double* gs = g.data();
    int s = 0;
    for (; s + 1 < ConeProblem<D>::NS; s += 2, gs += 4) {
      const std::int64_t o = p.stencil[s], o1 = p.stencil[s + 1];
      const __m256d gg = _mm256_loadu_pd(gs);  // g_s[0], g_s[1], g_s+1[0], g_s+1[1]
      __m256d f = _mm256_mul_pd(t0, _mm256_movedup_pd(gg));
      f = _mm256_fmadd_pd(t1, _mm256_permute_pd(gg, 0b1111), f);
      const __m256d m = _mm256_loadu2_m128d(im[o1].data(), im[o].data());
      const __m256d v = _mm256_fmadd_pd(m, f, _mm256_loadu2_m128d(u[o1].data(), u[o].data()));
      _mm_storeu_pd(u[o].data(), _mm256_castpd256_pd128(v));
      _mm_storeu_pd(u[o1].data(), _mm256_extractf128_pd(v, 1));
    }
    for (; s < ConeProblem<D>::NS; ++s, gs += 2) {
      const std::int64_t o = p.stencil[s];
      const __m128d gg = _mm_loadu_pd(gs);
      __m128d f = _mm_mul_pd(_mm256_castpd256_pd128(t0), _mm_movedup_pd(gg));
      f = _mm_fmadd_pd(_mm256_castpd256_pd128(t1), _mm_permute_pd(gg, 0b11), f);
      _mm_storeu_pd(u[o].data(),
                    _mm_fmadd_pd(_mm_loadu_pd(im[o].data()), f, _mm_loadu_pd(u[o].data())));
    }
    return;
  }
#endif
  for (int s = 0; s < ConeProblem<D>::NS; ++s) {
    const std::int64_t o = p.stencil[s];
    u[o] += im[o].cwiseProduct(T * g.col(s));
  }
}

}  // namespace solver_detail
}  // namespace sablier
