// Rigid bodies at a concave fold of a polygon or mesh (physics/corners.hpp,
// faces_over; docs/scenes.md "Rigid boxes, polygons and meshes"): near a
// fold that turns inward (a V-groove's bottom) the solid is the union of
// its two faces' half-spaces, and a point there must stay outside both.
// Two changes were needed (each measured alone below): a row for every
// face a corner lies over, not only the nearest (in 3D a cube's corner
// otherwise slipped across the fold into the other slope within a step),
// and a solver residual that counts each body row's own change (the two
// rows of one corner could trade stress with the body's velocity at rest
// over a sweep, and the solve stopped with its rows unsatisfied).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "body_fixtures.hpp"
#include "core/mesh.hpp"
#include "core/polygon.hpp"
#include "mesh_fixtures.hpp"
#include "physics/edges.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;
using test::num;

const auto* const kOneThread = testing::AddGlobalTestEnvironment(new test::OneThread);

// The grooved block's section across its groove (x, height): 30 cm wide,
// 10 cm tall, a 90-degree V cut 6 cm deep into its top, the fold at x =
// 0.3, height 0.04. Two convex folds at the rims, one concave at the bottom.
const double kSection[7][2] = {{0.15, 0.0}, {0.45, 0.0}, {0.45, 0.1}, {0.36, 0.1},
                               {0.3, 0.04}, {0.24, 0.1}, {0.15, 0.1}};

// The block as a mesh, the groove along y from 0.05 to 0.25: the ends fanned
// from the fold's vertex (the section is star-shaped about it), the sides
// two triangles per edge of the section, all outward.
TriangleMesh grooved_block() {
  TriangleMesh m;
  for (const double y : {0.05, 0.25})
    for (const auto& p : kSection) m.vertices.push_back({p[0], y, p[1]});
  for (int k : {5, 6, 0, 1, 2}) {
    m.triangles.push_back({4, (k + 1) % 7, k});
    m.triangles.push_back({11, 7 + k, 7 + (k + 1) % 7});
  }
  for (int k = 0; k < 7; ++k) {
    const int n = (k + 1) % 7;
    m.triangles.push_back({k, n, 7 + n});
    m.triangles.push_back({k, 7 + n, 7 + k});
  }
  return m;
}

