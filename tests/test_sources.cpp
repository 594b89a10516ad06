// Sand sources (docs/scenes.md, [[sand]] shapes and [[spout]]): each shape
// seeds its volume's worth of particles (source: the exact area or volume of
// the shape times particles per unit volume, within lattice error) and only
// inside it; mesh files of every format fill the same; bad sources get
// one-line errors; a spout pours rho phi_max |v| A (source: mass
// conservation, nothing leaving the box); emission is the same whatever the
// thread count and across an interrupted and resumed run.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "core/mesh.hpp"
#include "io/writers.hpp"
#include "mesh_fixtures.hpp"
#include "physics/emission.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;
using test::icosphere;
using test::Tri;

using test::kPi;

// A folder of this process (ctest runs the tests side by side).
fs::path temp_dir(const std::string& name) { return test::temp_dir("sources_" + name); }

std::string message_of(const std::string& text) {
  try {
    parse_scene(text, "bad.toml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// ------------------------------------------------------------------ meshes

// The unit cube, faces as quads (OBJ fan-triangulates them), outward.
const std::vector<Point3> kCubeV{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const std::vector<std::vector<int>> kCubeF{{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5},
                                           {4, 8, 7, 3}, {1, 5, 8, 4}, {2, 3, 7, 6}};
// The unit corner tetrahedron (volume 1/6).
const std::vector<Point3> kTetV{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::vector<std::vector<int>> kTetF{{1, 3, 2}, {1, 2, 4}, {2, 3, 4}, {1, 4, 3}};

std::vector<Tri> triangles(const std::vector<Point3>& v, const std::vector<std::vector<int>>& f) {
  std::vector<Tri> t;
  for (const auto& face : f)
    for (std::size_t k = 1; k + 1 < face.size(); ++k)
      t.push_back({v[face[0] - 1], v[face[k] - 1], v[face[k + 1] - 1]});
  return t;
}

void write_obj(const fs::path& p, const std::vector<Point3>& v,
               const std::vector<std::vector<int>>& f) {
  std::ofstream out(p);
  out << "# test mesh\no thing\n";
  for (const Point3& x : v) out << "v " << x[0] << " " << x[1] << " " << x[2] << "\n";
  out << "vn 0 0 1\n";
  for (const auto& face : f) {
    out << "f";
    for (int i : face) out << " " << i << "//1";  // with a normal index, as exporters write
    out << "\n";
  }
}

void write_ascii_stl(const fs::path& p, const std::vector<Tri>& tris) {
  std::ofstream out(p);
  out << "solid test\n";
  for (const Tri& t : tris) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (const Point3& x : t) out << "      vertex " << x[0] << " " << x[1] << " " << x[2] << "\n";
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid test\n";
}

void write_binary_stl(const fs::path& p, const std::vector<Tri>& tris) {
  std::string bytes(80, 'x');  // a header (even one starting "solid" must work)
  bytes.replace(0, 5, "solid");
  const auto put32 = [&](std::uint32_t u) {
    for (int k = 0; k < 4; ++k) bytes += static_cast<char>(u >> (8 * k) & 0xff);
  };
  const auto put_float = [&](double x) {
    const float f = static_cast<float>(x);
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    put32(u);
  };
  put32(static_cast<std::uint32_t>(tris.size()));
  for (const Tri& t : tris) {
    for (int k = 0; k < 3; ++k) put_float(0.0);
    for (const Point3& x : t)
      for (double c : x) put_float(c);
    bytes += std::string(2, '\0');
  }
  std::ofstream(p, std::ios::binary) << bytes;
}

const std::string kBox3D = R"(dimension = 3
[grid]
size = [0.4, 0.4, 0.4]
resolution = [20, 20, 20]
)";

std::string mesh_scene(const fs::path& file, double scale, const std::string& extra = "") {
  return kBox3D + "[[sand]]\nshape = \"mesh\"\nfile = \"" + file.string() +
         "\"\nscale = " + std::to_string(scale) +
         "\ntranslate = [0.1234, 0.1111, 0.1357]\njitter = 0.5\nparticles_per_cell = 2\n" + extra;
}

// Particles of a scene; spacing 0.01 m (h = 0.02, 2 per cell and axis, which the
// 3D scenes below set).
template <int D>
Particles<D> seeded(const std::string& text) {
  return seed_particles<D>(parse_scene(text, "good.toml"));
}

double lattice_count(double volume) { return volume / 1e-6; }

// Point in the tetrahedron scale * corner tetrahedron + offset.
bool in_tetrahedron(const Vec<3>& x, double scale) {
  const double a = (x[0] - 0.1234) / scale, b = (x[1] - 0.1111) / scale,
               c = (x[2] - 0.1357) / scale;
  return a >= 0 && b >= 0 && c >= 0 && a + b + c <= 1;
}

TEST(Sources, MeshesFillTheirVolumeInEveryFormat) {
  const fs::path dir = temp_dir("formats");
  const double cube = 0.15, tet = 0.25;
  write_obj(dir / "cube.obj", kCubeV, kCubeF);
  write_ascii_stl(dir / "cube.stl", triangles(kCubeV, kCubeF));
  write_binary_stl(dir / "cube_bin.STL", triangles(kCubeV, kCubeF));
  write_obj(dir / "tet.obj", kTetV, kTetF);
  write_ascii_stl(dir / "tet.stl", triangles(kTetV, kTetF));
  write_binary_stl(dir / "tet_bin.stl", triangles(kTetV, kTetF));
  for (const char* name : {"cube.obj", "cube.stl", "cube_bin.STL"}) {
    SCOPED_TRACE(name);
    const SceneConfig s = parse_scene(mesh_scene(dir / name, cube), "good.toml");
    EXPECT_NEAR(s.sand[0].mesh->volume(), cube * cube * cube, 1e-9);
    const Particles<3> p = seed_particles<3>(s);
    const double expected = lattice_count(cube * cube * cube);
    std::cout << name << ": " << p.size() << " particles, " << expected << " expected\n";
    EXPECT_NEAR(p.size(), expected, 0.03 * expected);
    const double lo[3] = {0.1234, 0.1111, 0.1357};
    for (const Vec<3>& x : p.position)
      for (int a = 0; a < 3; ++a)
        ASSERT_TRUE(x[a] >= lo[a] - 1e-6 && x[a] <= lo[a] + cube + 1e-6) << x.transpose();
  }
  for (const char* name : {"tet.obj", "tet.stl", "tet_bin.stl"}) {
    SCOPED_TRACE(name);
    const Particles<3> p = seeded<3>(mesh_scene(dir / name, tet));
    const double expected = lattice_count(tet * tet * tet / 6.0);
    std::cout << name << ": " << p.size() << " particles, " << expected << " expected\n";
    EXPECT_NEAR(p.size(), expected, 0.04 * expected);
    for (const Vec<3>& x : p.position) ASSERT_TRUE(in_tetrahedron(x, tet)) << x.transpose();
  }
  fs::remove_all(dir);
}

// The tree's far-field sums against the exact sum over every triangle, on a
// subdivided icosahedron (1280 triangles) and points around it.

double exact_winding(const std::vector<Tri>& tris, const Point3& p) {
  double w = 0.0;
  for (const Tri& t : tris) {
    Point3 a, b, c;
    for (int i = 0; i < 3; ++i) a[i] = t[0][i] - p[i], b[i] = t[1][i] - p[i], c[i] = t[2][i] - p[i];
    const auto dot = [](const Point3& x, const Point3& y) {
      return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    };
    const Point3 bxc{b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2],
                     b[0] * c[1] - b[1] * c[0]};
    const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)), lc = std::sqrt(dot(c, c));
    w += 2 *
         std::atan2(dot(a, bxc), la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb);
  }
  return w / (4 * kPi);
}

TEST(Sources, FastWindingNumberMatchesTheExactSum) {
  const std::vector<Tri> tris = icosphere(3);
  const TriangleMesh mesh = test::soup(tris);
  const SolidMesh solid(mesh);
  EXPECT_EQ(solid.triangle_count(), 1280u);
  double worst = 0.0;
  std::uint64_t state = 12345;
  const auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53 * 4.0 - 2.0;
  };
  for (int k = 0; k < 2000; ++k) {
    const Point3 p{next(), next(), next()};
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (std::abs(r - 1.0) < 0.02) continue;  // the mesh is a polyhedron, not the sphere
    const double exact = exact_winding(tris, p), fast = solid.winding_number(p);
    worst = std::max(worst, std::abs(exact - fast));
    ASSERT_EQ(std::abs(exact) > 0.5, solid.contains(p)) << r;
  }
  std::cout << "largest |fast - exact| winding number: " << worst << "\n";
  EXPECT_LT(worst, 0.05);
}

