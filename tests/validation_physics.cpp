// Long validation runs (ctest -L validation): the silo's discharge against
// the fill height and the orifice's width, moved grains at a small orifice,
// and the convergence of a collapse as the grid is refined and as the solver
// tolerance tightens.
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

using test::fit_line;
using test::scene;

// A silo drains at a rate that does not depend on the fill height, unlike a
// liquid (Janssen screening; Beverloo et al. 1961; METHOD.md section 5). The
// 2D silo drains through a 6 cm orifice; the mass flow over 0.3-0.9 s and
// over 0.9-1.5 s must agree within 15% while the fill height drops.
// Measured 2026-12-02 (eighth session, grains moved): 104.4 and 109.9 kg/s
// per metre, 55% of the grains drained (with the push: 86.1 and 87.9).
TEST(Validation, SiloDischargeDoesNotDependOnFillHeight) {
  Simulation<2> sim(scene("silo2d.toml"));
  const double m0 = sim.grain_mass();
  std::vector<double> mass;  // at 0, 0.3, 0.6, ... s
  for (int k = 0; k <= 5; ++k) {
    const double t = 0.3 * k;
    test::run_until(sim, t, 1.0 / 30);
    mass.push_back(sim.grain_mass());
  }
  const double early = (mass[1] - mass[3]) / 0.6, late = (mass[3] - mass[5]) / 0.6;
  std::cout << "silo: discharge " << early << " kg/s (0.3-0.9 s), " << late
            << " kg/s (0.9-1.5 s), per unit depth; drained " << 1 - mass[5] / m0
            << " of the grains\n";
  EXPECT_GT(early, 0.0);
  EXPECT_NEAR(late / early, 1.0, 0.15);
}

// Beverloo's law: a silo's discharge grows with the orifice's width D like
// (D - D0)^(3/2) in 2D and (D - D0)^(5/2) in 3D, D0 of the order of a
// grain, unlike a liquid's, which grows like D in 2D and D^2 in 3D
// (Beverloo, Leniger & van de Velde 1961; in 2D, Mankoc et al. 2007,
// Granular Matter 9; METHOD.md section 5). Grains cross an orifice at about
// sqrt(g D), the free fall from an arch of the orifice's size, over an
// area D^(d-1): Q ~ rho_b sqrt(g D) D^(d-1). The shipped silo bins, widened
// so that they stay wider than 2.5 D (beyond which the rate does not depend
// on the bin's width, Mankoc et al.), drain through openings of n free
// floor nodes per side (D = n h). For each exponent e,
// Q = K (D - D0)^e is fitted (K, D0 free: Q^(1/e) is linear in D) with the
// squared misfit in log Q. Checks: Beverloo's e fits better than half a
// unit below and above it (the liquid's exponent is one of them); with it
// the fit passes within 4% of every width; and |D0| <= 1.5 h (the grid
// stands for the grains here). A fit with free e is reported, not checked:
// with four widths over a factor of 3 or 4, a few percent of noise on the
// smallest moves it by 0.2 (measured in 2D, below).
template <int D>
double silo_discharge(const char* name, const std::vector<std::string>& overrides, double t0,
                      double t1) {
  Simulation<D> sim(scene(name, overrides));
  double mass[2] = {0.0, 0.0};
  const double times[2] = {t0, t1};
  for (int k = 0; k < 2; ++k) {
    test::run_until(sim, times[k], 1.0 / 30);
    mass[k] = sim.grain_mass();
  }
  return (mass[0] - mass[1]) / (t1 - t0);
}

// The opening's corner coordinate: n free nodes centred on `centre`, none
// beyond (nodes every h).
std::string opening_edge(double centre, int free_nodes, double h, double sign) {
  return std::to_string(centre + sign * (0.5 * (free_nodes - 1) * h + 0.3 * h));
}