// The faces a point lies over (SolidMesh::faces_over, SolidPolygon::
// faces_over): over the groove, 1 cm above its fold, both slopes (each at
// 1 / sqrt(2) cm, normals (-+1, 1) / sqrt(2)); over the block's flat top
// away from the groove, that one face; over a box none (a convex solid has
// no concave fold, and outside it a point lies over one face at most, the
// nearest, which the point's own row holds). Geometry, exact to round-off.
TEST(ConcaveFolds, OnlyConcaveFoldsHaveFacesOver) {
  const TriangleMesh block = grooved_block();
  EXPECT_TRUE(has_concave_fold(block));
  EXPECT_FALSE(has_concave_fold(test::box_mesh({0, 0, 0}, {1, 1, 1})));
  TriangleMesh octahedron;  // welded: its triangles share their edges
  octahedron.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  octahedron.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                          {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  EXPECT_FALSE(has_concave_fold(octahedron));
  const SolidMesh mesh(block);
  Point3 n[4];
  double d[4];
  const Point3 up{0, 0, 1};
  ASSERT_EQ(mesh.faces_over({0.3, 0.15, 0.05}, up, 0.02, 1e-4, n, d, 4), 2);
  for (int f = 0; f < 2; ++f) {
    EXPECT_NEAR(d[f], 0.01 / std::sqrt(2.0), 1e-15);
    EXPECT_NEAR(std::abs(n[f][0]), std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(n[f][2], std::sqrt(0.5), 1e-15);
  }
  EXPECT_LT(n[0][0] * n[1][0], 0.0);
  EXPECT_EQ(mesh.faces_over({0.2, 0.15, 0.105}, up, 0.02, 1e-4, n, d, 4), 1);
  const SolidMesh box(test::box_mesh({0, 0, 0}, {1, 1, 1}));
  EXPECT_EQ(box.faces_over({0.5, 0.5, 1.01}, up, 0.02, 1e-4, n, d, 4), 0);
  std::vector<SolidPolygon::Point2> corners;
  for (const auto& p : kSection) corners.push_back({p[0], p[1]});
  const SolidPolygon polygon(corners);
  double nx[4], ny[4];
  ASSERT_EQ(polygon.faces_over(0.3, 0.05, 0.0, 1.0, 0.02, 1e-4, nx, ny, d, 4), 2);
  EXPECT_NEAR(d[0], 0.01 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(d[1], 0.01 / std::sqrt(2.0), 1e-15);
  const SolidPolygon square({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_EQ(square.faces_over(0.5, 1.01, 0.0, 1.0, 0.02, 1e-4, nx, ny, d, 4), 0);
}

// How deep a point (x, height) is in the block near its groove (|x - 0.3|
// < 0.06, below the rims): its distance to the groove's free space, the
// quarter plane above the fold, a convex cone, whose distance is that to
// the nearer of its two boundary rays.
double depth_in_groove(double x, double height) {
  const Eigen::Vector2d q(x - 0.3, height - 0.04);
  if (q[1] >= std::abs(q[0])) return 0.0;
  double d = 1e300;
  for (const double side : {-1.0, 1.0}) {
    const Eigen::Vector2d r(side * std::sqrt(0.5), std::sqrt(0.5));
    d = std::min(d, (q - std::max(0.0, q.dot(r)) * r).norm());
  }
  return d;
}

// The deepest of 201 points along each edge of the body's outline in the
// groove (the depth is convex along a segment, so its corners bound it;
// the samples show where it is).
template <int D>
double deepest_in_groove(const Obstacle<D>& body) {
  std::vector<Vec<D>> corners;
  std::vector<std::pair<Vec<D>, Vec<D>>> edges;
  if constexpr (D == 2) {
    body_points(body, corners);
    for (std::size_t k = 0; k < corners.size(); ++k)
      edges.push_back({corners[k], corners[(k + 1) % corners.size()]});
  } else {
    std::vector<SolidEdge> solid;
    solid_edges(body, body.a, 1e300, solid);
    for (const SolidEdge& e : solid) edges.push_back({e.from, e.to});
  }
  double worst = 0.0;
  for (const auto& [from, to] : edges)
    for (int k = 0; k <= 200; ++k) {
      const Vec<D> p = from + (k / 200.0) * (to - from);
      worst = std::max(worst, depth_in_groove(p[0], p[D - 1]));
    }
  return worst;
}

// A square box (4 cm, 500 kg/m^3) dropped tumbling (turned 20 degrees; in
// 3D about (0.3, 1, 0.2)) into the groove, whose fold is 2 cm under its
// centre. Non-penetration: over 1 s no point of its outline is deeper in
// the block than 1e-3 of a cell (the bound the tumbling plank of
// test_edge_contacts.cpp keeps), and the fold does not enter it; it comes
// to rest (1e-3 m/s, rad/s) in the groove, seated on its two lower faces:
// its centre over the fold and half a diagonal above it to 1e-3 of a cell;
// the same bits on 1 and 2 threads over its first 10 steps.
// Measured before: 0.0023 of a cell deep at worst in 2D; in 3D 0.017 deep,
// where it stayed, 0.011 off the fold. With the rows of every face but the
// old residual: 2D 0.0059 deep and 0.004 off; with the residual but one row
// per point: 3D stopped at the solver's cap (residual 5.3e-5).
template <int D>
void cube_settles_into_a_groove() {
  const fs::path dir = test::temp_dir("groove"), obj = dir / "groove.obj";
  std::string text;
  if constexpr (D == 2) {
    std::string vertices;
    for (const auto& p : kSection)
      vertices +=
          std::string(vertices.empty() ? "" : ", ") + "[" + num(p[0]) + ", " + num(p[1]) + "]";
    text =
        "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [1.0, 0.5]\n"
        "resolution = [50, 25]\n[boundary]\ndefault = \"stick\"\n[[obstacle]]\n"
        "shape = \"polygon\"\nvertices = [" +
        vertices +
        "]\n[[obstacle]]\nshape = \"box\"\nmin = [0.28, 0.08]\nmax = [0.32, 0.12]\n"
        "density = 500\nangle = 20\n" +
        test::kSpeck2D;
  } else {
    test::write_exact_obj(obj, grooved_block());
    text =
        "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.8, 0.3, 0.3]\n"
        "resolution = [40, 15, 15]\n[boundary]\ndefault = \"stick\"\n[[obstacle]]\n"
        "shape = \"mesh\"\nfile = \"" +
        obj.string() +
        "\"\n[[obstacle]]\nshape = \"box\"\nmin = [0.28, 0.13, 0.08]\nmax = [0.32, 0.17, 0.12]\n"
        "density = 500\nangle = 20\naxis = [0.3, 1.0, 0.2]\n"
        "[[sand]]\nshape = \"box\"\nmin = [0.75, 0.0, 0.0]\nmax = [0.8, 0.05, 0.05]\n";
  }
  const SceneConfig scene = parse_scene(text, "groove.toml");
  fs::remove_all(dir);
  // The bodies' rows and what they trade are summed on one thread.
  test::expect_same_bits_on_1_and_2_threads<D>(scene, 10, 1);
  Simulation<D> sim(scene);
  const double h = sim.grid().h();
  double worst = 0.0, fold = 1e300;
  while (sim.time() < 1.0 - 1e-12) {
    const StepInfo info = sim.step(sim.adaptive_dt(1.0 - sim.time()));
    ASSERT_LE(info.solve.residual, sim.scene().solver.tolerance);
    const Obstacle<D>& cube = sim.obstacles()[1];
    worst = std::max(worst, deepest_in_groove<D>(cube));
    // The fold's line (in 2D its point) against the cube.
    Vec<D> at = Vec<D>::Zero(), n;
    at[0] = 0.3;
    at[D - 1] = 0.04;
    for (int k = 0; k <= (D == 2 ? 0 : 2000); ++k) {
      if constexpr (D == 3) at[1] = 0.05 + k * 1e-4;
      fold = std::min(fold, signed_distance(cube, at, &n));
    }
  }
  const Obstacle<D>& cube = sim.obstacles()[1];
  const double off = std::abs(cube.a[0] - 0.3) / h,
               seat = std::abs(cube.a[D - 1] - 0.04 - 0.02 * std::sqrt(2.0)) / h;
  std::cout << D << "D cube into a groove: deepest point in the block " << worst / h
            << " cells, the fold " << fold / h << " cells from the cube; at 1 s " << off
            << " cells off the fold, " << seat << " cells off its seat, speed "
            << cube.velocity.norm() << " m/s, spin " << cube.spin.norm() << " rad/s\n";
  EXPECT_LT(worst, 1e-3 * h);
  EXPECT_GT(fold, -1e-3 * h);
  EXPECT_LT(off, 1e-3);
  EXPECT_LT(seat, 1e-3);
  EXPECT_LT(cube.velocity.norm(), 1e-3);
  EXPECT_LT(cube.spin.norm(), 1e-3);
}

TEST(ConcaveFolds, CubeSettlesIntoAPolygonGroove2D) { cube_settles_into_a_groove<2>(); }
TEST(ConcaveFolds, CubeSettlesIntoAMeshGroove3D) { cube_settles_into_a_groove<3>(); }

}  // namespace
}  // namespace sablier
