// Edge-on-edge contacts in 3D (physics/edges.hpp, docs/scenes.md "Rigid
// boxes, polygons and meshes"): the segments' closest points, a mesh's
// convex edges, the crossings found between two solids, and bodies resting
// where only edges touch (no corner of either solid near the other).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>

#include "body_fixtures.hpp"
#include "core/mesh.hpp"
#include "mesh_fixtures.hpp"
#include "physics/edges.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;
using test::kPi;
using test::num;
using test::run_until;
using V3 = Vec<3>;

const auto* const kOneThread = testing::AddGlobalTestEnvironment(new test::OneThread);

// The distance from p0 + s (p1 - p0) to segment [q0, q1] is convex in s (the
// distance to a convex set along a line), so a ternary search on s finds
// the segments' distance independently of closest_points' case analysis.
double segment_distance_by_search(const V3& p0, const V3& p1, const V3& q0, const V3& q1) {
  const auto to_q = [&](double s) {
    const V3 p = p0 + s * (p1 - p0), d = q1 - q0;
    const double e = d.squaredNorm();
    const double t = e > 0.0 ? std::clamp((p - q0).dot(d) / e, 0.0, 1.0) : 0.0;
    return (p - q0 - t * d).norm();
  };
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double a = lo + (hi - lo) / 3.0, b = hi - (hi - lo) / 3.0;
    (to_q(a) < to_q(b) ? hi : lo) = to_q(a) < to_q(b) ? b : a;
  }
  return to_q(0.5 * (lo + hi));
}

// closest_points: the points lie on their segments at the parameters
// given, and their distance is the segments' distance, for random
// segments, parallel and collinear ones, ends touching insides, crossings
// beyond the ends and zero-length segments.
TEST(EdgeGeometry, ClosestPointsOfSegmentsMatchASearch) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto random = [&] { return V3(u(rng), u(rng), u(rng)); };
  std::vector<std::array<V3, 4>> cases;
  for (int i = 0; i < 2000; ++i) cases.push_back({random(), random(), random(), random()});
  const V3 x = V3::UnitX(), y = V3::UnitY(), z = V3::UnitZ();
  cases.push_back({V3::Zero(), x, y, V3(1, 1, 0)});                // parallel, side by side
  cases.push_back({V3::Zero(), x, V3(0.5, 0, 0), V3(2, 0, 0)});    // collinear, overlapping
  cases.push_back({V3::Zero(), x, V3(3, 0.1, 0), V3(2, 0.1, 0)});  // parallel, apart, reversed
  cases.push_back({V3::Zero(), x, V3(0.5, 1, 0), V3(0.5, 0, 0)});  // an end on the other's inside
  cases.push_back({V3::Zero(), x, V3(2, -1, 1), V3(2, 1, 1)});     // lines cross beyond an end
  cases.push_back({V3::Zero(), x, V3(0.3, -1, 0.2), V3(0.3, 1, 0.2)});  // crossing, 0.2 apart
  cases.push_back({V3::Zero(), V3::Zero(), y, z});                      // a point and a segment
  cases.push_back({x, x, y, y});                                        // two points
  for (const auto& [p0, p1, q0, q1] : cases) {
    const SegmentPair c = closest_points(p0, p1, q0, q1);
    ASSERT_GE(c.s, 0.0);
    ASSERT_LE(c.s, 1.0);
    ASSERT_GE(c.t, 0.0);
    ASSERT_LE(c.t, 1.0);
    EXPECT_LT((c.p - (p0 + c.s * (p1 - p0))).norm(), 1e-15);
    EXPECT_LT((c.q - (q0 + c.t * (q1 - q0))).norm(), 1e-15);
    EXPECT_NEAR((c.p - c.q).norm(), segment_distance_by_search(p0, p1, q0, q1), 1e-12);
  }
  // The crossing 0.2 apart: at the middle of the first, 0.3 along it.
  const SegmentPair c = closest_points(V3::Zero(), x, V3(0.3, -1, 0.2), V3(0.3, 1, 0.2));
  EXPECT_NEAR(c.s, 0.3, 1e-15);
  EXPECT_NEAR(c.t, 0.5, 1e-15);
  EXPECT_NEAR((c.q - c.p - 0.2 * z).norm(), 0.0, 1e-15);
}

