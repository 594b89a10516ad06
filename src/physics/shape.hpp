// Q1 (bilinear / trilinear) shape functions of a cell's 2^d corner nodes at a
// point: corner c selects the upper node on axis a when bit a of c is set.
#pragma once

#include <array>

#include "core/tensor.hpp"

namespace sablier {

template <int D>
struct Q1Stencil {
  static constexpr int NC = ipow(2, D);
  std::array<double, NC> w;     // N_c(x)
  std::array<Vec<D>, NC> grad;  // grad N_c(x), 1/m
};

// `local` is (x - cell origin) / h, in [0, 1]^d.
template <int D>
inline Q1Stencil<D> q1_stencil(const Vec<D>& local, double h) {
  Q1Stencil<D> s;
  double f[D][2], df[D][2];
  for (int a = 0; a < D; ++a) {
    f[a][0] = 1.0 - local[a];
    f[a][1] = local[a];
    df[a][0] = -1.0 / h;
    df[a][1] = 1.0 / h;
  }
  for (int c = 0; c < Q1Stencil<D>::NC; ++c) {
    double w = 1.0;
    for (int a = 0; a < D; ++a) w *= f[a][(c >> a) & 1];
    s.w[c] = w;
    for (int a = 0; a < D; ++a) {
      double g = df[a][(c >> a) & 1];
      for (int b = 0; b < D; ++b)
        if (b != a) g *= f[b][(c >> b) & 1];
      s.grad[c][a] = g;
    }
  }
  return s;
}

// The stencil limited to the corners whose bit is clear in `across` (the
// compatible transfer next to thin solids, physics/thin_solids.cpp):
// weights N_c / S and gradients (grad N_c - N_c grad S / S) / S over the
// kept corners, S their weights' sum, so that the weights still sum to one
// and the gradients to zero; the others zero. `across` 0 leaves it whole.
template <int D>
inline void keep_corners(unsigned across, Q1Stencil<D>& s) {
  constexpr int NC = Q1Stencil<D>::NC;
  if (across == 0) return;
  double S = 0.0;
  Vec<D> gS = Vec<D>::Zero();
  for (int c = 0; c < NC; ++c)
    if (!(across >> c & 1)) {
      S += s.w[c];
      gS += s.grad[c];
    }
  for (int c = 0; c < NC; ++c) {
    if (across >> c & 1) {
      s.w[c] = 0.0;
      s.grad[c].setZero();
    } else {
      s.w[c] /= S;
      s.grad[c] = (s.grad[c] - s.w[c] * gS) / S;
    }
  }
}

}  // namespace sablier
