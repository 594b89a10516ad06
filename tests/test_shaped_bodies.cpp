// Rigid polygons (2D) and meshes (3D): their mass properties, and bodies of
// those shapes meeting walls, ramps and sand (docs/scenes.md, "Rigid
// bodies of any shape").
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>

#include "body_fixtures.hpp"
#include "core/mass_properties.hpp"
#include "mesh_fixtures.hpp"
#include "physics/obstacle.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;
using test::kPi;
using test::kSpeck2D;
using test::kSpeck3D;
using test::num;
using test::run_until;

// Sources: the unit square, and an L of two rectangles by the parallel-axis
// theorem (area 3, centroid (5/6, 5/6), polar moment 11/6 about it);
// either orientation gives the same.
TEST(MassProperties, Polygons) {
  std::vector<std::array<double, 2>> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int turn = 0; turn < 2; ++turn) {
    const MassProperties m = polygon_mass_properties(square);
    EXPECT_NEAR(m.measure, 1.0, 1e-15);
    EXPECT_NEAR(m.centroid[0], 0.5, 1e-15);
    EXPECT_NEAR(m.centroid[1], 0.5, 1e-15);
    EXPECT_NEAR(m.inertia[2][2], 1.0 / 6.0, 1e-15);
    std::reverse(square.begin(), square.end());
  }
  const MassProperties l =
      polygon_mass_properties({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  EXPECT_NEAR(l.measure, 3.0, 1e-14);
  EXPECT_NEAR(l.centroid[0], 5.0 / 6.0, 1e-14);
  EXPECT_NEAR(l.centroid[1], 5.0 / 6.0, 1e-14);
  EXPECT_NEAR(l.inertia[2][2], 11.0 / 6.0, 1e-14);
}

// Sources: a box of sides (1, 2, 3) (J = V (b^2 + c^2) / 12, ...), the
// same box turned by R (J' = R J R^T, off-diagonal terms), and a sphere
// (V = 4/3 pi r^3, J = 2/5 V r^2) approached by an icosphere.
TEST(MassProperties, Meshes) {
  const MassProperties box = mesh_mass_properties(test::box_mesh({0, 0, 0}, {1, 2, 3}));
  EXPECT_NEAR(box.measure, 6.0, 1e-14);
  const double c[3] = {0.5, 1.0, 1.5}, j[3] = {6.5, 5.0, 2.5};
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(box.centroid[r], c[r], 1e-14);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(box.inertia[r][k], r == k ? j[r] : 0.0, 1e-13);
  }
  // Turned by 30 degrees about (1, 1, 1) and moved.
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(kPi / 6.0, Eigen::Vector3d(1, 1, 1).normalized()).toRotationMatrix();
  TriangleMesh turned = test::box_mesh({0, 0, 0}, {1, 2, 3});
  for (Point3& p : turned.vertices) {
    const Eigen::Vector3d x = R * Eigen::Vector3d(p[0], p[1], p[2]) + Eigen::Vector3d(2, -1, 5);
    p = {x[0], x[1], x[2]};
  }
  const MassProperties t = mesh_mass_properties(turned);
  const Eigen::Matrix3d expected = R * Eigen::Vector3d(6.5, 5.0, 2.5).asDiagonal() * R.transpose();
  const Eigen::Vector3d centre = R * Eigen::Vector3d(0.5, 1.0, 1.5) + Eigen::Vector3d(2, -1, 5);
  EXPECT_NEAR(t.measure, 6.0, 1e-13);
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(t.centroid[r], centre[r], 1e-13);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(t.inertia[r][k], expected(r, k), 1e-12);
  }
  const MassProperties ball = mesh_mass_properties(test::soup(test::icosphere(4)));
  const double v = 4.0 / 3.0 * kPi;
  std::cout << "icosphere (5120 triangles): volume " << ball.measure << " against " << v
            << ", J_xx " << ball.inertia[0][0] << " against " << 0.4 * v << "\n";
  EXPECT_NEAR(ball.measure / v, 1.0, 5e-3);
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(ball.centroid[r], 0.0, 1e-12);
    EXPECT_NEAR(ball.inertia[r][r] / (0.4 * v), 1.0, 1e-2);
    for (int k = 0; k < 3; ++k) {
      if (k != r) {
        EXPECT_NEAR(ball.inertia[r][k], 0.0, 1e-12);
      }
    }
  }
}

