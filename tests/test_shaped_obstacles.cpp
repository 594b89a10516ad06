// Obstacles of any shape: polygons (2D) and closed triangle meshes (3D),
// given by their signed distance like the other obstacles (METHOD.md
// section 3; physics/obstacle.hpp). Their distance is checked against
// geometry, their contact rows against the same statics and Coulomb
// sliding as a plane's (tests/test_obstacles.cpp), and the hourglass they
// make against Beverloo's law (the discharge does not depend on the height
// of sand above the neck).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/distance_grid.hpp"
#include "core/mesh.hpp"
#include "core/polygon.hpp"
#include "mesh_fixtures.hpp"
#include "physics/obstacle.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

const testing::Environment* const kOneThread =
    testing::AddGlobalTestEnvironment(new test::OneThread);

namespace fs = std::filesystem;
using test::run_until;
using test::scene;

// ------------------------------------------------------------ the distances

// An L-shaped polygon (the unit square less its upper-right quarter),
// clockwise, so that the orientation does not matter: distances and
// normals against the geometry, at points outside, inside, near the
// reflex corner and on the boundary.
TEST(ShapedObstacles, PolygonDistanceIsExact) {
  const SolidPolygon L({{0, 0}, {0, 1}, {0.5, 1}, {0.5, 0.5}, {1, 0.5}, {1, 0}});
  struct Case {
    double x, y, dist, nx, ny;
  };
  const Case cases[] = {
      {-0.3, 0.2, 0.3, -1, 0},    // left of the left edge
      {1.3, 0.2, 0.3, 1, 0},      // right of the right edge
      {1.3, 0.9, 0.5, 0.6, 0.8},  // beyond the corner (1, 0.5), offset (0.3, 0.4)
      {0.8, 0.7, 0.2, 0, 1},      // in the notch, 0.2 above its floor y = 0.5
      {0.2, 0.1, -0.1, 0, -1},    // inside, nearest the bottom edge
      {0.25, 1.0, 0.0, 0, 1},     // on the top edge
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << c.x << ", " << c.y);
    double nx = 0, ny = 0;
    EXPECT_NEAR(L.signed_distance(c.x, c.y, &nx, &ny), c.dist, 1e-14);
    EXPECT_NEAR(nx, c.nx, 1e-14);
    EXPECT_NEAR(ny, c.ny, 1e-14);
  }
  // A repeated corner (a zero-length edge) changes nothing, even at the
  // corner itself, where the normal is an adjacent edge's.
  const SolidPolygon twice({{0, 0}, {0, 0}, {0, 1}, {0.5, 1}, {0.5, 0.5}, {1, 0.5}, {1, 0}});
  for (const Case& c : cases) {
    double nx = 0, ny = 0;
    EXPECT_NEAR(twice.signed_distance(c.x, c.y, &nx, &ny), c.dist, 1e-14);
    EXPECT_NEAR(nx, c.nx, 1e-14);
    EXPECT_NEAR(ny, c.ny, 1e-14);
  }
  {
    double nx = 0, ny = 0;
    EXPECT_EQ(twice.signed_distance(0.0, 0.0, &nx, &ny), 0.0);
    EXPECT_NEAR(std::hypot(nx, ny), 1.0, 1e-14);
  }
  // Inside, nearest the reflex corner (0.5, 0.5) itself, offset (-0.05, -0.1).
  double nx = 0, ny = 0;
  const double d = std::hypot(0.05, 0.1);
  EXPECT_NEAR(L.signed_distance(0.45, 0.4, &nx, &ny), -d, 1e-14);
  EXPECT_NEAR(nx, 0.05 / d, 1e-14);
  EXPECT_NEAR(ny, 0.1 / d, 1e-14);
}