// Q = K (D - D0)^e with e given (Q^(1/e) linear in D): D0, the squared
// misfit in log Q, and the largest relative gap between fit and data.
struct PowerFit {
  double D0, misfit, worst;
};
PowerFit fit_power(const std::vector<double>& D, const std::vector<double>& Q, double e) {
  std::vector<double> y;
  for (double q : Q) y.push_back(std::pow(q, 1.0 / e));
  double a = 0.0, b = 0.0;
  fit_line(D, y, &a, &b);
  PowerFit f{-b / a, 0.0, 0.0};
  for (std::size_t k = 0; k < D.size(); ++k) {
    const double v = a * D[k] + b;
    if (!(v > 0.0)) return {f.D0, 1e300, 1e300};
    const double fitted = std::pow(v, e);
    f.misfit += std::pow(std::log(fitted / Q[k]), 2);
    f.worst = std::max(f.worst, std::abs(fitted / Q[k] - 1.0));
  }
  return f;
}

void check_beverloo(const std::vector<double>& D, const std::vector<double>& Q, double exponent,
                    double h) {
  double best_e = 1.0;
  for (int i = 100; i <= 400; ++i)
    if (fit_power(D, Q, 0.01 * i).misfit < fit_power(D, Q, best_e).misfit) best_e = 0.01 * i;
  const PowerFit lower = fit_power(D, Q, exponent - 0.5), upper = fit_power(D, Q, exponent + 0.5);
  const PowerFit f = fit_power(D, Q, exponent);
  std::cout << "misfit in log Q: " << lower.misfit << " (e = " << exponent - 0.5 << "), "
            << f.misfit << " (" << exponent << "), " << upper.misfit << " (" << exponent + 0.5
            << "); best free exponent " << best_e << "; with " << exponent << ": D0 = " << f.D0 / h
            << " h, widths within " << f.worst << " of the fit\n";
  EXPECT_LT(f.misfit, lower.misfit);
  EXPECT_LT(f.misfit, upper.misfit);
  EXPECT_LT(f.worst, 0.04);
  EXPECT_LE(std::abs(f.D0), 1.5 * h);
}

// 2D: the silo2d bin widened to 0.81 m (1 cm cells), n = 4, 6, 10 and 16 free nodes,
// the discharge over 0.2-0.6 s (the bin stays at least half full).
// Measured 2026-12-02 (eighth session, grains moved, the default since
// 0.2.0): Q = 56.4, 102.2, 217.0 and 435.6 kg/s per metre; with 3/2,
// D0 = -0.13 h and the widths within 0.19% of the fit; misfits 0.077
// (e = 1), 0.0000049 (3/2), 0.0076 (2); best free exponent 1.49. Under the
// projection, the default since 0.3.0 (thirty-second session): Q = 57.1,
// 97.7, 203.6 and 412.5 kg/s per metre; widths within 2.7% of the 3/2 fit,
// D0 = -0.30 h; misfits 0.090, 0.0010, 0.0026; best free exponent 1.65. With the
// push (seventh session, 4 grains per cell and axis): Q = 50.0, 91.1, 193.0
// and 400.2 kg/s per metre of depth (the same widths run by `sablier run`,
// whose sub-steps divide each frame equally: 50.6, 89.9, 193.5 and 401.7);
// with 3/2, D0 = 0.04 h and the widths within 1.7% of the fit (3.1%);
// misfits 0.11 (e = 1), 0.00062 (3/2), 0.0048 (2); best free exponent
// 1.59 (1.65).
TEST(Validation, SiloDischargeFollowsBeverloo2D) {
  constexpr double h = 0.01, centre = 0.405;
  std::vector<double> D, Q;
  for (int n : {4, 6, 10, 16}) {
    D.push_back(n * h);
    Q.push_back(silo_discharge<2>(
        "silo2d.toml",
        {"grid.size=[0.81,0.61]", "grid.resolution=[81,61]", "sand.0.max=[0.81,0.45]",
         "boundary.opening.0.min=[" + opening_edge(centre, n, h, -1) + ",0.0]",
         "boundary.opening.0.max=[" + opening_edge(centre, n, h, 1) + ",0.0]"},
        0.2, 0.6));
    std::cout << "silo2d, " << n << " free nodes (D = " << D.back() << " m): " << Q.back()
              << " kg/s per metre\n";
  }
  check_beverloo(D, Q, 1.5, h);
}