// A rigid triangle (legs 20 and 6 cm) lying on its long leg on a rough
// polygon ramp at 30 degrees, mu = 0.3: any rigid block that does not tip
// slides at g (sin theta - mu cos theta), without turning.
TEST(ShapedBodies, TriangleSlidesDownAPolygonRampAtCoulombsRate) {
  const double theta = 30.0 * kPi / 180.0, tn = std::tan(theta), mu = 0.3;
  const auto y = [&](double x) { return 0.45 - x * tn; };
  // The triangle laid on the ramp: corners along and across the slope.
  const double s = std::sin(theta), c = std::cos(theta), x0 = 0.2, lift = 1e-4;
  const auto corner = [&](double along, double up) {
    return "[" + num(x0 + along * c + (up + lift) * s) + ", " +
           num(y(x0) - along * s + (up + lift) * c) + "]";
  };
  const std::string text =
      "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
      "resolution = [50, 25]\n[[obstacle]]\nshape = \"polygon\"\nvertices = [[-0.1, " +
      num(y(-0.1)) + "], [1.1, " + num(y(1.1)) + "], [1.1, -0.5], [-0.1, -0.5]]\nmu = " + num(mu) +
      "\n[[obstacle]]\nshape = \"polygon\"\nvertices = [" + corner(0, 0) + ", " + corner(0.2, 0) +
      ", " + corner(0, 0.06) + "]\ndensity = 1000\nmu = " + num(mu) + "\n" + kSpeck2D;
  Simulation<2> sim(parse_scene(text, "ramp.toml"));
  double spin = 0.0;
  const double a = test::body_acceleration(sim, 1, &spin);
  const double expected = 9.81 * (std::sin(theta) - mu * std::cos(theta));
  std::cout << "2D triangle on a 30-degree ramp, mu 0.3: " << a << " m/s^2 against Coulomb's "
            << expected << " (relative difference " << a / expected - 1.0 << "); spin " << spin
            << " rad/s\n";
  EXPECT_NEAR(a / expected, 1.0, 1e-6);
  EXPECT_LT(spin, 1e-4);
}

// A rigid box read from a mesh file (20 x 10 x 5 cm, its vertices turned in
// the file by 30 degrees about (1, 1, 1) and turned back by the scene's
// `angle`, so that its inertia tensor in the file's axes is not diagonal)
// on the floor under gravity tilted 25 degrees about y, mu = 0.2: it slides
// at g (sin theta - mu cos theta) without turning, as the box body does.
TEST(ShapedBodies, MeshBoxSlidesOnATiltedFloorAtCoulombsRate) {
  const double theta = 25.0 * kPi / 180.0, mu = 0.2;
  const fs::path dir = test::temp_dir("mesh_body"), obj = dir / "block.obj";
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(kPi / 6.0, Eigen::Vector3d(1, 1, 1).normalized()).toRotationMatrix();
  TriangleMesh block = test::box_mesh({-0.1, -0.05, -0.025}, {0.1, 0.05, 0.025});
  for (Point3& p : block.vertices) {
    const Eigen::Vector3d x =
        R * Eigen::Vector3d(p[0], p[1], p[2]) + Eigen::Vector3d(0.15, 0.15, 0.0251);
    p = {x[0], x[1], x[2]};
  }
  test::write_obj(obj, {block});
  const std::string text = "dimension = 3\ngravity = [" + num(9.81 * std::sin(theta)) + ", 0.0, " +
                           num(-9.81 * std::cos(theta)) +
                           "]\n[grid]\nsize = [0.6, 0.3, 0.3]\nresolution = [30, 15, 15]\n"
                           "[boundary]\ndefault = \"stick\"\n[[obstacle]]\nshape = \"mesh\"\n"
                           "file = \"" +
                           obj.string() +
                           "\"\ndensity = 1000\nangle = -30\naxis = [1, 1, 1]\nmu = " + num(mu) +
                           "\n" + kSpeck3D;
  const SceneConfig scene = parse_scene(text, "floor.toml");
  fs::remove_all(dir);
  Simulation<3> sim(scene);
  const Obstacle<3>& body = sim.obstacles()[0];
  EXPECT_NEAR(body.mass, 1000.0 * 0.2 * 0.1 * 0.05, 1e-5);             // the OBJ file's 6 digits
  EXPECT_GT(std::abs(body.inertia(0, 1)), 1e-6 * body.inertia(0, 0));  // not diagonal
  double spin = 0.0;
  const double a = test::body_acceleration(sim, 0, &spin);
  const double expected = 9.81 * (std::sin(theta) - mu * std::cos(theta));
  std::cout << "3D mesh box on a floor tilted 25 degrees, mu 0.2: " << a
            << " m/s^2 against Coulomb's " << expected << " (relative difference "
            << a / expected - 1.0 << "); spin " << spin << " rad/s\n";
  EXPECT_NEAR(a / expected, 1.0, 1e-6);
  EXPECT_LT(spin, 1e-4);
}

