// Fixed solids that are turned or turn (obstacle[].angle, axis and spin on a
// fixed box, polygon or mesh; spin on a fixed disk or sphere): laid out as
// rigid bodies are (physics/obstacle.hpp, `posed`), their orientation at
// time t spin t past the scene's, their surface moving at velocity + spin x
// (x - centre). Checked against Coulomb's sliding block on a turned box,
// the kinematics of a turning paddle, and thread independence.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "body_fixtures.hpp"
#include "mesh_fixtures.hpp"
#include "physics/obstacle.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

const testing::Environment* const kOneThread =
    testing::AddGlobalTestEnvironment(new test::OneThread);

using test::kPi;
using test::kSpeck2D;
using test::num;
using test::run_until;

// A box body (20 x 5 cm, 1 t/m^2) laid flat on a fixed slab (1.4 x 0.2 m)
// turned -30 degrees, Coulomb mu = 0.3 between them. Source: a rigid block
// on an incline slides at g (sin theta - mu cos theta) (the same check as
// BoxSlidesDownAPolygonRampAtCoulombsRate, the ramp a turned box instead of
// a polygon). Measured: relative difference below 1e-8.
TEST(TurningSolids, BoxSlidesDownATurnedFixedBoxAtCoulombsRate) {
  const double theta = 30.0 * kPi / 180.0, mu = 0.3;
  const double s = std::sin(theta), c = std::cos(theta);
  const double w = 0.2, t = 0.05, x0 = 0.2;
  // The ramp's top face: the line through (0, 0.45) with normal (s, c).
  const auto on_ramp = [&](double along) {
    return std::array<double, 2>{along * c, 0.45 - along * s};
  };
  const auto slab = on_ramp((0.5 + 0.1 * s) / c);  // the slab's centre, 0.1 below the face
  const double sx = slab[0] - 0.1 * s, sy = slab[1] - 0.1 * c;
  const auto box = on_ramp(x0 / c);
  const double cx = box[0] + (0.5 * t + 1e-4) * s, cy = box[1] + (0.5 * t + 1e-4) * c;
  const std::string text =
      "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
      "resolution = [50, 25]\n[[obstacle]]\nshape = \"box\"\nmin = [" +
      num(sx - 0.7) + ", " + num(sy - 0.1) + "]\nmax = [" + num(sx + 0.7) + ", " + num(sy + 0.1) +
      "]\nangle = -30\nmu = " + num(mu) + "\n[[obstacle]]\nshape = \"box\"\nmin = [" +
      num(cx - 0.5 * w) + ", " + num(cy - 0.5 * t) + "]\nmax = [" + num(cx + 0.5 * w) + ", " +
      num(cy + 0.5 * t) + "]\ndensity = 1000\nangle = -30\nmu = " + num(mu) + "\n" + kSpeck2D;
  Simulation<2> sim(parse_scene(text, "turned_ramp.toml"));
  ASSERT_TRUE(sim.obstacles()[0].posed);
  double spin = 0.0;
  const double a = test::body_acceleration(sim, 1, &spin);
  const double expected = 9.81 * (s - mu * c);
  std::cout << "box on a fixed box turned 30 degrees, mu 0.3: " << a << " m/s^2 against Coulomb's "
            << expected << " (relative difference " << a / expected - 1.0 << "), spin " << spin
            << " rad/s\n";
  EXPECT_NEAR(a / expected, 1.0, 1e-6);
  EXPECT_LT(spin, 1e-4);
}

// A paddle (a fixed box 12 x 2 cm) turning at 3 rad/s about its centre in a
// 15 cm bed (1 cm cells, 3 grains per cell and axis, jittered). Sources:
// kinematics (its orientation at t is 3 t rad; no grain is inside it) and
// the phi_max bound (a turning solid drives into the sand, so the scene
// takes the projection). Measured over 1 s: largest phi after the first
// step 0.6006, no grain deeper in the paddle than put back, same bits on 1
// and 2 threads.
const std::string kPaddle =
    "dimension = 2\ngravity = [0.0, -9.81]\nseed = 1\n[grid]\nsize = [0.5, 0.3]\n"
    "resolution = [50, 30]\n[boundary]\ndefault = \"stick\"\nymax = \"free\"\n"
    "[[sand]]\nshape = \"box\"\nmin = [0.0, 0.0]\nmax = [0.5, 0.15]\njitter = 0.3\n"
    "[[obstacle]]\nshape = \"box\"\nmin = [0.19, 0.07]\nmax = [0.31, 0.09]\nspin = 3.0\n";

