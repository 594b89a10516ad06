// Physical checks of the engine (METHOD.md section 5), each against a number
// with a source: the weight of the sand above (hydrostatics), the energy
// balance of the supplement (section 1), volume conservation, the
// Mohr-Coulomb limit of an inclined layer, and the laboratory trend of the
// column collapse.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "heap_fixture.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

// One thread (test_support.hpp); the determinism tests set their own.
const testing::Environment* const kOneThread =
    testing::AddGlobalTestEnvironment(new test::OneThread);

using test::run_until;
using test::scene;

// A bed of depth H at rest: after 1 s it has not moved (max speed < 1e-3
// m/s), the vertical stress one node above the floor is within 5% of the
// weight above, rho phi_max g (H - h) (hydrostatics: the side walls are
// frictionless, so they carry none of it), and every node's stress lies in
// the Drucker-Prager cone.
template <int D>
void bed_at_rest(const char* file, double depth) {
  Simulation<D> sim(scene(file));
  run_until(sim, 1.0);
  EXPECT_LT(sim.max_speed(), 1e-3);
  const auto& P = sim.problem();
  const double h = sim.grid().h();
  const auto& m = sim.scene().material;
  // Layer one node above the floor: the area-weighted mean vertical stress
  // (total load over area, which force balance fixes) and, for the report,
  // the interior mean and the lateral-to-vertical ratio.
  double load = 0.0, area = 0.0, interior = 0.0, lateral = 0.0;
  int count = 0;
  for (int j = 0; j < P.rows(); ++j) {
    const double tr = P.lambda[j][0];
    EXPECT_GE(tr, -1e-9 * std::abs(tr) - 1e-12) << "tension at row " << j;
    EXPECT_LE(deviatoric_norm<D>(P.lambda[j]), P.aperture[j] * tr * (1 + 1e-9) + 1e-9)
        << "outside the cone at row " << j;
    const auto n = sim.grid().node_coords(P.node[j]);
    if (n[D - 1] != 1) continue;
    const Mat<D> s = sim.row_bulk_stress(j);
    const double a = P.volume[j] / h;  // horizontal area (length in 2D) of the node's support
    load += a * s(D - 1, D - 1);
    area += a;
    bool inside = true;
    for (int k = 0; k < D - 1; ++k) inside &= n[k] >= 2 && n[k] <= sim.grid().cells()[k] - 2;
    if (!inside) continue;
    interior += s(D - 1, D - 1);
    lateral += s(0, 0);
    ++count;
  }
  ASSERT_GT(count, 0);
  const double vertical = load / area;
  interior /= count;
  lateral /= count;
  const double weight = m.density * m.phi_max * 9.81 * (depth - h);
  std::cout << file << ": sigma_v one node above the floor = " << vertical << " Pa (interior "
            << interior << "), weight above = " << weight << " Pa ("
            << 100 * (vertical / weight - 1) << "%); lateral/vertical K = " << lateral / interior
            << "\n";
  EXPECT_NEAR(vertical / weight, 1.0, 0.05);
}

TEST(Physics, BedAtRest2D) { bed_at_rest<2>("bed2d.toml", 0.3); }
TEST(Physics, BedAtRest3D) { bed_at_rest<3>("bed3d.toml", 0.25); }