// The sampled distance of a box is exact wherever the nearest sample cell
// sees one face only (a linear function, which trilinear interpolation
// reproduces), and its error near edges and corners is below the spacing.
TEST(ShapedObstacles, SampledMeshDistanceMatchesTheBox) {
  const Point3 lo{0.2, 0.3, 0.1}, hi{0.6, 0.5, 0.4};
  const auto mesh = std::make_shared<const SolidMesh>(test::box_mesh(lo, hi));
  const double h = 0.01;
  const DistanceGrid grid(mesh, {0, 0, 0}, {1, 1, 1}, h, 1.0);
  ObstacleConfig c;
  c.shape = ObstacleShape::Box;
  c.min = lo;
  c.max = hi;
  const Obstacle<3> box = make_obstacle<3>(c);
  double worst = 0.0, worst_face = 0.0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j)
      for (int k = 0; k <= 40; ++k) {
        const Point3 p{0.1 + 0.6 * i / 40.0 + 1e-3, 0.2 + 0.4 * j / 40.0 + 2e-3,
                       0.02 + 0.5 * k / 40.0 + 3e-3};
        Point3 n{};
        const double s = grid.signed_distance(p, &n);
        Vec<3> nb;
        const double exact = signed_distance(box, Vec<3>(p[0], p[1], p[2]), &nb);
        worst = std::max(worst, std::abs(s - exact));
        // Away from the edges (within 0.05 of exactly one face's plane).
        int near_planes = 0;
        for (int a = 0; a < 3; ++a)
          near_planes += (std::abs(p[a] - lo[a]) < 0.05) + (std::abs(p[a] - hi[a]) < 0.05);
        if (near_planes == 1 && std::abs(exact) < 0.04) {
          worst_face = std::max(worst_face, std::abs(s - exact));
          EXPECT_NEAR(n[0] * nb[0] + n[1] * nb[1] + n[2] * nb[2], 1.0, 1e-9);
        }
      }
  std::cout << "sampled cube distance: largest error " << worst << " m (spacing " << h
            << "), away from edges " << worst_face << " m\n";
  // Cut to a band of 5 cm: the same values within 4 cm of the surface (band
  // less a spacing), beyond that at least 4 cm in magnitude, of the same
  // sign.
  const DistanceGrid banded(mesh, {0, 0, 0}, {1, 1, 1}, h, 0.05);
  for (int i = 0; i <= 50; ++i) {
    const Point3 p{0.01 + 0.98 * i / 50.0, 0.41, 0.23};
    Point3 n{};
    const double full = grid.signed_distance(p, &n), cut = banded.signed_distance(p, &n);
    if (std::abs(full) <= 0.04) {
      EXPECT_EQ(cut, full) << p[0];
    } else {
      EXPECT_GE(std::abs(cut), 0.04) << p[0];
      EXPECT_EQ(cut > 0, full > 0) << p[0];
    }
  }
  EXPECT_LT(worst_face, 1e-12);
  EXPECT_LT(worst, h);
}

// --------------------------------------------------------------- the physics

// A cohesive block (5 kPa, so that it moves as one) resting on a polygon
// ramp inclined at theta = 20 degrees, gravity vertical: it slides with
// g (sin theta - mu_RB cos theta) when mu_RB = 0.2 < tan(theta) and stays
// when mu_RB = 0.45 > tan(theta) = 0.36. The ramp's surface cuts the grid
// at an angle, unlike the plane of tests/test_obstacles.cpp, which lies
// along the grid with tilted gravity.
double ramp_speed(double mu_rb, double t) {
  const double theta = 20.0 * test::kPi / 180.0, c = std::cos(theta), s = std::sin(theta);
  // The ramp's surface: the line through (0, 0.2) going down to the right
  // at theta, tangent (c, -s), normal (s, c).
  const auto on = [&](double along, double up) {
    return "[" + std::to_string(along * c + up * s) + ", " +
           std::to_string(0.2 - along * s + up * c) + "]";
  };
  // A block 30 x 4 cm on it, from 5 cm along the surface.
  const std::string text = R"(dimension = 2
gravity = [0.0, -9.81]
[grid]
size = [0.5, 0.25]
resolution = [100, 50]
[time]
fps = 30
frames = 10
[material]
density = 2500
mu = 0.5
phi_max = 0.6
cohesion = 5000
[boundary]
default = "free"
[[sand]]
shape = "polygon"
particles_per_cell = 2
vertices = [)" + on(0.05, 0.0) +
                           ", " + on(0.35, 0.0) + ", " + on(0.35, 0.04) + ", " + on(0.05, 0.04) +
                           "]\n";
  SceneConfig sc = parse_scene(text, "ramp.toml");
  ObstacleConfig ramp;
  ramp.shape = ObstacleShape::Polygon;
  ramp.vertices = {
      {-0.1, 0.2 + 0.1 * s / c, 0}, {0.6, 0.2 - 0.6 * s / c, 0}, {0.6, -0.5, 0}, {-0.1, -0.5, 0}};
  std::vector<SolidPolygon::Point2> corners;
  for (const Vec3d& v : ramp.vertices) corners.push_back({v[0], v[1]});
  ramp.polygon = std::make_shared<const SolidPolygon>(corners);
  ramp.mu = mu_rb;
  sc.obstacles.push_back(ramp);
  Simulation<2> sim(sc);
  const Obstacle<2> solid = make_obstacle<2>(ramp);
  run_until(sim, t);
  double momentum = 0.0, mass = 0.0, deepest = 0.0;
  for (std::size_t p = 0; p < sim.particles().size(); ++p) {
    const Vec<2>& v = sim.particles().velocity[p];
    momentum += sim.particles().volume[p] * (v[0] * c - v[1] * s);
    mass += sim.particles().volume[p];
    Vec<2> n;
    deepest = std::min(deepest, signed_distance(solid, sim.particles().position[p], &n));
  }
  EXPECT_GE(deepest, -1e-9) << "a grain inside the ramp";
  return momentum / mass;
}

