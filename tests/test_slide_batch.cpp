// The batched slide solve (solver/slide_batch.hpp), which the Gauss-Seidel
// sweep uses for every sand row that neither separates nor sticks: on random
// well-posed slide problems each lane's answer must be a point of DP(a) to
// 1e-10 relative (cone, complementarity, flow rule), agree with the scalar
// solve (drucker_prager.hpp) from the same guess, and depend only on its own
// problem, not on its lane or on the other problems of its batch (so that
// the sweep's results do not depend on how rows are batched, hence on the
// thread count).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "dp_checks.hpp"
#include "solver/slide_batch.hpp"

namespace sablier::test {
namespace {

template <int S>
struct SlideCase {
  MatS<S> Wm;
  LocalDelassus<S> W;
  VecS<S> b;  // rotated
  double aperture, guess;
};

// Random problems that need a slide solve (separation and stick fail), half
// of them with a guess of the multiplier from 1e-3 to 1e3 times the root.
template <int S>
std::vector<SlideCase<S>> slide_cases(std::uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), mu(0.05, 1.5), g(-3.0, 3.0);
  std::vector<SlideCase<S>> out;
  while (static_cast<int>(out.size()) < n) {
    SlideCase<S> c;
    c.Wm = random_spd<S>(rng);
    c.W.set(c.Wm);
    VecS<S> b;
    for (int k = 0; k < S; ++k) b[k] = u(rng);
    b[0] = -std::abs(b[0]);
    c.b = c.W.rotate(b);
    c.aperture = mu(rng);
    VecS<S> x;
    DPCase result;
    if (solve_without_slide<S>(c.W, c.b, c.aperture, x, result)) continue;
    double beta = 0.0;
    solve_drucker_prager_rotated<S>(c.W, c.b, c.aperture, x, beta);
    c.guess = out.size() % 2 == 0 ? 0.0 : beta * std::pow(10.0, g(rng));
    out.push_back(c);
  }
  return out;
}

// Solves the cases `which` as one batch, in that order; x and beta per case.
template <int S>
void solve_batch(const std::vector<SlideCase<S>>& cases, const std::vector<int>& which,
                 std::vector<VecS<S>>& x, std::vector<double>& beta) {
  SlideBatch<S> batch;
  for (int i : which) batch.add(cases[i].W, cases[i].b, cases[i].aperture, cases[i].guess);
  batch.solve();
  for (std::size_t l = 0; l < which.size(); ++l) {
    x[which[l]] = batch.solution(static_cast<int>(l));
    beta[which[l]] = batch.beta[l];
  }
}

template <int S>
void random_slides(std::uint64_t seed) {
  constexpr int kCases = 4000;
  const std::vector<SlideCase<S>> cases = slide_cases<S>(seed, kCases);
  std::vector<VecS<S>> x(kCases);
  std::vector<double> beta(kCases);
  // Batches of every size from 1 to 8.
  for (int i = 0, size = 1; i < kCases; i += size, size = size % 8 + 1) {
    std::vector<int> which;
    for (int k = i; k < std::min(kCases, i + size); ++k) which.push_back(k);
    solve_batch<S>(cases, which, x, beta);
  }
  int other_root = 0;
  for (int i = 0; i < kCases; ++i) {
    const SlideCase<S>& c = cases[i];
    ASSERT_GT(beta[i], 0.0) << "case " << i;
    ASSERT_TRUE(in_drucker_prager<S>(c.Wm, c.W.unrotate(c.b), c.aperture, c.W.unrotate(x[i])))
        << "case " << i;
    VecS<S> xs;
    double bs = c.guess;
    ASSERT_EQ(solve_drucker_prager_rotated<S>(c.W, c.b, c.aperture, xs, bs), DPCase::Slide);
    // In 3D the slide equation may have several roots (test_drucker_prager.cpp),
    // and where the two iterations differ (beta below the root with x_N <= 0)
    // they may reach different ones; both are exact local solutions.
    if ((x[i] - xs).norm() > kTol * xs.norm()) {
      ++other_root;
    } else {
      EXPECT_NEAR(beta[i], bs, 1e-8 * bs) << "case " << i;
    }
  }
  if (S == 3) {
    EXPECT_EQ(other_root, 0);
  }
  EXPECT_LE(other_root * 100, kCases) << "the batch left the scalar solve's root too often";
}

TEST(SlideBatch, RandomSlides2D) { random_slides<3>(21); }
TEST(SlideBatch, RandomSlides3D) { random_slides<6>(22); }

// Guesses far beyond the root (1e30 to 1e300 of W's scale: a row whose
// traction decays step after step, test_drucker_prager.cpp) leave every
// lane's answer finite and a point of DP(a): the batch's x(beta) overflows
// past beta ~ 1e28 in 3D, so such a guess starts from W's scale
// (slide_start).
template <int S>
void absurd_guesses(std::uint64_t seed) {
  std::vector<SlideCase<S>> cases = slide_cases<S>(seed, 400);
  const double guesses[] = {1e30, 1e85, 1e200, 1e300};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const double scale = std::max(cases[i].W.ev.maxCoeff(), cases[i].W.w_nn);
    cases[i].guess = guesses[i % 4] * scale;
  }
  std::vector<VecS<S>> x(cases.size());
  std::vector<double> beta(cases.size());
  for (std::size_t i = 0; i < cases.size(); i += 8) {
    std::vector<int> which;
    for (std::size_t k = i; k < std::min(cases.size(), i + 8); ++k) which.push_back(int(k));
    solve_batch<S>(cases, which, x, beta);
  }
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const SlideCase<S>& c = cases[i];
    ASSERT_TRUE(x[i].allFinite()) << "case " << i;
    ASSERT_TRUE(in_drucker_prager<S>(c.Wm, c.W.unrotate(c.b), c.aperture, c.W.unrotate(x[i])))
        << "case " << i;
  }
}

TEST(SlideBatch, AbsurdGuesses2D) { absurd_guesses<3>(23); }
TEST(SlideBatch, AbsurdGuesses3D) { absurd_guesses<6>(24); }

// Every case solved once in order and once shuffled into other lanes and
// other company: bit-identical answers.
template <int S>
void lanes_independent(std::uint64_t seed) {
  constexpr int kCases = 800;
  const std::vector<SlideCase<S>> cases = slide_cases<S>(seed, kCases);
  std::vector<VecS<S>> x0(kCases), x1(kCases);
  std::vector<double> b0(kCases), b1(kCases);
  std::vector<int> order(kCases);
  for (int i = 0; i < kCases; ++i) order[i] = i;
  for (int i = 0; i < kCases; i += 8)
    solve_batch<S>(cases, std::vector<int>(order.begin() + i, order.begin() + i + 8), x0, b0);
  std::mt19937_64 rng(seed + 1);
  std::shuffle(order.begin(), order.end(), rng);
  for (int i = 0; i < kCases; i += 5)  // batches of 5: padded lanes too
    solve_batch<S>(cases, std::vector<int>(order.begin() + i, order.begin() + i + 5), x1, b1);
  for (int i = 0; i < kCases; ++i) {
    EXPECT_EQ(std::memcmp(x0[i].data(), x1[i].data(), sizeof(double) * S), 0) << "case " << i;
    EXPECT_EQ(std::memcmp(&b0[i], &b1[i], sizeof(double)), 0) << "case " << i;
  }
}

TEST(SlideBatch, LanesIndependent2D) { lanes_independent<3>(31); }
TEST(SlideBatch, LanesIndependent3D) { lanes_independent<6>(32); }

}  // namespace
}  // namespace sablier::test
