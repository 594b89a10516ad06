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

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/tensor.hpp"
#include "solver/cone_problem.hpp"

namespace sablier {
namespace solver_detail {

#ifdef SABLIER_STENCIL_LANES
// Four lanes from x, of which the callers use the first three (the fourth
// is the next entry's, read but never used: the arrays it reads carry
// ConeProblem::kLanePadding entries past their end).
inline __m256d load4(const double* x) { return _mm256_loadu_pd(x); }
inline __m256d load4(const float* x) { return _mm256_cvtps_pd(_mm_loadu_ps(x)); }
#endif

// The velocity the sweeps see at entry i, and its update: in 3D a grid
// node's in ConeProblem::velocity_by_axis, a rigid body's (entries from
// first_body_entry on, which only the body rows and the solver's loops over
// all entries touch) in ConeProblem::velocity; in 2D ConeProblem::velocity.
template <int D>
inline Vec<D> velocity_at(const ConeProblem<D>& p, std::int64_t i) {
  if constexpr (D == 3) {
    if (i >= p.first_body_entry) return p.velocity[i];
    return Vec<D>(p.velocity_by_axis[0][i], p.velocity_by_axis[1][i], p.velocity_by_axis[2][i]);
  } else {
    return p.velocity[i];
  }
}
template <int D>
inline void set_velocity_at(ConeProblem<D>& p, std::int64_t i, const Vec<D>& v) {
  if constexpr (D == 3) {
    if (i >= p.first_body_entry) {
      p.velocity[i] = v;
      return;
    }
    for (int c = 0; c < 3; ++c) p.velocity_by_axis[c][i] = v[c];
  } else {
    p.velocity[i] = v;
  }
}

// 3D: the velocities and inverse masses by component from p.velocity and
// p.inv_mass (before the sweeps), and p.velocity back from them (after).
template <int D>
inline void velocities_to_axes(ConeProblem<D>& p) {
  if constexpr (D == 3) {
    const std::int64_t n = static_cast<std::int64_t>(p.velocity.size());
    for (int c = 0; c < 3; ++c) {
      std::vector<double>& u = p.velocity_by_axis[c];
      std::vector<double>& m = p.inv_mass_by_axis[c];
      u.assign(n + ConeProblem<D>::kLanePadding, 0.0);
      m.assign(n + ConeProblem<D>::kLanePadding, 0.0);
      for (std::int64_t i = 0; i < n; ++i) {
        u[i] = p.velocity[i][c];
        m[i] = p.inv_mass[i][c];
      }
    }
  }
}
template <int D>
inline void velocities_from_axes(ConeProblem<D>& p) {
  if constexpr (D == 3) {
    const std::int64_t n =
        std::min<std::int64_t>(static_cast<std::int64_t>(p.velocity.size()), p.first_body_entry);
    for (std::int64_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) p.velocity[i][c] = p.velocity_by_axis[c][i];
  }
}

// 3D: the sand rows' coupling vectors by stencil line (ConeProblem::
// coupling_lines): line l (nodes 3l, 3l + 1, 3l + 2 of the stencil, which
// differ by one along x) holds the x components of its three nodes, then
// their y and z components, in single precision: half the bytes of the
// sweeps' largest stream (324 instead of 648 per row; 5-9% less time per
// sweep of the 3D bed, docs/benchmarks.md, twenty-fifth session). The rows'
// couplings in p.coupling are rounded to the same values, so that B, its
// transpose and the Delassus blocks (assemble_delassus) stay one operator:
// a relative change of at most 6e-8 per entry, far below the quadrature's
// own error, and the energy bound (B and B^T exact transposes) unchanged.
template <int D>
inline void pack_coupling_lines(ConeProblem<D>& p, int sand_rows) {
  if constexpr (D == 3) {
    constexpr int kLine = ConeProblem<D>::kLineEntries;
    for (int s = 0; s < ConeProblem<D>::NS; ++s)
      if (p.stencil[s] != p.stencil[s - s % 3] + s % 3)
        throw std::logic_error(
            "pack_coupling_lines: stencil nodes 3l, 3l+1, 3l+2 are not consecutive");
    p.coupling_lines.resize(std::size_t(sand_rows) * kLine + ConeProblem<D>::kLanePadding);
    std::fill(p.coupling_lines.end() - ConeProblem<D>::kLanePadding, p.coupling_lines.end(), 0.0f);
#pragma omp parallel for schedule(static)
    for (int j = 0; j < sand_rows; ++j) {
      float* out = p.coupling_lines.data() + std::size_t(j) * kLine;
      auto& g = p.coupling[j];
      for (int l = 0; l < 9; ++l)
        for (int c = 0; c < 3; ++c)
          for (int x = 0; x < 3; ++x) {
            const float r = static_cast<float>(g(c, 3 * l + x));
            out[9 * l + 3 * c + x] = r;
            g(c, 3 * l + x) = r;
          }
    }
  }
}

// Sand row j's coupling vectors by line (3D, pack_coupling_lines).
template <int D>
inline const float* coupling_line(const ConeProblem<D>& p, int j) {
  return p.coupling_lines.data() + std::size_t(j) * ConeProblem<D>::kLineEntries;
}

// sum_s sym((M_s^{-1} T g_s) g_s^T) for each basis tensor T (column k for
// basis element k), over n nodes s, node(s) giving (M_s^{-1}, g_s): the
// diagonal block of a row with coupling vectors g_s, before its scaling
// (assemble_delassus, assemble_cells).
template <int D, class Node>
SymMat<D> local_delassus(int n, const Node& node) {
  constexpr int SD = sym_size(D);
  SymMat<D> W;
  for (int c = 0; c < SD; ++c) {
    SymVec<D> e = SymVec<D>::Zero();
    e[c] = 1.0;
    const Mat<D> T = from_sym<D>(e);
    Mat<D> L = Mat<D>::Zero();
    for (int s = 0; s < n; ++s) {
      const auto [im, g] = node(s);
      const Vec<D> du = im.cwiseProduct(T * g);
      L.noalias() += du * g.transpose();
    }
    W.col(c) = to_sym<D>(L);
  }
  return W;
}

// (B u)_j: the symmetric part of sum_i u_i g_ji^T, in basis coordinates.
template <int D>
inline SymVec<D> apply_B(const ConeProblem<D>& p, int j) {
  Mat<D> L = Mat<D>::Zero();
  if constexpr (D == 3) {
#ifdef SABLIER_STENCIL_LANES
    // Lines in lanes: for each of the stencil's 9 lines (three nodes along
    // x, consecutive indices) one four-lane load of each velocity component
    // (ConeProblem::velocity_by_axis) and of each coupling component
    // (coupling_lines), and nine sums of lane products a[c][d] += u_c * g_d:
    // lane x holds the line's node x. The fourth lanes (the next node's
    // velocity, the next component's coupling) are never used. Each entry
    // L(c, d) is then (lane 0 + lane 1) + lane 2: the same fused products and
    // sums as the loop below (bit-identical results).
    const std::int64_t c0 = p.node[j];
    const float* gl = coupling_line<D>(p, j);
    const double* ux = p.velocity_by_axis[0].data() + c0;
    const double* uy = p.velocity_by_axis[1].data() + c0;
    const double* uz = p.velocity_by_axis[2].data() + c0;
    __m256d a[3][3];
    for (auto& r : a) r[0] = r[1] = r[2] = _mm256_setzero_pd();
    for (int l = 0; l < 9; ++l, gl += 9) {
      const std::int64_t o = p.stencil[3 * l];
      const __m256d v[3] = {load4(ux + o), load4(uy + o), load4(uz + o)};
      const __m256d w[3] = {load4(gl), load4(gl + 3), load4(gl + 6)};
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d) a[c][d] = _mm256_fmadd_pd(v[c], w[d], a[c][d]);
    }
    // The sums' lanes 0, 1, 2 gathered into three registers by a 4 x 4
    // transpose, four sums at a time (entries 0-3 and 4-7 of a in row
    // order), the ninth alone.
    const auto lane_sums = [](__m256d r0, __m256d r1, __m256d r2, __m256d r3) {
      const __m256d lo01 = _mm256_unpacklo_pd(r0, r1), hi01 = _mm256_unpackhi_pd(r0, r1);
      const __m256d lo23 = _mm256_unpacklo_pd(r2, r3), hi23 = _mm256_unpackhi_pd(r2, r3);
      const __m256d l0 = _mm256_permute2f128_pd(lo01, lo23, 0x20);
      const __m256d l1 = _mm256_permute2f128_pd(hi01, hi23, 0x20);
      const __m256d l2 = _mm256_permute2f128_pd(lo01, lo23, 0x31);
      return _mm256_add_pd(_mm256_add_pd(l0, l1), l2);
    };
    alignas(32) double e[9];
    _mm256_store_pd(e, lane_sums(a[0][0], a[0][1], a[0][2], a[1][0]));
    _mm256_store_pd(e + 4, lane_sums(a[1][1], a[1][2], a[2][0], a[2][1]));
    const __m128d low = _mm256_castpd256_pd128(a[2][2]);
    e[8] = _mm_cvtsd_f64(
        _mm_add_sd(_mm_add_sd(low, _mm_unpackhi_pd(low, low)), _mm256_extractf128_pd(a[2][2], 1)));
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) L(c, d) = e[3 * c + d];
#else
    // Entry (c, d) in partial sum x (the node's place in its line), as the
    // lanes above.
    const std::int64_t c0 = p.node[j];
    const float* gl = coupling_line<D>(p, j);
    double e[3][3][3] = {};  // [c][d][x]
    for (int l = 0; l < 9; ++l, gl += 9) {
      const std::int64_t o = c0 + p.stencil[3 * l];
      for (int c = 0; c < 3; ++c)
        for (int d = 0; d < 3; ++d)
          for (int x = 0; x < 3; ++x)
            e[c][d][x] = std::fma(p.velocity_by_axis[c][o + x], gl[3 * d + x], e[c][d][x]);
    }
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) L(c, d) = (e[c][d][0] + e[c][d][1]) + e[c][d][2];
#endif
  } else {
    // 2D: the velocities and couplings as the problem stores them.
    const Vec<D>* u = p.velocity.data() + p.node[j];
    const auto& g = p.coupling[j];
#ifdef SABLIER_STENCIL_LANES
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
#else
    for (int s = 0; s < ConeProblem<D>::NS; ++s)
      L.noalias() += u[p.stencil[s]] * g.col(s).transpose();
#endif
  }
  return to_sym<D>(L);
}