// Torque-free rotation of the same file-turned box: its inertia tensor is
// full, so the solve takes its inverse (not a diagonal). Euler's equations
// keep the angular momentum J omega (world axes) and the energy: checked
// over 1 s in steps of 1/100 s, as for the box body.
TEST(ShapedBodies, FreeRotationOfAMeshKeepsAngularMomentum) {
  const fs::path dir = test::temp_dir("mesh_spin"), obj = dir / "block.obj";
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(kPi / 6.0, Eigen::Vector3d(1, 1, 1).normalized()).toRotationMatrix();
  TriangleMesh block = test::box_mesh({-0.08, -0.05, -0.03}, {0.08, 0.05, 0.03});
  for (Point3& p : block.vertices) {
    const Eigen::Vector3d x =
        R * Eigen::Vector3d(p[0], p[1], p[2]) + Eigen::Vector3d(0.3, 0.15, 0.15);
    p = {x[0], x[1], x[2]};
  }
  test::write_obj(obj, {block});
  const std::string text =
      "dimension = 3\ngravity = [0.0, 0.0, 0.0]\n[grid]\nsize = [0.6, 0.3, 0.3]\n"
      "resolution = [30, 15, 15]\n[[obstacle]]\nshape = \"mesh\"\nfile = \"" +
      obj.string() + "\"\ndensity = 700\n" + kSpeck3D;
  const SceneConfig scene = parse_scene(text, "spin.toml");
  fs::remove_all(dir);
  Simulation<3> sim(scene);
  const Obstacle<3>& body = sim.obstacles()[0];
  // Spin mostly about the block's own shortest axis (its largest moment).
  const Vec<3> w0 = R * Vec<3>(0.3, 0.5, 5.0);
  sim.set_body_state(0, body.a, Vec<3>::Zero(), w0, 0.0, body.quaternion);
  const auto momentum = [&] {
    return Vec<3>(body.rotation * body.inertia * body.rotation.transpose() * body.spin);
  };
  const auto energy = [&] {
    return 0.5 *
           body.spin.dot(body.rotation * body.inertia * body.rotation.transpose() * body.spin);
  };
  const Vec<3> L0 = momentum();
  const double E0 = energy();
  for (int i = 0; i < 100; ++i) sim.step(0.01);
  const Vec<3> L1 = momentum();
  const double E1 = energy();
  std::cout << "mesh free rotation, 1 s: |L| " << L0.norm() << " -> " << L1.norm()
            << ", direction off by "
            << std::acos(std::min(1.0, L0.normalized().dot(L1.normalized()))) << " rad; energy "
            << E0 << " -> " << E1 << " J\n";
  EXPECT_NEAR(L1.norm() / L0.norm(), 1.0, 1e-3);
  EXPECT_NEAR(E1 / E0, 1.0, 1e-3);
}

// Bodies released turned onto the floor (stick walls): an L-shaped polygon
// (2D) and a tetrahedron (3D) land and come to rest lying on a face: at
// least D of their corners on the floor (to 1e-3 of a cell) and none below
// it. The contacts only dissipate (supplement, section 1, here for a body
// alone): each step's solve leaves the body less kinetic energy than it
// had with gravity's impulse and no contact, both measured with the
// inertia of the orientation the step starts from. (The total energy may
// still grow by O(dt^2 omega^2 r) of m g when a body pivots on a corner:
// its position moves along a finite turn, not the velocities' tangent.)
template <int D>
void comes_to_rest_on_a_face(const std::string& text) {
  Simulation<D> sim(parse_scene(text, "rest.toml"));
  const Obstacle<D>& body = sim.obstacles()[0];
  const double h = sim.grid().h();
  Vec<D> g;
  for (int a = 0; a < D; ++a) g[a] = sim.scene().gravity[a];
  const auto kinetic = [&](const Vec<D>& v, const Vec<D>& w, const Mat<D>& R) {
    double spin = 0.0;
    if constexpr (D == 2) {
      spin = body.inertia(0, 0) * w[0] * w[0];
    } else {
      spin = w.dot(R * body.inertia * R.transpose() * w);
    }
    return 0.5 * body.mass * v.squaredNorm() + 0.5 * spin;
  };
  double worst = -1e300;
  while (sim.time() < 1.5 - 1e-12) {
    const double dt = sim.adaptive_dt(1.5 - sim.time());
    const Mat<D> R = body.rotation;
    const double free = kinetic(Vec<D>(body.velocity + dt * g), body.spin, R);
    const StepInfo info = sim.step(dt);
    ASSERT_FALSE(info.solve.hit_cap) << "step " << sim.steps();
    worst = std::max(worst, (kinetic(body.velocity, body.spin, R) - free) / (body.mass * 9.81 * h));
  }
  int on_floor = 0;
  double lowest = 1e300;
  for (const Vec<D>& p : body_points(body)) {
    lowest = std::min(lowest, p[D - 1]);
    on_floor += std::abs(p[D - 1]) < 1e-3 * h;
  }
  std::cout << D << "D body after 1.5 s: " << on_floor << " corners on the floor, lowest at "
            << lowest << " m, speed " << body.velocity.norm() << " m/s, spin " << body.spin.norm()
            << " rad/s; largest kinetic energy a solve added " << worst << " of m g h\n";
  EXPECT_GE(on_floor, D);
  EXPECT_GT(lowest, -1e-3 * h);
  EXPECT_LT(body.velocity.norm(), 1e-3);
  EXPECT_LT(body.spin.norm(), 1e-2);
  EXPECT_LT(worst, 1e-9);
}