TEST(Sources, MeshFileErrorsAreOneLine) {
  const fs::path dir = temp_dir("mesh_errors");
  std::vector<std::vector<int>> open_faces(kCubeF.begin(), kCubeF.end() - 1);  // no right face
  write_obj(dir / "open.obj", kCubeV, open_faces);
  std::ofstream(dir / "garbage.stl") << "this is not a mesh\n";
  std::ofstream(dir / "garbage.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  std::ofstream(dir / "empty.obj") << "# nothing\n";
  std::ofstream(dir / "cube.ply") << "ply\n";
  write_obj(dir / "cube.obj", kCubeV, kCubeF);
  struct Case {
    std::string scene, fragment;
  };
  const std::string open = (dir / "open.obj").string();
  const Case cases[] = {
      {mesh_scene(dir / "missing.obj", 0.1), "cannot open the file (No such file or directory)"},
      {mesh_scene(dir / "open.obj", 0.1),
       "the mesh in \"" + open + "\" is not closed: 4 open edges"},
      {mesh_scene(dir / "garbage.stl", 0.1), "neither binary STL"},
      {mesh_scene(dir / "garbage.obj", 0.1), "line 4: face vertex 7 does not exist (3 vertices"},
      {mesh_scene(dir / "empty.obj", 0.1), "no triangles"},
      {mesh_scene(dir / "cube.ply", 0.1), "unknown mesh format \".ply\""},
      {mesh_scene(dir / "cube.obj", 0.5),
       "bad.toml:9: sand[0].translate: the sand region [0.1234, "
       "0.6234] on x leaves the box"},
  };
  for (const Case& c : cases) {
    const std::string msg = message_of(c.scene);
    EXPECT_EQ(msg.rfind("bad.toml:", 0), 0u) << msg;
    EXPECT_TRUE(contains(msg, c.fragment)) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    if (!contains(c.fragment, "translate")) {
      EXPECT_TRUE(contains(msg, "bad.toml:7: sand[0].file: ")) << msg;
      EXPECT_TRUE(contains(msg, "allowed: a closed triangle mesh")) << msg;
    }
  }
  // The file is relative to the scene file's folder.
  std::ofstream(dir / "scene.toml") << kBox3D +
                                           "[[sand]]\nshape = \"mesh\"\nfile = \"cube.obj\"\n"
                                           "scale = 0.1\ntranslate = [0.1, 0.1, 0.1]\n";
  const SceneConfig s = load_scene((dir / "scene.toml").string());
  EXPECT_EQ(fs::path(s.sand[0].file_path), fs::absolute(dir / "cube.obj"));
  EXPECT_TRUE(contains(scene_to_toml(s), fs::absolute(dir / "cube.obj").string()));
  fs::remove_all(dir);
}

// ------------------------------------------------------- spheres, polygons

TEST(Sources, SphereSeedsItsVolume) {
  const double r = 0.1;
  const Particles<3> p = seeded<3>(kBox3D +
                                   "[[sand]]\nshape = \"sphere\"\ncenter = [0.2, 0.21, 0.19]\n"
                                   "radius = 0.1\njitter = 0.5\nparticles_per_cell = 2\n");
  const double expected = lattice_count(4.0 / 3.0 * kPi * r * r * r);
  std::cout << "sphere: " << p.size() << " particles, " << expected << " expected\n";
  EXPECT_NEAR(p.size(), expected, 0.02 * expected);
  for (const Vec<3>& x : p.position)
    ASSERT_LT((x - Vec<3>(0.2, 0.21, 0.19)).norm(), r) << x.transpose();
}

const std::string kBox2D = R"(dimension = 2
[grid]
size = [0.5, 0.4]
resolution = [50, 40]
)";