// u_i += M_i^{-1} Lambda g_ji over row j's stencil.
template <int D>
inline void scatter_stress(ConeProblem<D>& p, int j, const SymVec<D>& dlambda) {
  const Mat<D> T = from_sym<D>(dlambda);
  if constexpr (D == 3) {
#ifdef SABLIER_STENCIL_LANES
    // Lines in lanes, as in apply_B: for each line the three nodes' x, y and
    // z components of T g_s, each from the coupling's three component loads
    // (T(c, c) g_c, then T(c, c + 1) g_{c+1} and T(c, c + 2) g_{c+2} fused,
    // indices mod 3), and u_c += M_c^{-1} (T g)_c in lanes, stored by three
    // lanes only (the fourth is the next node's, which this row does not
    // move). The loop below does the same (bit-identical results).
    const std::int64_t c0 = p.node[j];
    const float* gl = coupling_line<D>(p, j);
    double* uc[3] = {p.velocity_by_axis[0].data() + c0, p.velocity_by_axis[1].data() + c0,
                     p.velocity_by_axis[2].data() + c0};
    const double* mc[3] = {p.inv_mass_by_axis[0].data() + c0, p.inv_mass_by_axis[1].data() + c0,
                           p.inv_mass_by_axis[2].data() + c0};
    __m256d t[3][3];
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) t[c][d] = _mm256_set1_pd(T(c, d));
    const __m256i three = _mm256_setr_epi64x(-1, -1, -1, 0);
    for (int l = 0; l < 9; ++l, gl += 9) {
      const std::int64_t o = p.stencil[3 * l];
      const __m256d w[3] = {load4(gl), load4(gl + 3), load4(gl + 6)};
      for (int c = 0; c < 3; ++c) {
        const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
        __m256d f = _mm256_mul_pd(t[c][c], w[c]);
        f = _mm256_fmadd_pd(t[c][c1], w[c1], f);
        f = _mm256_fmadd_pd(t[c][c2], w[c2], f);
        _mm256_maskstore_pd(uc[c] + o, three,
                            _mm256_fmadd_pd(load4(mc[c] + o), f, load4(uc[c] + o)));
      }
    }
#else
    for (int s = 0; s < ConeProblem<D>::NS; ++s) {
      // T(c, c) g_c + T(c, c + 1) g_{c+1} + T(c, c + 2) g_{c+2}, as the lanes
      // above, from the coupling by lines.
      const float* gl = coupling_line<D>(p, j) + 9 * (s / 3) + s % 3;
      const std::int64_t i = p.node[j] + p.stencil[s];
      for (int c = 0; c < 3; ++c) {
        double f = T(c, c) * gl[3 * c];
        f = std::fma(T(c, (c + 1) % 3), gl[3 * ((c + 1) % 3)], f);
        f = std::fma(T(c, (c + 2) % 3), gl[3 * ((c + 2) % 3)], f);
        double& ui = p.velocity_by_axis[c][i];
        ui = std::fma(p.inv_mass_by_axis[c][i], f, ui);
      }
    }
#endif
  } else {
    // 2D: the velocities, inverse masses and couplings as the problem
    // stores them.
    Vec<D>* u = p.velocity.data() + p.node[j];
    const Vec<D>* im = p.inv_mass.data() + p.node[j];
    const auto& g = p.coupling[j];
#ifdef SABLIER_STENCIL_LANES
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
#else
    for (int s = 0; s < ConeProblem<D>::NS; ++s) {
      const std::int64_t o = p.stencil[s];
      u[o] += im[o].cwiseProduct(T * g.col(s));
    }
#endif
  }
}

}  // namespace solver_detail
}  // namespace sablier