// Runs `sim` to time t: the largest phi a grain sees after the first step
// (the first is the jittered seeding's own) and the deepest any grain is
// inside solid 0 where it is at the end of each step (0: none inside).
struct PaddleRun {
  double most_phi = 0.0, deepest = 0.0;
};

template <int D>
PaddleRun run_paddle(Simulation<D>& sim, double t) {
  PaddleRun r;
  while (sim.time() < t - 1e-12) {
    sim.step(sim.adaptive_dt(std::min(1.0 / 30, t - sim.time())));
    if (sim.steps() > 1)
      for (double p : sim.particles().phi) r.most_phi = std::max(r.most_phi, p);
    const Obstacle<D> paddle = sim.obstacles_at(sim.time())[0];
    for (const Vec<D>& x : sim.particles().position) {
      Vec<D> n;
      r.deepest = std::min(r.deepest, signed_distance(paddle, x, &n));
    }
  }
  return r;
}

TEST(TurningSolids, TurningPaddleStirsTheSandAndKeepsPhi2D) {
  const SceneConfig s = parse_scene(kPaddle, "paddle.toml");
  ASSERT_EQ(s.solver.decompaction, Decompaction::Project);  // chosen for the turning paddle
  Simulation<2> sim(s);
  const auto [most_phi, deepest] = run_paddle(sim, 1.0);
  const Obstacle<2> paddle = sim.obstacles_at(1.0)[0];
  double fastest = 0.0;
  for (const Vec<2>& u : sim.particles().velocity) fastest = std::max(fastest, u.norm());
  std::cout << "turning paddle: angle at 1 s " << paddle.angle << " rad, largest phi " << most_phi
            << ", deepest grain " << deepest << " m, fastest grain " << fastest << " m/s\n";
  EXPECT_NEAR(paddle.angle, 3.0, 1e-12);
  EXPECT_LT(most_phi, 0.61);
  EXPECT_GT(deepest, -1e-6 * 0.01 - 1e-12);
  // The tips move at 3 rad/s x 6 cm = 0.18 m/s and stir the sand.
  EXPECT_GT(fastest, 0.05);
}

// The paddle is two cells thick: nodes along its middle have grains on both
// faces within their reach. Every sand row whose node lies h/2 or more
// inside it (where the step's rows are built, at the step's start) is left
// out of the cone problem: no coupling, no stress (build_rows). Without
// that, such rows carried 1e5 to 1.6e7 Pa against at most 7e4 Pa for the
// sand's over the first 24 steps (docs/method.md). Grains read their stress
// from the other rows, so none carries more than the largest row's.
TEST(TurningSolids, RowsInsideThePaddleAreLeftOut2D) {
  Simulation<2> sim(parse_scene(kPaddle, "paddle.toml"));
  const double h = sim.grid().h();
  int left_out = 0;
  while (sim.steps() < 24) {
    const Obstacle<2> paddle = sim.obstacles_at(sim.time())[0];
    sim.step(sim.adaptive_dt(1.0 / 30));
    const ConeProblem<2>& P = sim.problem();
    double largest = 0.0;
    for (int j = 0; j < sim.first_obstacle_row(); ++j) {
      const auto nc = sim.grid().node_coords(P.node[j]);
      const Vec<2> x(nc[0] * h, nc[1] * h);
      Vec<2> n;
      largest = std::max(largest, P.lambda[j].norm());
      if (signed_distance(paddle, x, &n) > -0.5 * h) continue;
      ++left_out;
      EXPECT_EQ(P.coupling[j].norm(), 0.0) << "row " << j << " at step " << sim.steps();
      EXPECT_EQ(P.lambda[j].norm(), 0.0) << "row " << j << " at step " << sim.steps();
    }
    for (const SymVec<2>& l : sim.particles().stress) ASSERT_LE(l.norm(), largest * (1 + 1e-12));
  }
  std::cout << "rows left out inside the paddle over 24 steps: " << left_out << "\n";
  EXPECT_GT(left_out, 24);
}

