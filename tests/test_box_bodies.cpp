// Rigid boxes (obstacles with a density, docs/scenes.md "Rigid bodies"):
// corner contacts against walls, fixed solids and other bodies, the full
// inverse inertia tensor in the solve, and two-way coupling with the sand.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>

#include "body_fixtures.hpp"
#include "mesh_fixtures.hpp"
#include "physics/obstacle.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

constexpr double kPiQuarter = 0.78539816339744830962;

using test::kPi;
using test::kSpeck2D;
using test::kSpeck3D;
using test::num;
using test::run_until;

// A box (20 x 5 cm, 1 t/m^2) laid flat on a rough polygon ramp at theta =
// 30 degrees, Coulomb mu = 0.3 between them: a rigid block on an incline
// slides at g (sin theta - mu cos theta) without turning (its two lower
// corners carry it; the torque of friction only shifts the load between
// them). With mu = 0.7 > tan theta it stays put.
double box_on_polygon_ramp(double mu, double* spin, double* angle_drift) {
  const double theta = 30.0 * kPi / 180.0, tn = std::tan(theta);
  const double w = 0.2, t = 0.05, x0 = 0.2;
  const auto y = [&](double x) { return 0.45 - x * tn; };
  // The box's centre: half its thickness above the ramp, along the normal.
  const double cx = x0 + 0.5 * t * std::sin(theta) + 1e-4 * std::sin(theta);
  const double cy = y(x0) + 0.5 * t * std::cos(theta) + 1e-4 * std::cos(theta);
  const std::string text =
      "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
      "resolution = [50, 25]\n[[obstacle]]\nshape = \"polygon\"\nvertices = [[-0.1, " +
      num(y(-0.1)) + "], [1.1, " + num(y(1.1)) + "], [1.1, -0.5], [-0.1, -0.5]]\nmu = " + num(mu) +
      "\n[[obstacle]]\nshape = \"box\"\nmin = [" + num(cx - 0.5 * w) + ", " + num(cy - 0.5 * t) +
      "]\nmax = [" + num(cx + 0.5 * w) + ", " + num(cy + 0.5 * t) +
      "]\ndensity = 1000\nangle = -30\nmu = " + num(mu) + "\n" + kSpeck2D;
  Simulation<2> sim(parse_scene(text, "ramp.toml"));
  const double a = test::body_acceleration(sim, 1, spin);
  *angle_drift = std::abs(sim.obstacles()[1].angle + theta);
  return a;
}

TEST(BoxBodies, BoxSlidesDownAPolygonRampAtCoulombsRate) {
  const double theta = 30.0 * kPi / 180.0;
  double spin = 0.0, drift = 0.0;
  const double a = box_on_polygon_ramp(0.3, &spin, &drift);
  const double expected = 9.81 * (std::sin(theta) - 0.3 * std::cos(theta));
  std::cout << "2D box on a 30-degree ramp, mu 0.3: " << a << " m/s^2 against Coulomb's "
            << expected << " (relative difference " << a / expected - 1.0 << "); spin " << spin
            << " rad/s, turned by " << drift << " rad\n";
  EXPECT_NEAR(a / expected, 1.0, 1e-6);
  EXPECT_LT(spin, 1e-4);
  EXPECT_LT(drift, 1e-4);
  const double held = box_on_polygon_ramp(0.7, &spin, &drift);
  std::cout << "  mu 0.7: " << held << " m/s^2 (holds)\n";
  EXPECT_LT(std::abs(held), 1e-4);
}

// A 3D box (20 x 10 x 5 cm) on the stick floor of the box under gravity
// tilted by theta = 25 degrees about y: its four lower corners carry it, and
// it slides at g (sin theta - mu cos theta) along x with mu = 0.2 (the
// body's own mu against stick walls), without turning.
TEST(BoxBodies, BoxSlidesOnATiltedFloorAtCoulombsRate3D) {
  const double theta = 25.0 * kPi / 180.0, mu = 0.2;
  const std::string text = "dimension = 3\ngravity = [" + num(9.81 * std::sin(theta)) + ", 0.0, " +
                           num(-9.81 * std::cos(theta)) +
                           "]\n[grid]\nsize = [0.6, 0.3, 0.3]\nresolution = [30, 15, 15]\n"
                           "[boundary]\ndefault = \"stick\"\n[[obstacle]]\nshape = \"box\"\n"
                           "min = [0.05, 0.1, 0.0001]\nmax = [0.25, 0.2, 0.0501]\n"
                           "density = 1000\nmu = " +
                           num(mu) + "\n" + kSpeck3D;
  Simulation<3> sim(parse_scene(text, "floor.toml"));
  double spin = 0.0;
  const double a = test::body_acceleration(sim, 0, &spin);
  const double expected = 9.81 * (std::sin(theta) - mu * std::cos(theta));
  const auto& q = sim.obstacles()[0].quaternion;
  std::cout << "3D box on a floor tilted 25 degrees, mu 0.2: " << a << " m/s^2 against Coulomb's "
            << expected << " (relative difference " << a / expected - 1.0 << "); spin " << spin
            << " rad/s, orientation (" << q[0] << ", " << q[1] << ", " << q[2] << ", " << q[3]
            << ")\n";
  EXPECT_NEAR(a / expected, 1.0, 1e-6);
  EXPECT_LT(spin, 1e-4);
  EXPECT_NEAR(q[0], 1.0, 1e-8);
}

}  // namespace
}  // namespace sablier