// A box's convex edges are its 12 (its faces' diagonals are flat), each
// with a 90-degree normal cone whose axis points out of the box across the
// edge; the mesh turned inside out gives the same.
TEST(EdgeGeometry, FeatureEdgesOfABoxAndAPrism) {
  TriangleMesh box = test::box_mesh({0, 0, 0}, {1, 2, 3});
  for (int inside_out = 0; inside_out < 2; ++inside_out) {
    if (inside_out)
      for (auto& t : box.triangles) std::swap(t[1], t[2]);
    const std::vector<FeatureEdge> edges = feature_edges(box);
    ASSERT_EQ(edges.size(), 12u);
    for (const FeatureEdge& e : edges) {
      const V3 a(e.from[0], e.from[1], e.from[2]), b(e.to[0], e.to[1], e.to[2]);
      const V3 axis(e.bisector[0], e.bisector[1], e.bisector[2]);
      const V3 mid = 0.5 * (a + b), centre(0.5, 1.0, 1.5);
      EXPECT_NEAR(e.cos_half, std::sqrt(0.5), 1e-15);
      // Between its two faces' outward normals: +-1/sqrt(2) on the two axes
      // across the edge, on the sides of the box's centre the edge is on.
      for (int k = 0; k < 3; ++k) {
        const double across = a[k] == b[k] ? (mid[k] > centre[k] ? 1.0 : -1.0) : 0.0;
        EXPECT_NEAR(axis[k], across * std::sqrt(0.5), 1e-15) << k;
      }
    }
  }
  // A triangular prism (a right-angled ridge): its 9 edges, the ridge's
  // cone of half-angle 45 degrees pointing up, the base's 67.5.
  TriangleMesh prism;
  prism.vertices = {{-1, 0, 0}, {1, 0, 0}, {0, 0, 1}, {-1, 3, 0}, {1, 3, 0}, {0, 3, 1}};
  prism.triangles = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3},
                     {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  ASSERT_EQ(open_edge_count(prism), 0u);
  const std::vector<FeatureEdge> edges = feature_edges(prism);
  ASSERT_EQ(edges.size(), 9u);
  int ridges = 0;
  for (const FeatureEdge& e : edges)
    if (e.from[2] == 1.0 && e.to[2] == 1.0) {
      ++ridges;
      EXPECT_NEAR(e.cos_half, std::sqrt(0.5), 1e-15);
      EXPECT_NEAR(e.bisector[2], 1.0, 1e-15);
    }
  EXPECT_EQ(ridges, 1);
}

// A box body of half sides `half` centred at `centre`, turned by `degrees`
// about `axis`.
Obstacle<3> box_body(const V3& centre, const V3& half, double degrees, const V3& axis) {
  Obstacle<3> o;
  o.shape = ObstacleShape::Box;
  o.dynamic = true;
  o.posed = true;  // laid out as a body
  o.a = centre;
  o.b = half;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(degrees * kPi / 180.0, axis.normalized()));
  o.quaternion = {q.w(), q.x(), q.y(), q.z()};
  set_orientation(o);
  return o;
}