// Energy in a closed box (supplement, section 1): without external work the
// model dissipates, d(E_kin + E_pot)/dt <= 0. Discretely, the grid step is
// dissipative ((lambda ; gamma) in DP gives lambda.gamma <= 0 and the clamped
// phi_max term k >= 0), gravity's work on the grid equals the change of
// potential energy of the advected particles exactly (partition of unity),
// and G2P cannot raise the kinetic energy (Jensen). The only source is the
// APIC P2G transfer, which can add at most the particles' affine energy
// E_aff = 1/2 rho sum_p V_p sum_i N_i |B_p (x_i - x_p)|^2 (Cauchy-Schwarz).
// The grains of over-full nodes are moved apart after advection (the default,
// solver.decompaction = "move", docs/method.md): the moves change positions
// only, and restoring_work is the work against gravity of the grains they
// lift. With "push" over-full nodes are decompressed gradually through the
// cone problem (k_j < 0); that term's power is bounded by
// -2 sum_j lambda_N k_j, then reported as restoring_work. So
// E(n+1) <= E(n) + E_aff(n) + restoring_work, up to the
// solver's inexactness: the last
// sweep changes the velocities by a relative amount `residual` in the
// kinetic-energy norm, and the velocities' error |du|_M is taken as at most
// 10 * tolerance times the step's whole stress correction |u - u_f|_M. That
// error changes the kinetic energy by at most |u|_M |du|_M and, through the
// advection, the potential energy by at most dt |g| sqrt(m) |du|_M (m the
// grains' mass), where |u - u_f|_M <= |u|_M + |u_n|_M + sqrt(m) |g| dt. So
// the slack is 10 * tolerance * (E_kin + E_aff) for the first term, and
// 10 * tolerance * m |g| dt (|g| dt + |u|_M / sqrt(m) + |u_n|_M / sqrt(m))
// for the second, which is what a standing block (no kinetic energy, but a
// stress correction that cancels gravity's |g| dt every step) is left
// with: measured on the cohesive block below with 3 grains per cell and
// axis, excesses over the bound without that term of 5.3e-10, 1.9e-10 and
// 4e-11 E(0) at tolerances 1e-8, 1e-9 and 1e-10, from velocities of
// 1.5-5e-7 m/s where the block stands; plus 1e-12 E_pot for rounding.
// Returns E(end) / E(0) after checking the bound at every step.
template <int D = 2>
double check_energy_bound(const SceneConfig& s, double duration) {
  Simulation<D> sim(s);
  const double e0 = sim.kinetic_energy() + sim.potential_energy();
  double e_prev = e0;
  double worst = -1e300, restoring = 0.0;
  const double mass = sim.grain_mass(),
               g = std::sqrt(s.gravity[0] * s.gravity[0] + s.gravity[1] * s.gravity[1] +
                             s.gravity[2] * s.gravity[2]);
  while (sim.time() < duration) {
    const double affine = sim.affine_energy();
    const double kinetic = sim.kinetic_energy();
    const StepInfo info = sim.step(sim.adaptive_dt(1.0 / 30));
    const double e = sim.kinetic_energy() + sim.potential_energy();
    const double correction = g * info.dt + std::sqrt(2.0 * sim.kinetic_energy() / mass) +
                              std::sqrt(2.0 * kinetic / mass);  // bounds |u - u_f|_M / sqrt(m)
    const double slack =
        10 * s.solver.tolerance * (kinetic + affine + mass * g * info.dt * correction) +
        1e-12 * std::abs(e);
    const double bound = e_prev + affine + info.restoring_work;
    worst = std::max(worst, (e - bound) / std::abs(e0));
    restoring += info.restoring_work;
    EXPECT_LE(e, bound + slack) << "step " << sim.steps();
    e_prev = e;
  }
  std::cout << "energy: E(" << duration << " s) / E(0) = " << e_prev / e0
            << ", worst relative excess over the bound: " << worst
            << ", total restoring work / E(0): " << restoring / std::abs(e0) << "\n";
  return e_prev / e0;
}

TEST(Physics, EnergyNeverGrowsInAClosedBox) {
  const SceneConfig s = scene("collapse2d.toml", {"boundary.ymax=\"slip\"", "solver.tolerance=1e-6",
                                                  "solver.max_iterations=20000", "time.cfl=0.5"});
  EXPECT_LT(check_energy_bound(s, 1.0), 1.0);
}

// The same bound when the cone problem pushes over-full nodes apart
// (solver.decompaction = "push", the default before 0.2.0).
TEST(Physics, EnergyNeverGrowsInAClosedBoxWithPushedGrains) {
  const SceneConfig s = scene("collapse2d.toml", {"boundary.ymax=\"slip\"", "solver.tolerance=1e-6",
                                                  "solver.max_iterations=20000", "time.cfl=0.5",
                                                  "solver.decompaction=\"push\""});
  EXPECT_LT(check_energy_bound(s, 1.0), 1.0);
}