TEST(TurningSolids, TurningPaddleGivesTheSameBitsOnAnyThreadCount) {
  test::expect_same_bits_on_1_and_2_threads<2>(parse_scene(kPaddle, "paddle.toml"), 12);
}

// A roller: a fixed disk (radius 0.4 m, centre below the box) turning at
// -0.25 rad/s, its top moving at V = 0.1 m/s along x, and a rigid disk
// (radius 2 cm) set on its top. Source: a uniform disk placed on a surface
// moving at V slides, pushed by Coulomb friction, until it rolls, at V / (1
// + m r^2 / I) = V / 3 (angular momentum about the contact point; the
// rolling ball on a conveyor belt reaches 2/7 of it, test_body_contacts).
// Measured at 0.02 s, when it rolls and has moved 0.5 mm along the drum:
// 0.2% above V / 3 (the test allows 2%).
TEST(TurningSolids, DiskOnARollerRidesAtAThirdOfItsSurfaceSpeed2D) {
  const double R = 0.4, r = 0.02, V = 0.1;
  const std::string text =
      "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\nresolution = [50, 25]\n"
      "[[obstacle]]\nshape = \"disk\"\ncenter = [0.5, " +
      num(0.1 - R) + "]\nradius = " + num(R) + "\nspin = " + num(-V / R) +
      "\n[[obstacle]]\nshape = \"disk\"\ncenter = [0.5, " + num(0.1 + r + 1e-5) +
      "]\nradius = " + num(r) + "\ndensity = 1000\n" + kSpeck2D;
  Simulation<2> sim(parse_scene(text, "roller.toml"));
  run_until(sim, 0.02, 1.0 / 600);
  const double v = sim.obstacles()[1].velocity[0];
  std::cout << "disk on a roller: " << v << " m/s against V / 3 = " << V / 3 << "\n";
  EXPECT_NEAR(v / (V / 3), 1.0, 0.02);
}

// 3D: a turned box given as a mesh file and the same box as a box block,
// both turned 30 degrees about (1, 1, 0) and spinning about z, have the same
// signed distance where they are at 0.4 s wherever the nearest feature is a
// face (the mesh's distance is sampled at half a cell and interpolated,
// which is exact where the distance is one face's linear one: points
// outside the box over a face, two sample spacings from its edges). Checks
// that a posed mesh is read in its own frame and turned about its centroid
// as a posed box is about its middle. Near edges the sampling rounds them
// (printed, not checked).
TEST(TurningSolids, TurnedMeshAndTurnedBoxAgree3D) {
  const auto dir = test::temp_dir("turned_mesh");
  const auto obj = dir / "slab.obj";
  test::write_obj(obj, {test::box_mesh({0.2, 0.2, 0.1}, {0.4, 0.3, 0.15})});
  const std::string base =
      "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.6, 0.5, 0.3]\n"
      "resolution = [30, 25, 15]\n[[sand]]\nshape = \"box\"\nmin = [0.0, 0.0, 0.0]\n"
      "max = [0.05, 0.05, 0.05]\n[[obstacle]]\n";
  const std::string turn = "angle = 30\naxis = [1, 1, 0]\nspin = [0, 0, 0.5]\n";
  const SceneConfig as_mesh =
      parse_scene(base + "shape = \"mesh\"\nfile = \"" + obj.string() + "\"\n" + turn, "m.toml");
  const SceneConfig as_box = parse_scene(
      base + "shape = \"box\"\nmin = [0.2, 0.2, 0.1]\nmax = [0.4, 0.3, 0.15]\n" + turn, "b.toml");
  std::filesystem::remove_all(dir);
  const Obstacle<3> m = at_time(make_obstacle<3>(as_mesh.obstacles[0]), 0.4);
  const Obstacle<3> b = at_time(make_obstacle<3>(as_box.obstacles[0]), 0.4);
  EXPECT_LT((m.a - b.a).norm(), 1e-12);  // both turn about (0.3, 0.25, 0.125)
  const double spacing = 0.01;           // half the 2 cm cell
  double on_faces = 0.0, near_edges = 0.0;
  int faces = 0;
  for (int i = 0; i < 4000; ++i) {
    // Points about the slab, spread in its own frame.
    const Vec<3> u(std::sin(1.7 * i), std::cos(2.3 * i), std::sin(0.9 * i + 1.0));
    const Vec<3> x = b.a + b.rotation * (u.cwiseProduct(b.b + Vec<3>::Constant(0.03)));
    Vec<3> nm, nb;
    const double dm = signed_distance(m, x, &nm), db = signed_distance(b, x, &nb);
    if (db <= 0.0 || db > 0.03) continue;  // outside, within the sampled band
    const Vec<3> local = b.rotation.transpose() * (x - b.a);
    int over_face = 0;  // axes on which x lies over the face, 2 spacings from its edges
    for (int k = 0; k < 3; ++k) over_face += std::abs(local[k]) < b.b[k] - 2.0 * spacing;
    if (over_face == 2) {
      on_faces = std::max(on_faces, std::abs(dm - db));
      ++faces;
    } else {
      near_edges = std::max(near_edges, std::abs(dm - db));
    }
  }
  std::cout << "turned mesh against turned box: over faces (" << faces << " points) " << on_faces
            << " m, near edges " << near_edges << " m\n";
  EXPECT_GT(faces, 100);
  EXPECT_LT(on_faces, 1e-9);
}

