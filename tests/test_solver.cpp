// The Gauss-Seidel cone solver with and without Anderson acceleration
// (docs/method.md, "The solver"). Both iterate the same fixed-point map, so
// where both converge they must return the same grid velocities; the
// accelerated solver must get there in fewer sweeps, and its answer must lie
// in the cones (it stops only after a plain sweep).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

using test::scene;

// The first step of a collapse builds the column's whole stress field from
// a zero warm start: the hardest solve of the run. Returns the grid
// velocities and the sweeps, and checks that the answer reached the
// tolerance and lies in the cones.
template <int D>
std::vector<Vec<D>> first_step(const char* name, const std::string& resolution, const char* tol,
                               int depth, int* sweeps) {
  Simulation<D> sim(scene(name, {"grid.resolution=" + resolution, std::string("solver.tolerance=") + tol,
                                 "solver.max_iterations=30000", "solver.anderson=" + std::to_string(depth)}));
  const StepInfo info = sim.step(sim.adaptive_dt(1.0 / 30));
  EXPECT_FALSE(info.solve.hit_cap) << name << " depth " << depth << " residual " << info.solve.residual;
  *sweeps = info.solve.iterations;
  // Every row's stress lies in its (cohesionless) cone: |lambda_T| <= a lambda_N.
  const ConeProblem<D>& p = sim.problem();
  for (int j = 0; j < p.rows(); ++j) {
    const SymVec<D>& l = p.lambda[j];
    const double tangential = l.tail(sym_size(D) - 1).norm();
    EXPECT_LE(tangential, p.aperture[j] * l[0] + 1e-10 * std::abs(l[0]) + 1e-12)
        << name << " depth " << depth << " row " << j;
  }
  return sim.problem().velocity;
}

template <int D>
double relative_difference(const std::vector<Vec<D>>& a, const std::vector<Vec<D>>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, (a[i] - b[i]).norm());
    scale = std::max(scale, a[i].norm());
  }
  return diff / scale;
}

// 3D (a coarse channel), where plain sweeps converge: driven to 1e-8 both
// solvers reach the same velocities, the accelerated one in fewer sweeps.
// Measured: 7,401 plain sweeps against 2,511 to reach 1e-7.
TEST(Solver, AndersonMatchesGaussSeidel3D) {
  int plain = 0, mixed = 0;
  const auto a = first_step<3>("collapse3d.toml", "[40,4,10]", "1e-8", 0, &plain);
  const auto b = first_step<3>("collapse3d.toml", "[40,4,10]", "1e-8", 5, &mixed);
  const double diff = relative_difference<3>(a, b);
  std::cout << "collapse3d first step to 1e-8: plain " << plain << " sweeps, Anderson(5) " << mixed
            << "; velocities differ by " << diff << " of the fastest node\n";
  EXPECT_LT(mixed, plain);
  EXPECT_LT(diff, 1e-4);
}

// 2D, 1 cm cells: on the first step plain sweeps stall (measured: residual
// 2.7e-4 after 30,000 sweeps, cycling along the column's shear band), while
// the accelerated solver converges: it reaches 1e-6 and then 1e-7, and the
// two answers agree to within the error the measured convergence rate
// predicts, so it has found a fixed point rather than a lucky dip. With a
// linear rate rho per sweep, the error after reaching residual r is about
// r / (1 - rho), and 1 - rho = ln(10) / (sweeps to 1e-7 - sweeps to 1e-6).
TEST(Solver, AndersonConvergesWherePlainSweepsStall2D) {
  int s6 = 0, s7 = 0;
  const auto a = first_step<2>("collapse2d.toml", "[100,25]", "1e-6", 5, &s6);
  const auto b = first_step<2>("collapse2d.toml", "[100,25]", "1e-7", 5, &s7);
  const double diff = relative_difference<2>(a, b);
  ASSERT_GT(s7, s6);
  const double predicted = 1e-6 * (s7 - s6) / std::log(10.0);
  std::cout << "collapse2d first step: Anderson(5) " << s6 << " sweeps to 1e-6, " << s7
            << " to 1e-7; velocities differ by " << diff << " of the fastest node (predicted error "
            << predicted << ")\n";
  EXPECT_LT(diff, predicted);
}

}  // namespace
}  // namespace sablier
