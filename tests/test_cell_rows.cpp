// The node-to-node stabilisation (solver/cell_rows.hpp, solver.stabilization):
// its operator leaves affine velocity fields alone and sees strain rates
// that alternate from cell to cell, the solve ends on its viscous law, it
// only dissipates, and the result does not depend on the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "solver/cell_rows.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

using test::scene;

// Node n of a cell row's footprint, coordinates -1 ... 2 from the cell's
// lowest corner (cell_gradient_table).
template <int D>
Vec<D> footprint_node(int n, double h) {
  Vec<D> x;
  for (int a = 0; a < D; ++a, n /= 4) x[a] = (n % 4 - 1) * h;
  return x;
}

// A_c u = sym(sum_n u_n G_n^T) for u given at the footprint's nodes.
template <int D, class U>
Mat<D> node_to_node_strain(double h, const U& u) {
  const auto G = solver_detail::cell_gradient_table<D>(h);
  Mat<D> L = Mat<D>::Zero();
  for (int n = 0; n < G.cols(); ++n) L += u(footprint_node<D>(n, h), n) * G.col(n).transpose();
  return 0.5 * (L + L.transpose());
}

// Affine fields u = a + B x (any B: stretching, shear, rotation) are
// invisible to the rows: both means of the gradient are B (to rounding).
// A vertical velocity alternating from node to node along y, u_y =
// (-1)^{i_y}, has cell strain rates eps_yy = -/+ 2 / h alternating from
// cell to cell; their (1, 2, 1) / 4 average vanishes, so A_c is the cell's
// own strain rate, while the stress rows, which average a cell with its
// neighbours, barely see it (docs/validation.md, "Settled deposits on fine
// grids").
template <int D>
void check_table() {
  const double h = 0.01;
  Mat<D> B = Mat<D>::Random();
  const Vec<D> a = Vec<D>::Random();
  const Mat<D> affine =
      node_to_node_strain<D>(h, [&](const Vec<D>& x, int) -> Vec<D> { return a + B * x; });
  EXPECT_LT(affine.norm(), 1e-12 * (B.norm() + a.norm() / h)) << "D = " << D;
  const Mat<D> alternating = node_to_node_strain<D>(h, [&](const Vec<D>& x, int) -> Vec<D> {
    Vec<D> u = Vec<D>::Zero();
    const int iy = static_cast<int>(std::lround(x[1] / h));
    u[1] = (iy % 2 == 0) ? 1.0 : -1.0;
    return u;
  });
  // The cell spans nodes y = 0 (u_y = 1) and y = h (u_y = -1): eps_yy = -2 / h.
  EXPECT_NEAR(alternating(1, 1), -2.0 / h, 1e-9 / h) << "D = " << D;
  EXPECT_NEAR(alternating.norm(), 2.0 / h, 1e-9 / h) << "D = " << D;
}

TEST(CellRows, AffineFieldsAreInvisibleAlternatingStrainIsSeen) {
  check_table<2>();
  check_table<3>();
}

// A_c u at a cell row of a solved problem, from the problem's velocities.
template <int D>
SymVec<D> strain_of(const ConeProblem<D>& p, int c) {
  Mat<D> L = Mat<D>::Zero();
  for (int n = 0; n < ConeProblem<D>::NF; ++n)
    L += p.velocity[p.cell_base[c] + p.cell_stencil[n]] * p.cell_gradient.col(n).transpose();
  return to_sym<D>(L);
}

