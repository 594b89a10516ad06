// Under-relaxation of the stress rows that cycle between stick and slide
// (solver/relaxation.hpp, docs/method.md "Rows that cycle between stick and
// slide"): the projection that keeps relaxed stresses in their cones, which
// rows are relaxed, and a solve of pile2d that cycled to its cap without it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "cone_problem_file.hpp"
#include "io/writers.hpp"
#include "physics/simulation.hpp"
#include "solver/relaxation.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

const auto* const kOneThread = testing::AddGlobalTestEnvironment(new test::OneThread);

// Moreau's decomposition characterises the Euclidean projection p of x onto
// a closed convex cone K: p in K, x - p in the polar cone K° = {y : y.k <= 0
// for all k in K}, and p . (x - p) = 0. For K = {|x_T| <= a x_N}, K° =
// {|y_T| <= -y_N / a}.
template <int S>
void check_projection(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> apertures(0.05, 2.0);
  for (int trial = 0; trial < 2000; ++trial) {
    Eigen::Matrix<double, S, 1> x;
    for (int k = 0; k < S; ++k) x[k] = normal(rng);
    const double a = apertures(rng);
    Eigen::Matrix<double, S, 1> p = x;
    project_onto_cone<S>(p, a);
    const Eigen::Matrix<double, S, 1> q = x - p;
    const double scale = x.norm();
    EXPECT_LE(p.template tail<S - 1>().norm(), a * p[0] + 1e-12 * scale) << "trial " << trial;
    EXPECT_LE(q.template tail<S - 1>().norm(), -q[0] / a + 1e-12 * scale / a) << "trial " << trial;
    EXPECT_NEAR(p.dot(q), 0.0, 1e-12 * scale * scale) << "trial " << trial;
    Eigen::Matrix<double, S, 1> again = p;
    project_onto_cone<S>(again, a);
    EXPECT_LE((again - p).norm(), 1e-14 * scale) << "trial " << trial;
  }
}

TEST(Relaxation, ProjectionIsMoreausDecomposition) {
  std::mt19937 rng(7);
  check_projection<3>(rng);
  check_projection<6>(rng);
}

// A one-row problem for the bookkeeping: the row's case history is played
// through relaxed_row.
ConeProblem<2> one_row(double relaxation) {
  ConeProblem<2> p;
  p.relaxation = relaxation;
  p.state.assign(1, DPCase::Separation);
  p.flips.assign(1, 0);
  p.calm.assign(1, 0);
  return p;
}

bool play(ConeProblem<2>& p, DPCase next) {
  const bool relaxed = relaxed_row<2>(p, 0, next);
  p.state[0] = next;
  return relaxed;
}

// A row is relaxed from its third flip between stick and slide, as long as
// the flips come at most kCalmSweeps updates apart, and until it has been
// calm for longer; separation does not count as a flip; and with
// relaxation = 1 no row is ever relaxed.
TEST(Relaxation, OnlyRowsThatKeepFlippingAreRelaxed) {
  ConeProblem<2> p = one_row(0.5);
  EXPECT_FALSE(play(p, DPCase::Stick));  // from separation: no flip
  EXPECT_FALSE(play(p, DPCase::Slide));  // 1
  EXPECT_FALSE(play(p, DPCase::Stick));  // 2
  for (int k = 0; k < kCalmSweeps; ++k) EXPECT_FALSE(play(p, DPCase::Stick));
  EXPECT_TRUE(play(p, DPCase::Slide));  // 3, kCalmSweeps updates after the last
  for (int k = 0; k < kCalmSweeps; ++k) EXPECT_TRUE(play(p, DPCase::Slide)) << k;
  EXPECT_FALSE(play(p, DPCase::Slide));  // calm for longer: settled
  EXPECT_FALSE(play(p, DPCase::Stick));  // counting starts again
  EXPECT_FALSE(play(p, DPCase::Separation));
  EXPECT_FALSE(play(p, DPCase::Slide));  // separation in between: no flip

  // Flips further apart than kCalmSweeps never add up.
  ConeProblem<2> sparse = one_row(0.5);
  DPCase c = DPCase::Stick;
  play(sparse, c);
  for (int flip = 0; flip < 10; ++flip) {
    for (int k = 0; k <= kCalmSweeps; ++k) EXPECT_FALSE(play(sparse, c));
    c = c == DPCase::Stick ? DPCase::Slide : DPCase::Stick;
    EXPECT_FALSE(play(sparse, c)) << "flip " << flip;
  }

  ConeProblem<2> off = one_row(1.0);
  for (int k = 0; k < 10; ++k) EXPECT_FALSE(play(off, k % 2 ? DPCase::Slide : DPCase::Stick));
}

// The relaxed change keeps a fixed point (no local change, no change) and
// the answer in the cone, also from a stress outside it (as Anderson mixing
// may leave one); inside, it is the fraction `relaxation` of the change.
TEST(Relaxation, RelaxedStressStaysInTheCone) {
  ConeProblem<2> p = one_row(0.5);
  p.aperture.assign(1, 0.5);
  p.cohesion.assign(1, 100.0);
  p.lambda.assign(1, SymVec<2>(1000.0, 300.0, -200.0));  // |t| = 360.6 <= 0.5 (1000 + 100)
  EXPECT_EQ(relaxed_change<2>(p, 0, SymVec<2>::Zero()).norm(), 0.0);
  const SymVec<2> dl(-300.0, 20.0, 10.0);  // to (700, 320, -190), inside
  const SymVec<2> half = relaxed_change<2>(p, 0, dl);
  const SymVec<2> mid = p.lambda[0] + 0.5 * dl;  // (850, 310, -195), inside
  EXPECT_LT((p.lambda[0] + half - mid).norm(), 1e-12 * mid.norm());
  p.lambda[0] = SymVec<2>(100.0, 900.0, 0.0);  // outside: |t| = 900 > 0.5 (100 + 100)
  const SymVec<2> out = p.lambda[0] + relaxed_change<2>(p, 0, SymVec<2>(50.0, -100.0, 0.0));
  EXPECT_LE(out.tail(2).norm(), 0.5 * (out[0] + 100.0) * (1 + 1e-12));
}

