// The exact local Drucker-Prager solve (METHOD.md section 2, step 5): each of
// the three cases on a constructed problem, and 10,000 random well-posed
// problems per dimension whose solutions must satisfy the cone, the
// complementarity and the flow rule to 1e-10 relative.
#include <gtest/gtest.h>

#include <random>

#include "core/tensor.hpp"
#include "dp_checks.hpp"
#include "solver/drucker_prager.hpp"

namespace sablier::test {
namespace {

template <int S>
void random_problems(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> mu(0.0, 1.5);
  int counts[3] = {0, 0, 0};
  for (int trial = 0; trial < 10000; ++trial) {
    const MatS<S> W = random_spd<S>(rng);
    VecS<S> b;
    for (int k = 0; k < S; ++k) b[k] = u(rng);
    if (trial % 3 == 0) b[0] = -std::abs(b[0]);  // favour compressed problems
    const double a = trial % 50 == 0 ? 0.0 : mu(rng);
    VecS<S> x;
    const DPCase c = solve_drucker_prager<S>(W, b, a, x);
    ++counts[static_cast<int>(c)];
    ASSERT_TRUE(in_drucker_prager<S>(W, b, a, x)) << "trial " << trial << " case " << int(c);
  }
  for (int c = 0; c < 3; ++c) EXPECT_GT(counts[c], 100) << "case " << c << " rarely exercised";
}

// The solver's rows pass the previous sweep's plastic multiplier as a guess
// for the root search. Whatever the guess (1e-6 to 1e6 times the root), the
// answer is a point of DP(a). In 3D the slide equation can have several
// roots, each an exact local solution (here in about 1 of 2,500 slide
// problems), and the guess may then pick another one; otherwise the answer
// is the unguessed one to round-off.
template <int S>
void guessed_multiplier(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> mu(0.05, 1.5);
  std::uniform_real_distribution<double> g(-6.0, 6.0);
  int slides = 0, other_root = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const MatS<S> Wm = random_spd<S>(rng);
    LocalDelassus<S> W;
    W.set(Wm);
    VecS<S> b;
    for (int k = 0; k < S; ++k) b[k] = u(rng);
    b[0] = -std::abs(b[0]);
    const double a = mu(rng);
    const VecS<S> br = W.rotate(b);
    VecS<S> x0, x1;
    double beta0 = 0.0;
    const DPCase c0 = solve_drucker_prager_rotated<S>(W, br, a, x0, beta0);
    if (c0 != DPCase::Slide) continue;
    ++slides;
    ASSERT_GT(beta0, 0.0);
    double beta1 = beta0 * std::pow(10.0, g(rng));
    const DPCase c1 = solve_drucker_prager_rotated<S>(W, br, a, x1, beta1);
    ASSERT_EQ(c1, DPCase::Slide) << "trial " << trial;
    ASSERT_TRUE(in_drucker_prager<S>(Wm, b, a, W.unrotate(x1))) << "trial " << trial;
    if ((x1 - x0).norm() > kTol * x0.norm()) {
      ++other_root;
    } else {
      EXPECT_NEAR(beta1, beta0, 1e-8 * beta0) << "trial " << trial;
    }
  }
  EXPECT_GT(slides, 1000);
  EXPECT_LE(other_root * 100, slides) << "the guess changed the answer too often";
}

TEST(DruckerPrager, GuessedMultiplier2D) { guessed_multiplier<3>(11); }
TEST(DruckerPrager, GuessedMultiplier3D) { guessed_multiplier<6>(12); }

// A row whose traction decays towards zero step after step keeps a slide
// multiplier that grows without bound (a body's unloaded second contact
// with a wall, on W's scale 1e-6: beta 1e85 within a few steps). Evaluated
// at such a beta, the 2D form of x(beta) overflowed into a NaN, which the
// body then carried. Whatever the guess, up to 1e300, the answer must be a
// point of DP(a), in 2D the unguessed one (in 3D the slide equation may
// have other roots, above); W scaled down to 1e-6 as there.
template <int S>
void absurd_guess(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), mu(0.05, 1.5);
  int slides = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const MatS<S> Wm = 1e-6 * random_spd<S>(rng);
    LocalDelassus<S> W;
    W.set(Wm);
    VecS<S> b;
    for (int k = 0; k < S; ++k) b[k] = 1e-10 * u(rng);
    b[0] = -std::abs(b[0]);
    const double a = mu(rng);
    const VecS<S> br = W.rotate(b);
    VecS<S> x0;
    double beta0 = 0.0;
    if (solve_drucker_prager_rotated<S>(W, br, a, x0, beta0) != DPCase::Slide) continue;
    ++slides;
    for (double guess : {1e30, 1e85, 1e200, 1e300}) {
      VecS<S> x;
      double beta = guess;
      ASSERT_EQ(solve_drucker_prager_rotated<S>(W, br, a, x, beta), DPCase::Slide);
      ASSERT_TRUE(x.allFinite()) << "trial " << trial << ", guess " << guess;
      ASSERT_TRUE(in_drucker_prager<S>(Wm, b, a, W.unrotate(x)))
          << "trial " << trial << ", guess " << guess;
      if (S == 3) {
        EXPECT_LE((x - x0).norm(), kTol * x0.norm()) << "trial " << trial << ", guess " << guess;
      }
    }
  }
  EXPECT_GT(slides, 100);
}