namespace sablier {
namespace {

// The energy of the rigid bodies, 1/2 m |V|^2 + 1/2 omega . J omega - m g.x.
template <int D>
double body_energy(const Simulation<D>& sim) {
  Vec<D> g;
  for (int a = 0; a < D; ++a) g[a] = sim.scene().gravity[a];
  double e = 0.0;
  for (const Obstacle<D>& o : sim.obstacles()) {
    if (!o.dynamic) continue;
    double spin = 0.0;
    if constexpr (D == 2) {
      spin = o.inertia(0, 0) * o.spin[0] * o.spin[0];
    } else {
      const Vec<D> w = o.rotation.transpose() * o.spin;  // in the body's axes
      spin = w.dot(o.inertia * w);
    }
    e += 0.5 * o.mass * o.velocity.squaredNorm() + 0.5 * spin - o.mass * g.dot(o.a);
  }
  return e;
}

// A box released turned onto the floor of an empty box (stick walls, mu
// 0.5) lands on a corner, tips over and comes to rest on a face: its centre
// at half a side above the floor, that side vertical. Its energy never
// grows (the contacts only dissipate, supplement section 1, here for the
// body alone: it has no sand to trade energy with).
template <int D>
void tilted_box_falls_flat(const std::string& orientation) {
  const std::string text =
      D == 2 ? "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
               "resolution = [50, 25]\n[boundary]\ndefault = \"stick\"\n[[obstacle]]\n"
               "shape = \"box\"\nmin = [0.4, 0.2]\nmax = [0.6, 0.28]\ndensity = 700\n" +
                   orientation + kSpeck2D
             : "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.6, 0.3, 0.3]\n"
               "resolution = [30, 15, 15]\n[boundary]\ndefault = \"stick\"\n[[obstacle]]\n"
               "shape = \"box\"\nmin = [0.2, 0.1, 0.15]\nmax = [0.36, 0.2, 0.21]\n"
               "density = 700\n" +
                   orientation + kSpeck3D;
  Simulation<D> sim(parse_scene(text, "tip.toml"));
  const Obstacle<D>& box = sim.obstacles()[0];
  const double scale = box.mass * 9.81 * box.a[D - 1];
  double e = body_energy(sim), worst = -1e300;
  while (sim.time() < 1.5 - 1e-12) {
    const StepInfo info = sim.step(sim.adaptive_dt(1.5 - sim.time()));
    ASSERT_FALSE(info.solve.hit_cap) << "step " << sim.steps();
    const double next = body_energy(sim);
    worst = std::max(worst, (next - e) / scale);
    e = next;
  }
  // The side along the body's axis nearest the vertical, and how far off.
  int up = 0;
  for (int k = 1; k < D; ++k)
    if (std::abs(box.rotation(D - 1, k)) > std::abs(box.rotation(D - 1, up))) up = k;
  const double tilt = std::acos(std::min(1.0, std::abs(box.rotation(D - 1, up))));
  std::cout << D << "D box released turned (" << orientation.substr(0, orientation.size() - 1)
            << "): after 1.5 s centre height " << box.a[D - 1] << " m on its side of half "
            << box.b[up] << " m, tilt " << tilt << " rad, speed " << box.velocity.norm()
            << " m/s, spin " << box.spin.norm() << " rad/s; largest energy gain of a step " << worst
            << " of m g z0\n";
  EXPECT_NEAR(box.a[D - 1], box.b[up], 1e-3 * box.b[up]);
  EXPECT_LT(tilt, 1e-3);
  EXPECT_LT(box.velocity.norm(), 1e-3);
  EXPECT_LT(box.spin.norm(), 1e-2);
  EXPECT_LT(worst, 1e-9);
}

TEST(BoxBodies, TurnedBoxFallsFlatAndNeverGainsEnergy2D) {
  tilted_box_falls_flat<2>("angle = 35\n");
}
TEST(BoxBodies, TurnedBoxFallsFlatAndNeverGainsEnergy3D) {
  tilted_box_falls_flat<3>("angle = 40\naxis = [1, 2, 0.5]\n");
}

// Torque-free rotation (no gravity, nothing touched) conserves the angular
// momentum J omega about world axes and the kinetic energy (Euler's
// equations). A box spinning mostly about its largest axis, started off it,
// precesses: checked over 1 s with steps of 1/100 s.
TEST(BoxBodies, FreeRotationKeepsAngularMomentum3D) {
  const std::string text =
      "dimension = 3\ngravity = [0.0, 0.0, 0.0]\n[grid]\nsize = [0.6, 0.3, 0.3]\n"
      "resolution = [30, 15, 15]\n[[obstacle]]\nshape = \"box\"\nmin = [0.2, 0.1, 0.1]\n"
      "max = [0.36, 0.2, 0.16]\ndensity = 700\n" +
      kSpeck3D;
  Simulation<3> sim(parse_scene(text, "spin.toml"));
  const Obstacle<3>& box = sim.obstacles()[0];
  sim.set_body_state(0, box.a, Vec<3>::Zero(), Vec<3>(0.3, 0.5, 5.0), 0.0, box.quaternion);
  const auto momentum = [&] {
    return Vec<3>(box.rotation * box.inertia * box.rotation.transpose() * box.spin);
  };
  const Vec<3> L0 = momentum();
  const double E0 = body_energy(sim);
  for (int i = 0; i < 100; ++i) sim.step(0.01);
  const Vec<3> L1 = momentum();
  const double E1 = body_energy(sim);
  std::cout << "free rotation, 1 s: |L| " << L0.norm() << " -> " << L1.norm()
            << ", direction off by "
            << std::acos(std::min(1.0, L0.normalized().dot(L1.normalized()))) << " rad; energy "
            << E0 << " -> " << E1 << " J\n";
  EXPECT_NEAR(L1.norm() / L0.norm(), 1.0, 1e-3);
  EXPECT_NEAR(E1 / E0, 1.0, 1e-3);
}

}  // namespace
}  // namespace sablier

