// Checks shared by the tests of the local Drucker-Prager solves
// (test_drucker_prager.cpp, test_slide_batch.cpp): whether a solution lies in
// DP(a), and random well-posed local problems.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>

namespace sablier::test {

inline constexpr double kTol = 1e-10;

template <int S>
using VecS = Eigen::Matrix<double, S, 1>;
template <int S>
using MatS = Eigen::Matrix<double, S, S>;

// Checks (x ; y = W x + b) in DP(a); returns a description of the failure.
template <int S>
::testing::AssertionResult in_drucker_prager(const MatS<S>& W, const VecS<S>& b, double a,
                                             const VecS<S>& x) {
  const VecS<S> y = W * x + b;
  const double xs = std::max(x.norm(), 1e-300);
  const double ys = std::max(b.norm(), W.norm() * x.norm());
  const double xn = x[0], yn = y[0];
  const double xt = x.template tail<S - 1>().norm();
  const auto yt = y.template tail<S - 1>();
  if (xn < -kTol * xs) return ::testing::AssertionFailure() << "x_N < 0: " << xn;
  if (yn < -kTol * ys) return ::testing::AssertionFailure() << "y_N < 0: " << yn;
  if (xt > a * xn + kTol * xs)
    return ::testing::AssertionFailure() << "outside cone: |x_T| " << xt << " > " << a * xn;
  if (std::abs(xn * yn) > kTol * xs * ys)
    return ::testing::AssertionFailure() << "complementarity x_N y_N = " << xn * yn;
  if (xn > kTol * xs) {
    // Compressed: either sticking (y = 0) or sliding on the cone with
    // y_T = -beta x_T, beta >= 0 (the stress opposes the shearing).
    if (xt < a * xn * (1.0 - 1e-8)) {
      if (y.norm() > kTol * ys) return ::testing::AssertionFailure() << "inside cone but y != 0";
    } else if (xt > 0.0) {
      const VecS<S - 1> xhat = x.template tail<S - 1>() / xt;
      const double along = yt.dot(xhat);
      if (along > kTol * ys) return ::testing::AssertionFailure() << "y_T along +x_T: " << along;
      if ((yt - along * xhat).norm() > kTol * ys)
        return ::testing::AssertionFailure() << "y_T not parallel to x_T";
    }
  }
  return ::testing::AssertionSuccess();
}

template <int S>
MatS<S> random_spd(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> e(-3.0, 3.0);
  MatS<S> A;
  for (int i = 0; i < S; ++i)
    for (int j = 0; j < S; ++j) A(i, j) = u(rng);
  // Condition numbers up to about 1e4, scales from 1e-3 to 1e3.
  return std::pow(10.0, e(rng)) * (A * A.transpose() + 1e-4 * MatS<S>::Identity());
}

}  // namespace sablier::test