// Point in polygon by ray parity (independent of the seeding's winding rule).
bool in_polygon(const std::vector<std::array<double, 2>>& v, double x, double y) {
  bool in = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
    if ((v[i][1] > y) != (v[j][1] > y) &&
        x < (v[j][0] - v[i][0]) * (y - v[i][1]) / (v[j][1] - v[i][1]) + v[i][0])
      in = !in;
  return in;
}

TEST(Sources, PolygonSeedsItsShoelaceArea) {
  // A concave arrow, clockwise (the orientation does not matter).
  const std::vector<std::array<double, 2>> v{{0.05, 0.05}, {0.2, 0.3}, {0.45, 0.05}, {0.2, 0.15}};
  std::string text = kBox2D + "[[sand]]\nshape = \"polygon\"\njitter = 0.5\nvertices = [";
  double twice_area = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto &a = v[i], &b = v[(i + 1) % v.size()];
    twice_area += a[0] * b[1] - b[0] * a[1];
    text += (i ? ", [" : "[") + std::to_string(a[0]) + ", " + std::to_string(a[1]) + "]";
  }
  const Particles<2> p = seeded<2>(text + "]\n");
  const double s = 0.01 / 5;  // h = 0.01, the 2D default of 5 per cell and axis
  const double expected = std::abs(twice_area) / 2 / (s * s);
  std::cout << "polygon: " << p.size() << " particles, " << expected << " expected\n";
  EXPECT_NEAR(p.size(), expected, 0.03 * expected);
  for (const Vec<2>& x : p.position) ASSERT_TRUE(in_polygon(v, x[0], x[1])) << x.transpose();
}