// A solve that cycles between stick and slide, recorded: pile2d (the shipped
// scene) with seed 2 and the relaxation off, its step 259 at 0.636 s (485
// rows), as the solver received it (recorded 2026-12-07 by
// DISABLED_RecordPile2DCycle below, with the build 191c36f). Solved
// without relaxation, one row next to the middle of the stick floor, its
// block nearly singular (Schur complement 5.4% of w_NN), is still flipping
// between stick and slide at the cap, as in the first such cycle measured
// (2026-12-06, docs/benchmarks.md, twenty-seventh section). Until the
// fortieth session the test replayed the pour itself, and rested on a chaotic
// trajectory: any change of the engine moved which steps cap.
const std::string kCycleFile = SABLIER_SOURCE_DIR "/tests/data/pile2d_cycle.bin";

// Without relaxation the recorded solve stops at the cap; with the
// shipped relaxation (0.5) it reaches the tolerance, its stresses in their
// cones, in a fraction of the cap (68 sweeps when recorded).
TEST(Relaxation, EndsPile2DStickSlideCycle) {
  const SceneConfig scene = test::scene("pile2d.toml");
  ASSERT_EQ(scene.solver.relaxation, 0.5);
  const ConeProblem<2> recorded = test::load_cone_problem<2>(kCycleFile);
  ASSERT_EQ(recorded.rows(), 485);
  auto solve = [&](double relaxation) {
    ConeProblem<2> p = recorded;
    p.relaxation = relaxation;
    const SolveReport r = solve_gauss_seidel(p, scene.solver.tolerance, scene.solver.max_iterations,
                                             scene.solver.anderson);
    test::expect_stresses_in_cones(p, "pile2d's recorded step");
    std::cout << "relaxation " << relaxation << ": " << r.iterations << " sweeps, residual "
              << r.residual << "\n";
    return r;
  };
  const SolveReport plain = solve(1.0), relaxed = solve(scene.solver.relaxation);
  EXPECT_TRUE(plain.hit_cap);
  EXPECT_EQ(plain.iterations, scene.solver.max_iterations);
  EXPECT_FALSE(relaxed.hit_cap);
  EXPECT_LE(relaxed.residual, scene.solver.tolerance);
  EXPECT_LT(relaxed.iterations, scene.solver.max_iterations / 4);
}

// The recorded file reads back what was saved: every stored field to the
// bit, and a cut file is refused rather than read short.
TEST(Relaxation, RecordedProblemRoundTrips) {
  const ConeProblem<2> a = test::load_cone_problem<2>(kCycleFile);
  const std::string copy = testing::TempDir() + "cone_problem_copy.bin";
  test::save_cone_problem(a, copy);
  const ConeProblem<2> b = test::load_cone_problem<2>(copy);
  ASSERT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.velocity, b.velocity);
  EXPECT_EQ(a.inv_mass, b.inv_mass);
  EXPECT_EQ(a.stencil, b.stencil);
  EXPECT_EQ(a.colour_start, b.colour_start);
  EXPECT_EQ(a.zones, b.zones);
  EXPECT_EQ(a.node, b.node);
  EXPECT_EQ(a.coupling, b.coupling);
  EXPECT_EQ(a.volume, b.volume);
  EXPECT_EQ(a.k, b.k);
  EXPECT_EQ(a.aperture, b.aperture);
  EXPECT_EQ(a.cohesion, b.cohesion);
  EXPECT_EQ(a.lambda, b.lambda);
  const std::string bytes = read_file(copy);
  write_file_atomic(copy, bytes.substr(0, bytes.size() / 2));
  EXPECT_THROW(test::load_cone_problem<2>(copy), std::runtime_error);
  std::remove(copy.c_str());
}

// Records kCycleFile again (run it alone, with
// --gtest_also_run_disabled_tests): pile2d with seed 2 and the relaxation
// off, up to its first step that stops at the cap without relaxation and
// reaches the tolerance with it. Which step that is depends on the engine:
// since 3a9ee8a it is step 615 (806 rows, 823 sweeps relaxed), so a new
// recording needs the expectations above (485 rows, 68 sweeps) updated.
TEST(Relaxation, DISABLED_RecordPile2DCycle) {
  const SceneConfig plain = test::scene("pile2d.toml", {"solver.relaxation=1", "seed=2"});
  Simulation<2> sim(plain);
  ConeProblem<2> before;
  sim.before_solve = [&](const ConeProblem<2>& p) { before = p; };
  while (sim.time() < 2.0) {
    const double frame_end = std::floor(sim.time() * 30 + 1 + 1e-9) / 30;
    if (!sim.step(sim.adaptive_dt(frame_end - sim.time())).solve.hit_cap) continue;
    ConeProblem<2> p = before;
    p.relaxation = 0.5;
    const SolveReport r = solve_gauss_seidel(p, plain.solver.tolerance, plain.solver.max_iterations,
                                             plain.solver.anderson);
    if (r.hit_cap) continue;
    test::save_cone_problem(before, kCycleFile);
    std::cout << "recorded step " << sim.steps() << " (" << before.rows()
              << " rows): " << r.iterations << " sweeps relaxed\n";
    return;
  }
  FAIL() << "no capped step of pile2d's first 2 s that the relaxation ends";
}

}  // namespace
}  // namespace sablier