// Moving the grains (the default) keeps the volume fraction at phi_max, where
// the cone problem alone (METHOD.md's pure clamp) lets the transfer crowd
// them: the shipped 2D collapse (12.5 mm, 3 grains per cell and axis) at 0.9 s,
// median phi at the grains. Measured 2026-12-02: 0.623 with the pure clamp
// (`sablier run`, seed 1, jitter 0.5), 0.602 with 4 moves (docs/method.md);
// as this test steps, 0.6035, and 0.6044 since moves never oppose a grain's
// velocity (seventh session).
TEST(Physics, MovedGrainsHoldPhiMax) {
  Simulation<2> sim(scene("collapse2d.toml", {}));
  run_until(sim, 0.9, 1.0 / 30);
  std::vector<double> phi(sim.particles().phi.begin(), sim.particles().phi.end());
  std::sort(phi.begin(), phi.end());
  const double median = phi[phi.size() / 2], p99 = phi[phi.size() * 99 / 100];
  std::cout << "moved grains, collapse2d at 0.9 s: median phi " << median << ", 99th percentile "
            << p99 << "\n";
  EXPECT_LT(median, 1.01 * 0.6);
  EXPECT_LT(p99, 1.05 * 0.6);
}

// StepInfo::overfill (stats.csv's column), the grain volume beyond phi_max as
// a fraction of all of it, against its definition where the answer is
// exact: sand filling the whole box on the regular lattice puts phi_max V_j
// at every node (the Q1 shape functions sum to one, and at a wall both the
// node's volume and its grains halve), so with every grain's volume scaled
// by f and nothing moving (no gravity; the pure clamp, which moves no grain)
// the overfill is (f - 1) / f, and 0 for f <= 1.
template <int D>
void overfill_of_scaled_grains(const char* file, const std::string& size) {
  for (double f : {0.8, 1.0, 1.25, 2.0}) {
    Simulation<D> sim(
        scene(file, {"gravity=[0.0,0.0" + std::string(D == 3 ? ",0.0]" : "]"),
                     std::string("sand.0.min=[0.0,0.0") + (D == 3 ? ",0.0]" : "]"),
                     "sand.0.max=" + size, "sand.0.jitter=0.0", "solver.decompaction=\"clamp\""}));
    for (double& v : sim.particles().volume) v *= f;
    const StepInfo info = sim.step(0.01);
    EXPECT_NEAR(info.overfill, std::max(0.0, (f - 1.0) / f), 1e-12) << file << ", f = " << f;
  }
}

TEST(Physics, OverfillIsTheGrainVolumeBeyondPhiMax2D) {
  overfill_of_scaled_grains<2>("bed2d.toml", "[1.0,0.5]");
}
TEST(Physics, OverfillIsTheGrainVolumeBeyondPhiMax3D) {
  overfill_of_scaled_grains<3>("bed3d.toml", "[0.5,0.25,0.35]");
}

// The same bound with cohesion, which shifts the cone's apex to a tension:
// the supplement's proof still applies (lambda + c e_0 in the cone gives
// lambda.gamma = -c gamma_N <= 0) provided cohesive nodes have no room to
// compact (build_rows). Two cases: a strongly cohesive block (30 kPa) that
// stands, where any injected energy would show as growth (before that rule
// this block's energy grew from 46.0 to 57.1 J/m in 0.12 s), and a column
// with a third of the 1.2 kPa cohesion a free 20 cm column needs
// (rho g H (1 - mu) / 2 in 2D), decaying under shear, that collapses. The
// standing block has little kinetic energy for the slack to scale with, while
// the stress holding it carries the solver's error (measured with 2 grains
// per cell and axis and the slack's first term alone: excesses of 4e-7 E at
// tolerance 1e-6, none at 1e-8; with 3, 5.3e-10 E at 1e-8, which the slack's
// advection term covers, check_energy_bound), hence its tighter tolerance.
TEST(Physics, EnergyNeverGrowsWithCohesion) {
  const SceneConfig block =
      scene("cohesive_block2d.toml",
            {"boundary.ymax=\"slip\"", "solver.tolerance=1e-8", "solver.max_iterations=20000",
             "material.cohesion=30000", "material.cohesion_decay=0", "grid.resolution=[100,30]"});
  EXPECT_LE(check_energy_bound(block, 0.15), 1.0);
  const SceneConfig column =
      scene("collapse2d.toml",
            {"boundary.ymax=\"slip\"", "solver.tolerance=1e-6", "solver.max_iterations=20000",
             "time.cfl=0.5", "material.cohesion=400", "material.cohesion_decay=2"});
  EXPECT_LT(check_energy_bound(column, 0.6), 1.0);
}