TEST(ShapedBodies, LShapedPolygonComesToRestOnAFace) {
  comes_to_rest_on_a_face<2>(
      "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\nresolution = [50, 25]\n"
      "[boundary]\ndefault = \"stick\"\n[[obstacle]]\nshape = \"polygon\"\nvertices = [[0.4, 0.2], "
      "[0.6, 0.2], [0.6, 0.25], [0.45, 0.25], [0.45, 0.35], [0.4, 0.35]]\ndensity = 700\n"
      "angle = 20\n" +
      kSpeck2D);
}

TEST(ShapedBodies, TetrahedronComesToRestOnAFace) {
  const fs::path dir = test::temp_dir("tetra"), obj = dir / "tetra.obj";
  TriangleMesh tet;
  tet.vertices = {{0.2, 0.1, 0.1}, {0.32, 0.1, 0.1}, {0.2, 0.2, 0.1}, {0.2, 0.1, 0.18}};
  tet.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  test::write_obj(obj, {tet});
  const std::string text =
      "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.6, 0.3, 0.3]\n"
      "resolution = [30, 15, 15]\n[boundary]\ndefault = \"stick\"\n[[obstacle]]\nshape = "
      "\"mesh\"\nfile = \"" +
      obj.string() + "\"\ndensity = 700\nangle = 35\naxis = [1, 2, 0.5]\n" + kSpeck3D;
  comes_to_rest_on_a_face<3>(text);
  fs::remove_all(dir);
}

// A coarse icosphere (r = 4 cm, 80 triangles) of density 1500 dropped onto a
// bed: the sand meets it through its sampled distance. Sources as for the
// balls and boxes dropped on sand: the momentum balance at every step, and
// statics once it has stopped (the sand carries its weight to 1%).
TEST(ShapedBodies, MeshDroppedOnSandRestsOnIt) {
  const fs::path dir = test::temp_dir("pebble"), obj = dir / "pebble.obj";
  TriangleMesh pebble = test::soup(test::icosphere(1));
  for (Point3& p : pebble.vertices) p = {0.2 + 0.04 * p[0], 0.15 + 0.04 * p[1], 0.2 + 0.04 * p[2]};
  test::write_obj(obj, {pebble});
  const std::string text =
      "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.4, 0.3, 0.3]\n"
      "resolution = [16, 12, 12]\n[boundary]\ndefault = \"slip\"\nzmin = \"stick\"\n"
      "zmax = \"free\"\n[[sand]]\nshape = \"box\"\nmin = [0.0, 0.0, 0.0]\nmax = [0.4, 0.3, 0.1]\n"
      "[[obstacle]]\nshape = \"mesh\"\nfile = \"" +
      obj.string() + "\"\ndensity = 1500\nvelocity = [0.0, 0.0, -1.0]\n";
  const SceneConfig scene = parse_scene(text, "pebble.toml");
  fs::remove_all(dir);
  Simulation<3> sim(scene);
  const double weight = sim.obstacles()[0].mass * 9.81;
  const test::BodyBalance run = test::run_body_balance(sim, 1.0);
  const Obstacle<3>& b = sim.obstacles()[0];
  std::cout << "3D icosphere mesh dropped on a bed: after 1 s centre at " << b.a[2]
            << " m (surface 0.1), speed " << b.velocity.norm() << " m/s, mean force of the sand "
            << "over the second half " << run.mean_force << " N against weight " << weight
            << " N; momentum balance to " << run.worst << "\n";
  EXPECT_LT(run.worst, 1e-9);
  EXPECT_NEAR(run.mean_force, weight, 0.01 * weight);
  EXPECT_LT(b.velocity.norm(), 1e-2);
  EXPECT_LT(b.a[2], 0.1 + 0.04);
  EXPECT_GT(b.a[2], 0.1 - 0.04);
}

}  // namespace
}  // namespace sablier
