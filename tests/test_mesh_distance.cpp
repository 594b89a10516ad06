// The distance from a point to a triangle mesh (SolidMesh::distance, the
// branch and bound over the winding-number tree): against the analytic
// distance to a cube's faces, edges and corners, against a brute-force
// minimum over every triangle of a subdivided icosahedron (written here
// independently: projection onto the plane, else the nearest edge), within
// the chord error of the sphere it approximates, and its nearest point on
// the surface. The time per query is printed, not checked. And the sampled
// distance of mesh obstacles (DistanceGrid): a plate thinner than its
// samples keeps its inside, flat faces stay interpolated.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <memory>
#include <random>
#include <vector>

#include "core/distance_grid.hpp"
#include "core/mesh.hpp"
#include "mesh_fixtures.hpp"

namespace sablier {
namespace {

using test::icosphere;
using test::soup;
using test::Tri;

TriangleMesh unit_cube() { return test::box_mesh({0, 0, 0}, {1, 1, 1}); }

Point3 minus(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot3(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 cross3(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double length(const Point3& a) { return std::sqrt(dot3(a, a)); }

// Brute force, by another route than the library's Voronoi regions: the
// foot of the perpendicular onto the triangle's plane when it falls inside
// (on the inner side of all three edges), else the nearest of the edges.
double segment_distance(const Point3& p, const Point3& a, const Point3& b) {
  const Point3 ab = minus(b, a), ap = minus(p, a);
  const double len2 = dot3(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(dot3(ap, ab) / len2, 0.0, 1.0) : 0.0;
  return length({ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]});
}

double triangle_distance(const Point3& p, const Tri& t) {
  const Point3 n = cross3(minus(t[1], t[0]), minus(t[2], t[0]));
  const double n2 = dot3(n, n);
  if (n2 > 0.0) {
    const double h = dot3(n, minus(p, t[0])) / n2;
    const Point3 q{p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]};
    bool inside = true;
    for (int k = 0; k < 3; ++k)
      inside = inside && dot3(cross3(minus(t[(k + 1) % 3], t[k]), minus(q, t[k])), n) >= 0.0;
    if (inside) return std::abs(h) * std::sqrt(n2);
  }
  return std::min({segment_distance(p, t[0], t[1]), segment_distance(p, t[1], t[2]),
                   segment_distance(p, t[2], t[0])});
}

double brute_distance(const std::vector<Tri>& tris, const Point3& p) {
  double d = HUGE_VAL;
  for (const Tri& t : tris) d = std::min(d, triangle_distance(p, t));
  return d;
}

void expect_point_near(const Point3& a, const Point3& b, double tol) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tol) << "component " << i;
}

// Outside near a face, an edge and a corner; inside, nearest one face; on a
// face: the distance and nearest point of the box, exact to round-off.
TEST(MeshDistance, CubeMatchesTheAnalyticDistance) {
  const SolidMesh cube(unit_cube());
  struct Case {
    const char* where;
    Point3 p, nearest;
    double distance;
  };
  const Case cases[] = {
      {"outside a face", {0.5, 0.4, 1.3}, {0.5, 0.4, 1.0}, 0.3},
      {"outside an edge", {1.2, 0.5, -0.4}, {1.0, 0.5, 0.0}, std::hypot(0.2, 0.4)},
      {"outside a corner", {-0.3, 1.4, 1.2}, {0.0, 1.0, 1.0}, std::sqrt(0.09 + 0.16 + 0.04)},
      {"far outside a corner", {7.0, 8.0, -9.0}, {1.0, 1.0, 0.0}, std::sqrt(36.0 + 49.0 + 81.0)},
      {"inside, nearest z = 1", {0.3, 0.6, 0.85}, {0.3, 0.6, 1.0}, 0.15},
      {"inside, nearest x = 0", {0.1, 0.45, 0.55}, {0.0, 0.45, 0.55}, 0.1},
      {"on the face y = 0", {0.25, 0.0, 0.7}, {0.25, 0.0, 0.7}, 0.0},
      {"on the edge x = y = 1", {1.0, 1.0, 0.3}, {1.0, 1.0, 0.3}, 0.0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.where);
    Point3 q{};
    EXPECT_NEAR(cube.distance(c.p, &q), c.distance, 1e-12);
    expect_point_near(q, c.nearest, 1e-12);
    EXPECT_NEAR(cube.distance(c.p), c.distance, 1e-12);  // without the nearest point
  }
  // The centre is 1/2 from all six faces: the distance is unique, the
  // nearest point one of six.
  Point3 q{};
  EXPECT_NEAR(cube.distance({0.5, 0.5, 0.5}, &q), 0.5, 1e-12);
  EXPECT_NEAR(length(minus(q, {0.5, 0.5, 0.5})), 0.5, 1e-12);
}

// 1000 points in [-2, 2]^3 around a 5120-triangle icosphere: the tree's
// distance is the minimum over every triangle, and within the chord error
// h (the deepest the flat faces sink below the unit sphere) of ||p| - 1|.
// The polyhedron lies between radii 1 - h and 1 and is star-shaped about
// the origin, so ||p| - 1| - h <= distance <= ||p| - 1| + h.
TEST(MeshDistance, SphereMatchesBruteForce) {
  const std::vector<Tri> tris = icosphere(4);
  const SolidMesh sphere(soup(tris));
  ASSERT_EQ(sphere.triangle_count(), 5120u);
  const double chord = 1.0 - brute_distance(tris, {0, 0, 0});
  EXPECT_GT(chord, 0.0);
  EXPECT_LT(chord, 2e-3);
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  std::vector<Point3> points(1000);
  for (Point3& p : points) p = {coord(rng), coord(rng), coord(rng)};
  double worst = 0.0;
  for (const Point3& p : points) {
    const double d = sphere.distance(p), exact = brute_distance(tris, p);
    // Relative, but absolute below 1 m: the two routes round differently,
    // by ~1e-16 of the coordinates, however near the surface p is.
    ASSERT_NEAR(d, exact, 1e-12 * std::max(1.0, exact)) << p[0] << " " << p[1] << " " << p[2];
    worst = std::max(worst, std::abs(d - exact));
    ASSERT_LE(std::abs(d - std::abs(length(p) - 1.0)), chord + 1e-12);
    // With a limit: the same below it, the limit itself beyond.
    const double limit = 0.3;
    ASSERT_EQ(sphere.distance(p, nullptr, limit), d < limit ? d : limit);
  }
  std::cout << "largest |tree - brute force| distance: " << worst << ", chord error " << chord
            << "\n";

  // Timing, reported only: 100,000 queries at 1000 points around it.
  const int queries = 100000;
  double sum = 0.0;  // used, so that the loop is not optimised away
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < queries; ++k) sum += sphere.distance(points[k % points.size()]);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "distance: " << 1e6 * seconds / queries << " us per query (" << queries
            << " queries, 5120 triangles, checksum " << sum << ")\n";
}

// The nearest point given back is on the surface (its own distance is 0 to
// round-off) and at the distance given back from p.
TEST(MeshDistance, NearestPointLiesOnTheSurface) {
  const std::vector<Tri> tris = icosphere(3);
  const SolidMesh sphere(soup(tris));
  const SolidMesh cube(unit_cube());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  for (int k = 0; k < 1000; ++k) {
    const Point3 p{coord(rng), coord(rng), coord(rng)};
    for (const SolidMesh* mesh : {&sphere, &cube}) {
      Point3 q{};
      const double d = mesh->distance(p, &q);
      ASSERT_LT(mesh->distance(q), 1e-12);
      ASSERT_NEAR(length(minus(p, q)), d, 1e-12 * std::max(1.0, d));
    }
  }
}

// Zero-area triangles (a sliver with collinear corners, a point) are at the
// distance of their segment or point, never NaN; an empty mesh is
// infinitely far.
TEST(MeshDistance, DegenerateTrianglesAndEmptyMesh) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {5, 5, 5}};
  m.triangles = {{0, 2, 1}, {3, 3, 3}};
  const SolidMesh degenerate(m);
  Point3 q{};
  EXPECT_NEAR(degenerate.distance({1.5, 0.3, -0.4}, &q), 0.5, 1e-12);
  expect_point_near(q, {1.5, 0, 0}, 1e-12);
  EXPECT_NEAR(degenerate.distance({-3, 4, 0}, &q), 5.0, 1e-12);
  expect_point_near(q, {0, 0, 0}, 1e-12);
  EXPECT_NEAR(degenerate.distance({5, 5, 6}, &q), 1.0, 1e-12);
  expect_point_near(q, {5, 5, 5}, 1e-12);

  const SolidMesh empty(TriangleMesh{});
  q = {1, 2, 3};
  EXPECT_EQ(empty.distance({0, 0, 0}, &q), HUGE_VAL);
  expect_point_near(q, {1, 2, 3}, 0.0);
}