TEST(DruckerPrager, AbsurdGuessedMultiplier2D) { absurd_guess<3>(13); }
TEST(DruckerPrager, AbsurdGuessedMultiplier3D) { absurd_guess<6>(14); }

TEST(DruckerPrager, RandomProblems2D) { random_problems<3>(1); }
TEST(DruckerPrager, RandomProblems3D) { random_problems<6>(2); }

template <int S>
void three_cases() {
  std::mt19937_64 rng(7);
  const MatS<S> W = random_spd<S>(rng);
  const double a = 0.5;
  VecS<S> x;
  // Separation: the unconstrained strain rate expands (b_N > 0).
  VecS<S> b = VecS<S>::Zero();
  b[0] = 1.0;
  b[1] = -3.0;
  EXPECT_EQ(solve_drucker_prager<S>(W, b, a, x), DPCase::Separation);
  EXPECT_EQ(x.norm(), 0.0);
  // Stick: b = -W x* with x* strictly inside the cone gives back x*.
  VecS<S> xs = VecS<S>::Zero();
  xs[0] = 2.0;
  xs[1] = 0.3;
  b = -W * xs;
  if (b[0] < 0.0) {
    EXPECT_EQ(solve_drucker_prager<S>(W, b, a, x), DPCase::Stick);
    EXPECT_LT((x - xs).norm(), 1e-10 * xs.norm());
  }
  // Slide: a compressive b with a large shear gives a point on the cone.
  b = VecS<S>::Zero();
  b[0] = -1.0;
  b[S - 1] = 50.0;
  EXPECT_EQ(solve_drucker_prager<S>(W, b, a, x), DPCase::Slide);
  EXPECT_NEAR(x.template tail<S - 1>().norm(), a * x[0], 1e-12 * x.norm());
  EXPECT_TRUE(in_drucker_prager<S>(W, b, a, x));
}

TEST(DruckerPrager, ThreeCases2D) { three_cases<3>(); }
TEST(DruckerPrager, ThreeCases3D) { three_cases<6>(); }

// A row's local problem in rotated coordinates (LocalDelassus::
// rotated_problem, with AVX2 lanes in 3D) and its stress change
// (unrotated_change) against their definitions: x_old = (lambda_N, Q^T
// lambda_T), b = rotate(y) - W_rot x_old, and the change unrotate(x -
// x_old) less the shift along e_0, on random blocks W = A A^T; to round-off.
template <int S>
void rotations(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  using VecS = Eigen::Matrix<double, S, 1>;
  for (int t = 0; t < 2000; ++t) {
    Eigen::Matrix<double, S, S> A;
    for (int i = 0; i < S * S; ++i) A.data()[i] = u(rng);
    LocalDelassus<S> W;
    W.set(A * A.transpose());
    VecS y, lambda, x;
    for (int i = 0; i < S; ++i) y[i] = u(rng), lambda[i] = u(rng), x[i] = u(rng);
    VecS x_old, b;
    W.rotated_problem(y, lambda, x_old, b);
    const VecS x_ref = W.rotate(lambda);
    const VecS b_ref = W.rotate(y) - W.apply_rotated(x_ref);
    EXPECT_LE((x_old - x_ref).norm(), 1e-14 * (1.0 + x_ref.norm())) << "case " << t;
    EXPECT_LE((b - b_ref).norm(), 1e-13 * (1.0 + b_ref.norm())) << "case " << t;
    const double shift = u(rng);
    VecS change_ref = W.unrotate(x - x_old);
    change_ref[0] -= shift;
    EXPECT_LE((W.unrotated_change(x, x_old, shift) - change_ref).norm(),
              1e-14 * (1.0 + change_ref.norm()))
        << "case " << t;
  }
}

