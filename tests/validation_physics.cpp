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

// The run-out converges as the solver tolerance tightens: going from 1e-5 to
// 1e-6 changes it by less than going from 1e-4 to 1e-5, and by under 2%. The
// front is the 99th percentile of the grains' x (the farthest single grain
// moves by a cell between runs: at 1.2 s it is a stray, not the deposit).
TEST(Validation, CollapseConvergesWithSolverTolerance) {
  std::vector<double> runout;
  for (const char* tol : {"1e-4", "1e-5", "1e-6"}) {
    Simulation<2> sim(scene("collapse2d.toml", {std::string("solver.tolerance=") + tol,
                                                "solver.max_iterations=20000"}));
    while (sim.time() < 1.2 - 1e-12) sim.step(sim.adaptive_dt(std::min(1.0 / 30, 1.2 - sim.time())));
    std::vector<double> xs;
    for (const Vec<2>& x : sim.particles().position) xs.push_back(x[0]);
    std::sort(xs.begin(), xs.end());
    const double front = xs[static_cast<std::size_t>(0.99 * (xs.size() - 1))];
    runout.push_back((front - 0.25) / 0.25);
    std::cout << "collapse2d, tolerance " << tol << ": run-out " << runout.back() << "\n";
  }
  EXPECT_LT(std::abs(runout[2] - runout[1]), 0.02 * runout[2]);
  EXPECT_LE(std::abs(runout[2] - runout[1]), std::abs(runout[1] - runout[0]) + 1e-3);
}

}  // namespace
}  // namespace sablier