namespace sablier {
namespace {

// A box (density 1000) dropped turned onto a bed of sand (surface at 0.15 m
// in 2D, 0.1 m in 3D), through the whole simulation. Sources: the body's
// momentum balance, step by step, m (V_n - V_{n-1}) = (F_n + m g) dt_n,
// F_n the force the sand's rows put on it (obstacles.csv's force); its
// statics once it has stopped (over the last half second the sand carries
// its weight: the mean force, weighted by dt, is m g to 1%; its speed is
// below 1 cm/s and its spin below 0.1 rad/s); it rests on the surface,
// sunk by less than its half thickness. Same bits on 1 and 2 threads.
template <int D>
void box_dropped_on_sand() {
  const std::string text =
      D == 2 ? "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
               "resolution = [60, 30]\n[time]\nfps = 30\nframes = 30\n[boundary]\n"
               "default = \"slip\"\nymin = \"stick\"\nymax = \"free\"\n[[sand]]\nshape = "
               "\"box\"\nmin = [0.0, 0.0]\nmax = [1.0, 0.15]\n[[obstacle]]\nshape = \"box\"\n"
               "min = [0.4, 0.25]\nmax = [0.6, 0.31]\ndensity = 1000\nangle = 25\n"
               "velocity = [0.0, -1.0]\n"
             : "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.4, 0.3, 0.3]\n"
               "resolution = [16, 12, 12]\n[time]\nfps = 30\nframes = 30\n[boundary]\n"
               "default = \"slip\"\nzmin = \"stick\"\nzmax = \"free\"\n[[sand]]\nshape = "
               "\"box\"\nmin = [0.0, 0.0, 0.0]\nmax = [0.4, 0.3, 0.1]\n[[obstacle]]\n"
               "shape = \"box\"\nmin = [0.12, 0.09, 0.17]\nmax = [0.28, 0.21, 0.23]\n"
               "density = 1000\nangle = 25\naxis = [1, 1, 0]\nvelocity = [0.0, 0.0, -1.0]\n";
  const double surface = D == 2 ? 0.15 : 0.1, duration = 1.0;
  const SceneConfig scene = parse_scene(text, "crate.toml");
  Simulation<D> sim(scene);
  const double m = sim.obstacles()[0].mass;
  Vec<D> g;
  for (int a = 0; a < D; ++a) g[a] = scene.gravity[a];
  const test::BodyBalance run = test::run_body_balance(sim, duration);
  const Obstacle<D>& b = sim.obstacles()[0];
  const double weight = m * g.norm();
  // The lowest corner's height.
  double bottom = 1e300;
  for (const Vec<D>& c : body_points(b)) bottom = std::min(bottom, c[D - 1]);
  std::cout << D << "D box dropped turned on a bed: after " << duration << " s lowest corner at "
            << bottom << " m (surface " << surface << "), speed " << b.velocity.norm()
            << " m/s, spin " << b.spin.norm() << " rad/s, mean force of the sand over the last "
            << "0.5 s " << run.mean_force << " N against weight " << weight
            << " N; momentum balance to " << run.worst << "\n";
  EXPECT_LT(run.worst, 1e-9);
  EXPECT_NEAR(run.mean_force, weight, 0.01 * weight);
  EXPECT_LT(b.velocity.norm(), 1e-2);
  EXPECT_LT(b.spin.norm(), 0.1);
  EXPECT_LT(bottom, surface);
  EXPECT_GT(bottom, surface - b.b.minCoeff());
  // The same run on 2 threads, to the bit.
  test::expect_same_bits_on_1_and_2_threads<D>(scene, 12, 0);
}

TEST(BoxBodies, BoxDroppedOnSandRestsOnIt2D) { box_dropped_on_sand<2>(); }
TEST(BoxBodies, BoxDroppedOnSandRestsOnIt3D) { box_dropped_on_sand<3>(); }

}  // namespace
}  // namespace sablier