TEST(ShapedObstacles, BlockSlidesDownAPolygonRampWithCoulombFriction) {
  const double theta = 20.0 * test::kPi / 180.0, t = 0.3;
  const double expected = 9.81 * (std::sin(theta) - 0.2 * std::cos(theta)) * t;
  const double v = ramp_speed(0.2, t);
  std::cout << "block on a 20 degree polygon ramp, mu_RB = 0.2: mean speed along it at " << t
            << " s = " << v << " m/s, Coulomb block " << expected << " m/s\n";
  EXPECT_NEAR(v / expected, 1.0, 1e-3);
  const double held = ramp_speed(0.45, t);
  std::cout << "the same, mu_RB = 0.45: " << held << " m/s\n";
  EXPECT_LT(std::abs(held), 1e-3);
}

// A 10 cm bed resting on a mesh slab (its top at z = 4.5 cm, between grid
// nodes), as tests/test_obstacles.cpp rests one on a plane: after 0.5 s
// the bed is at rest, no grain is inside the slab, and the force the sand
// puts on the slab balances the sand's weight (statics; the frictionless
// side walls carry no vertical load).
TEST(ShapedObstacles, BedRestsOnAMeshSlab) {
  const fs::path obj = test::temp_dir("slab") / "slab.obj";
  test::write_obj(obj, {test::box_mesh({-0.1, -0.1, -0.1}, {0.3, 0.2, 0.045})});
  SceneConfig s = load_scene(
      test::scene_file("bed3d.toml"),
      {"grid.size=[0.2,0.1,0.2]", "grid.resolution=[20,10,20]", "sand.0.min=[0.0,0.0,0.045]",
       "sand.0.max=[0.2,0.1,0.145]", "obstacle=[{shape=\"mesh\",file=\"" + obj.string() + "\"}]"});
  fs::remove_all(obj.parent_path());
  ASSERT_EQ(s.obstacles.size(), 1u);
  Simulation<3> sim(s);
  StepInfo last;
  while (sim.time() < 0.5 - 1e-12) {
    last = sim.step(sim.adaptive_dt(0.5 - sim.time()));
    ASSERT_TRUE(last.solve.residual <= s.solver.tolerance || last.solve.hit_cap);
  }
  const double weight = sim.grain_mass() * 9.81;
  const double vertical = last.obstacle_force.at(0)[2];
  double lowest = 1e300;
  for (const Vec<3>& x : sim.particles().position) lowest = std::min(lowest, x[2]);
  std::cout << "3D bed on a mesh slab: force on it " << vertical << " against weight " << -weight
            << ", max speed " << sim.max_speed() << " m/s, lowest grain " << lowest << " m\n";
  EXPECT_NEAR(-vertical / weight, 1.0, 0.02);
  EXPECT_LT(sim.max_speed(), 1e-3);
  EXPECT_GE(lowest, 0.045);
}