// The bound in 3D: a square column of sand, 10 cm wide and 25 cm tall (2 cm
// cells, 3 grains per cell and axis), collapsing in a box closed on top.
SceneConfig column3d(const std::string& cohesion, const std::string& decay) {
  return scene(
      "bed3d.toml",
      {"grid.size=[0.4,0.4,0.3]", "grid.resolution=[20,20,15]", "sand.0.min=[0.15,0.15,0.0]",
       "sand.0.max=[0.25,0.25,0.25]", "sand.0.particles_per_cell=3", "boundary.zmax=\"slip\"",
       "solver.tolerance=1e-6", "solver.max_iterations=20000", "time.cfl=0.5",
       "material.cohesion=" + cohesion, "material.cohesion_decay=" + decay});
}

TEST(Physics, EnergyNeverGrowsInAClosedBox3D) {
  EXPECT_LT(check_energy_bound<3>(column3d("0", "0"), 0.6), 0.95);
}

// The same bound in 3D, on a cohesive square column 10 cm wide and 25 cm
// tall with half the cohesion of the lower bound below, decaying under
// shear, that falls (measured, docs/validation.md), in a box closed on top.
TEST(Physics, EnergyNeverGrowsWithCohesion3D) {
  EXPECT_LT(check_energy_bound<3>(column3d("1260", "2"), 0.6), 0.95);
}

// A cohesive column of width b and height H on a rough floor, in 2D
// (Mohr-Coulomb with sin(phi_f) = mu, bulk cohesion c_MC = phi_max c /
// cos(phi_f), bulk weight gamma = rho phi_max g). Limit analysis brackets
// the cohesion it needs. Lower bound: the uniaxial stress field (vertical
// stress gamma z, none sideways) is admissible while gamma H is below the
// unconfined strength 2 c_MC tan(45 deg + phi_f / 2), i.e. c > rho g H (1 -
// mu) / 2. Upper bound: the block above a plane through the column slides
// when its weight's drive exceeds the plane's strength (the best plane
// maximises the cohesion needed). The column must stand at 1.1 times the
// first and fall at 0.9 times the second.
template <int D = 2>
double column_top(const SceneConfig& s, double t = 1.0, bool by_frames = false) {
  Simulation<D> sim(s);
  if (by_frames) {  // each frame's steps as `sablier run` takes them
    for (int k = 1; k <= std::lround(t * s.time.fps); ++k) run_until(sim, k / s.time.fps);
  } else {
    run_until(sim, t);
  }
  std::vector<double> y;
  for (const Vec<D>& x : sim.particles().position) y.push_back(x[D - 1]);
  std::sort(y.begin(), y.end());
  return y[static_cast<std::size_t>(0.99 * static_cast<double>(y.size()))];
}

// The largest cohesion(theta, volume, length) over planes at theta through a
// column (through its width, or out through its top): the volume above the
// plane and the plane's length, per unit width across the column.
template <class F>
double worst_plane(double width, double height, const F& cohesion) {
  double worst = 0.0;
  for (int i = 1; i < 900; ++i) {
    const double theta = i * M_PI / 1800;
    if (width * std::tan(theta) <= height) {
      worst = std::max(worst, cohesion(theta, width * (height - width * std::tan(theta) / 2),
                                       width / std::cos(theta)));
    } else {
      worst = std::max(
          worst, cohesion(theta, height * height / std::tan(theta) / 2, height / std::sin(theta)));
    }
  }
  return worst;
}

TEST(Physics, CohesiveColumnStandsOrFallsAsLimitAnalysisBrackets) {
  const double rho = 2500, g = 9.81, mu = 0.5, phi_max = 0.6, height = 0.25, width = 0.1;
  const double stands_above = rho * g * height * (1 - mu) / 2;
  const double friction_angle = std::asin(mu);
  const double falls_below =
      worst_plane(width, height, [&](double theta, double volume, double length) {
        const double weight = rho * phi_max * g * volume;
        const double c_mc =
            weight * (std::sin(theta) - std::cos(theta) * mu / std::cos(friction_angle)) / length;
        return c_mc * std::cos(friction_angle) / phi_max;
      });
  std::cout << "cohesive column: falls below " << falls_below << " Pa, stands above "
            << stands_above << " Pa\n";
  const double start = height - 0.25 * 0.01;  // top particles a quarter cell down
  const std::vector<std::string> base = {"grid.resolution=[100,30]", "material.cohesion_decay=0"};
  auto with = [&](double c) {
    std::vector<std::string> o = base;
    o.push_back("material.cohesion=" + std::to_string(c));
    return scene("cohesive_block2d.toml", o);
  };
  const double strong = column_top(with(1.1 * stands_above));
  const double weak = column_top(with(0.9 * falls_below));
  std::cout << "top after 1 s: " << strong << " m at 1.1x, " << weak << " m at 0.9x\n";
  EXPECT_NEAR(strong, start, 0.005);
  EXPECT_LT(weak, start - 0.03);
}