// The silo3d scene in a 0.3 x 0.3 m bin filled 0.15 m deep, cells of h
// (a divisor of 0.3 m), drained through a square opening of n x n free
// nodes, with a looser solver (below) and 2 grains per cell and axis, as
// measured below (the scene seeds 3 since 2026-12-04; 3 would take these
// runs from about 3 to about 10 minutes).
std::vector<std::string> silo3d_with_opening(int n, double h = 0.01, double fill = 0.15,
                                             double height = 0.2) {
  constexpr double centre = 0.15;
  const std::string lo = opening_edge(centre, n, h, -1), hi = opening_edge(centre, n, h, 1);
  const int across = static_cast<int>(std::lround(0.3 / h)),
            up = static_cast<int>(std::lround(height / h));
  return {"grid.size=[0.3,0.3," + std::to_string(up * h) + "]",
          "grid.resolution=[" + std::to_string(across) + "," + std::to_string(across) + "," +
              std::to_string(up) + "]",
          "sand.0.max=[0.3,0.3," + std::to_string(fill) + "]",
          "sand.0.particles_per_cell=2",
          "solver.tolerance=1e-4",
          "solver.max_iterations=500",
          "boundary.opening.0.min=[" + lo + "," + lo + ",0.0]",
          "boundary.opening.0.max=[" + hi + "," + hi + ",0.0]"};
}

// 3D: the silo3d scene in a 0.3 x 0.3 m bin filled 0.25 m deep (0.15 m
// until the thirtieth session, below), 7.5 mm cells, square openings of
// n x n free nodes, n = 3, 5, 7 and 9 (D = 2.25 to 6.75 cm), the discharge
// over 0.1-0.4 s (at least 90% of the grains stay in), with a looser solver
// (tolerance 1e-4, 500 sweeps at most) than the default: with 5 x 5 nodes at
// 1 cm the discharge was 2.678 kg/s with it and 2.674 at 1e-5 (743 sweeps
// per step against 155, a minute against 14 s). Measured 2026-12-02 (eighth
// session, grains moved, the default since 0.2.0): Q = 0.387, 1.500, 3.439
// and 6.481 kg/s (`sablier run`: 0.379, 1.442, 3.438 and 6.426); with 5/2,
// D0 = 0.09 h and the widths within 2.5% of the fit (0.9%); misfits 0.0064
// (e = 2), 0.0011 (5/2), 0.0090 (3); best free exponent 2.32. At 1 cm cells
// (D = 3 to 9 cm) the moves gave 0.768, 2.965, 6.971 and 12.597 kg/s, widths
// within 4.03% of the fit and best free exponent 2.22: the 3-cell orifice
// is at the grid's limit and the 9 cm one at the bin's (docs/method.md).
// Before, with the push, at 1 cm: Q = 0.70, 2.62, 6.45 and 11.83 kg/s
// (`sablier run`: 0.67, 2.67, 6.49 and 12.08);
// with 5/2, D0 = 0.16 h (0.23 h) and the widths within 2.3% of the fit
// (1.9%); misfits 0.013 (e = 2), 0.00084 (5/2), 0.0059 (3); best free
// exponent 2.47 (2.37). The prefactor, C = 1.09 with rho_b = rho phi_max
// and the square's side for D, is about twice Beverloo's 0.58 for round
// orifices (0.81 with the diameter of the round orifice of the same area):
// not checked (docs/validation.md).
// The fill: Beverloo's law holds where the discharge does not depend on the
// fill's height. At 0.15 m (2.2 D for the widest orifice) the projection's
// does: through `sablier run`, grains leaving over 0.1-0.4 s with 9 x 9
// free nodes rose from 21,815 to 24,623 (+12.9%) with a 0.25 m fill, with
// 3 x 3 from 1,348 to 1,438; the moves' fell from 24,437 to 24,000. So at
// 0.15 m the projection failed this test (best free exponent 2.21, the
// widest orifice 4.3% off the 5/2 fit; Q = 0.355, 1.383, 3.180 and 5.831
// kg/s). At 0.25 m both rules give nearly the same discharge (grains,
// projection / moves: 1,438 / 1,469, 5,558 / 5,516, 12,976 / 13,033 and
// 24,623 / 24,000) and both fit 5/2 through `sablier run` (widths within
// 1.3% and 1.8% of the fit, best free exponents 2.41 and 2.37). As this
// test steps, the moves at 0.25 m: Q = 0.384, 1.489, 3.405 and 6.434 kg/s,
// D0 = 0.09 h, widths within 2.4% of the fit, best free exponent 2.33
// (11 minutes on two threads, 3 at 0.15 m); with the projection 0.386,
// 1.481, 3.415 and 6.571 kg/s, within 1.4%, best free exponent 2.45.
// With the projection after the moves (the default since 0.3.0,
// thirty-second session): 0.392, 1.507, 3.420 and 6.700 kg/s, D0 = 0.14 h,
// within 2.4%; misfits 0.014, 0.0010, 0.0056; best free exponent 2.49.
TEST(Validation, SiloDischargeFollowsBeverloo3D) {
  constexpr double h = 0.0075;
  std::vector<double> D, Q;
  for (int n : {3, 5, 7, 9}) {
    D.push_back(n * h);
    Q.push_back(silo_discharge<3>("silo3d.toml", silo3d_with_opening(n, h, 0.25, 0.3), 0.1, 0.4));
    std::cout << "silo3d, " << n << " x " << n << " free nodes (D = " << D.back()
              << " m): " << Q.back() << " kg/s\n";
  }
  check_beverloo(D, Q, 2.5, h);
}

