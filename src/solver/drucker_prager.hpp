// The exact local Drucker-Prager solve on one stress node (METHOD.md section 2,
// step 5): find x with y = W x + b and (x ; y) in DP(aperture), where, in the
// coordinates of core/tensor.hpp (N = trace coordinate 0, T = the others):
//   separation: x = 0 and y_N >= 0;
//   stick:      y = 0 and |x_T| <= aperture x_N;
//   slide:      |x_T| = aperture x_N > 0, y_N = 0, y_T = -beta x_T with beta > 0.
//
// W is stored as `LocalDelassus`: its tangential block is diagonalised once per
// time step, W_TT = Q diag(ev) Q^T, so that every candidate solution costs
// O(SD) in the rotated coordinates r = (x_N, Q^T x_T). The cone, separation and
// flow rule are invariant under that rotation, so the solve runs entirely in
// rotated coordinates. For a plastic multiplier beta, (W + beta P_T) x = -b has
// the closed-form solution
//   x_N(beta) = (-b_N + sum_k c_k d_k / (ev_k + beta)) / (w_NN - sum_k c_k^2 / (ev_k + beta)),
//   z_k(beta) = -(d_k + c_k x_N) / (ev_k + beta),
// with c = Q^T w_TN, d = Q^T b_T, z = Q^T x_T; beta = 0 is the stick candidate.
#pragma once

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define SABLIER_ROTATION_LANES 1
#endif

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace sablier {

enum class DPCase : unsigned char { Separation = 0, Stick = 1, Slide = 2, Inactive = 3 };

// A slide solve's Newton iteration ends with a step no larger than this
// fraction of beta, taken to first order in x without a further evaluation
// (its error is of order the step squared).
inline constexpr double kLastNewtonStep = 1e-7;

template <int S>
struct LocalDelassus {
  static constexpr int T = S - 1;
  using VecS = Eigen::Matrix<double, S, 1>;
  using VecT = Eigen::Matrix<double, T, 1>;
  using MatS = Eigen::Matrix<double, S, S>;
  using MatT = Eigen::Matrix<double, T, T>;

  double w_nn = 0.0;
  VecT c = VecT::Zero();   // Q^T w_TN
  VecT ev = VecT::Zero();  // eigenvalues of W_TT (+ regularisation)
  MatT Q = MatT::Identity();
  MatT Qt = MatT::Identity();  // Q^T: its columns are Q's rows (rotated_problem's lanes)
  // For the stick candidate (beta = 0) without divisions: 1 / ev, c / ev and
  // 1 / (w_nn - c . (c / ev)), the inverse Schur complement of W_TT.
  VecT inv_ev = VecT::Zero();
  VecT c_inv_ev = VecT::Zero();
  double inv_schur = 0.0;
  bool degenerate = true;  // W == 0: the node cannot act on any free velocity

  // Relative Tikhonov shift added to W (a compliance of 1e-13 of W's scale):
  // keeps W_jj invertible on nodes whose particles span too few directions.
  static constexpr double kRegularisation = 1e-13;

  void set(const MatS& W) {
    const double scale = W.trace() / S;
    degenerate = !(scale > 0.0);
    if (degenerate) return;
    const double eps = kRegularisation * scale;
    w_nn = W(0, 0) + eps;
    const MatT wtt = W.template bottomRightCorner<T, T>();
    Eigen::SelfAdjointEigenSolver<MatT> eig;
    if constexpr (T <= 3) {
      eig.computeDirect(wtt);
    } else {
      eig.compute(wtt);
    }
    Q = eig.eigenvectors();
    Qt = Q.transpose();
    ev = eig.eigenvalues().array().max(0.0) + eps;
    c = Q.transpose() * W.template bottomLeftCorner<T, 1>();
    inv_ev = ev.cwiseInverse();
    c_inv_ev = c.cwiseProduct(inv_ev);
    inv_schur = 1.0 / (w_nn - c_inv_ev.dot(c));
  }

  // W as this block models it (regularised, eigenvalues clamped), unrotated:
  // its first row and its inverse, for ConeProblem::unrotated. In rotated
  // coordinates W^{-1} is [s, -s (c/ev)^T; -s (c/ev), diag(1/ev) + s (c/ev)
  // (c/ev)^T] with s = inv_schur (the Schur complement's inverse), and
  // unrotated R W^{-1} R^T with R = diag(1, Q). Exactly symmetric.
  void unrotated(VecS& first_row, MatS& inverse) const {
    first_row.setZero();
    inverse.setZero();
    if (degenerate) return;
    first_row[0] = w_nn;
    first_row.template tail<T>() = Q * c;
    // By blocks: with q = Q (c/ev), W^{-1} = [s, -s q^T; -s q, Q diag(1/ev)
    // Q^T + s q q^T] (a third of the products of R W^{-1} R^T in full).
    const VecT q = Q * c_inv_ev;
    inverse(0, 0) = inv_schur;
    inverse.template bottomLeftCorner<T, 1>() = -inv_schur * q;
    inverse.template topRightCorner<1, T>() = -inv_schur * q.transpose();
    for (int a = 0; a < T; ++a)
      for (int b = 0; b <= a; ++b) {
        double v = inv_schur * q[a] * q[b];
        for (int k = 0; k < T; ++k) v += Q(a, k) * inv_ev[k] * Q(b, k);
        inverse(1 + a, 1 + b) = inverse(1 + b, 1 + a) = v;
      }
  }

  VecS rotate(const VecS& x) const {
    VecS r;
    r[0] = x[0];
    r.template tail<T>() = Q.transpose() * x.template tail<T>();
    return r;
  }
  VecS unrotate(const VecS& r) const {
    VecS x;
    x[0] = r[0];
    x.template tail<T>() = Q * r.template tail<T>();
    return x;
  }
  // A row's old stress x_old = rotate(lambda) and b = rotate(y) - W x_old in
  // rotated coordinates, from its strain rate y and stress lambda.
  void rotated_problem(const VecS& y, const VecS& lambda, VecS& x_old, VecS& b) const {
#ifdef SABLIER_ROTATION_LANES
    if constexpr (T == 5) {
      // 3D: the products with Q^T for k = 0..3 in four lanes (a row of Q is
      // a column of Qt), k = 4 alone; each lane does the loop's fused
      // products and sums in its order (bit-identical results).
      __m256d zv = _mm256_setzero_pd(), yv = _mm256_setzero_pd();
      double z4 = 0.0, y4 = 0.0;
      for (int m = 0; m < T; ++m) {
        const __m256d q = _mm256_loadu_pd(Qt.data() + T * m);
        zv = _mm256_fmadd_pd(q, _mm256_set1_pd(lambda[1 + m]), zv);
        yv = _mm256_fmadd_pd(q, _mm256_set1_pd(y[1 + m]), yv);
        z4 = std::fma(Q(m, 4), lambda[1 + m], z4);
        y4 = std::fma(Q(m, 4), y[1 + m], y4);
      }
      const __m256d t = _mm256_fnmadd_pd(_mm256_loadu_pd(c.data()), _mm256_set1_pd(lambda[0]), yv);
      alignas(32) double z[4], bt[4];
      _mm256_store_pd(z, zv);
      _mm256_store_pd(bt, _mm256_fnmadd_pd(_mm256_loadu_pd(ev.data()), zv, t));
      x_old[0] = lambda[0];
      double b0 = std::fma(-w_nn, lambda[0], y[0]);
      for (int k = 0; k < 4; ++k) {
        x_old[1 + k] = z[k];
        b0 = std::fma(-c[k], z[k], b0);
        b[1 + k] = bt[k];
      }
      x_old[5] = z4;
      b[0] = std::fma(-c[4], z4, b0);
      b[5] = std::fma(-ev[4], z4, std::fma(-c[4], lambda[0], y4));
      return;
    }
#endif
    x_old[0] = lambda[0];
    double b0 = y[0] - w_nn * lambda[0];
    for (int k = 0; k < T; ++k) {
      double z = 0.0, yt = 0.0;
      for (int m = 0; m < T; ++m) {
        z += Q(m, k) * lambda[1 + m];
        yt += Q(m, k) * y[1 + m];
      }
      x_old[1 + k] = z;
      b0 -= c[k] * z;
      b[1 + k] = yt - c[k] * lambda[0] - ev[k] * z;
    }
    b[0] = b0;
  }
  // The stress change unrotate(x - x_old) less `shift` along e_0 (plain
  // loops: Eigen's small temporaries cost more than the arithmetic here).
  VecS unrotated_change(const VecS& x, const VecS& x_old, double shift) const {
    VecS out;
    out[0] = x[0] - shift - x_old[0];
#ifdef SABLIER_ROTATION_LANES
    if constexpr (T == 5) {
      // 3D: m = 0..3 in four lanes (a column of Q), m = 4 alone, the loop's
      // products and sums in its order (bit-identical results).
      __m256d ov = _mm256_setzero_pd();
      double o4 = 0.0;
      for (int k = 0; k < T; ++k) {
        const double d = x[1 + k] - x_old[1 + k];
        ov = _mm256_fmadd_pd(_mm256_loadu_pd(Q.data() + T * k), _mm256_set1_pd(d), ov);
        o4 = std::fma(Q(4, k), d, o4);
      }
      alignas(32) double o[4];
      _mm256_store_pd(o, ov);
      for (int m = 0; m < 4; ++m) out[1 + m] = o[m];
      out[5] = o4;
      return out;
    }
#endif
    for (int m = 0; m < T; ++m) {
      double s = 0.0;
      for (int k = 0; k < T; ++k) s += Q(m, k) * (x[1 + k] - x_old[1 + k]);
      out[1 + m] = s;
    }
    return out;
  }
  // W r in rotated coordinates.
  VecS apply_rotated(const VecS& r) const {
    VecS out;
    const VecT z = r.template tail<T>();
    out[0] = w_nn * r[0] + c.dot(z);
    out.template tail<T>() = c * r[0] + ev.cwiseProduct(z);
    return out;
  }
};

namespace detail {

// x(beta) of (W + beta P_T) x = -b in rotated coordinates, its derivative
// in beta, and a slide function f(beta) with its derivative and the size
// |f| below which beta counts as its root. Where x_N > 0, f = |z|^2 -
// (aperture x_N)^2, which has the sign and the root of |z| - aperture x_N
// and needs no square root; elsewhere (x_N <= 0, where the slide cannot
// hold) f = |z| - aperture x_N, which is positive there.
template <int S>
struct SlideEval {
  double beta, xn, dxn, f, df, tol;
  Eigen::Matrix<double, S - 1, 1> z, dz;
};

template <int S>
inline SlideEval<S> eval_slide(const LocalDelassus<S>& W, double bn,
                               const Eigen::Matrix<double, S - 1, 1>& d, double aperture,
                               double beta) {
  using VecT = Eigen::Matrix<double, S - 1, 1>;
  VecT r;
  double inv_den;
  // 2D: r_k = 1 / (ev_k + beta) and 1 / (w_nn - c . (c r)) from one
  // division: with e_k = ev_k + beta, p = e_0 e_1 and the denominator times
  // p, den_p = w_nn p - c_0^2 e_1 - c_1^2 e_0, q = 1 / (p den_p) gives
  // 1 / p = den_p q and 1 / den = p / den_p = p^2 q. p den_p and p^2 grow
  // as beta^4 and overflow for beta beyond about 1e77; there (slide_start
  // keeps the first beta far below, the bracket's quadrupling may still
  // reach it) the divisions one by one.
  double e0 = 0.0, e1 = 0.0, p = 0.0, den_p = 0.0;
  if constexpr (S == 3) {
    e0 = W.ev[0] + beta, e1 = W.ev[1] + beta;
    p = e0 * e1;
    den_p = W.w_nn * p - W.c[0] * W.c[0] * e1 - W.c[1] * W.c[1] * e0;
  }
  constexpr double kMax = std::numeric_limits<double>::max();
  if (S == 3 && std::abs(p * den_p) < kMax && p * p < kMax) {
    const double q = 1.0 / (p * den_p);
    const double inv_p = den_p * q;
    r[0] = e1 * inv_p;
    r[1] = e0 * inv_p;
    inv_den = p * p * q;
  } else {
    r = (W.ev.array() + beta).inverse();
    inv_den = 1.0 / (W.w_nn - W.c.cwiseProduct(r).dot(W.c));
  }
  const VecT cr = W.c.cwiseProduct(r);
  const double num = -bn + cr.dot(d);
  SlideEval<S> e;
  e.beta = beta;
  e.xn = num * inv_den;
  const VecT dc = d + W.c * e.xn;
  e.z = -dc.cwiseProduct(r);
  const VecT crr = cr.cwiseProduct(r);
  const double dnum = -crr.dot(d);
  const double dden = crr.dot(W.c);
  e.dxn = (dnum - e.xn * dden) * inv_den;
  e.dz = -cr * e.dxn + dc.cwiseProduct(r.cwiseProduct(r));
  const double zz = e.z.squaredNorm();
  if (e.xn > 0.0) {
    const double ax = aperture * e.xn;
    e.f = zz - ax * ax;
    e.df = 2.0 * (e.z.dot(e.dz) - aperture * ax * e.dxn);
    e.tol = 1e-15 * (zz + ax * ax);
  } else {
    const double zn = std::sqrt(zz);
    e.f = zn - aperture * e.xn;
    e.df = (zn > 0.0 ? e.z.dot(e.dz) / zn : 0.0) - aperture * e.dxn;
    e.tol = 1e-15 * (zn + aperture * std::abs(e.xn));
  }
  return e;
}

}  // namespace detail

// Steps 1 and 2 of the local solve in rotated coordinates (b and x rotated,
// r = (x_N, Q^T x_T)): separation, the frictionless case and the stick
// candidate. Returns false, with x = 0, when none holds and the row needs a
// slide solve (step 3: solve_drucker_prager_rotated, or a SlideBatch).
template <int S>
inline bool solve_without_slide(const LocalDelassus<S>& W, const Eigen::Matrix<double, S, 1>& b,
                                double aperture, Eigen::Matrix<double, S, 1>& x, DPCase& result) {
  constexpr int T = S - 1;
  x.setZero();
  // 1. Separation: the material is not compressed at this node.
  if (W.degenerate || b[0] >= 0.0) {
    result = DPCase::Separation;
    return true;
  }
  // Frictionless: x_T = 0 exactly, y_N = 0.
  if (aperture <= 0.0) {
    x[0] = -b[0] / W.w_nn;
    result = DPCase::Slide;
    return true;
  }
  // 2. Stick: x = -W^{-1} b, from the stored inverses (no division).
  double xn = -b[0];
  for (int k = 0; k < T; ++k) xn += W.c_inv_ev[k] * b[1 + k];
  xn *= W.inv_schur;
  double zz = 0.0;
  for (int k = 0; k < T; ++k) {
    const double z = -(b[1 + k] + W.c[k] * xn) * W.inv_ev[k];
    x[1 + k] = z;
    zz += z * z;
  }
  if (xn > 0.0 && zz <= aperture * aperture * xn * xn) {
    x[0] = xn;
    result = DPCase::Stick;
    return true;
  }
  x.setZero();
  return false;
}

// Steps 1 and 2 (separation, stick) without rotations, from the block's
// first row w0 and inverse Winv unrotated (LocalDelassus::unrotated), the
// row's stress lambda, its strain rate y at that stress and the cone's apex
// shift s e_0 (cohesion): with b_N = y_N - w0 . (lambda + s e_0) (rotations
// leave e_0 alone), the stress separates where b_N >= 0 (change -lambda -
// s e_0); else the stick stress is lambda - Winv y (the rotated stick
// solution x = -W^{-1} b, unrotated), which holds where it lies in the cone,
// |t| <= aperture (n + s) (rotations keep |t|). True with the stress change
// dl and the case; false where neither holds or the row is frictionless
// (aperture <= 0), for the rotated solve. Agrees with the rotated steps to
// round-off (tests/test_drucker_prager.cpp).
template <int S>
inline bool separate_or_stick_unrotated(const Eigen::Matrix<double, S, 1>& w0,
                                        const Eigen::Matrix<double, S, S>& inverse,
                                        const Eigen::Matrix<double, S, 1>& lambda,
                                        const Eigen::Matrix<double, S, 1>& y, double shift,
                                        double aperture, Eigen::Matrix<double, S, 1>& dl,
                                        DPCase& result) {
  if (!(aperture > 0.0)) return false;
  double bn = std::fma(-w0[0], shift, y[0]);
  for (int k = 0; k < S; ++k) bn = std::fma(-w0[k], lambda[k], bn);
  if (bn >= 0.0) {
    dl = -lambda;
    dl[0] -= shift;
    result = DPCase::Separation;
    return true;
  }
  Eigen::Matrix<double, S, 1> m = inverse.col(0) * y[0];
  for (int k = 1; k < S; ++k) m += inverse.col(k) * y[k];
  dl = -m;
  const double xn = lambda[0] - m[0] + shift;
  double tt = 0.0;
  for (int k = 1; k < S; ++k) {
    const double t = lambda[k] - m[k];
    tt = std::fma(t, t, tt);
  }
  if (xn > 0.0 && tt <= aperture * aperture * xn * xn) {
    result = DPCase::Stick;
    return true;
  }
  return false;
}

// The slide solve's first beta: the row's last one (`guess`, 0 for none),
// else W's scale. A guess beyond kSlideGuessLimit times the scale starts
// from the scale instead: beta grows without bound on a row whose traction
// decays towards zero step after step (a body's unloaded second contact
// with a wall: 1e-16 of its traction left per step, beta 1e85 within a few
// steps), and evaluating x(beta) there overflows (eval_slide).
constexpr double kSlideGuessLimit = 1e20;
template <int S>
inline double slide_start(const LocalDelassus<S>& W, double guess) {
  const double scale = std::max(W.ev.maxCoeff(), W.w_nn);
  return guess > 0.0 && guess < kSlideGuessLimit * scale ? guess : scale;
}

// Solves the local problem in rotated coordinates; b and x are rotated
// (r = (x_N, Q^T x_T)). Returns the case that holds.
// `beta` is in/out: on entry a guess of the plastic multiplier (0 for none,
// e.g. the row's value from the previous sweep), on exit the multiplier of
// the slide solution (0 in the other cases). A good guess shortens the root
// search (2D collapse: 6.7 evaluations per slide solve without, 16% less
// sweep time with). Where the slide equation has several roots (seen in 3D,
// about 1 in 2,500 random slide problems, tests/test_drucker_prager.cpp),
// each one an exact local solution, the guess may select another root.
template <int S>
inline DPCase solve_drucker_prager_rotated(const LocalDelassus<S>& W,
                                           const Eigen::Matrix<double, S, 1>& b, double aperture,
                                           Eigen::Matrix<double, S, 1>& x, double& beta) {
  using VecT = Eigen::Matrix<double, S - 1, 1>;
  constexpr int T = S - 1;
  const double guess = beta;
  beta = 0.0;
  DPCase result;
  if (solve_without_slide<S>(W, b, aperture, x, result)) return result;
  const VecT d = b.template tail<T>();
  // 3. Slide: f(0) > 0 here and f < 0 for large beta (x_N -> -b_N / w_nn > 0,
  // z -> 0). Safeguarded Newton from the guess (or from W's scale without
  // one): steps leaving the bracket [lo, hi] bisect it, or, while no point
  // with f < 0 is known (hi infinite), quadruple beta.
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double lo = 0.0, hi = kInf;
  beta = slide_start<S>(W, guess);
  detail::SlideEval<S> e;
  for (int it = 0; it < 200; ++it) {
    e = detail::eval_slide<S>(W, b[0], d, aperture, beta);
    if (std::abs(e.f) <= e.tol) break;
    if (e.f > 0.0) {
      lo = beta;
    } else {
      hi = beta;
    }
    if (hi < kInf && hi - lo <= 1e-15 * hi) break;
    double next = kInf;  // no usable Newton step
    if (e.df < 0.0) {
      const double step = -e.f / e.df;
      // Quadratic convergence: a Newton step this small leaves an error of
      // order step^2, far below round-off relative to beta, so take the
      // step and move x to first order along it instead of evaluating again.
      if (std::abs(step) <= kLastNewtonStep * beta && beta + step > lo && beta + step < hi) {
        e.xn += step * e.dxn;
        e.z += step * e.dz;
        e.beta = beta + step;
        break;
      }
      next = beta + step;
    }
    if (!(next > lo && next < hi)) next = (hi == kInf) ? 4.0 * beta : 0.5 * (lo + hi);
    beta = next;
  }
  beta = e.beta;
  // Put x exactly on the cone (the correction is at round-off level).
  const double zn = e.z.norm();
  x[0] = e.xn;
  x.template tail<T>() = zn > 0.0 ? VecT(e.z * (aperture * e.xn / zn)) : e.z;
  return DPCase::Slide;
}

// Convenience form in unrotated coordinates (tests, tools).
template <int S>
inline DPCase solve_drucker_prager(const Eigen::Matrix<double, S, S>& Wmat,
                                   const Eigen::Matrix<double, S, 1>& b, double aperture,
                                   Eigen::Matrix<double, S, 1>& x) {
  LocalDelassus<S> W;
  W.set(Wmat);
  Eigen::Matrix<double, S, 1> xr;
  double beta = 0.0;
  const DPCase c = solve_drucker_prager_rotated<S>(W, W.rotate(b), aperture, xr, beta);
  x = W.unrotate(xr);
  return c;
}

}  // namespace sablier