// The same in 3D: a square column, b = 10 cm wide and H = 25 cm tall, on a
// rough floor. In our coordinates the cone is |Dev lambda| <= a lambda_0 + c
// with a = mu sqrt(2/3) and lambda_0 = Tr lambda / sqrt(6). Lower bound: the
// uniaxial field (vertical stress s) has |Dev lambda| = s / sqrt(3) and
// lambda_0 = s / sqrt(6), so it is admissible while c >= rho g H (1 /
// sqrt(3) - mu / 3). Upper bound: the block above a plane through the
// column (across its whole width, inclined at theta) slides with a velocity
// jump at the dilation angle psi that associated flow on the cone needs for
// a planar jump, sin^2 psi (1/6 - a^2/12) = a^2/4; the jump dissipates
// 2 c sin(psi) / (sqrt(6) a) per unit area and speed (the cone's support
// function, c e_0 / a times two for the basis), against the block's weight
// times sin(theta - psi). A non-associated material is no stronger than the
// associated one, so it falls below that bound too. In 2D the same
// construction gives psi = asin(mu) and the bounds above.
TEST(Physics, CohesiveColumnStandsOrFallsAsLimitAnalysisBrackets3D) {
  const double rho = 2500, g = 9.81, mu = 0.5, height = 0.25, width = 0.1;
  const double stands_above = rho * g * height * (1 / std::sqrt(3.0) - mu / 3);
  const double a = mu * std::sqrt(2.0 / 3.0);
  const double sin_psi = std::sqrt(a * a / 4 / (1.0 / 6 - a * a / 12)), psi = std::asin(sin_psi);
  const double falls_below =
      worst_plane(width, height, [&](double theta, double volume, double area) {
        const double dissipation_per_c = area * 2 * sin_psi / (std::sqrt(6.0) * a);
        return rho * g * volume * std::sin(theta - psi) / dissipation_per_c;
      });
  std::cout << "3D cohesive column: falls below " << falls_below << " Pa, stands above "
            << stands_above << " Pa (dilation angle " << psi * 180 / M_PI << " degrees)\n";
  auto with = [&](double c) {
    return scene("bed3d.toml",
                 {"grid.size=[0.4,0.4,0.3]", "grid.resolution=[32,32,24]",
                  "sand.0.min=[0.15,0.15,0.0]", "sand.0.max=[0.25,0.25,0.25]",
                  "sand.0.particles_per_cell=3", "material.cohesion=" + std::to_string(c)});
  };
  const double start = column_top<3>(with(stands_above), 0.0);
  const double strong = column_top<3>(with(1.1 * stands_above));
  const double weak = column_top<3>(with(0.9 * falls_below));
  std::cout << "top " << start << " m at 0 s; after 1 s " << strong << " m at 1.1x, " << weak
            << " m at 0.9x\n";
  EXPECT_NEAR(strong, start, 0.005);
  EXPECT_LT(weak, start - 0.03);
}

// Cohesion that decays under shear decays with the plastic shear only (the
// shear where the grain's stress nodes do not stick). A rigid-plastic block
// above the 2D lower bound (two tests up) stands with no plastic strain, so its
// cohesion must not wear away. Solved to the default tolerance, though, a
// block at rest creeps (velocities of about the tolerance times g dt times
// the slowest mode's amplification: 2 mm/s here at 1e-5, a hundred times
// less at 1e-7), and with the decay driven by every grain's shear that
// creep wore `cohesive_block2d` at 1.05 times the bound (1,610 Pa, 5 mm
// cells, the scene's 5 grains per cell and axis) down until it fell at 2-2.5
// s (the potential energy down 36 J/m of 46 by 2.5 s).
TEST(Physics, CohesiveBlockAboveItsStrengthKeepsItsCohesion) {
  const double stands_above = 2500 * 9.81 * 0.25 * (1 - 0.5) / 2;
  const SceneConfig s = scene(
      "cohesive_block2d.toml",
      {"material.cohesion=" + std::to_string(1.05 * stands_above), "material.cohesion_decay=5"});
  ASSERT_EQ(s.resolution[0], 200);  // 5 mm cells, as the creep was measured
  const double start = column_top(s, 0.0), top = column_top(s, 2.5, true);
  std::cout << "cohesive block at 1.05x its lower bound, decaying: top " << start << " m at 0 s, "
            << top << " m at 2.5 s\n";
  EXPECT_NEAR(top, start, 0.005);
}