// Grains moved apart (solver.decompaction = "move", the default of 0.2.0)
// must not hold back a flow converging on an orifice. There the excess over
// phi_max peaks just above the orifice, and moving grains down its gradient
// sends them back up into the bin: through the 3 x 3 node orifice of the
// bin above, 4 moves per step cut the discharge to 0.44 kg/s, against 0.70
// with the push and 0.80 under the pure clamp of METHOD.md (an experiment;
// measured 2026-12-02, seventh session). Moves never oppose a grain's
// velocity (decompaction.cpp): 0.79 through `sablier run`, 0.77 as this
// test steps (eighth session: 0.768 against 0.779 under the pure clamp as
// this test steps). The default projection begins with these moves.
// The check: with 4 moves the discharge is at least 90% of the pure clamp's
// (solver.decompaction = "clamp", METHOD.md's rule alone, which moves no
// grain); the rule before the fix gave 55%.
TEST(Validation, MovedGrainsDoNotHoldBackASmallOrifice) {
  std::vector<std::string> clamped = silo3d_with_opening(3);
  clamped.push_back("solver.decompaction=\"clamp\"");
  const double reference = silo_discharge<3>("silo3d.toml", clamped, 0.1, 0.4);
  std::vector<std::string> moved = silo3d_with_opening(3);
  moved.push_back("solver.decompaction=\"move\"");
  const double q = silo_discharge<3>("silo3d.toml", moved, 0.1, 0.4);
  std::cout << "silo3d, 3 x 3 free nodes: " << reference << " kg/s under the pure clamp, " << q
            << " kg/s with grains moved\n";
  EXPECT_GT(q, 0.9 * reference);
}