TEST(Sources, ShapeErrorsAreOneLine) {
  const std::string poly = kBox2D + "[[sand]]\nshape = \"polygon\"\n";
  const std::string spout = kBox2D + "[[spout]]\ncenter = [0.25, 0.3]\n";
  struct Case {
    std::string scene, prefix, fragment;
  };
  const Case cases[] = {
      {kBox2D + "[[sand]]\nshape = \"sphere\"\ncenter = [0.1, 0.1]\nradius = 0.05\n",
       "bad.toml:6: sand[0].shape: \"sphere\" is only valid in 3D",
       "\"box\", \"disk\", \"polygon\""},
      {kBox3D + "[[sand]]\nshape = \"polygon\"\nvertices = [[0, 0], [1, 0], [0, 1]]\n",
       "bad.toml:6: sand[0].shape: \"polygon\" is only valid in 2D", "\"sphere\", \"mesh\""},
      {kBox3D + "[[sand]]\nshape = \"sphere\"\ncenter = [0.375, 0.2, 0.2]\nradius = 0.125\n",
       "bad.toml:7: sand[0].center: the sand region [0.25, 0.5] on x leaves the box",
       "allowed: within [0, 0.4]"},
      {kBox3D + "[[sand]]\nshape = \"sphere\"\ncenter = [0.2, 0.2, 0.2]\nradius = 0.1\nmin = [0, "
                "0, 0]\n",
       "bad.toml:9: sand[0].min: not used by shape \"sphere\"", "allowed: center, radius"},
      {kBox2D + "[[sand]]\nshape = \"box\"\nmin = [0, 0]\nmax = [0.1, 0.1]\nvertices = [[0, 0]]\n",
       "bad.toml:9: sand[0].vertices: not used by shape \"box\"", "allowed: min, max"},
      {poly + "vertices = [[0.1, 0.1], [0.2, 0.1]]\n", "bad.toml:7: sand[0].vertices: 2 vertices",
       "at least 3 points"},
      {poly + "vertices = [[0.1, 0.1], [0.2, 0.2], [0.3, 0.3]]\n",
       "bad.toml:7: sand[0].vertices: the polygon has zero area", "positive area"},
      {poly + "vertices = [[0.1, 0.1], [0.6, 0.1], [0.3, 0.3]]\n",
       "bad.toml:7: sand[0].vertices: the sand region [0.1, 0.6] on x leaves the box", "[0, 0.5]"},
      {poly + "vertices = [[0.1, 0.1], [0.2], [0.3, 0.3]]\n",
       "bad.toml:7: sand[0].vertices: vertex 1 is not a point", "at least 3 points"},
      {poly, "bad.toml:5: sand[0].vertices: missing", "at least 3 points"},
      {kBox2D + "[[sand]]\nshape = \"disk\"\ncenter = [0.1, 0.1]\nradius = 0.001\n",
       "bad.toml:6: sand[0].shape: the region holds no particle", "at least one particle"},
      {kBox2D + "[[sand]]\nshape = \"box\"\nmin = [0, 0]\nmax = [0.2, 0.2]\n"
                "[[sand]]\nshape = \"disk\"\ncenter = [0.1, 0.1]\nradius = 0.05\n",
       "bad.toml:10: sand[1].shape: the region holds no particle", "covered by earlier"},
      {spout + "radius = 0.02\nvelocity = [0.0, 0.0]\n", "bad.toml:8: spout[0].velocity: zero",
       "nonzero"},
      {spout + "radius = 0.375\nvelocity = [0.0, -1.0]\n",
       "bad.toml:7: spout[0].radius: the spout's cross-section [-0.125, 0.625] on x leaves the box",
       "[0, 0.5]"},
      {kBox2D + "[[spout]]\ncenter = [0.25, 0.5]\nradius = 0.02\nvelocity = [0.0, -1.0]\n",
       "bad.toml:6: spout[0].center: the spout's cross-section [0.5, 0.5] on y", "[0, 0.4]"},
      {spout + "radius = 0.02\nvelocity = [0.0, -1.0]\nstart = 1.0\nstop = 0.5\n",
       "bad.toml:10: spout[0].stop: 0.5 is out of range", "stop > 1"},
      {spout + "radius = 0.02\nvelocity = [0.0, -1.0]\nstop = 0.001\n",
       "bad.toml:9: spout[0].stop: the spout closes before one layer", "emits nothing"},
      {spout + "radius = 0.0001\nvelocity = [0.0, -1.0]\n",
       "bad.toml:7: spout[0].radius: the cross-section holds no particle", "radius >"},
      {spout + "radius = 0.02\nvelocity = [0.0, -1.0]\nrate = 3\n",
       "bad.toml:9: spout[0].rate: unknown key", "allowed here"},
      {kBox2D, "bad.toml: sand: missing", "at least one [[sand]] block (or a [[spout]])"},
  };
  for (const Case& c : cases) {
    const std::string msg = message_of(c.scene);
    EXPECT_EQ(msg.rfind(c.prefix, 0), 0u) << c.scene << "-> " << msg;
    EXPECT_TRUE(contains(msg, c.fragment)) << msg;
    EXPECT_TRUE(contains(msg, "allowed") || contains(msg, "required")) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}
// ------------------------------------------------------------------ obstacles

// A box of sand with a disk obstacle in its middle: the points inside the
// disk are not seeded, and the others are exactly those seeded without it
// (the same jitter, in the same order).
TEST(Sources, SeedingSkipsTheInsideOfObstacles2D) {
  const std::string text =
      "seed = 3\n" + kBox2D +
      "[[sand]]\nshape = \"box\"\nmin = [0, 0]\nmax = [0.4, 0.4]\njitter = 0.5\n";
  const Particles<2> all = seeded<2>(text);
  const Particles<2> holed =
      seeded<2>(text + "[[obstacle]]\nshape = \"disk\"\ncenter = [0.2, 0.2]\nradius = 0.1\n");
  std::vector<Vec<2>> outside;
  for (const Vec<2>& x : all.position)
    if ((x - Vec<2>(0.2, 0.2)).norm() >= 0.1) outside.push_back(x);
  ASSERT_EQ(holed.size(), outside.size());
  for (std::size_t k = 0; k < outside.size(); ++k)
    ASSERT_TRUE(holed.position[k] == outside[k]) << k;
  const double s = 0.01 / 5;  // the 2D default spacing (5 per cell and axis)
  const double hole = kPi * 0.1 * 0.1 / (s * s);
  EXPECT_NEAR(double(all.size() - holed.size()), hole, 0.02 * hole);
}

// 3D, no jitter: a floor plane and a post; exactly the lattice points
// outside both are seeded.
TEST(Sources, SeedingSkipsTheInsideOfObstacles3D) {
  const Particles<3> p = seeded<3>(kBox3D + R"([[sand]]
shape = "box"
min = [0, 0, 0]
max = [0.2, 0.2, 0.2]
particles_per_cell = 2
[[obstacle]]
shape = "plane"
point = [0, 0, 0.03]
normal = [0, 0, 2]
[[obstacle]]
shape = "cylinder"
center = [0.1, 0.1, 0.05]
radius = 0.05
height = 0.1
)");
  const auto free = [](double x, double y, double z) {
    const double r2 = (x - 0.1) * (x - 0.1) + (y - 0.1) * (y - 0.1);
    return z >= 0.03 && (r2 >= 0.05 * 0.05 || z < 0.05 || z > 0.15);
  };
  std::size_t expected = 0;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 20; ++k)
        expected += free((i + 0.5) * 0.01, (j + 0.5) * 0.01, (k + 0.5) * 0.01);
  EXPECT_EQ(p.size(), expected);
  EXPECT_LT(expected, 8000u - 1200u);  // the floor took 3 layers, the post more
  for (const Vec<3>& x : p.position) ASSERT_TRUE(free(x[0], x[1], x[2])) << x.transpose();
}