// Frictionless sand (mu = 0) cannot hold a slope: a column spreads into a
// layer of uniform depth, equal by volume conservation to the column's area
// over the box width. Without friction nothing but the inelastic impacts
// dissipates, so the layer sloshes between the walls like an inviscid
// liquid; a small viscosity (2 Pa s) damps the sloshing within 4 s.
TEST(Physics, FrictionlessColumnBecomesAFlatLayer) {
  SceneConfig s =
      scene("collapse2d.toml", {"material.mu=0", "material.viscosity=2", "grid.resolution=[80,20]",
                                "sand.0.max=[0.2,0.2]", "boundary.xmax=\"slip\""});
  Simulation<2> sim(s);
  run_until(sim, 4.0);
  const double h = sim.grid().h();
  const int columns = sim.grid().cells()[0];
  std::vector<double> top(columns, 0.0);
  for (const Vec<2>& x : sim.particles().position) {
    const int c = std::min(columns - 1, static_cast<int>(x[0] / h));
    top[c] = std::max(top[c], x[1]);
  }
  const double lo = *std::min_element(top.begin(), top.end());
  const double hi = *std::max_element(top.begin(), top.end());
  double mean = 0.0;
  for (double t : top) mean += t / columns;
  // At 2 particles per cell and axis, the top particles sit about a quarter
  // of a cell below the surface.
  const double expected = 0.2 * 0.2 / 1.0 - 0.25 * h;
  std::cout << "frictionless layer at 4 s: top particles between " << lo << " and " << hi
            << " m, mean " << mean << " m, expected " << expected << " m\n";
  EXPECT_LT(hi - lo, h);
  EXPECT_NEAR(mean, expected, 0.5 * h);
}

// A layer on a rough floor under gravity tilted by theta. With walls at both
// ends it stops when tan(theta) < mu (an infinite layer on a rough base holds
// up to tan(theta) = mu); with a free downhill end it keeps flowing when
// theta is clearly above the 2D Mohr-Coulomb limit asin(mu) (the angle above
// which no stress in the cone balances the layer's own slope).
double tilted_layer_speed(double theta_deg, double mu, bool free_end, double t) {
  Simulation<2> sim(test::tilted_layer(theta_deg, mu, free_end));
  run_until(sim, t);
  return sim.max_speed();
}

TEST(Physics, TiltedLayerStopsBelowFrictionAngle) {
  // tan(20 deg) = 0.36 < mu = 0.5.
  const double v = tilted_layer_speed(20.0, 0.5, false, 1.5);
  std::cout << "tilted 20 deg, mu 0.5, walled: max speed at 1.5 s = " << v << " m/s\n";
  EXPECT_LT(v, 1e-2);
}

TEST(Physics, TiltedLayerFlowsAboveMohrCoulombLimit) {
  // asin(0.4) = 23.6 deg < 35 deg.
  const double v = tilted_layer_speed(35.0, 0.4, true, 1.0);
  std::cout << "tilted 35 deg, mu 0.4, free end: max speed at 1 s = " << v << " m/s\n";
  EXPECT_GT(v, 0.3);
}