// The projection (solver.decompaction = "project") must not hold back that
// flow either. It bounded the grain volume at the opening's nodes too, and
// pushed the grains crowding above the orifice back into the bin: 402
// grains over 0.1-0.4 s through `sablier run` against 1,270 under the pure
// clamp. The grains there are leaving, so those nodes are not bounded
// (decompaction.cpp, project_capacities): 1,166 grains; 0.739 kg/s against
// 0.801 as this test steps (2026-12-06); 0.743 since the moves come first
// (thirty-second session). Same check, 90% of the pure clamp's discharge.
TEST(Validation, ProjectedGrainsDoNotHoldBackASmallOrifice) {
  std::vector<std::string> clamped = silo3d_with_opening(3), projected = silo3d_with_opening(3);
  clamped.push_back("solver.decompaction=\"clamp\"");
  projected.push_back("solver.decompaction=\"project\"");
  const double reference = silo_discharge<3>("silo3d.toml", clamped, 0.1, 0.4);
  const double q = silo_discharge<3>("silo3d.toml", projected, 0.1, 0.4);
  std::cout << "silo3d, 3 x 3 free nodes: " << reference << " kg/s under the pure clamp, " << q
            << " kg/s with the projection\n";
  EXPECT_GT(q, 0.9 * reference);
}

// Axisymmetric collapse in 3D (collapse_axisym3d, 6 mm cells, mu = 0.5):
// cylinders of aspect ratio a = H0/R0 = 0.5, 1, 2 and 3 released on a rough
// floor, the run-out (R - R0)/R0 at 0.6 s (the 99.5th percentile of the
// grains' distance from the axis; every column has stopped by then, kinetic
// energy below 1e-4 of its peak). Source: the experiments of Lube et al.
// (2004), whose fits are 1.24 a for a < 1.7 and 1.6 a^(1/2) above, a
// change of regime; Lajeunesse et al. (2004) report two regimes too.
// Checks: the run-out grows with a, more slowly than linearly from a = 2 to
// 3 (the second regime), and lies within 20% of the fit for each a
// (granular materials differ: in 2D channels Balmforth & Kerswell 2005
// found the prefactors of such fits material-dependent). Measured
// 2026-12-04 (thirteenth session, 3 grains per cell and axis): 0.59,
// 1.21, 2.13 and 2.93 against 0.62, 1.24, 2.26 and 2.77; with 2
// (2026-12-02, eighth session, grains moved, the default since 0.2.0):
// 0.57, 1.23, 2.20 and 3.04 (seventh session, with the push: 0.55, 1.17,
// 2.17 and 2.90). Under the projection (the default since 0.3.0,
// thirty-second session): 0.59, 1.21, 2.15 and 2.94.
TEST(Validation, AxisymmetricCollapseFollowsLube2004) {
  const double cases[4][2] = {{0.5, 0.08}, {1.0, 0.06}, {2.0, 0.045}, {3.0, 0.04}};  // a, R0
  std::vector<double> runout;
  for (const auto& c : cases) {
    const double a = c[0], r0 = c[1], h0 = a * r0;
    const int nz = static_cast<int>(std::ceil((h0 + 0.03) / 0.006));
    Simulation<3> sim(
        scene("collapse_axisym3d.toml",
              {"grid.size=[0.36,0.36," + std::to_string(nz * 0.006) + "]",
               "grid.resolution=[60,60," + std::to_string(nz) + "]",
               "sand.0.radius=" + std::to_string(r0), "sand.0.height=" + std::to_string(h0)}));
    test::run_until(sim, 0.6, 1.0 / 30);
    std::vector<double> r;
    for (const Vec<3>& x : sim.particles().position)
      r.push_back(std::hypot(x[0] - 0.18, x[1] - 0.18));
    std::sort(r.begin(), r.end());
    runout.push_back((r[static_cast<std::size_t>(0.995 * (r.size() - 1))] - r0) / r0);
    const double fit = a < 1.7 ? 1.24 * a : 1.6 * std::sqrt(a);
    std::cout << "axisymmetric collapse a = " << a << ": run-out " << runout.back()
              << ", Lube et al. 2004: " << fit << "\n";
    EXPECT_NEAR(runout.back() / fit, 1.0, 0.2) << "a = " << a;
  }
  for (std::size_t k = 1; k < runout.size(); ++k) EXPECT_GT(runout[k], runout[k - 1]);
  EXPECT_LT(runout[3] / 3.0, runout[2] / 2.0);  // sub-linear in the second regime
}