// The 2D hourglass of scenes/hourglass2d.toml, its first 1.3 s: the sand
// drains through the neck, no grain ever enters the polygonal walls, and
// the discharge holds: Beverloo's law makes it independent of the height
// of sand above the neck, so the grains through the neck over 0.5-0.9 s
// and over 0.9-1.3 s agree within 15% (the bound of the silo's validation
// test). Measured through `sablier run` (5 grains per cell and axis, 12,602
// grains): 6,500 grains per second over 0.2-0.6 s, while the flow sets in,
// 6,628 over 0.6-1.0 s, 6,733 over 1.0-1.4 s and 6,363 over 1.4-1.7 s; the
// test's windows 6,493 and 6,618.
TEST(ShapedObstacles, HourglassDrainsThroughItsNeck) {
  const SceneConfig s = scene("hourglass2d.toml");
  Simulation<2> sim(s);
  std::vector<Obstacle<2>> walls;
  for (const ObstacleConfig& c : s.obstacles) walls.push_back(make_obstacle<2>(c));
  const auto below_neck = [&] {
    std::size_t n = 0;
    double deepest = 0.0;
    for (const Vec<2>& x : sim.particles().position) {
      n += x[1] < 0.27;
      Vec<2> normal;
      deepest = std::min(deepest, obstacle_distance(walls, x, &normal));
    }
    EXPECT_GE(deepest, -1e-9) << "a grain inside a wall at t = " << sim.time();
    return static_cast<double>(n);
  };
  std::vector<double> through;
  for (double t : {0.5, 0.9, 1.3}) {
    run_until(sim, t);
    through.push_back(below_neck());
  }
  const double early = (through[1] - through[0]) / 0.4, late = (through[2] - through[1]) / 0.4;
  std::cout << "hourglass: " << early << " grains/s through the neck over 0.5-0.9 s, " << late
            << " over 0.9-1.3 s, of " << sim.particles().size() << "\n";
  EXPECT_GT(early, 0.0);
  EXPECT_NEAR(late / early, 1.0, 0.15);
}

// The grains' clearances (Simulation::move_outside_solids, and advection
// where no solid moves: transfer_to_particles), which skip the solids'
// distance queries, are lower bounds on their distance to the solids: at
// the end of each step, every grain lies at least its clearance from the
// nearest solid (exact distances move by no more than the point; the slack
// of 1e-9 h covers rounding). The clearances follow the grains through the
// sort, which drops the grains that left and takes in those a spout
// emitted. Returns the least distance less clearance over `duration`; the
// largest clearance, the grains emitted and those that left in the others.
double least_distance_less_clearance(const SceneConfig& s, double duration, double* largest,
                                     std::int64_t* emitted, std::int64_t* left) {
  Simulation<2> sim(s);
  std::vector<Obstacle<2>> walls;
  for (const ObstacleConfig& c : s.obstacles) walls.push_back(make_obstacle<2>(c));
  double worst = 1e300;
  std::size_t checked = 0;
  std::unordered_set<std::int64_t> ids;  // every grain seen, seeded or emitted
  *largest = 0.0;
  while (sim.time() < duration - 1e-12) {
    sim.step(sim.adaptive_dt(std::min(1.0 / 30, duration - sim.time())));
    const std::vector<double>& clearance = sim.clearances();
    EXPECT_EQ(clearance.size(), sim.particles().size());
    if (clearance.size() != sim.particles().size()) return -1.0;
    for (std::size_t p = 0; p < clearance.size(); ++p) {
      Vec<2> normal;
      const double d = obstacle_distance(walls, sim.particles().position[p], &normal);
      EXPECT_GE(clearance[p], 0.0);
      worst = std::min(worst, d - clearance[p]);
      *largest = std::max(*largest, clearance[p]);
      ids.insert(sim.particles().id[p]);
      ++checked;
    }
  }
  const auto seeded = static_cast<std::int64_t>(Simulation<2>(s).particles().size());
  const auto seen = static_cast<std::int64_t>(ids.size());
  *emitted = seen - seeded;
  *left = seen - static_cast<std::int64_t>(sim.particles().size());
  std::cout << checked << " grain-steps, distance less clearance at least " << worst
            << " m, largest clearance " << *largest << " m, " << *emitted << " grains emitted, "
            << *left << " left\n";
  return worst;
}