namespace sablier {
namespace {

// Bodies on bodies, no sand: a box resting on the floor, a smaller box
// dropped turned onto it, and a ball dropped onto that (stick walls, mu
// 0.5). Box on box meets by the corners of each against the other, the ball
// on a box by its centre against the box's distance. All come to rest
// stacked: each resting on the one below, to 1e-3 of a cell.
template <int D>
void stack_comes_to_rest() {
  const std::string text =
      D == 2 ? "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
               "resolution = [50, 25]\n[boundary]\ndefault = \"stick\"\n"
               "[[obstacle]]\nshape = \"box\"\nmin = [0.3, 0.0]\nmax = [0.7, 0.1]\ndensity = 900\n"
               "[[obstacle]]\nshape = \"box\"\nmin = [0.42, 0.2]\nmax = [0.58, 0.26]\n"
               "density = 500\nangle = 15\n"
               "[[obstacle]]\nshape = \"disk\"\ncenter = [0.5, 0.4]\nradius = 0.03\n"
               "density = 300\n" +
                   kSpeck2D
             : "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.6, 0.3, 0.3]\n"
               "resolution = [30, 15, 15]\n[boundary]\ndefault = \"stick\"\n"
               "[[obstacle]]\nshape = \"box\"\nmin = [0.1, 0.05, 0.0]\nmax = [0.4, 0.25, 0.05]\n"
               "density = 900\n"
               "[[obstacle]]\nshape = \"box\"\nmin = [0.19, 0.1, 0.1]\nmax = [0.31, 0.2, 0.14]\n"
               "density = 500\nangle = 15\naxis = [1, 1, 0]\n"
               "[[obstacle]]\nshape = \"sphere\"\ncenter = [0.25, 0.15, 0.22]\nradius = 0.02\n"
               "density = 300\n" +
                   kSpeck3D;
  Simulation<D> sim(parse_scene(text, "stack.toml"));
  run_until(sim, 1.5);
  const auto& o = sim.obstacles();
  const double floor_box_top = o[0].a[D - 1] + o[0].b[D - 1];
  double top_low = 1e300, top_high = -1e300;
  for (const Vec<D>& c : body_points(o[1])) {
    top_low = std::min(top_low, c[D - 1]);
    top_high = std::max(top_high, c[D - 1]);
  }
  const double ball_low = o[2].a[D - 1] - o[2].radius;
  const double h = sim.grid().h();
  std::cout << D << "D stack after 1.5 s: lower box centre " << o[0].a[D - 1] << " (half "
            << o[0].b[D - 1] << "), its top " << floor_box_top << "; upper box from " << top_low
            << " to " << top_high << "; ball's bottom " << ball_low << "; speeds "
            << o[0].velocity.norm() << ", " << o[1].velocity.norm() << ", " << o[2].velocity.norm()
            << " m/s\n";
  EXPECT_NEAR(o[0].a[D - 1], o[0].b[D - 1], 1e-3 * h);
  EXPECT_NEAR(top_low, floor_box_top, 1e-3 * h);
  EXPECT_NEAR(ball_low, top_high, 1e-3 * h);
  for (int k = 0; k < 3; ++k) EXPECT_LT(o[k].velocity.norm(), 1e-3) << k;
}

TEST(BoxBodies, StackOfBoxesAndABallComesToRest2D) { stack_comes_to_rest<2>(); }
TEST(BoxBodies, StackOfBoxesAndABallComesToRest3D) { stack_comes_to_rest<3>(); }

}  // namespace
}  // namespace sablier