// A heap: a right-angled wedge of sand 12 cm high against a frictionless
// wall, its flank at theta, on a rough floor (mu = 0.5, 5 mm cells). Below
// atan(mu) = 26.6 deg the flank is held by the stress an infinite slope
// holds while tan(theta) <= mu (METHOD.md section 4: a heap's repose angle
// is close to atan(mu)), so a heap at 22 deg must stand; above the 2D
// Mohr-Coulomb limit asin(mu) = 30 deg no stress in the cone holds an
// infinite slope, so a heap at 40 deg must slump and come to rest below 30
// deg. (In between the rigid-plastic model admits either; measured, a heap
// at 27.5 or 28 deg slumps.) The flank's angle: a line fitted to the
// highest grain of each cell-wide column between 20% and 80% of the heap's
// height. Measured (thirty-second session, 1.5 s, as this test steps):
// 21.9 deg, 0.1177 m high, median grain speed 8e-6 m/s; the 40 deg heap
// down to 19.8 deg, 0.0752 m, 7e-6 m/s. Slumped heaps stop below atan(mu)
// (`sablier run`: from 28, 32 and 40 deg, 23.5, 22.3 and 19.9 deg; from 28
// at cfl 0.25, 24.9): the slump's momentum carries them past the angle at
// which they would stop from rest. The scene and the measure:
// tests/heap_fixture.hpp; how the slumped angle depends on the grid and the
// grains per cell: tests/validation_heap.cpp.
using test::Heap;
using test::heap_after;

TEST(Physics, HeapStandsBelowItsAngleAndSlumpsAboveMohrCoulombs) {
  const double atan_mu = std::atan(0.5) * 180.0 / M_PI, asin_mu = std::asin(0.5) * 180.0 / M_PI;
  const Heap gentle = heap_after(22.0, 1.5), steep = heap_after(40.0, 1.5);
  std::cout << "heap at 22 deg after 1.5 s: flank " << gentle.angle_deg << " deg, height "
            << gentle.height << " m, median speed " << gentle.median_speed
            << " m/s; heap at 40 deg: flank " << steep.angle_deg << " deg, height " << steep.height
            << " m, median speed " << steep.median_speed << " m/s (atan(mu) " << atan_mu
            << ", asin(mu) " << asin_mu << ")\n";
  EXPECT_NEAR(gentle.angle_deg, 22.0, 1.0);
  EXPECT_GT(gentle.height, 0.95 * 0.12);
  EXPECT_LT(gentle.median_speed, 1e-3);
  EXPECT_LT(steep.angle_deg, asin_mu);
  EXPECT_LT(steep.height, 0.9 * 0.12);
  EXPECT_LT(steep.median_speed, 1e-3);
}

// 2D column collapse: the column stops in finite time and its run-out grows
// with the aspect ratio a = H0 / L0 (Lajeunesse, Mangeney-Castelnau & Vilotte
// 2004; Lube et al. 2005: (L_inf - L0) / L0 grows roughly linearly for a < 3).
// "Stopped" at 1.5 s: the kinetic energy of the bulk (all grains but the
// fastest 1%) is below 1e-3 of the peak and the front (99th percentile of x)
// has moved less than a tenth of a cell over the last 0.3 s.
TEST(Physics, CollapseRunOutGrowsWithAspectRatio) {
  const double h0 = 0.1;
  double previous = 0.0;
  for (const double a : {0.5, 1.0, 2.0}) {
    const double l0 = h0 / a;
    SceneConfig s =
        scene("collapse2d.toml", {"grid.resolution=[100,25]", "sand.0.max=[" + std::to_string(l0) +
                                                                  "," + std::to_string(h0) + "]"});
    Simulation<2> sim(s);
    // The front is the 99th percentile of the grains' x, not the farthest
    // grain: a lone grain ahead of the deposit slides on a layer one particle
    // thick and its position is not converged in the solver tolerance
    // (measured, a = 2: plain Gauss-Seidel at 1e-6 moves it 6 mm in the
    // last 0.3 s while the 99th percentile moves 0.8 mm).
    const auto front = [&] {
      std::vector<double> xs;
      for (const Vec<2>& x : sim.particles().position) xs.push_back(x[0]);
      std::sort(xs.begin(), xs.end());
      return xs[static_cast<std::size_t>(0.99 * (xs.size() - 1))];
    };
    double peak = 0.0;
    for (int f = 1; f <= 36; ++f) {
      run_until(sim, f / 30.0);
      peak = std::max(peak, sim.kinetic_energy());
    }
    // Kinetic energy of the bulk: all grains but the fastest 1%. The push
    // (solver.decompaction = "push", the default before 0.2.0) could pop a
    // single surface grain (measured, a = 2: one grain at 0.24 m/s, kinetic
    // energy 4.8e-4 J, was nearly all of KE(1.5 s) = 1.05e-3 of the peak,
    // while the other 99% of the grains carried 1.4e-5 of it); the question
    // here is whether the collapse has stopped, not that grain. With the
    // moves (eighth session) KE(1.5 s) is 1e-7 of the peak, the bulk's 2e-8
    // to 9e-8, no grain faster than 1.2 mm/s.
    const auto bulk_kinetic_energy = [&] {
      const auto& P = sim.particles();
      std::vector<std::pair<double, double>> e;  // (speed, kinetic energy)
      for (std::size_t p = 0; p < P.size(); ++p)
        e.push_back({P.velocity[p].norm(),
                     0.5 * s.material.density * P.volume[p] * P.velocity[p].squaredNorm()});
      std::sort(e.begin(), e.end());
      double sum = 0.0;
      for (std::size_t k = 0; k < e.size() - e.size() / 100; ++k) sum += e[k].second;
      return sum;
    };
    const double front_early = front();
    run_until(sim, 1.5);
    const double runout = (front() - l0) / l0;
    std::cout << "collapse a = " << a << ": run-out (L - L0)/L0 = " << runout
              << ", KE(1.5 s)/peak = " << sim.kinetic_energy() / peak << " (bulk "
              << bulk_kinetic_energy() / peak << ")"
              << ", front moved " << front() - front_early << " m in the last 0.3 s"
              << ", max grain speed " << sim.max_speed() << " m/s\n";
    EXPECT_LT(bulk_kinetic_energy(), 1e-3 * peak) << "a = " << a << " still moving";
    EXPECT_LT(front() - front_early, 0.1 * sim.grid().h()) << "a = " << a << " front moving";
    EXPECT_GT(runout, previous) << "a = " << a;
    previous = runout;
  }
}