// A spout pouring onto a peg: the grains that would appear inside it are
// not emitted, the others are, with the same ids.
TEST(Sources, SpoutsEmitNothingInsideObstacles) {
  const std::string text = kBox2D +
                           "[[spout]]\ncenter = [0.25, 0.35]\nradius = 0.05\n"
                           "velocity = [0.0, -0.5]\njitter = 0.5\n";
  Particles<2> all, some;
  emit_spout_particles<2>(parse_scene(text, "spout.toml"), 0.0, 0.4, all);
  emit_spout_particles<2>(
      parse_scene(text + "[[obstacle]]\nshape = \"disk\"\ncenter = [0.25, 0.25]\nradius = 0.03\n",
                  "peg.toml"),
      0.0, 0.4, some);
  std::vector<std::int64_t> ids;
  for (std::size_t k = 0; k < all.size(); ++k)
    if ((all.position[k] - Vec<2>(0.25, 0.25)).norm() >= 0.03) ids.push_back(all.id[k]);
  EXPECT_LT(ids.size(), all.size());
  EXPECT_EQ(some.id, ids);
}

// -------------------------------------------------------------------- spouts

// 2D, closed box: after t the grain mass is rho phi_max |v| A t (here the
// width 2 r holds exactly 8 particles of spacing 5 mm).
TEST(Sources, SpoutPoursItsMassRate2D) {
  const SceneConfig s = parse_scene(R"(dimension = 2
[grid]
size = [0.2, 0.3]
resolution = [20, 30]
[boundary]
default = "stick"
[[spout]]
center = [0.1, 0.25]
radius = 0.02
velocity = [0.6, -0.8]
start = 0.05
jitter = 0.5
)",
                                    "spout.toml");
  omp_set_num_threads(1);  // ctest runs tests side by side on few cores
  Simulation<2> sim(s);
  EXPECT_EQ(sim.particles().size(), 0u);
  const double t = 0.35;
  while (sim.time() < t - 1e-12) sim.step(sim.adaptive_dt(t - sim.time()));
  const double expected = 2500 * 0.6 * 1.0 * 0.04 * (t - 0.05);
  std::cout << "2D spout: " << sim.grain_mass() << " kg/m poured, " << expected << " expected, "
            << sim.particles().size() << " particles\n";
  EXPECT_NEAR(sim.grain_mass(), expected, 0.05 * expected);
  std::set<std::int64_t> ids(sim.particles().id.begin(), sim.particles().id.end());
  EXPECT_EQ(ids.size(), sim.particles().size());
  for (const std::int64_t id : ids) EXPECT_EQ(id >> 40, 1);  // spout 0
  EXPECT_NEAR(spout_nominal_rate(s, s.spouts[0]), 60.0, 1e-9);
}