// The hourglass's polygons, 0.5 s, where grains slide along the walls and
// through the neck; the clearances are not all zero (else the skips never
// act: most grains are several cells from the walls). Then a spout pouring
// onto a fixed disk in a box with free sides, 0.5 s: grains are emitted and
// leave between the steps, so that the sort's reordering is checked too.
TEST(ShapedObstacles, ClearanceBoundsEachGrainsDistanceToTheSolids) {
  double largest = 0.0;
  std::int64_t emitted = 0, left = 0;
  EXPECT_GE(
      least_distance_less_clearance(scene("hourglass2d.toml"), 0.5, &largest, &emitted, &left),
      -1e-12);
  EXPECT_GT(largest, 0.05);
  const SceneConfig pour = scene(
      "pile2d.toml", {"grid.size=[0.2,0.3]", "grid.resolution=[40,60]", "spout.0.center=[0.1,0.25]",
                      "obstacle=[{shape=\"disk\",center=[0.1,0.12],radius=0.03}]"});
  EXPECT_GE(least_distance_less_clearance(pour, 0.5, &largest, &emitted, &left), -1e-12);
  EXPECT_GT(largest, 0.02);
  EXPECT_GT(emitted, 1000);
  EXPECT_GT(left, 20);
}

// The acceleration of rigid body `k` between 0.1 s and 0.25 s, checking
// that it rolls (omega r = v; `spin_sign` and `spin_axis` give the spin
// component that rolls it: about z clockwise in 2D, about y in 3D here).
template <int D>
double rolling_acceleration(Simulation<D>& sim, std::size_t k, double r, int spin_axis,
                            double spin_sign) {
  const auto speed = [&] {
    const Obstacle<D>& ball = sim.obstacles().at(k);
    const double v = ball.velocity.norm();
    EXPECT_NEAR(spin_sign * ball.spin[spin_axis] * r, v, 1e-6 * v);
    return v;
  };
  run_until(sim, 0.1);
  const double v1 = speed(), t1 = sim.time();
  run_until(sim, 0.25);
  const double v2 = speed(), t2 = sim.time();
  return (v2 - v1) / (t2 - t1);
}

// A rigid disk (2 t/m^3, r = 4 cm) released on a rough polygon ramp at
// theta = 20 degrees, away from the sand: its contact with the polygon is
// a ball's contact with any solid (docs/method.md, "Frictional
// obstacles"), so it rolls without slipping and accelerates at
// 2/3 g sin(theta), the rigid-body value 1 / (1 + J / (m r^2)) for a disk,
// with omega r = v.
TEST(ShapedObstacles, DiskRollsDownAPolygonRamp) {
  const double theta = 20.0 * test::kPi / 180.0, tn = std::tan(theta);
  const double r = 0.04, x0 = 0.1;
  // The ramp's surface: through (0, 0.4), down to the right at theta.
  const auto y = [&](double x) { return 0.4 - x * tn; };
  const std::string text =
      "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
      "resolution = [50, 25]\n[[obstacle]]\nshape = \"polygon\"\nvertices = [[-0.1, " +
      std::to_string(y(-0.1)) + "], [1.1, " + std::to_string(y(1.1)) +
      "], [1.1, -0.5], [-0.1, -0.5]]\n[[obstacle]]\nshape = \"disk\"\ncenter = [" +
      std::to_string(x0 + r * std::sin(theta)) + ", " +
      std::to_string(y(x0) + r * std::cos(theta) + 1e-4) +
      "]\nradius = 0.04\ndensity = 2000\n[[sand]]\nshape = \"box\"\nmin = [0.9, 0.4]\n"
      "max = [0.95, 0.45]\n";
  Simulation<2> sim(parse_scene(text, "roll.toml"));
  const double a = rolling_acceleration(sim, 1, r, 0, -1.0);
  const double expected = 2.0 / 3.0 * 9.81 * std::sin(theta);
  std::cout << "disk on a polygon ramp: " << a << " m/s^2, rolling " << expected << "\n";
  EXPECT_NEAR(a / expected, 1.0, 1e-6);
}