// One step of a collapse solved tightly: every cell row ends on its law
// s_c = -2 eta A_c u (to the solve's accuracy, relative to the largest
// stress), which makes its dissipation V_c s_c . A_c u = -2 eta V_c |A_c u|^2
// <= 0; the stress rows lie in their cones. Measured (stabilization 10):
// 2D, 12.5 mm, 243 cell rows, law error 3.6e-6 of the largest stress (363
// Pa); 3D, 92 cell rows.
template <int D>
void check_law(const char* name, const std::string& resolution) {
  Simulation<D> sim(scene(name, {"grid.resolution=" + resolution, "solver.stabilization=10",
                                 "solver.tolerance=1e-9", "solver.max_iterations=100000"}));
  sim.step(sim.adaptive_dt(1.0 / 30));
  sim.step(sim.adaptive_dt(1.0 / 30));
  const ConeProblem<D>& p = sim.problem();
  ASSERT_GT(p.cells(), 50) << name;
  double largest = 0.0, error = 0.0, dissipation = 0.0;
  for (int c = 0; c < p.cells(); ++c) {
    const SymVec<D> law = -2.0 * p.cell_viscosity * strain_of<D>(p, c);
    largest = std::max(largest, p.cell_stress[c].norm());
    error = std::max(error, (p.cell_stress[c] - law).norm());
    dissipation += p.cell_volume * p.cell_stress[c].dot(strain_of<D>(p, c));
  }
  std::cout << name << ": " << p.cells() << " cell rows, largest stress " << largest
            << " Pa, law error " << error << " Pa, power " << dissipation << " W\n";
  ASSERT_GT(largest, 0.0) << name;
  EXPECT_LT(error, 1e-5 * largest) << name;
  EXPECT_LE(dissipation, 0.0) << name;
  test::expect_stresses_in_cones(p, name);
}

TEST(CellRows, SolveEndsOnTheViscousLaw2D) { check_law<2>("collapse2d.toml", "[80,20]"); }
TEST(CellRows, SolveEndsOnTheViscousLaw3D) { check_law<3>("collapse3d.toml", "[40,4,10]"); }

// The rows are swept in colours shared by the team: the same bits on one
// and two threads.
TEST(CellRows, SameBitsOnOneAndTwoThreads2D) {
  test::expect_same_bits_on_1_and_2_threads<2>(
      scene("collapse2d.toml", {"solver.stabilization=10"}), 12);
}
TEST(CellRows, SameBitsOnOneAndTwoThreads3D) {
  test::expect_same_bits_on_1_and_2_threads<3>(
      scene("collapse3d.toml", {"grid.resolution=[40,4,10]", "solver.stabilization=10"}), 6);
}

// The rows act only on sand at rest (full corners slower than 0.1 sqrt(g h),
// Simulation::build_cells): a draining bin's flow is left alone. silo2d
// from 0.25 to 0.5 s, potential energy lost per second (the discharge's
// measure, Beverloo's rate times the fall): with stabilization 10 within 3%
// of the rate without. Measured: 0.6% slower over 0.25-0.75 s; with every
// full interior cell stabilised, moving or not, 21% slower.
TEST(CellRows, LeaveADrainingBinAlone2D) {
  double rate[2];
  for (int k = 0; k < 2; ++k) {
    Simulation<2> sim(
        scene("silo2d.toml", {k ? "solver.stabilization=10" : "solver.stabilization=0"}));
    test::run_until(sim, 0.25);
    const double before = sim.potential_energy();
    test::run_until(sim, 0.5);
    rate[k] = (before - sim.potential_energy()) / 0.25;
  }
  std::cout << "silo2d, 0.25-0.5 s: potential energy lost at " << rate[0] << " W/m without, "
            << rate[1] << " with stabilization 10\n";
  ASSERT_GT(rate[0], 0.0);
  EXPECT_NEAR(rate[1] / rate[0], 1.0, 0.03);
}

// What the rows are for: a settled deposit on a fine grid stays settled.
// collapse2d at 5 mm (the lattice, 3 grains per cell and axis) to 3 s with
// stabilization 100: after 1.6 s (the deposit has stopped by about 1.2 s)
// its kinetic energy stays below 1e-4 J/m, where without the rows it slid
// again, to 5.1e-2 J/m at 1.3 s (docs/validation.md, "Settled deposits on
// fine grids"). Measured with the rows: at most 1.2e-5 J/m after 1.6 s.
TEST(CellRows, SettledDepositOnAFineGridStaysSettled2D) {
  Simulation<2> sim(
      scene("collapse2d.toml", {"grid.resolution=[200,50]", "solver.stabilization=100"}));
  double largest = 0.0;
  const double frame = 1.0 / 30;
  while (sim.time() < 3.0 - 1e-9) {
    const double end = (std::floor(sim.time() / frame + 1e-9) + 1) * frame;
    sim.step(sim.adaptive_dt(end - sim.time()));
    if (sim.time() > 1.6) largest = std::max(largest, sim.kinetic_energy());
  }
  std::cout << "5 mm deposit, stabilization 100: largest kinetic energy after 1.6 s " << largest
            << " J/m\n";
  EXPECT_LT(largest, 1e-4);
}

}  // namespace
}  // namespace sablier