// Two square beams (6 cm), each turned 45 degrees about its own long axis,
// crossed at right angles: the upper one's lowest edge (along x) crosses
// the lower one's top edge (along y) under their centres, and nothing else
// comes near. One contact there, normal straight down from the upper body,
// separation the gap between the edges; none once the gap is over a cell.
TEST(EdgeContacts, CrossedTurnedBeamsMeetAtOnePoint) {
  const double h = 0.02, r = 0.03 * std::sqrt(2.0), gap = 0.004;
  const Obstacle<3> lower = box_body(V3(0.3, 0.15, 0.1), V3(0.03, 0.15, 0.03), 45, V3::UnitY());
  const Obstacle<3> upper =
      box_body(V3(0.3, 0.15, 0.1 + 2 * r + gap), V3(0.15, 0.03, 0.03), 45, V3::UnitX());
  EdgeScratch w;
  std::vector<EdgeContact> out;
  edge_contacts(upper, lower, h, w, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR((out[0].normal - V3(0, 0, -1)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(out[0].separation, gap, 1e-15);
  EXPECT_NEAR((out[0].on_body - V3(0.3, 0.15, 0.1 + r + gap)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((out[0].on_solid - V3(0.3, 0.15, 0.1 + r)).norm(), 0.0, 1e-15);
  // Seen from the lower body, the normal points up.
  edge_contacts(lower, upper, h, w, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR((out[0].normal - V3(0, 0, 1)).norm(), 0.0, 1e-15);
  Obstacle<3> far = upper;
  far.a[2] += h;
  edge_contacts(far, lower, h, w, out);
  EXPECT_TRUE(out.empty());
}

// A plank lying flat across a fixed beam narrower than it, or on a wide
// table: across the beam its two lower long edges cross the beam's two top
// edges, four contacts with the plank's face normal (down) on the rims of
// both cones; on the table (the plank's bottom within the table's top
// face) the lines cross beyond the segments' ends, and its corners are
// what the existing rows see. A plank turned edge-on over a face meets it
// edge to face: no edge crossing either.
TEST(EdgeContacts, PlankAcrossABeamCrossesItsTwoEdges) {
  const double h = 0.02, gap = 0.001;
  Obstacle<3> beam;
  beam.shape = ObstacleShape::Box;
  beam.a = V3(0.28, 0.05, 0.0);
  beam.b = V3(0.32, 0.25, 0.1);
  const Obstacle<3> plank =
      box_body(V3(0.3, 0.15, 0.13 + gap), V3(0.15, 0.03, 0.03), 0.0, V3::UnitX());
  EdgeScratch w;
  std::vector<EdgeContact> out;
  edge_contacts(plank, beam, h, w, out);
  ASSERT_EQ(out.size(), 4u);
  for (const EdgeContact& c : out) {
    EXPECT_NEAR((c.normal - V3(0, 0, -1)).norm(), 0.0, 1e-15);
    EXPECT_NEAR(c.separation, gap, 1e-15);
    EXPECT_NEAR(std::abs(c.on_body[0] - 0.3), 0.02, 1e-15);
    EXPECT_NEAR(std::abs(c.on_body[1] - 0.15), 0.03, 1e-15);
  }
  Obstacle<3> table = beam;
  table.a = V3(0.1, 0.05, 0.0);
  table.b = V3(0.5, 0.25, 0.1);
  edge_contacts(plank, table, h, w, out);
  EXPECT_TRUE(out.empty());
  const Obstacle<3> edge_on = box_body(V3(0.3, 0.15, 0.1 + 0.03 * std::sqrt(2.0) + gap),
                                       V3(0.15, 0.03, 0.03), 45, V3::UnitX());
  edge_contacts(edge_on, table, h, w, out);
  EXPECT_TRUE(out.empty());
}

// The force the last step's contact rows put on body k (the [[obstacle]]
// of that index), and how many rows carry one: a row pushes its body with
// -Lambda_j g_j and its second body, if any, with +Lambda_j g_j
// (cone_problem.hpp).
V3 contact_force(const Simulation<3>& sim, std::size_t k, int* rows) {
  const ConeProblem<3>& P = sim.problem();
  std::int64_t entry = P.first_body_entry;
  for (std::size_t m = 0; m < k; ++m) entry += sim.obstacles()[m].dynamic ? 2 : 0;
  constexpr int centre = ConeProblem<3>::NS / 2;
  V3 total = V3::Zero();
  *rows = 0;
  for (int j = P.first_body_row; j < P.rows(); ++j) {
    const int c = j - P.first_contact;
    const V3 f = from_sym<3>(P.lambda[j]) * P.coupling[j].col(centre);
    if (f.norm() == 0.0) continue;
    if (P.contact_body[c] == entry) total -= f, ++*rows;
    if (P.other_body(c) == entry) total += f, ++*rows;
  }
  return total;
}

// A room with stick walls, and a speck of sand resting in its far corner
// (a scene needs one; falling from above, its splash pushed a body on the
// floor).
const std::string kRoom =
    "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.8, 0.3, 0.3]\n"
    "resolution = [40, 15, 15]\n[boundary]\ndefault = \"stick\"\n[[sand]]\nshape = \"box\"\n"
    "min = [0.75, 0.0, 0.0]\nmax = [0.8, 0.05, 0.05]\n";

// The same plank rolled 0.2 rad about its long axis, its lower long edge
// touching the beam's two top edges: those crossings are edge contacts
// (n down, on the cones), and the far lower edge, 6 sin(0.2) cm up, crosses
// them where the plank's face passes the beam's edges (n outside its
// cone): its rows keep it above them, so that the plank rolling back flat
// lands on them instead of passing through.
TEST(EdgeContacts, RollingPlankSeesItsFarEdgeComing) {
  const double h = 0.02, r = 0.2, w = 0.06;
  Obstacle<3> beam;
  beam.shape = ObstacleShape::Box;
  beam.a = V3(0.28, 0.05, 0.0);
  beam.b = V3(0.32, 0.25, 0.1);
  // The lower edge (local y = -3 cm, z = -3 cm) at height 0.1.
  const V3 down = Eigen::AngleAxisd(r, V3::UnitX()) * V3(0.0, -0.03, -0.03);
  const Obstacle<3> plank =
      box_body(V3(0.3, 0.15, 0.1) - down, V3(0.15, 0.03, 0.03), r * 180.0 / kPi, V3::UnitX());
  EdgeScratch ws;
  std::vector<EdgeContact> out;
  edge_contacts(plank, beam, h, ws, out);
  ASSERT_EQ(out.size(), 4u);
  int near = 0, far = 0;
  for (const EdgeContact& c : out) {
    EXPECT_NEAR((c.normal - V3(0, 0, -1)).norm(), 0.0, 1e-15);
    if (std::abs(c.separation) < 1e-15) ++near;
    if (std::abs(c.separation - w * std::sin(r)) < 1e-15) ++far;
  }
  EXPECT_EQ(near, 2);
  EXPECT_EQ(far, 2);
}

// A body (obstacle `k`) released a tenth of a cell above a support that
// only its edges can meet, run for 0.5 s. Static equilibrium (Newton's
// first law): at rest, the contact rows carry its weight, F = m g, to the
// solver's tolerance (1e-5 m/s on velocities: 1e-4 of g dt at these
// steps), and it rests on the support, its lowest point at the support's
// top (`top`, or that of box body `support`) to 1e-3 of a cell (as the
// stacked boxes do, test_box_bodies.cpp).
struct Rest {
  double depth;  // the support's top less the body's lowest point, in cells
  double speed, spin, force_error;
  int rows;
};

Rest rest_on_edges(Simulation<3>& sim, std::size_t k, double top, int support,
                   const std::string& what) {
  run_until(sim, 0.5);
  const Obstacle<3>& b = sim.obstacles()[k];
  if (support >= 0) top = sim.obstacles()[support].a[2] + sim.obstacles()[support].b[2];
  double lowest = 1e300;
  for (const V3& c : body_points(b)) lowest = std::min(lowest, c[2]);
  Rest r{(top - lowest) / sim.grid().h(), b.velocity.norm(), b.spin.norm(), 0.0, 0};
  const V3 weight = b.mass * V3(0.0, 0.0, 9.81);
  const V3 f = contact_force(sim, k, &r.rows);
  r.force_error = (f - weight).norm() / weight.norm();
  std::cout << what << " after 0.5 s: lowest point " << r.depth << " cells under the top, speed "
            << r.speed << " m/s, spin " << r.spin << " rad/s, " << r.rows << " rows, contact force "
            << f.transpose() << " N against weight " << weight[2] << " N (" << r.force_error
            << " off)\n";
  return r;
}

// At rest on its edge rows: `rows` of them, its lowest point at the
// support's top and its speed, spin and force balance within 1e-3 (of a
// cell, m/s, rad/s, its weight).
void expect_rests(const Rest& r, int rows) {
  EXPECT_EQ(r.rows, rows);
  EXPECT_LT(std::abs(r.depth), 1e-3);
  EXPECT_LT(r.speed, 1e-3);
  EXPECT_LT(r.spin, 1e-3);
  EXPECT_LT(r.force_error, 1e-3);
}

// A plank (30 x 6 x 6 cm, 500 kg/m^3) dropped flat across a fixed beam 4 cm
// wide: its corners are 13 cm off the beam and the beam's top corners 7 cm
// off the plank, so four edge crossings hold it (before them, nothing did:
// it fell through the beam onto the floor, as did the box of the ridge
// test below). Same bits on 1 and 2 threads.
TEST(EdgeContacts, PlankRestsAcrossAFixedBeam) {
  const double top = 0.1;
  const std::string text =
      kRoom +
      "[[obstacle]]\nshape = \"box\"\nmin = [0.28, 0.05, 0.0]\nmax = [0.32, 0.25, 0.1]\n"
      "[[obstacle]]\nshape = \"box\"\nmin = [0.15, 0.12, 0.102]\nmax = [0.45, 0.18, 0.162]\n"
      "density = 500\n";
  const SceneConfig scene = parse_scene(text, "plank.toml");
  Simulation<3> sim(scene);
  const Rest r = rest_on_edges(sim, 1, top, -1, "plank across a fixed beam");
  expect_rests(r, 4);
  test::expect_same_bits_on_1_and_2_threads<3>(scene, 12, 1);
}

// The same plank read from a mesh file: its 12 convex edges (the faces'
// diagonals left out) cross the beam's as the box's do.
TEST(EdgeContacts, MeshPlankRestsAcrossAFixedBeam) {
  const fs::path dir = test::temp_dir("mesh_plank"), obj = dir / "plank.obj";
  test::write_exact_obj(obj, test::box_mesh({0.15, 0.12, 0.102}, {0.45, 0.18, 0.162}));
  const std::string text =
      kRoom +
      "[[obstacle]]\nshape = \"box\"\nmin = [0.28, 0.05, 0.0]\nmax = [0.32, 0.25, 0.1]\n"
      "[[obstacle]]\nshape = \"mesh\"\nfile = \"" +
      obj.string() + "\"\ndensity = 500\n";
  Simulation<3> sim(parse_scene(text, "mesh_plank.toml"));
  fs::remove_all(dir);
  const Rest r = rest_on_edges(sim, 1, 0.1, -1, "mesh plank across a fixed beam");
  expect_rests(r, 4);
}

// Edge on edge alone: a square beam (6 cm) turned 45 degrees about its long
// axis x, released over the ridge of a fixed mesh (a square beam along y
// turned 45 degrees about y): their edges cross at one point under its
// centre of mass, where it balances (an unstable balance, but a symmetric
// one: the row's force passes through the centre).
TEST(EdgeContacts, TurnedBoxRestsOnAMeshRidgeEdgeToEdge) {
  const fs::path dir = test::temp_dir("ridge"), obj = dir / "ridge.obj";
  TriangleMesh ridge = test::box_mesh({-0.03, -0.1, -0.03}, {0.03, 0.1, 0.03});
  const double c = std::sqrt(0.5);
  double top = -1e300;
  for (Point3& p : ridge.vertices) {
    p = {0.3 + c * (p[0] + p[2]), 0.15 + p[1], 0.05 + c * (p[2] - p[0])};
    top = std::max(top, p[2]);
  }
  test::write_exact_obj(obj, ridge);
  const double half_diagonal = 0.03 * std::sqrt(2.0), z = top + half_diagonal + 0.002;
  const std::string text = kRoom + "[[obstacle]]\nshape = \"mesh\"\nfile = \"" + obj.string() +
                           "\"\n[[obstacle]]\nshape = \"box\"\nmin = [0.15, 0.12, " +
                           num(z - 0.03) + "]\nmax = [0.45, 0.18, " + num(z + 0.03) +
                           "]\ndensity = 500\nangle = 45\naxis = [1, 0, 0]\n";
  Simulation<3> sim(parse_scene(text, "ridge.toml"));
  fs::remove_all(dir);
  const Rest r = rest_on_edges(sim, 1, top, -1, "turned box on a mesh ridge");
  expect_rests(r, 1);
}

// Edge along edge: the same square beam turned 45 degrees about its own
// long axis, laid lengthwise along the ridge of a fixed mesh (the ridge
// turned `yaw` about z: parallel, and within the milliradian below which
// the edge rows take two edges as parallel and leave them to their ends),
// 16 cm long (its ends on the ridge) or 26 cm (beyond the ridge's 20 cm).
// Statics: it rests balanced on the ridge, its lowest point at the ridge's
// top. Before the corners chose the normal of the ridge's cone that faces
// them (physics/corners.hpp, corner_distance: here the ridge edge's bisector, up)
// their rows took one slope's normal or the sampled distance's rounded
// one: the beams sank 0.13-0.17 of a cell or rolled off the ridge.
void rests_along_a_ridge(double yaw, double length) {
  const fs::path dir = test::temp_dir("ridge_along"), obj = dir / "ridge.obj";
  TriangleMesh ridge = test::box_mesh({-0.03, -0.1, -0.03}, {0.03, 0.1, 0.03});
  const double c = std::sqrt(0.5), cy = std::cos(yaw), sy = std::sin(yaw);
  double top = -1e300;
  for (Point3& p : ridge.vertices) {
    const double x = c * (p[0] + p[2]), y = p[1], z = c * (p[2] - p[0]);
    p = {0.3 + cy * x - sy * y, 0.15 + sy * x + cy * y, 0.05 + z};
    top = std::max(top, p[2]);
  }
  test::write_exact_obj(obj, ridge);
  const double z = top + 0.03 * std::sqrt(2.0) + 0.002;
  const std::string text = kRoom + "[[obstacle]]\nshape = \"mesh\"\nfile = \"" + obj.string() +
                           "\"\n[[obstacle]]\nshape = \"box\"\nmin = [0.27, " +
                           num(0.15 - length / 2) + ", " + num(z - 0.03) + "]\nmax = [0.33, " +
                           num(0.15 + length / 2) + ", " + num(z + 0.03) +
                           "]\ndensity = 500\nangle = 45\naxis = [0, 1, 0]\n";
  Simulation<3> sim(parse_scene(text, "ridge_along.toml"));
  fs::remove_all(dir);
  const Rest r =
      rest_on_edges(sim, 1, top, -1, "beam " + num(length) + " m along a ridge turned " + num(yaw));
  EXPECT_LT(std::abs(r.depth), 1e-3);
  EXPECT_LT(r.speed, 1e-3);
  EXPECT_LT(r.spin, 1e-3);
  EXPECT_LT(r.force_error, 1e-3);
}

TEST(EdgeContacts, BeamRestsLengthwiseAlongAMeshRidge) {
  for (const double yaw : {0.0, 5e-4, 2e-3})
    for (const double length : {0.16, 0.26}) rests_along_a_ridge(yaw, length);
}

// Body on body: the plank across a beam that is itself a body (2000 kg/m^3)
// resting on the floor. The plank's four edge rows hold it against the
// beam; the beam at rest too, the net force of its rows (the floor's up,
// the plank's down) is its own weight.
TEST(EdgeContacts, PlankRestsAcrossABeamBody) {
  const std::string text =
      kRoom +
      "[[obstacle]]\nshape = \"box\"\nmin = [0.28, 0.05, 0.0]\nmax = [0.32, 0.25, 0.1]\n"
      "density = 2000\n"
      "[[obstacle]]\nshape = \"box\"\nmin = [0.15, 0.12, 0.102]\nmax = [0.45, 0.18, 0.162]\n"
      "density = 500\n";
  Simulation<3> sim(parse_scene(text, "plank_on_body.toml"));
  const Rest r = rest_on_edges(sim, 1, 0.0, 0, "plank across a beam body");
  const Obstacle<3>& beam = sim.obstacles()[0];
  int rows = 0;
  const V3 on_beam = contact_force(sim, 0, &rows);
  const double weight = beam.mass * 9.81;
  std::cout << "the beam body: speed " << beam.velocity.norm() << " m/s, net force of its " << rows
            << " rows " << on_beam.transpose() << " N against its weight " << weight << " N ("
            << (on_beam - V3(0, 0, weight)).norm() / weight << " off)\n";
  expect_rests(r, 4);
  EXPECT_LT(beam.velocity.norm(), 1e-3);
  EXPECT_LT((on_beam - V3(0, 0, weight)).norm(), 1e-3 * weight);
}

// The plank dropped from 6 cm above the beam turned 20 degrees about (0.3,
// 1, 0.2): it lands on a corner and an edge, rolls and rocks across the
// beam. The contact rows are Signorini conditions (no overlap): at every
// step no point of the beam's edges is inside the plank and no point of
// the plank's edges inside the beam by more than 1e-3 of a cell (sampled
// every 1/200 of each edge). Before the far edge's rows the plank rolling
// flat passed through the beam's edge, which ended 1.5 cm (0.75 cells)
// inside it. It comes to rest (across the beam) within the second.
TEST(EdgeContacts, PlankTumblingOntoABeamNeverEntersIt) {
  const std::string text =
      kRoom +
      "[[obstacle]]\nshape = \"box\"\nmin = [0.28, 0.05, 0.0]\nmax = [0.32, 0.25, 0.1]\n"
      "[[obstacle]]\nshape = \"box\"\nmin = [0.17, 0.12, 0.16]\nmax = [0.47, 0.18, 0.22]\n"
      "density = 500\nangle = 20\naxis = [0.3, 1.0, 0.2]\n";
  Simulation<3> sim(parse_scene(text, "tumble.toml"));
  std::vector<SolidEdge> edges;
  // The deepest sampled point of one solid's edges inside the other.
  const auto deepest = [&](const Obstacle<3>& of, const Obstacle<3>& in) {
    solid_edges(of, of.a, 1e300, edges);
    double depth = 1e300;
    V3 n;
    for (const SolidEdge& e : edges)
      for (int k = 0; k <= 200; ++k)
        depth =
            std::min(depth, signed_distance(in, V3(e.from + (k / 200.0) * (e.to - e.from)), &n));
    return depth;
  };
  double worst = 1e300;
  while (sim.time() < 1.0 - 1e-12) {
    const StepInfo info = sim.step(sim.adaptive_dt(1.0 - sim.time()));
    ASSERT_LE(info.solve.residual, sim.scene().solver.tolerance);
    const auto now = sim.obstacles_at(sim.time());
    worst = std::min({worst, deepest(now[0], now[1]), deepest(now[1], now[0])});
  }
  const Obstacle<3>& plank = sim.obstacles()[1];
  std::cout << "plank tumbling onto a beam: deepest edge point inside the other solid "
            << -worst / sim.grid().h() << " cells; after 1 s centre at " << plank.a.transpose()
            << ", speed " << plank.velocity.norm() << " m/s\n";
  EXPECT_GT(worst, -1e-3 * sim.grid().h());
  EXPECT_LT(plank.velocity.norm(), 1e-3);
}

}  // namespace
}  // namespace sablier
