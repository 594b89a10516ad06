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

}  // namespace sablier
