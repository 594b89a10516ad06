// A stress row's gather and scatter over its stencil (cone_problem.cpp):
// (B u)_j from the velocities and the stress force's velocity change, with
// AVX2 paths where Eigen leaves the small vectors' arithmetic scalar. Each
// path does the same fused products and sums, in the same order, as the
// plain loops after it, so results do not depend on which one runs
// (tests/test_stencil.cpp compiles the loops alone, with
// SABLIER_STENCIL_LOOPS defined, and compares the two bit for bit).
#pragma once

#if defined(__AVX2__) && defined(__FMA__) && !defined(SABLIER_STENCIL_LOOPS)
#define SABLIER_STENCIL_LANES 1
#include <immintrin.h>
#endif

#include <cmath>
#include <cstdint>

#include "core/tensor.hpp"
#include "solver/cone_problem.hpp"

namespace sablier {
namespace solver_detail {

#ifdef SABLIER_STENCIL_LANES
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
// All four lanes from x: the fourth is the next vector's first component,
// read but never used (x must not be the storage's last vector).
inline __m256d load4(const double* x) { return _mm256_loadu_pd(x); }
// Lanes (x1, x2, x0, x3) and (x2, x0, x1, x3).
inline __m256d rot1(__m256d x) { return _mm256_permute4x64_pd(x, 0b11001001); }
inline __m256d rot2(__m256d x) { return _mm256_permute4x64_pd(x, 0b11010010); }
#endif

// (B u)_j: the symmetric part of sum_i u_i g_ji^T, in basis coordinates.
template <int D>
inline SymVec<D> apply_B(const ConeProblem<D>& p, int j) {
  const Vec<D>* u = p.velocity.data() + p.node[j];
  const auto& g = p.coupling[j];
  Mat<D> L = Mat<D>::Zero();
#ifdef SABLIER_STENCIL_LANES
  if constexpr (D == 3) {
    // Three sums of lane products over the stencil: u_s * g_s gives the
    // diagonal (L00, L11, L22), u_s * rot1(g_s) gives (L01, L12, L20) and
    // u_s * rot2(g_s) gives (L02, L10, L21), with rot1 (g1, g2, g0) and
    // rot2 (g2, g0, g1) lane permutations. Two loads per node instead of
    // five (three broadcasts of g_s); the fourth lanes hold the next
    // node's first component and are never used (stencil nodes but the last
    // have a higher index after them: load4). Each sum is kept in three
    // partial sums (s = 0, 1, 2 mod 3) added at the end, so that no chain of
    // 27 fused multiply-adds waits on itself. The loop below does the same
    // products and sums (bit-identical results; docs/benchmarks.md,
    // twenty-first session).
    const double* gs = g.data();
    __m256d a[3][3];
    for (auto& r : a) r[0] = r[1] = r[2] = _mm256_setzero_pd();
    for (int s = 0; s < ConeProblem<D>::NS; s += 3) {
      for (int t = 0; t < 3; ++t) {
        const int k = s + t;
        const bool last = k == ConeProblem<D>::NS - 1;
        const double* uk = u[p.stencil[k]].data();
        const __m256d v = last ? load3(uk) : load4(uk);
        const __m256d w = last ? load3(gs + 3 * k) : load4(gs + 3 * k);
        a[t][0] = _mm256_fmadd_pd(v, w, a[t][0]);
        a[t][1] = _mm256_fmadd_pd(v, rot1(w), a[t][1]);
        a[t][2] = _mm256_fmadd_pd(v, rot2(w), a[t][2]);
      }
    }
    alignas(32) double d[3][4];
    for (int r = 0; r < 3; ++r)
      _mm256_store_pd(d[r], _mm256_add_pd(_mm256_add_pd(a[0][r], a[1][r]), a[2][r]));
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) L(c, (c + r) % 3) = d[r][c];
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
  if constexpr (D == 3) {
    // Entry (c, (c + r) % 3) in partial sum s % 3, as the lanes above.
    double d[3][3][3] = {};  // [s % 3][r][c]
    for (int s = 0; s < ConeProblem<D>::NS; ++s) {
      const Vec<D>& us = u[p.stencil[s]];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          d[s % 3][r][c] = std::fma(us[c], g(static_cast<int>((c + r) % 3), s), d[s % 3][r][c]);
    }
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) L(c, (c + r) % 3) = (d[0][r][c] + d[1][r][c]) + d[2][r][c];
  } else {
    for (int s = 0; s < ConeProblem<D>::NS; ++s)
      L.noalias() += u[p.stencil[s]] * g.col(s).transpose();
  }
  return to_sym<D>(L);
}

// u_i += M_i^{-1} Lambda g_ji over row j's stencil.
template <int D>
inline void scatter_stress(ConeProblem<D>& p, int j, const SymVec<D>& dlambda) {
  const Mat<D> T = from_sym<D>(dlambda);
  Vec<D>* u = p.velocity.data() + p.node[j];
  const Vec<D>* im = p.inv_mass.data() + p.node[j];
  const auto& g = p.coupling[j];
#ifdef SABLIER_STENCIL_LANES
  if constexpr (D == 3) {
    // T g_s = diag(T) * g_s + (T01, T12, T20) * rot1(g_s) + (T02, T10, T21)
    // * rot2(g_s), lane by lane (rot1, rot2 and load4 as in apply_B): one
    // load of g_s instead of three broadcasts, and one each of u and M^-1.
    const __m256d t0 = _mm256_setr_pd(T(0, 0), T(1, 1), T(2, 2), 0.0),
                  t1 = _mm256_setr_pd(T(0, 1), T(1, 2), T(2, 0), 0.0),
                  t2 = _mm256_setr_pd(T(0, 2), T(1, 0), T(2, 1), 0.0);
    const double* gs = g.data();
    for (int s = 0; s < ConeProblem<D>::NS; ++s, gs += 3) {
      const std::int64_t o = p.stencil[s];
      const bool last = s == ConeProblem<D>::NS - 1;
      const __m256d w = last ? load3(gs) : load4(gs);
      __m256d f = _mm256_mul_pd(t0, w);
      f = _mm256_fmadd_pd(t1, rot1(w), f);
      f = _mm256_fmadd_pd(t2, rot2(w), f);
      const __m256d m = last ? load3(im[o].data()) : load4(im[o].data());
      const __m256d v = last ? load3(u[o].data()) : load4(u[o].data());
      store3(u[o].data(), _mm256_fmadd_pd(m, f, v));
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
    if constexpr (D == 3) {
      // T(c, c) g_c + T(c, c + 1) g_{c+1} + T(c, c + 2) g_{c+2}, as the lanes above.
      for (int c = 0; c < 3; ++c) {
        double f = T(c, c) * g(c, s);
        f = std::fma(T(c, (c + 1) % 3), g((c + 1) % 3, s), f);
        f = std::fma(T(c, (c + 2) % 3), g((c + 2) % 3, s), f);
        u[o][c] = std::fma(im[o][c], f, u[o][c]);
      }
    } else {
      u[o] += im[o].cwiseProduct(T * g.col(s));
    }
  }
}

}  // namespace solver_detail
}  // namespace sablier