namespace sablier {
namespace {

// Body 1 of `text` (a box) after 0.5 s: resting level with its bottom at
// `top` (1e-3 of a cell; 1e-4 rad; below 1e-6 m/s).
template <int D>
void expect_box_rests_level(const std::string& text, double top, const char* what) {
  Simulation<D> sim(parse_scene(text, "rest.toml"));
  run_until(sim, 0.5);
  const Obstacle<D>& box = sim.obstacles()[1];
  const double bottom = box.a[D - 1] - box.b[D - 1];
  const double tilt = std::acos(std::min(1.0, box.rotation(D - 1, D - 1)));
  std::cout << D << "D box on " << what << ": bottom at " << bottom << " m (top " << top
            << "), tilt " << tilt << " rad, speed " << box.velocity.norm() << " m/s\n";
  EXPECT_NEAR(bottom, top, 1e-3 * sim.grid().h());
  EXPECT_LT(tilt, 1e-4);
  EXPECT_LT(box.velocity.norm(), 1e-6);
}

// A box resting on a fixed post narrower than its bottom face, under its
// centre: none of the box's corners is over the post, so it is the post's
// corners that hold it (their rows against the box's faces). Balanced, it
// stays on the post, its bottom face at the post's top, level (to 1e-4
// rad: the solves stop at a velocity residual of 1e-5; falling off would
// turn it by order 1).
template <int D>
void box_rests_on_a_post() {
  const std::string text =
      D == 2 ? "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
               "resolution = [50, 25]\n[[obstacle]]\nshape = \"box\"\nmin = [0.49, 0.0]\n"
               "max = [0.51, 0.2]\n[[obstacle]]\nshape = \"box\"\nmin = [0.4, 0.2]\n"
               "max = [0.6, 0.25]\ndensity = 800\n" +
                   kSpeck2D
             : "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.6, 0.3, 0.3]\n"
               "resolution = [30, 15, 15]\n[[obstacle]]\nshape = \"box\"\n"
               "min = [0.29, 0.14, 0.0]\nmax = [0.31, 0.16, 0.1]\n[[obstacle]]\nshape = \"box\"\n"
               "min = [0.2, 0.1, 0.1]\nmax = [0.4, 0.2, 0.15]\ndensity = 800\n" +
                   kSpeck3D;
  expect_box_rests_level<D>(text, D == 2 ? 0.2 : 0.1, "a post");
}

TEST(BoxBodies, BoxRestsOnANarrowPost2D) { box_rests_on_a_post<2>(); }
TEST(BoxBodies, BoxRestsOnANarrowPost3D) { box_rests_on_a_post<3>(); }

// A box set flat on top of a fixed drum (a disk in 2D, a sphere in 3D of
// radius 0.2 m, its top 1e-4 m below the box): the drum touches the middle
// of the box's bottom face, where no corner or edge of the box is, so it is
// the drum's centre, reaching its radius further, that holds it (its row
// against the box's face). Source: statics: balanced on the top, the box
// rests there, level, its bottom at the drum's top (1e-3 of a cell; without
// the row it sank 6.4 mm, until its corners met the drum).
template <int D>
void box_rests_on_a_drum() {
  const std::string text =
      D == 2 ? "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
               "resolution = [50, 25]\n[[obstacle]]\nshape = \"disk\"\ncenter = [0.5, -0.1]\n"
               "radius = 0.2\n[[obstacle]]\nshape = \"box\"\nmin = [0.45, 0.1001]\n"
               "max = [0.55, 0.1201]\ndensity = 1000\n" +
                   kSpeck2D
             : "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.6, 0.3, 0.3]\n"
               "resolution = [30, 15, 15]\n[[obstacle]]\nshape = \"sphere\"\n"
               "center = [0.3, 0.15, -0.1]\nradius = 0.2\n[[obstacle]]\nshape = \"box\"\n"
               "min = [0.25, 0.1, 0.1001]\nmax = [0.35, 0.2, 0.1201]\ndensity = 1000\n" +
                   kSpeck3D;
  expect_box_rests_level<D>(text, 0.1, "a drum");
}

TEST(BoxBodies, BoxRestsOnADrum2D) { box_rests_on_a_drum<2>(); }
TEST(BoxBodies, BoxRestsOnADrum3D) { box_rests_on_a_drum<3>(); }

// A 3D scene (a 0.6 x 0.3 x 0.3 m box of 2 cm cells, gravity gz along z)
// with a fixed cylinder post (`post`: its centre, radius and height) and a
// box body (`box`: its keys, and any tables after it).
std::string post_scene(double gz, const std::string& post, const std::string& box) {
  return "dimension = 3\ngravity = [0.0, 0.0, " + std::to_string(gz) +
         "]\n[grid]\nsize = [0.6, 0.3, 0.3]\nresolution = [30, 15, 15]\n[[obstacle]]\n"
         "shape = \"cylinder\"\n" +
         post + "[[obstacle]]\nshape = \"box\"\n" + box + kSpeck3D;
}

// A box set flat on a fixed cylinder post (radius 3 cm, under the middle of
// the box's 20 x 10 cm bottom face): none of the box's corners or edges is
// over the post, so it is the points of the post's top rim that hold it
// (their rows against the box's face). Source: statics, a symmetric
// balance: the box rests level, its bottom at the post's top (without the
// rim's rows it fell past the post to the floor, 10 cm lower). The solves go
// to 1e-8: at the default 1e-5 the sixteen frictional rows, more than the
// box needs, leave it wandering sideways at up to 7e-7 m/s.
TEST(BoxBodies, BoxRestsOnANarrowCylinder3D) {
  const std::string text =
      post_scene(-9.81, "center = [0.3, 0.15, 0.0]\nradius = 0.03\nheight = 0.1\n",
                 "min = [0.2, 0.1, 0.1001]\nmax = [0.4, 0.2, 0.15]\ndensity = 800\n[solver]\n"
                 "tolerance = 1e-8\n");
  expect_box_rests_level<3>(text, 0.1, "a narrow cylinder");
}

// A box sliding at 0.5 m/s (no gravity) into a fixed post taller than
// itself, the post (radius 2 cm) facing the middle of the box's front face:
// no corner or edge of the box meets it, and neither rim is within the
// face, so it is the balls inside the post on its axis, at the heights of
// the face's bottom and top, that stop the box (their rows against the
// face). Source: kinematics of a rigid contact: the face ends against the post's side (within 1e-3
// of a cell: the rows stop the approach in the step that closes the gap), nothing turns it (the
// push is through its centre), and it has stopped (without the row the box passed through the
// post).
TEST(BoxBodies, BoxStopsAgainstAPostsSide3D) {
  const std::string text =
      post_scene(0.0, "center = [0.35, 0.15, 0.0]\nradius = 0.02\nheight = 0.3\n",
                 "min = [0.1, 0.1, 0.1]\nmax = [0.2, 0.2, 0.15]\ndensity = 800\n"
                 "velocity = [0.5, 0.0, 0.0]\n");
  Simulation<3> sim(parse_scene(text, "post.toml"));
  run_until(sim, 0.5);
  const Obstacle<3>& box = sim.obstacles()[1];
  const double front = box.a[0] + box.b[0];  // the box's half-size b along its own axes
  const double tilt = std::acos(std::min(1.0, box.rotation(0, 0)));
  std::cout << "box against a post: front face at " << front << " m (post side at 0.33), tilt "
            << tilt << " rad, speed " << box.velocity.norm() << " m/s\n";
  EXPECT_NEAR(front, 0.33, 1e-3 * sim.grid().h());
  EXPECT_LT(tilt, 1e-6);
  EXPECT_LT(box.velocity.norm(), 1e-6);
}

// A square beam (30 x 6 x 6 cm) turned 45 degrees about its long axis, set
// edge-down across the top of a fixed post (radius 6 cm), its lower edge
// 3 cm off the post's axis: the edge crosses the top disk along a chord,
// its corners far beyond the post, and the top rim's points lie 7 and 12 mm
// to either side of the edge, under its faces. It is the edge's own rows,
// at the chord's ends, that hold it. Source: statics, a symmetric balance
// (the chord's middle under the beam's centre): the edge rests on the
// disk, the beam not turned further (without the edge's rows the edge
// sank 1.0 cm into the post and the beam rolled 0.055 rad, until its faces
// met the rim's points).
TEST(BoxBodies, BeamEdgeRestsAcrossACylindersTop3D) {
  const std::string text =
      post_scene(-9.81, "center = [0.3, 0.15, 0.0]\nradius = 0.06\nheight = 0.1\n",
                 "min = [0.15, 0.15, 0.11253]\nmax = [0.45, 0.21, 0.17253]\ndensity = 500\n"
                 "angle = 45\naxis = [1, 0, 0]\n[solver]\ntolerance = 1e-8\n");
  Simulation<3> sim(parse_scene(text, "beam.toml"));
  run_until(sim, 0.5);
  const Obstacle<3>& beam = sim.obstacles()[1];
  // The lowest point: the centre less the half-sizes b along the turned axes.
  double lowest = beam.a[2];
  for (int k = 0; k < 3; ++k) lowest -= std::abs(beam.rotation(2, k)) * beam.b[k];
  // The turn about the long axis (45 degrees as set).
  const double roll = std::atan2(beam.rotation(2, 1), beam.rotation(1, 1));
  std::cout << "beam edge-down across a post: lowest edge at " << lowest
            << " m (post top 0.1), roll " << roll << " rad (pi/4 = " << kPiQuarter << "), speed "
            << beam.velocity.norm() << " m/s\n";
  EXPECT_NEAR(lowest, 0.1, 1e-3 * sim.grid().h());
  EXPECT_NEAR(roll, kPiQuarter, 1e-4);
  EXPECT_LT(beam.velocity.norm(), 1e-6);
}

// A box set flat on the apex of a fixed mesh pyramid (its top 1e-4 m below
// the box, under the middle of the box's bottom face): no corner or edge of
// the box meets the pyramid, whose apex vertex holds it (the mesh's
// vertices get rows against a body's faces as a fixed box's corners do).
// Source: statics, a symmetric balance: the box rests level, its bottom at
// the apex (without the vertices' rows it sank 5.1 cm onto the slopes).
TEST(BoxBodies, BoxRestsOnAMeshApex3D) {
  const auto dir = test::temp_dir("apex");
  const auto obj = dir / "pyramid.obj";
  TriangleMesh pyramid;
  pyramid.vertices = {
      {0.2, 0.05, 0.0}, {0.4, 0.05, 0.0}, {0.4, 0.25, 0.0}, {0.2, 0.25, 0.0}, {0.3, 0.15, 0.1}};
  pyramid.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  test::write_obj(obj, {pyramid});
  const std::string text =
      "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.6, 0.3, 0.3]\n"
      "resolution = [30, 15, 15]\n[[obstacle]]\nshape = \"mesh\"\nfile = \"" +
      obj.string() +
      "\"\n[[obstacle]]\nshape = \"box\"\nmin = [0.25, 0.1, 0.1001]\nmax = [0.35, 0.2, "
      "0.1201]\ndensity = 1000\n" +
      kSpeck3D;
  expect_box_rests_level<3>(text, 0.1, "a mesh pyramid's apex");
  std::filesystem::remove_all(dir);
}

// A box set flush on another of the same footprint (the crates of a
// stack): each corner of either sits on an edge or corner of the other,
// where the nearest face is a matter of round-off, a side face as near as
// the top. Static equilibrium (face on face): it rests with its bottom on
// the lower box's top, level, to 1e-3 of a cell, and does not move
// sideways. In 2D also as polygons (the same squares' corners), either
// one or both; in 3D as meshes (the boxes' triangles) on a fixed box or
// mesh, and a box on a fixed mesh. Measured before the corners chose their face by their own
// direction (physics/corners.hpp, corner_distance): the upper box sank 0.07 to
// 0.6 of a cell into the lower one (2 cm cells) and, 10 um off flush on a
// box body in 3D, fell through it to the floor; polygons 0.14 to 0.53,
// meshes 0.001 to 0.25 (a mesh's sampled distance rounds its corners).
// Also a box overhanging the lower one by a tenth of a cell (beyond
// kCornerSlack: its overhanging corners meet the lower box's edge, and
// the lower box's corners its face).
enum class Solid { Box, Polygon, Mesh };

template <int D>
std::string flush_solid(Solid shape, double x0, double z0, double x1, double z1) {
  if (shape == Solid::Mesh) {  // 3D only: the box as a triangle mesh, in a file
    static int files = 0;
    const std::filesystem::path obj = test::temp_path("flush_" + std::to_string(files++), ".obj");
    test::write_obj(obj, {test::box_mesh({x0, 0.1, z0}, {x1, 0.2, z1})});
    return "shape = \"mesh\"\nfile = \"" + obj.string() + "\"\n";
  }
  if (shape == Solid::Polygon)  // 2D only
    return "shape = \"polygon\"\nvertices = [[" + num(x0) + ", " + num(z0) + "], [" + num(x1) +
           ", " + num(z0) + "], [" + num(x1) + ", " + num(z1) + "], [" + num(x0) + ", " + num(z1) +
           "]]\n";
  const std::string y0 = D == 3 ? "0.1, " : "", y1 = D == 3 ? "0.2, " : "";
  return "shape = \"box\"\nmin = [" + num(x0) + ", " + y0 + num(z0) + "]\nmax = [" + num(x1) +
         ", " + y1 + num(z1) + "]\n";
}

template <int D>
void flush_box_rests(double offset, bool lower_is_body, Solid lower = Solid::Box,
                     Solid upper = Solid::Box) {
  const std::string text =
      (D == 2 ? "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
                "resolution = [50, 25]\n"
              : "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.6, 0.3, 0.3]\n"
                "resolution = [30, 15, 15]\n") +
      std::string("[boundary]\ndefault = \"stick\"\n[[obstacle]]\n") +
      flush_solid<D>(lower, 0.2, 0.0, 0.3, 0.05) + (lower_is_body ? "density = 900\n" : "") +
      "[[obstacle]]\n" + flush_solid<D>(upper, 0.2 + offset, 0.052, 0.3 + offset, 0.102) +
      "density = 500\n" + (D == 2 ? kSpeck2D : kSpeck3D);
  Simulation<D> sim(parse_scene(text, "flush.toml"));
  run_until(sim, 1.0);
  const auto& o = sim.obstacles();
  const double h = sim.grid().h();
  const double top = 0.05 + (lower_is_body ? o[0].a[D - 1] - 0.025 : 0.0);
  double low = 1e300, high = -1e300;
  for (const Vec<D>& c : body_points(o[1])) {
    low = std::min(low, c[D - 1]);
    high = std::max(high, c[D - 1]);
  }
  const double moved = std::abs(o[1].a[0] - (0.25 + offset));
  const auto name = [](Solid x) {
    return x == Solid::Box ? "box" : x == Solid::Polygon ? "polygon" : "mesh";
  };
  std::cout << D << "D " << name(upper) << " " << offset << " m off flush on a " << name(lower)
            << (lower_is_body ? " body" : "") << ": its corners " << (top - low) / h << " and "
            << (top + 0.05 - high) / h << " cells under where they rest, moved " << moved / h
            << " cells, speed " << o[1].velocity.norm() << " m/s\n";
  EXPECT_LT(std::abs(low - top), 1e-3 * h);
  EXPECT_LT(std::abs(high - 0.05 - top), 1e-3 * h);  // level: its top 5 cm above
  EXPECT_LT(moved, 1e-3 * h);
  EXPECT_LT(o[1].velocity.norm(), 1e-3);
}

TEST(BoxBodies, BoxSetFlushOnABoxRestsOnIt2D) {
  for (const double offset : {0.0, 1e-5, 2e-3})
    for (const bool body : {false, true}) flush_box_rests<2>(offset, body);
  for (const double offset : {0.0, 1e-5}) {
    flush_box_rests<2>(offset, false, Solid::Box, Solid::Polygon);
    flush_box_rests<2>(offset, true, Solid::Box, Solid::Polygon);
    flush_box_rests<2>(offset, false, Solid::Polygon, Solid::Box);
    flush_box_rests<2>(offset, true, Solid::Polygon, Solid::Polygon);
  }
}

TEST(BoxBodies, BoxSetFlushOnABoxRestsOnIt3D) {
  for (const double offset : {0.0, 1e-5, 2e-3})
    for (const bool body : {false, true}) flush_box_rests<3>(offset, body);
  for (const double offset : {0.0, 1e-5}) {
    flush_box_rests<3>(offset, false, Solid::Box, Solid::Mesh);
    flush_box_rests<3>(offset, false, Solid::Mesh, Solid::Box);
    flush_box_rests<3>(offset, false, Solid::Mesh, Solid::Mesh);
  }
}

}  // namespace
}  // namespace sablier