// 3D: the disk's lattice (radius 6 spacings) against pi r^2, and emission
// is stateless: one call over [0, t2] emits what [0, t1] and [t1, t2] do.
TEST(Sources, SpoutEmitsADiskLatticeStatelessly3D) {
  const SceneConfig s = parse_scene(kBox3D + R"([[spout]]
center = [0.2, 0.2, 0.3]
radius = 0.06
velocity = [0.3, 0.0, -0.4]
jitter = 1.0
)",
                                    "spout.toml");
  Particles<3> whole, parts;
  emit_spout_particles<3>(s, 0.0, 0.4, whole);
  emit_spout_particles<3>(s, 0.0, 0.2, parts);
  const double v = 0.5, t = 0.4;
  double volume = 0.0;
  for (double x : whole.volume) volume += x;
  const double expected = 0.6 * v * kPi * 0.06 * 0.06 * t;
  std::cout << "3D spout: " << volume << " m^3 of grains, " << expected << " expected, "
            << whole.size() << " particles\n";
  EXPECT_NEAR(volume, expected, 0.05 * expected);
  // Advance the first part as emission assumes (straight at the velocity).
  for (Vec<3>& x : parts.position) x += 0.2 * Vec<3>(0.3, 0.0, -0.4);
  emit_spout_particles<3>(s, 0.2, 0.4, parts);
  ASSERT_EQ(parts.size(), whole.size());
  for (std::size_t k = 0; k < whole.size(); ++k) {
    EXPECT_EQ(parts.id[k], whole.id[k]);
    EXPECT_LT((parts.position[k] - whole.position[k]).norm(), 1e-12);
  }
  EXPECT_EQ(spout_layer_size(3, 0.06, 0.01), 112u);
}