// METHOD.md section 5: results converge as the grid is refined. The 2D
// collapse (collapse2d, jitter 0.5, seed 1) with its over-full nodes' grains
// moved apart (the default since 0.3.0 takes them back to phi_max after the
// moves; 0.2.0's moves alone) rather than pushed, and 4 grains per
// cell and axis, at 25, 12.5, 6.25 and 3.125 mm (the step shrinks with the
// cell), to 0.9 s, when the fronts have long stopped. Compared: the deposit's
// thickness profile, grain volume per 2 cm of x over phi_max, on [0, 0.8] m;
// the mean gap between the profiles of successive grids must shrink at each
// refinement. Measured 2026-12-02: gaps 3.9, 1.8 and 1.3 mm (`sablier run`,
// which divides frames into equal sub-steps: 4.1, 2.0 and 1.4); run-outs
// (L - L0)/L0 1.00, 1.16, 1.19, 1.23; median phi 0.600-0.617. Since moves
// never oppose a grain's velocity (seventh session): gaps 4.6, 2.3 and
// 1.7 mm (`sablier run`: 4.4, 2.2 and 1.4), run-outs 1.01, 1.18, 1.21,
// 1.23, median phi 0.600-0.620. Under the default projection (thirty-second
// session): gaps 4.3, 2.5 and 1.3 mm. With solver.decompaction = "push" (the
// default before 0.2.0; 3 grains per cell and axis) the gaps were 6.3, 4.9 and
// 14.7 mm and the run-outs 0.90, 1.11, 1.23, 1.45 (docs/validation.md,
// "Known limits"); pushed with 4 per cell and axis, 2.1 and 9.2 mm from 12.5 mm
// on: the push fails this test.
std::vector<double> collapse_profile(const std::string& resolution) {
  Simulation<2> sim(scene("collapse2d.toml", {"grid.resolution=" + resolution, "sand.0.jitter=0.5",
                                              "seed=1", "sand.0.particles_per_cell=4"}));
  test::run_until(sim, 0.9, 1.0 / 30);
  constexpr double bin = 0.02;
  std::vector<double> thickness(40, 0.0);
  const Particles<2>& p = sim.particles();
  for (std::size_t k = 0; k < p.size(); ++k) {
    const int b = static_cast<int>(p.position[k][0] / bin);
    if (b >= 0 && b < 40) thickness[b] += p.volume[k] / (bin * 0.6);
  }
  return thickness;
}

TEST(Validation, CollapseConvergesUnderGridRefinement) {
  const char* grids[] = {"[40,10]", "[80,20]", "[160,40]", "[320,80]"};
  std::vector<std::vector<double>> profiles;
  std::vector<double> gaps;
  for (const char* g : grids) {
    profiles.push_back(collapse_profile(g));
    if (profiles.size() < 2) continue;
    const auto& a = profiles[profiles.size() - 2];
    const auto& b = profiles.back();
    double gap = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) gap += std::abs(a[k] - b[k]) / a.size();
    gaps.push_back(gap);
    std::cout << "collapse2d " << g << ": mean gap to the coarser grid's profile " << 1e3 * gap
              << " mm\n";
  }
  EXPECT_LT(gaps[1], gaps[0]);
  EXPECT_LT(gaps[2], gaps[1]);
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
// deviation of 0.011-0.018 over the seeds; under the projection (the
// default since 0.3.0, thirty-second session) 1.171 (1e-5) and 1.176 (1e-6),
// standard error of the difference 0.015. The front is the 99th
// percentile of the grains' x (the farthest single grain is a stray).
double collapse_runout(const std::string& tolerance, int seed) {
  Simulation<2> sim(
      scene("collapse2d.toml", {"solver.tolerance=" + tolerance, "solver.max_iterations=20000",
                                "seed=" + std::to_string(seed), "sand.0.jitter=0.5"}));
  test::run_until(sim, 1.2, 1.0 / 30);
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