TEST(DruckerPrager, RotatedProblem2D) { rotations<3>(21); }
TEST(DruckerPrager, RotatedProblem3D) { rotations<6>(22); }

// The sweeps' first try (separate_or_stick_unrotated, with the block's first
// row and inverse from LocalDelassus::unrotated) against the rotated steps 1
// and 2 (rotated_problem, the cohesion's shift, solve_without_slide,
// unrotated_change): on random blocks W = A A^T, stresses, strain rates,
// shifts and apertures, the unrotated inverse times W is the identity, and
// both give the same case and the same stress change to round-off (times
// W's condition number), or both leave the row to the slide solve. Cases within round-off of a
// case's border (b_N or the stick stress's distance to the cone below 1e-9 of its scale) may go
// either way and are skipped.
template <int S>
void unrotated_cases(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> mu(0.05, 1.5);
  using VecS = Eigen::Matrix<double, S, 1>;
  int counts[3] = {0, 0, 0};  // separation, stick, neither
  for (int t = 0; t < 5000; ++t) {
    Eigen::Matrix<double, S, S> A;
    for (int i = 0; i < S * S; ++i) A.data()[i] = u(rng);
    const Eigen::Matrix<double, S, S> Wm = A * A.transpose();
    LocalDelassus<S> W;
    W.set(Wm);
    VecS w0;
    Eigen::Matrix<double, S, S> inv;
    W.unrotated(w0, inv);
    const double scale = Wm.norm();
    ASSERT_LE((inv * Wm - Eigen::Matrix<double, S, S>::Identity()).norm(),
              1e-9 * scale * inv.norm())
        << "case " << t;
    ASSERT_LE((w0 - Wm.row(0).transpose()).norm(), 1e-12 * scale) << "case " << t;
    VecS y, lambda;
    for (int i = 0; i < S; ++i) y[i] = u(rng), lambda[i] = u(rng);
    lambda[0] = std::abs(lambda[0]);
    const double shift = t % 4 == 0 ? 0.0 : 0.3 * std::abs(u(rng));
    const double a = mu(rng);
    if (t % 2 == 1) {
      // Half the cases aim inside the cone: y = W (lambda - lambda*) with
      // lambda* + shift e_0 within it, which sticks unless b_N >= 0.
      VecS target;
      for (int i = 0; i < S; ++i) target[i] = u(rng);
      target[0] = std::abs(target[0]) + 0.1;
      target.template tail<S - 1>() *=
          0.9 * a * (target[0] + shift) / target.template tail<S - 1>().norm();
      y = Wm * (lambda - target);
    }
    // The rotated steps, as the sweep did them before.
    VecS x_old, b, x;
    W.rotated_problem(y, lambda, x_old, b);
    VecS e0 = VecS::Zero();
    e0[0] = shift;
    b -= W.apply_rotated(e0);
    DPCase ref_case;
    const bool ref = solve_without_slide<S>(W, b, a, x, ref_case);
    // Near a border: skip.
    const VecS stick = -(inv * (W.unrotate(b)));
    const double xn = stick[0], tn = stick.template tail<S - 1>().norm();
    const double size = 1.0 + std::abs(b[0]) + stick.norm();
    if (std::abs(b[0]) < 1e-9 * size || std::abs(tn - a * xn) < 1e-9 * size) continue;
    VecS dl = VecS::Zero();  // set when got (zeroed: GCC 12 warns otherwise)
    DPCase got_case;
    const bool got = separate_or_stick_unrotated<S>(w0, inv, lambda, y, shift, a, dl, got_case);
    ASSERT_EQ(got, ref) << "case " << t;
    if (!got) {
      ++counts[2];
      continue;
    }
    ASSERT_EQ(got_case, ref_case) << "case " << t;
    ++counts[static_cast<int>(got_case)];
    const VecS dl_ref = W.unrotated_change(x, x_old, shift);
    // Both are W^{-1} applied to the same data, rounded differently: to
    // round-off amplified by W's condition number.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, S, S>> eig(Wm);
    const double cond = eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
    EXPECT_LE((dl - dl_ref).norm(), 1e-14 * cond * (1.0 + dl_ref.norm() + lambda.norm()))
        << "case " << t << " condition number " << cond;
  }
  for (int c = 0; c < 3; ++c) EXPECT_GT(counts[c], 300) << "outcome " << c << " rarely exercised";
}

TEST(DruckerPrager, UnrotatedSeparationAndStick2D) { unrotated_cases<3>(31); }
TEST(DruckerPrager, UnrotatedSeparationAndStick3D) { unrotated_cases<6>(32); }

}  // namespace
}  // namespace sablier::test