// `m` turned by `degrees` about the x axis through `pivot`.
TriangleMesh turned(TriangleMesh m, double degrees, const Point3& pivot) {
  const double a = degrees * 3.14159265358979323846 / 180.0, c = std::cos(a), s = std::sin(a);
  for (Point3& v : m.vertices) {
    const double y = v[1] - pivot[1], z = v[2] - pivot[2];
    v[1] = pivot[1] + c * y - s * z;
    v[2] = pivot[2] + s * y + c * z;
  }
  return m;
}

// `m` with every triangle's orientation reversed (normals inward).
TriangleMesh reversed(TriangleMesh m) {
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

// A prism along x over [x0, x1] whose section is an isosceles triangle with
// its tip at (y, z1), its base at z0 and the angle `degrees` at the tip.
TriangleMesh wedge(double x0, double x1, double y, double z0, double z1, double degrees) {
  const double w = (z1 - z0) * std::tan(0.5 * degrees * 3.14159265358979323846 / 180.0);
  TriangleMesh m;
  for (const double x : {x0, x1})
    for (const Point3& v : {Point3{x, y - w, z0}, Point3{x, y + w, z0}, Point3{x, y, z1}})
      m.vertices.push_back(v);
  // A0 B0 C0 = 0 1 2, A1 B1 C1 = 3 4 5, each edge once each way.
  m.triangles = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3},
                 {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  return m;
}

// Samples every 5 mm (half of a 1 cm cell, as the simulation samples) the
// distance of `mesh` and checks it at `points` random points of [lo, hi]
// that `where` accepts: its sign against the winding number, its normal's
// length, and inside no deeper than `deepest`; in the cells of exact
// distances, its size against the mesh's own (the tree's branch and
// bound), which the cell's list, read nearest first and cut short, must
// reproduce. Returns how many points were inside.
template <class Where>
int check_sampled_sign(const TriangleMesh& mesh, const Point3& lo, const Point3& hi, double deepest,
                       int points, const Where& where) {
  auto solid = std::make_shared<const SolidMesh>(mesh);
  const DistanceGrid grid(solid, {lo[0] - 0.03, lo[1] - 0.03, lo[2] - 0.03},
                          {hi[0] + 0.03, hi[1] + 0.03, hi[2] + 0.03}, 0.005, 0.04);
  EXPECT_GT(grid.exact_cells(), 0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int inside = 0, exact = 0;
  for (int k = 0; k < points; ++k) {
    Point3 p{};
    for (int a = 0; a < 3; ++a) p[a] = lo[a] + (hi[a] - lo[a]) * u(rng);
    if (!where(p)) continue;
    Point3 n{};
    const double d = grid.signed_distance(p, &n);
    const bool in = solid->contains(p);
    inside += in;
    EXPECT_EQ(d < 0.0, in) << "at " << p[0] << " " << p[1] << " " << p[2] << ": " << d;
    if (grid.exact_at(p)) {
      ++exact;
      EXPECT_NEAR(std::abs(d), solid->distance(p), 1e-12);
    }
    if (in) {
      EXPECT_GE(d, -deepest - 1e-12);
    }
    EXPECT_NEAR(length(n), 1.0, 1e-9);
  }
  std::cout << inside << " of " << points << " points inside, " << exact << " in "
            << grid.exact_cells() << " exact cells\n";
  EXPECT_GT(exact, points / 20);
  return inside;
}

// A plate 3 mm thick, turned 10 degrees, sampled every 5 mm: every sample
// lies outside it, so interpolation alone read a positive distance across
// the whole plate (measured before the exact cells: a sand box let 3,122
// of 27,216 grains through such a plate in 0.5 s). The cells near both its
// faces take the exact distance: at 20,000 random points around it the
// sign agrees with the winding number, and inside the plate the distance is
// at least minus half its thickness (the distance to its nearest face).
// The mesh's orientation does not matter.
TEST(MeshDistance, SampledDistanceSeesAPlateThinnerThanItsSamples) {
  const double t = 0.003;
  const TriangleMesh plate =
      turned(test::box_mesh({-0.02, -0.02, 0.1 - t / 2}, {0.12, 0.12, 0.1 + t / 2}), 10.0,
             {0.05, 0.05, 0.1});
  for (const TriangleMesh& m : {plate, reversed(plate)}) {
    // The slab z in [0.08, 0.12] holds the plate: 3 mm of its 4 cm, about
    // 1,500 of the points.
    std::cout << "thin plate: ";
    EXPECT_GT(check_sampled_sign(m, {0.0, 0.0, 0.08}, {0.1, 0.1, 0.12}, t / 2, 20000,
                                 [](const Point3&) { return true; }),
              1000);
  }
}

// A prism whose section's tip is 20 degrees sharp, turned 10 degrees: the
// 15 mm below its tip are thinner than a sample (5.3 mm). Points all around
// that part, beyond its ends included (nearest points on edges and
// vertices, where the side comes from the pseudo-normal). Its other folds
// are blunt (80 and 90 degrees between the sides, the base and the ends),
// interpolated and so rounded: points within about a millimetre inside
// them read outside, and are left out with the rest of the prism.
TEST(MeshDistance, SampledDistanceSeesASharpWedge) {
  const Point3 pivot{0.05, 0.05, 0.08};
  const TriangleMesh m = turned(wedge(0.02, 0.08, 0.05, 0.06, 0.1, 20.0), 10.0, pivot);
  const double c = std::cos(10.0 * 3.14159265358979323846 / 180.0),
               s = std::sin(10.0 * 3.14159265358979323846 / 180.0);
  const auto upper = [&](const Point3& p) {  // z in the wedge's own frame above 0.085
    return pivot[2] - s * (p[1] - pivot[1]) + c * (p[2] - pivot[2]) > 0.085;
  };
  std::cout << "sharp wedge: ";
  EXPECT_GT(check_sampled_sign(m, {0.01, 0.03, 0.05}, {0.09, 0.07, 0.11}, 0.01, 40000, upper), 300);
}

// The unit cube sampled every 1/16: its folds are right angles, blunter
// than DistanceGrid::kFoldAngle asks, so no cell takes the exact distance,
// and on its flat faces the interpolated distance is exact (a plane's
// distance is linear).
TEST(MeshDistance, SampledDistanceInterpolatesFlatFaces) {
  auto solid = std::make_shared<const SolidMesh>(unit_cube());
  const double h = 1.0 / 16;
  const DistanceGrid grid(solid, {-0.25, -0.25, -0.25}, {1.25, 1.25, 1.25}, h, 0.5);
  EXPECT_EQ(grid.exact_cells(), 0);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.2, 0.8), off(-0.15, 0.15);
  for (int k = 0; k < 2000; ++k) {
    // Near the face x = 1, away from its edges.
    const Point3 p{1.0 + off(rng), u(rng), u(rng)};
    Point3 n{};
    EXPECT_NEAR(grid.signed_distance(p, &n), p[0] - 1.0, 1e-12);
    EXPECT_NEAR(n[0], 1.0, 1e-9);
  }
}

}  // namespace
}  // namespace sablier