// The 3D counterpart on a mesh: a rigid sphere (r = 4 cm) on a ramp made
// of a closed mesh (a prism whose top face is inclined at 20 degrees,
// falling along +x) rolls without slipping at 5/7 g sin(theta). Its top
// face is flat, so the sampled distance is exact there (a linear function)
// and so is its normal.
TEST(ShapedObstacles, SphereRollsDownAMeshRamp) {
  const double theta = 20.0 * test::kPi / 180.0, tn = std::tan(theta);
  const double r = 0.04, x0 = 0.1;
  const auto z = [&](double x) { return 0.25 - x * tn; };
  const fs::path dir = test::temp_dir("ramp"), obj = dir / "ramp.obj";
  {
    // The cross-section in (x, z), extruded along y over [-0.1, 0.3].
    const double xz[4][2] = {{-0.1, z(-0.1)}, {0.7, z(0.7)}, {0.7, -0.3}, {-0.1, -0.3}};
    std::ofstream out(obj);
    for (double y : {-0.1, 0.3})
      for (const auto& p : xz) out << "v " << p[0] << " " << y << " " << p[1] << "\n";
    out << "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n";
  }
  const std::string text =
      "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.6, 0.2, 0.3]\n"
      "resolution = [30, 10, 15]\n[[obstacle]]\nshape = \"mesh\"\nfile = \"" +
      obj.string() + "\"\n[[obstacle]]\nshape = \"sphere\"\ncenter = [" +
      std::to_string(x0 + r * std::sin(theta)) + ", 0.1, " +
      std::to_string(z(x0) + r * std::cos(theta) + 1e-4) +
      "]\nradius = 0.04\ndensity = 2000\n[[sand]]\nshape = \"box\"\n"
      "min = [0.5, 0.0, 0.25]\nmax = [0.55, 0.05, 0.3]\n";
  Simulation<3> sim(parse_scene(text, "ramp.toml"));
  fs::remove_all(dir);
  const double a = rolling_acceleration(sim, 1, r, 1, 1.0);
  const double expected = 5.0 / 7.0 * 9.81 * std::sin(theta);
  std::cout << "sphere on a mesh ramp: " << a << " m/s^2, rolling " << expected << "\n";
  EXPECT_NEAR(a / expected, 1.0, 1e-6);
}

// A sphere of radius 4 cells dropped onto a mesh slab from 3 cm above it
// (1 cm cells) moves as it does over the same slab as box obstacles, whose
// distance is exact: the same heights at every step while it falls, and
// the same rest on the top face. A ball's contact with a solid is measured
// from its centre, so the sampled distance must be exact that far from the
// surface, not only within the few cells the grains need.
TEST(ShapedObstacles, LargeSphereFallsOntoAMeshSlabAsOntoABox) {
  const fs::path dir = test::temp_dir("bigball"), obj = dir / "slab.obj";
  // The slab and a post in a corner, one closed mesh of two boxes: the post
  // makes the mesh's bounds, and so the sampled region, reach above the
  // sphere.
  test::write_obj(obj, {test::box_mesh({-0.1, -0.1, -0.1}, {0.3, 0.3, 0.05}),
                        test::box_mesh({0.0, 0.0, 0.0}, {0.03, 0.03, 0.19})});
  const std::string head =
      "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.2, 0.2, 0.2]\n"
      "resolution = [20, 20, 20]\n[[sand]]\nshape = \"box\"\nmin = [0.17, 0.17, 0.15]\n"
      "max = [0.19, 0.19, 0.17]\n[[obstacle]]\n";
  const std::string ball =
      "[[obstacle]]\nshape = \"sphere\"\ncenter = [0.1, 0.1, 0.12]\nradius = 0.04\n"
      "density = 2000\n";
  Simulation<3> on_mesh(
      parse_scene(head + "shape = \"mesh\"\nfile = \"" + obj.string() + "\"\n" + ball, "m.toml"));
  Simulation<3> on_box(parse_scene(
      head + "shape = \"box\"\nmin = [-0.1, -0.1, -0.1]\nmax = [0.3, 0.3, 0.05]\n" +
          "[[obstacle]]\nshape = \"box\"\nmin = [0.0, 0.0, 0.0]\nmax = [0.03, 0.03, 0.19]\n" + ball,
      "b.toml"));
  fs::remove_all(dir);
  double worst = 0.0;
  while (on_box.time() < 0.3 - 1e-12) {
    const double dt = std::min(1.0 / 120, 0.3 - on_box.time());
    on_box.step(dt);
    on_mesh.step(dt);
    worst =
        std::max(worst, std::abs(on_mesh.obstacles().at(1).a[2] - on_box.obstacles().at(2).a[2]));
  }
  std::cout << "sphere onto a slab: mesh and box heights differ by at most " << worst
            << " m; at 0.3 s " << on_mesh.obstacles().at(1).a[2] << " and "
            << on_box.obstacles().at(2).a[2] << " m (rest: 0.09)\n";
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(on_mesh.obstacles().at(1).a[2], 0.09, 1e-6);
}