TEST(Physics, SolverReportsTheCap) {
  Simulation<2> sim(scene("collapse2d.toml", {"solver.max_iterations=2"}));
  const StepInfo info = sim.step(1.0 / 60);
  EXPECT_EQ(info.solve.iterations, 2);
  EXPECT_TRUE(info.solve.hit_cap);
  EXPECT_GT(info.solve.residual, sim.scene().solver.tolerance);
}

// Particle positions after 10 steps of 1/60 s on each thread count in turn.
std::vector<std::vector<Vec<2>>> positions_by_threads(const SceneConfig& s,
                                                      std::initializer_list<int> threads) {
  std::vector<std::vector<Vec<2>>> results;
  for (int t : threads) {
    omp_set_num_threads(t);
    Simulation<2> sim(s);
    for (int k = 0; k < 10; ++k) sim.step(1.0 / 60);
    results.push_back(sim.particles().position);
  }
  omp_set_num_threads(1);
  return results;
}

// Deterministic: the same scene and seed give the same particles, and so do
// different thread counts (coloured scatters and fixed-order reductions; the
// solve on every thread, which a scene this small would not otherwise use).
TEST(Physics, DeterministicWithJitterAndThreads) {
  const SceneConfig s =
      scene("collapse2d.toml", {"sand.0.jitter=0.8", "seed=7", "solver.zone_rows=100"});
  const auto results = positions_by_threads(s, {1, 2, 1});
  ASSERT_EQ(results[0].size(), results[1].size());
  for (std::size_t p = 0; p < results[0].size(); ++p) {
    ASSERT_EQ(results[0][p], results[1][p]) << "particle " << p;
    ASSERT_EQ(results[0][p], results[2][p]) << "particle " << p;
  }
  Simulation<2> other(scene("collapse2d.toml", {"sand.0.jitter=0.8", "seed=8"}));
  EXPECT_NE(other.particles().position[0], Simulation<2>(s).particles().position[0]);
}

// The same with over-full nodes pushed apart by the cone problem
// (solver.decompaction = "push").
TEST(Physics, PushedGrainsDeterministicWithThreads) {
  const auto results = positions_by_threads(
      scene("collapse2d.toml", {"sand.0.jitter=0.8", "seed=7", "solver.zone_rows=100",
                                "solver.decompaction=\"push\""}),
      {1, 2});
  ASSERT_EQ(results[0].size(), results[1].size());
  for (std::size_t p = 0; p < results[0].size(); ++p)
    ASSERT_EQ(results[0][p], results[1][p]) << "particle " << p;
}

}  // namespace
}  // namespace sablier