// 3D: a paddle (a fixed box 12 x 2 x 4 cm) turning at 3 rad/s about y in a
// bed, as mixer2d's in 2D: the scene takes the projection, no grain ends
// inside the paddle and the sand stays at phi_max (after the first step).
TEST(TurningSolids, TurningPaddleKeepsPhi3D) {
  const std::string text =
      "dimension = 3\ngravity = [0.0, 0.0, -9.81]\nseed = 1\n[grid]\nsize = [0.3, 0.1, 0.2]\n"
      "resolution = [15, 5, 10]\n[boundary]\ndefault = \"stick\"\nzmax = \"free\"\n"
      "[[sand]]\nshape = \"box\"\nmin = [0.0, 0.0, 0.0]\nmax = [0.3, 0.1, 0.12]\njitter = 0.3\n"
      "[[obstacle]]\nshape = \"box\"\nmin = [0.09, 0.03, 0.05]\nmax = [0.21, 0.07, 0.07]\n"
      "spin = [0, 3, 0]\n";
  const SceneConfig s = parse_scene(text, "paddle3d.toml");
  ASSERT_EQ(s.solver.decompaction, Decompaction::Project);
  Simulation<3> sim(s);
  const auto [most_phi, deepest] = run_paddle(sim, 0.3);
  std::cout << "3D turning paddle: largest phi " << most_phi << ", deepest grain " << deepest
            << " m\n";
  EXPECT_LT(most_phi, 0.61);
  EXPECT_GT(deepest, -1e-6 * 0.02 - 1e-12);
}

// 3D: a turned, turning box's orientation and surface velocity
// (surface_velocity): spin about (0, 0, 2) rad/s from a box turned 30
// degrees about x; at t its rotation is the turn by 2 t about z after the
// scene's, and a point r from its centre moves at spin x r.
TEST(TurningSolids, TurningBoxKinematics3D) {
  ObstacleConfig c;
  c.shape = ObstacleShape::Box;
  c.min = {0.1, 0.1, 0.1};
  c.max = {0.3, 0.2, 0.15};
  c.angle_degrees = 30.0;
  c.axis = {1.0, 0.0, 0.0};
  c.spin = {0.0, 0.0, 2.0};
  c.velocity = {0.1, 0.0, 0.0};
  ASSERT_TRUE(c.posed());
  const Obstacle<3> start = make_obstacle<3>(c);
  const Obstacle<3> later = at_time(start, 0.5);
  const Eigen::Matrix3d expected =
      Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
      Eigen::AngleAxisd(30.0 * kPi / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_LT((later.rotation - expected).norm(), 1e-14);
  EXPECT_LT((later.a - Vec<3>(0.25, 0.15, 0.125)).norm(), 1e-15);  // the centre moved 0.05 along x
  const Vec<3> x = later.a + Vec<3>(0.0, 0.1, 0.0);
  EXPECT_LT((surface_velocity(later, x) - Vec<3>(0.1 - 0.2, 0.0, 0.0)).norm(), 1e-15);
  EXPECT_TRUE(moves_into_sand(later));
}

}  // namespace
}  // namespace sablier
