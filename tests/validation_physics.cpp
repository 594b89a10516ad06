// Long validation runs (ctest -L validation): the silo's discharge and the
// convergence of a collapse as the solver tolerance tightens.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

using test::scene;

// A silo drains at a rate that does not depend on the fill height, unlike a
// liquid (Janssen screening; Beverloo et al. 1961; METHOD.md section 5). The
// 2D silo drains through a 6 cm orifice; the mass flow over 0.3-0.9 s and
// over 0.9-1.5 s must agree within 15% while the fill height drops.
TEST(Validation, SiloDischargeDoesNotDependOnFillHeight) {
  Simulation<2> sim(scene("silo2d.toml"));
  const double m0 = sim.grain_mass();
  std::vector<double> mass;  // at 0, 0.3, 0.6, ... s
  for (int k = 0; k <= 5; ++k) {
    const double t = 0.3 * k;
    while (sim.time() < t - 1e-12) sim.step(sim.adaptive_dt(std::min(1.0 / 30, t - sim.time())));
    mass.push_back(sim.grain_mass());
  }
  const double early = (mass[1] - mass[3]) / 0.6, late = (mass[3] - mass[5]) / 0.6;
  std::cout << "silo: discharge " << early << " kg/s (0.3-0.9 s), " << late
            << " kg/s (0.9-1.5 s), per unit depth; drained " << 1 - mass[5] / m0
            << " of the grains\n";
  EXPECT_GT(early, 0.0);
  EXPECT_NEAR(late / early, 1.0, 0.15);
}

// The run-out converges as the solver tolerance tightens. A collapse is
// chaotic at the grain scale: moving the initial particles by a fraction of
// their spacing (jitter 0.5, another seed) changes the 99th-percentile
// run-out at 1.2 s by 1-2% (measured: 1.084 to 1.113 over five seeds at the
// default tolerance 1e-5). A single pair of runs cannot tell the tolerance's
// effect from that noise: on the unjittered lattice the run-outs for 1e-4,
// 1e-5 and 1e-6 were 1.097, 1.086 and 1.100, not monotone. So we compare
// ensembles: over the same five seeds, the mean run-out at 1e-6 must agree
// with the mean at 1e-5 to 2% and to within three standard errors of the
// difference of the two means (the packing noise). Measured 2026-12-01:
// means 1.108 (1e-4), 1.103 (1e-5), 1.111 (1e-6), each with a standard
// deviation of 0.011-0.018 over the seeds. The front is the 99th
// percentile of the grains' x (the farthest single grain is a stray).
double collapse_runout(const std::string& tolerance, int seed) {
  Simulation<2> sim(scene("collapse2d.toml",
                          {"solver.tolerance=" + tolerance, "solver.max_iterations=20000",
                           "seed=" + std::to_string(seed), "sand.0.jitter=0.5"}));
  while (sim.time() < 1.2 - 1e-12) sim.step(sim.adaptive_dt(std::min(1.0 / 30, 1.2 - sim.time())));
  std::vector<double> xs;
  for (const Vec<2>& x : sim.particles().position) xs.push_back(x[0]);
  std::sort(xs.begin(), xs.end());
  const double front = xs[static_cast<std::size_t>(0.99 * (xs.size() - 1))];
  return (front - 0.25) / 0.25;
}

TEST(Validation, CollapseConvergesWithSolverTolerance) {
  constexpr int kSeeds = 5;
  double mean[2] = {0.0, 0.0}, var[2] = {0.0, 0.0};
  const char* tolerances[2] = {"1e-5", "1e-6"};
  for (int t = 0; t < 2; ++t) {
    std::vector<double> r;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      r.push_back(collapse_runout(tolerances[t], seed));
      std::cout << "collapse2d, tolerance " << tolerances[t] << ", seed " << seed << ": run-out "
                << r.back() << "\n";
    }
    for (double x : r) mean[t] += x / kSeeds;
    for (double x : r) var[t] += (x - mean[t]) * (x - mean[t]) / (kSeeds - 1);
  }
  const double se = std::sqrt((var[0] + var[1]) / kSeeds);
  std::cout << "mean run-out " << mean[0] << " (1e-5), " << mean[1] << " (1e-6); standard error "
            << "of the difference " << se << "\n";
  EXPECT_LT(std::abs(mean[1] - mean[0]), 0.02 * mean[1]);
  EXPECT_LE(std::abs(mean[1] - mean[0]), 3.0 * se);
}

}  // namespace
}  // namespace sablier
