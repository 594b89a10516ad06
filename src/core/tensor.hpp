// Small fixed-size types and the symmetric-tensor basis of METHOD.md section 4.
//
// A symmetric d x d tensor tau is stored as SD = d(d+1)/2 coordinates in a
// basis that is orthonormal for <a, b> = a:b / 2 (the paper's |tau|^2 =
// tau:tau / 2). Coordinate 0 is the trace part Tr(tau) / sqrt(2d); the others
// carry the deviatoric part, with Euclidean norm |Dev tau|. In these
// coordinates DP(mu) is a second-order cone: |x_T| <= aperture * x_N.
//
// Basis tensors (E_k, with tau = sum_k c_k E_k and c_k = E_k:tau / 2):
//   2D: E0 = I, E1 = xx - yy, E2 = xy + yx.
//   3D: E0 = sqrt(2/3) I, E1 = xx - yy, E2 = (xx + yy - 2 zz) / sqrt(3),
//       E3 = xy + yx, E4 = xz + zx, E5 = yz + zy.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace sablier {

constexpr int sym_size(int d) { return d * (d + 1) / 2; }
constexpr int ipow(int base, int e) { return e == 0 ? 1 : base * ipow(base, e - 1); }

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;
template <int D>
using Mat = Eigen::Matrix<double, D, D>;
template <int D>
using SymVec = Eigen::Matrix<double, sym_size(D), 1>;
template <int D>
using SymMat = Eigen::Matrix<double, sym_size(D), sym_size(D)>;

// sqrt(2d): Tr(tau) = sqrt(2d) * coordinate 0.
template <int D>
constexpr double trace_scale() {
  return D == 2 ? 2.0 : 2.449489742783178098197284;  // sqrt(4), sqrt(6)
}

// Cone aperture for the scene's simple-shear friction coefficient mu
// (METHOD.md section 4): aperture = mu * sqrt(2 / d).
template <int D>
inline double cone_aperture(double mu) {
  return mu * std::sqrt(2.0 / D);
}

// Coordinates of a symmetric tensor (only the symmetric part of `t` is used).
template <int D>
inline SymVec<D> to_sym(const Mat<D>& t) {
  SymVec<D> c;
  if constexpr (D == 2) {
    c[0] = 0.5 * (t(0, 0) + t(1, 1));
    c[1] = 0.5 * (t(0, 0) - t(1, 1));
    c[2] = 0.5 * (t(0, 1) + t(1, 0));
  } else {
    constexpr double inv_sqrt6 = 0.4082482904638630163662140;
    constexpr double inv_2sqrt3 = 0.2886751345948128822545744;
    c[0] = (t(0, 0) + t(1, 1) + t(2, 2)) * inv_sqrt6;
    c[1] = 0.5 * (t(0, 0) - t(1, 1));
    c[2] = (t(0, 0) + t(1, 1) - 2.0 * t(2, 2)) * inv_2sqrt3;
    c[3] = 0.5 * (t(0, 1) + t(1, 0));
    c[4] = 0.5 * (t(0, 2) + t(2, 0));
    c[5] = 0.5 * (t(1, 2) + t(2, 1));
  }
  return c;
}

// The symmetric tensor with coordinates c.
template <int D>
inline Mat<D> from_sym(const SymVec<D>& c) {
  Mat<D> t;
  if constexpr (D == 2) {
    t(0, 0) = c[0] + c[1];
    t(1, 1) = c[0] - c[1];
    t(0, 1) = t(1, 0) = c[2];
  } else {
    constexpr double sqrt2_3 = 0.8164965809277260327324280;
    constexpr double inv_sqrt3 = 0.5773502691896257645091488;
    const double iso = c[0] * sqrt2_3;
    t(0, 0) = iso + c[1] + c[2] * inv_sqrt3;
    t(1, 1) = iso - c[1] + c[2] * inv_sqrt3;
    t(2, 2) = iso - 2.0 * c[2] * inv_sqrt3;
    t(0, 1) = t(1, 0) = c[3];
    t(0, 2) = t(2, 0) = c[4];
    t(1, 2) = t(2, 1) = c[5];
  }
  return t;
}

template <int D>
inline double trace_of(const SymVec<D>& c) {
  return c[0] * trace_scale<D>();
}

// |Dev tau| in the paper's norm (sqrt(Dev tau : Dev tau / 2)).
template <int D>
inline double deviatoric_norm(const SymVec<D>& c) {
  return c.template tail<sym_size(D) - 1>().norm();
}

// Cartesian components in output order: 2D (xx, yy, xy), 3D (xx, yy, zz, xy, xz, yz).
template <int D>
inline SymVec<D> cartesian_components(const SymVec<D>& c) {
  const Mat<D> t = from_sym<D>(c);
  SymVec<D> out;
  if constexpr (D == 2) {
    out << t(0, 0), t(1, 1), t(0, 1);
  } else {
    out << t(0, 0), t(1, 1), t(2, 2), t(0, 1), t(0, 2), t(1, 2);
  }
  return out;
}

}  // namespace sablier