// ------------------------------------------------ threads and resume (CLI)

using test::Result;
using test::sablier;

// The shipped pile, short and coarse: 0.2 s of pouring.
std::string pile_args(const fs::path& dir, const std::string& extra) {
  return "run " + std::string(SABLIER_SOURCE_DIR) + "/scenes/pile2d.toml --out " + dir.string() +
         " --quiet --set time.frames=6 --set grid.resolution=[60,30]" + extra;
}

std::string file(const fs::path& p) { return read_file(p.string()); }

TEST(Sources, EmissionIsTheSameWithOneAndTwoThreads) {
  const fs::path a = temp_dir("threads1"), b = temp_dir("threads2");
  ASSERT_EQ(sablier(pile_args(a, " --threads 1 --set solver.zone_rows=100")).code, 0);
  ASSERT_EQ(sablier(pile_args(b, " --threads 2 --set solver.zone_rows=100")).code, 0);
  for (int f = 1; f <= 6; ++f) {
    const std::string name = "frames/particles_0000" + std::to_string(f) + ".vtp";
    EXPECT_EQ(file(a / name), file(b / name)) << name;
  }
  EXPECT_GT(file(a / "frames/particles_00006.vtp").size(),
            file(a / "frames/particles_00001.vtp").size());
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Sources, ResumedPourIsBitIdentical) {
  const fs::path a = temp_dir("resume_a"), b = temp_dir("resume_b");
  ASSERT_EQ(sablier(pile_args(a, " --threads 1")).code, 0);
  const Result stopped = sablier(pile_args(b, " --threads 1 --stop-after-frame 2"));
  ASSERT_EQ(stopped.code, 130) << stopped.output;
  const Result resumed = sablier("run --resume " + b.string() + " --threads 1 --quiet");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  for (int f = 3; f <= 6; ++f) {
    const std::string name = "frames/particles_0000" + std::to_string(f) + ".vtp";
    EXPECT_EQ(file(a / name), file(b / name)) << name;
  }
  EXPECT_EQ(file(a / "series.pvd"), file(b / "series.pvd"));
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Sources, CheckReportsRegionsAndRates) {
  const Result r = sablier("check " + std::string(SABLIER_SOURCE_DIR) + "/scenes/pile2d.toml");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "spout[0] rate 15 kg/s per m of depth")) << r.output;
  const Result c = sablier("check " + std::string(SABLIER_SOURCE_DIR) + "/scenes/collapse2d.toml");
  EXPECT_TRUE(contains(c.output, "sand[0]  box, ")) << c.output;
}

}  // namespace
}  // namespace sablier