// ------------------------------------------------------------- the output

// obstacles.obj (io/obstacle_geometry.hpp): every vertex it writes lies on
// its obstacle's surface (signed distance 0 to round-off: a plane's cut
// through the box, a box's corners, a sphere's and a cylinder's
// tessellation, a polygon's corners, a mesh's own vertices), objects come
// in the scene's order, faces index existing vertices, and a rigid body is
// left out. `sablier run` writes it beside the frames.
TEST(ShapedObstacles, ObstaclesObjHoldsTheirSurfaces) {
  const fs::path dir = test::temp_dir("objout");
  {
    std::ofstream out(dir / "tet.obj");
    out << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  }
  const std::string text = R"(dimension = 3
[grid]
size = [0.5, 0.25, 0.25]
resolution = [20, 10, 10]
[[sand]]
shape = "box"
min = [0.2, 0.0, 0.1]
max = [0.3, 0.1, 0.2]
[[obstacle]]
shape = "plane"
point = [0.0, 0.0, 0.02]
normal = [0.2, 0.1, 1.0]
[[obstacle]]
shape = "sphere"
center = [0.45, 0.2, 0.2]
radius = 0.03
[[obstacle]]
shape = "sphere"
center = [0.1, 0.1, 0.2]
radius = 0.03
density = 2000
[[obstacle]]
shape = "cylinder"
center = [0.05, 0.2, 0.0]
radius = 0.02
height = 0.1
[[obstacle]]
shape = "box"
min = [-0.1, -0.1, -0.1]
max = [0.02, 0.3, 0.3]
[[obstacle]]
shape = "mesh"
file = "tet.obj"
scale = 0.05
translate = [0.35, 0.1, 0.05]
)";
  const fs::path scene_path = dir / "scene.toml";
  std::ofstream(scene_path) << text;
  const SceneConfig s = load_scene(scene_path.string());
  const test::Result r = test::sablier("run " + scene_path.string() + " --out " +
                                       (dir / "out").string() + " --set time.frames=1 --quiet");
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "out" / "obstacles.obj");
  ASSERT_TRUE(in) << "no obstacles.obj";
  std::vector<Vec<3>> v;
  std::vector<int> owner, objects;
  std::string line;
  std::size_t faces = 0;
  while (std::getline(in, line)) {
    std::istringstream l(line);
    std::string tag;
    l >> tag;
    if (tag == "o") {
      std::string name;
      l >> name;
      ASSERT_EQ(name.rfind("obstacle_", 0), 0u);
      objects.push_back(std::stoi(name.substr(9)));
    } else if (tag == "v") {
      Vec<3> x;
      l >> x[0] >> x[1] >> x[2];
      v.push_back(x);
      owner.push_back(objects.back());
    } else if (tag == "f") {
      ++faces;
      int i = 0, n = 0;
      while (l >> i) {
        ASSERT_TRUE(i >= 1 && i <= static_cast<int>(v.size())) << line;
        ++n;
      }
      ASSERT_GE(n, 3);
    }
  }
  EXPECT_EQ(objects, (std::vector<int>{0, 1, 3, 4, 5}));  // not the body, 2
  EXPECT_GT(faces, 0u);
  for (std::size_t k = 0; k < v.size(); ++k) {
    const ObstacleConfig& c = s.obstacles[owner[k]];
    if (c.shape == ObstacleShape::Mesh) continue;  // its own vertices, as read
    Vec<3> n;
    // 1e-9 m: the file's 10 significant digits.
    EXPECT_NEAR(signed_distance(make_obstacle<3>(c), v[k], &n), 0.0, 1e-9)
        << "obstacle " << owner[k] << " vertex " << v[k].transpose();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sablier
