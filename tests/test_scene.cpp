// Scene files (docs/scenes.md): good scenes parse to the expected values and
// defaults, --set overrides are applied and checked like the file, the
// resolved scene round-trips exactly, every class of bad input gets a one-line
// error `<where>: <key>: <what is wrong>; <what is allowed>`, and the keys the
// reference documents are exactly the keys the parser accepts.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "core/polygon.hpp"
#include "scene/scene.hpp"
#include "scene_fixtures.hpp"

namespace sablier {
namespace {

using namespace sablier::test;

TEST(SceneFile, Defaults2D) {
  SceneConfig e;  // scene.hpp's defaults, but for what the scene gives
  e.dimension = 2;
  e.size = v(1.0, 0.5);
  e.resolution = {40, 20, 1};
  e.gravity = v(0, -9.81);
  e.sand = {SandConfig{SandShape::Box, v(0, 0), v(0.2, 0.4)}};
  e.sand[0].particles_per_cell = 5;  // the 2D default (scene.hpp)
  const SceneConfig s = parse_scene(kBase2D, "good.toml");
  EXPECT_EQ(s.source, "good.toml");
  EXPECT_DOUBLE_EQ(s.cell_size(), 0.025);
  expect_same(s, e);
}

TEST(SceneFile, Defaults3D) {
  SceneConfig e;
  e.dimension = 3;
  e.size = v(0.5, 0.25, 0.25);
  e.resolution = {20, 10, 10};
  e.gravity = v(0, 0, -9.81);
  e.sand = {SandConfig{SandShape::Cylinder, {}, {}, v(0.25, 0.125, 0), 0.1, 0.2}};
  expect_same(parse_scene(kBase3D, "good3d.toml"), e);
}

TEST(SceneFile, EveryKey2D) {
  using B = BoundaryType;
  SceneConfig e;
  e.dimension = 2;
  e.seed = 42;
  e.gravity = v(1.5, -9.0);
  e.size = v(2.0, 1.0);
  e.resolution = {80, 40, 1};
  e.time = TimeConfig{60, 12, 4, 0.5};
  e.material = MaterialConfig{1500, 0.38, 0.62, 0.01, 20.0, 3.0, MuIConfig{0.3, 0.3, 2e-3}};
  e.solver = SolverConfig{1e-6, 300, 3};
  e.solver.decompaction = Decompaction::Push;
  e.solver.decompaction_moves = 3;
  e.boundary.faces = {B::Stick, B::Slip, B::Stick, B::Free, B::Slip, B::Slip};
  e.boundary.openings = {Opening{YMin, v(0.9, 0), v(1.1, 0)}};
  e.sand = {SandConfig{SandShape::Cylinder, {}, {}, v(0.5, 0.5), 0.25, 0, 3, 0.5, v(1, -0.5)},
            SandConfig{SandShape::Box, v(1, 0), v(2, 0.5)}};
  e.sand[1].material = SandMaterial{2650, 0.7, 5.5, 0.25, MuIConfig{0.2, 0.4, 5e-4}};
  e.sand[1].particles_per_cell = 5;  // the 2D default
  SandConfig polygon;
  polygon.shape = SandShape::Polygon;
  polygon.particles_per_cell = 5;
  polygon.vertices = {v(0.1, 0.8), v(0.4, 0.8), v(0.25, 0.95)};
  e.sand.push_back(polygon);
  e.spouts = {SpoutConfig{v(1.5, 0.8), 0.05, v(0, -2), 0.1, 0.5, 3, 0.25}};
  const double len = std::sqrt(0.1 * 0.1 + 1.0 * 1.0);
  ObstacleConfig plane, box, disk;
  plane.point = v(0, 0.05);
  plane.normal = v(0.1 / len, 1.0 / len);
  plane.mu = 0.3;
  plane.velocity = v(1.0, -0.1);  // along the plane: a conveyor belt
  box.shape = ObstacleShape::Box;
  box.min = v(0.8, 0.6);
  box.max = v(0.9, 0.7);
  box.until = 0.5;  // taken away at 0.5 s
  disk.shape = ObstacleShape::Ball;
  disk.center = v(1.7, 0.8);
  disk.radius = 0.05;
  disk.mu = 0.0;
  ObstacleConfig body;  // a rigid body: a disk with a density, thrown
  body.shape = ObstacleShape::Ball;
  body.center = v(1.2, 0.7);
  body.radius = 0.04;
  body.density = 7800;
  body.velocity = v(0.5, -1.0);
  ObstacleConfig wedge;
  wedge.shape = ObstacleShape::Polygon;
  wedge.vertices = {v(0.6, 0.1), v(0.75, 0.1), v(0.7, 0.2)};
  wedge.polygon = std::make_shared<const SolidPolygon>(
      std::vector<SolidPolygon::Point2>{{0.6, 0.1}, {0.75, 0.1}, {0.7, 0.2}});
  e.obstacles = {plane, box, disk, body, wedge};
  expect_same(parse_scene(kFull2D, "full.toml"), e);
}

// [[obstacle]] blocks: shapes by dimension, the normal normalised (and kept
// bit for bit when already of unit length), mu's default, --set.
const std::string kObstacles3D = kBase3D + R"([[obstacle]]
shape = "plane"
point = [0.0, 0.0, 0.02]
normal = [0, 0, 3]
[[obstacle]]
shape = "sphere"
center = [0.45, 0.2, 0.2]
radius = 0.03
mu = 5
[[obstacle]]
shape = "cylinder"
center = [0.05, 0.2, 0.0]
radius = 0.02
height = 0.1
[[obstacle]]
shape = "box"
min = [-0.1, -0.1, -0.1]
max = [0.02, 0.3, 0.3]
)";

TEST(SceneFile, Obstacles) {
  const SceneConfig s = parse_scene(kObstacles3D, "obstacles.toml");
  ASSERT_EQ(s.obstacles.size(), 4u);
  EXPECT_EQ(s.obstacles[0].shape, ObstacleShape::Plane);
  EXPECT_EQ(s.obstacles[0].normal, v(0, 0, 1));
  EXPECT_EQ(s.obstacles[0].point, v(0, 0, 0.02));
  EXPECT_EQ(s.obstacles[0].mu, 0.5);               // the default
  EXPECT_EQ(s.obstacles[0].velocity, v(0, 0, 0));  // the default: fixed
  EXPECT_EQ(s.obstacles[1].shape, ObstacleShape::Ball);
  EXPECT_EQ(s.obstacles[1].radius, 0.03);
  EXPECT_EQ(s.obstacles[1].mu, kMaxObstacleMu);  // the bound is allowed
  EXPECT_EQ(s.obstacles[2].shape, ObstacleShape::Cylinder);
  EXPECT_EQ(s.obstacles[2].height, 0.1);
  EXPECT_EQ(s.obstacles[3].shape, ObstacleShape::Box);  // partly outside the box: allowed
  EXPECT_EQ(s.obstacles[3].max, v(0.02, 0.3, 0.3));

  const std::string plane2d = kBase2D + "[[obstacle]]\nshape = \"plane\"\npoint = [0.5, 0.1]\n";
  // The solid is x > 0.5, beside the sand.
  const SceneConfig a = parse_scene(plane2d + "normal = [-3, 4e-300]\n", "a.toml");
  EXPECT_EQ(a.obstacles.at(0).normal, v(-1, 4e-300 / 3));  // tiny components survive
  const SceneConfig b = parse_scene(plane2d + "normal = [-3e300, 4e300]\n", "b.toml");
  EXPECT_NEAR(b.obstacles.at(0).normal[0], -0.6, 1e-15);
  EXPECT_NEAR(b.obstacles.at(0).normal[1], 0.8, 1e-15);
  const Vec3d unit = b.obstacles[0].normal;  // of unit length within rounding: kept as is
  const SceneConfig c =
      parse_scene(plane2d + fmt::format("normal = [{}, {}]\n", unit[0], unit[1]), "c.toml");
  EXPECT_EQ(c.obstacles[0].normal, unit);

  const SceneConfig d =
      parse_scene(kObstacles3D, "d.toml", {"obstacle.1.mu=0.2", "obstacle.2.height=0.05"});
  EXPECT_EQ(d.obstacles[1].mu, 0.2);
  EXPECT_EQ(d.obstacles[2].height, 0.05);
  EXPECT_EQ(error_of(kObstacles3D, {"obstacle.0.mu=5.5"})
                .rfind("--set obstacle[0].mu: 5.5 is out of range; allowed: 0 <= mu <= 5", 0),
            0u);
  EXPECT_EQ(error_of(kBase2D, {"obstacle.0.mu=0.3"})
                .rfind("--set obstacle.0.mu=0.3: the scene has no [[obstacle]] blocks", 0),
            0u);
}

TEST(SceneFile, EquivalentSpellings) {
  // [material.mu_i] as a table, [[sand]] as an inline array, a 3D box, 3D faces.
  const SceneConfig s = parse_scene(R"(dimension = 3
sand = [{ shape = "box", min = [0, 0, 0], max = [0.5, 0.25, 0.1] }]
[grid]
size = [0.5, 0.25, 0.25]
resolution = [20, 10, 10]
[material.mu_i]
delta_mu = 0.26
I0 = 0.279
grain_diameter = 1e-3
[boundary]
zmin = "stick"
zmax = "free"
[[boundary.opening]]
face = "zmin"
min = [0.2, 0.1, 0.0]
max = [0.3, 0.15, 0.0]
)",
                                    "spellings.toml");
  ASSERT_TRUE(s.material.mu_i.has_value());
  EXPECT_EQ(s.material.mu_i->I0, 0.279);
  EXPECT_EQ(s.boundary.faces[ZMin], BoundaryType::Stick);
  EXPECT_EQ(s.boundary.faces[ZMax], BoundaryType::Free);
  EXPECT_EQ(s.boundary.openings.at(0).face, ZMin);
  EXPECT_EQ(s.sand.at(0).max, (Vec3d{0.5, 0.25, 0.1}));
}

TEST(SceneFile, ShippedScenesLoad) {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(SABLIER_SOURCE_DIR "/scenes")) {
    if (e.path().extension() != ".toml") continue;
    EXPECT_NO_THROW(load_scene(e.path().string())) << e.path();
    ++n;
  }
  EXPECT_GT(n, 0);
}

// ------------------------------------------------------------------ overrides

TEST(SceneFile, OverridesApply) {
  const SceneConfig s =
      parse_scene(kBase2D, "good.toml",
                  {"material.mu=0.3", "grid.resolution=[80,40]", "boundary.xmin=\"stick\"",
                   "boundary.xmax=free", "sand.0.jitter=0.25", "solver.tolerance=1e-3", "seed=7",
                   "time.frames=3", "time.frames=4",
                   "material.mu_i={delta_mu=0.1, I0=0.2, grain_diameter=1e-3}"});
  EXPECT_EQ(s.material.mu, 0.3);
  EXPECT_EQ(s.resolution, (Vec3i{80, 40, 1}));
  EXPECT_EQ(s.boundary.faces[XMin], BoundaryType::Stick);
  EXPECT_EQ(s.boundary.faces[XMax], BoundaryType::Free);
  EXPECT_EQ(s.sand[0].jitter, 0.25);
  EXPECT_EQ(s.solver.tolerance, 1e-3);  // [solver] created by the override
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.time.frames, 4);  // the last override wins
  ASSERT_TRUE(s.material.mu_i.has_value());
  EXPECT_EQ(s.material.mu_i->I0, 0.2);
  // A whole list of blocks replaces the file's blocks of that kind, or adds
  // them where the file has none (docs/scenes.md, "Overrides").
  const SceneConfig l =
      parse_scene(kBase2D, "good.toml",
                  {"sand=[{shape=\"box\", min=[0.6, 0], max=[0.7, 0.1]}]",
                   "obstacle=[{shape=\"disk\", center=[0.3, 0.1], radius=0.05}]"});
  ASSERT_EQ(l.sand.size(), 1u);
  EXPECT_EQ(l.sand[0].min[0], 0.6);
  ASSERT_EQ(l.obstacles.size(), 1u);
  EXPECT_EQ(l.obstacles[0].radius, 0.05);
}

TEST(SceneFile, BadOverrides) {
  struct Case {
    const char* set;
    const char* prefix;    // the message starts with this
    const char* fragment;  // and contains this
  };
  const Case cases[] = {
      {"material.mu=-1", "--set material.mu: -1 is out of range", "allowed: 0 <= mu <= 5"},
      {"material.mue=0.3", "--set material.mue: unknown key", "did you mean \"mu\"?"},
      {"materail.mu=1", "--set materail: unknown key", "did you mean \"material\"?"},
      {"grid.size=[1]", "--set grid.size: expected 2 components", "allowed: an array of 2"},
      {"grid.resolution=[80.0,40]", "--set grid.resolution: expected an integer", "80.0"},
      {"time.fps=fast", "--set time.fps: expected a number, found the string \"fast\"", "fps > 0"},
      {"boundary.zmin=stick", "--set boundary.zmin: only valid in 3D", "xmin, xmax, ymin, ymax"},
      {"material.mu_i.I0=0.3", "--set material.mu_i.delta_mu: missing", "delta_mu >= 0"},
      {"sand.0.shape=cylinder", "--set sand[0].shape: \"cylinder\" is only valid in 3D",
       "\"box\", \"disk\""},
      {"nokey", "--set nokey: no '='", "KEY=VALUE"},
      {"=3", "--set =3: empty key", "KEY=VALUE"},
      {"material..mu=1", "--set material..mu=1: empty name", "KEY=VALUE"},
      {"material.mu=[1,", "--set material.mu=[1,: \"[1,\" is not a TOML value", "KEY=VALUE"},
      {"material.mu=1 2", "--set material.mu=1 2: \"1 2\" is not a TOML value", "KEY=VALUE"},
      {"material.mu=", "--set material.mu=: \"\" is not a TOML value", "KEY=VALUE"},
      {"sand.5.jitter=0", "--set sand.5.jitter=0: \"5\" is not an index", "KEY=VALUE"},
      {"boundary.opening.0.face=ymin",
       "--set boundary.opening.0.face=ymin: the scene has no "
       "[[boundary.opening]] blocks",
       "KEY=VALUE"},
      {"sand.jitter=0", "--set sand.jitter=0: sand holds [[blocks]]", "sand.0.jitter"},
      {"dimension.x=1", "--set dimension.x=1: dimension is a value, not a table", "KEY=VALUE"},
  };
  for (const Case& c : cases) {
    const std::string msg = error_of(kBase2D, {c.set});
    EXPECT_EQ(msg.rfind(c.prefix, 0), 0u) << c.set << " -> " << msg;
    EXPECT_NE(msg.find(c.fragment), std::string::npos) << c.set << " -> " << msg;
  }
}

// ----------------------------------------------------------------- round trip

TEST(SceneFile, ResolvedSceneRoundTrips) {
  for (const std::string& text : {kBase2D, kBase3D, kFull2D, kObstacles3D}) {
    const SceneConfig a = parse_scene(text, "a.toml");
    const SceneConfig b = parse_scene(scene_to_toml(a), "a.toml");
    expect_same(a, b);
    EXPECT_EQ(scene_to_toml(a), scene_to_toml(b));
  }
}

TEST(SceneFile, RandomDoublesRoundTripExactly) {
  std::mt19937_64 rng(1234);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  SceneConfig s = parse_scene(kFull2D, "r.toml");
  SceneConfig s3 = parse_scene(kBase3D, "r3.toml",
                               {"material.mu_i={delta_mu=0.1, I0=0.2, "
                                "grain_diameter=1e-3}"});
  // The balls' radii vary about the fixture's, not cumulatively: grown
  // trial after trial they would overlap, which is an error for rigid bodies.
  const SceneConfig s0 = s, s30 = s3;
  for (int trial = 0; trial < 50; ++trial) {
    for (SceneConfig* x : {&s, &s3}) {
      const SceneConfig& base = x == &s ? s0 : s30;
      x->seed = rng() >> 1;
      x->gravity[0] = -20 * unit(rng);
      // At most 100 fps: kFull2D's spout, opening at 0.1 s, emits before its 12 frames end.
      x->time.fps = 100 * unit(rng) + 1e-9;
      x->time.cfl = 4 * unit(rng) + 1e-9;
      x->material.mu = 4 * unit(rng) + 1e-9;
      x->material.cohesion = 1e-300 * unit(rng);
      x->material.viscosity = std::ldexp(unit(rng), 200);
      x->material.mu_i->grain_diameter = 1e-3 * unit(rng) + 1e-12;
      x->solver.tolerance = unit(rng) * 0.5 + 1e-17;
      x->solver.zone_rows = static_cast<int>(5000 * unit(rng));
      x->solver.decompaction_moves = 1 + static_cast<int>(16 * unit(rng));
      x->solver.decompaction = static_cast<Decompaction>(static_cast<int>(3 * unit(rng)));
      x->sand[0].jitter = unit(rng);
      x->sand[0].radius = 0.1 * unit(rng) + 0.02;  // holds particles: not an error
      x->sand[0].velocity[1] = (unit(rng) - 0.5) * 1e5;
      x->sand[0].material.density = 1e4 * unit(rng) + 1e-9;
      x->sand.back().material.mu = 4 * unit(rng) + 1e-9;
      x->sand.back().material.mu_i =
          MuIConfig{unit(rng), unit(rng) + 1e-9, 1e-3 * unit(rng) + 1e-12};
      for (std::size_t k = 0; k < x->obstacles.size(); ++k) {
        ObstacleConfig& o = x->obstacles[k];
        o.mu = kMaxObstacleMu * unit(rng);
        if (o.shape == ObstacleShape::Plane) o.point[1] = 0.1 * unit(rng);  // clear of the sand
        if (o.shape == ObstacleShape::Ball)
          o.radius = base.obstacles[k].radius * (1.0 + 0.1 * unit(rng));
      }
      expect_same(*x, parse_scene(scene_to_toml(*x), "r.toml"));
    }
  }
}

// -------------------------------------------------------- the documented keys

// Leaf keys of a TOML document, arrays of tables as "name[]".
void collect_keys(const toml::table& t, const std::string& prefix, std::set<std::string>& out) {
  for (const auto& [k, v] : t) {
    const std::string key = prefix + std::string(k.str());
    if (const toml::table* sub = v.as_table()) {
      collect_keys(*sub, key + ".", out);
    } else if (v.is_array_of_tables()) {
      for (const toml::node& e : *v.as_array()) collect_keys(*e.as_table(), key + "[].", out);
    } else {
      out.insert(key);
    }
  }
}

std::set<std::string> known_set() {
  const std::vector<std::string> keys = known_scene_keys();
  std::set<std::string> set(keys.begin(), keys.end());
  EXPECT_EQ(set.size(), keys.size()) << "duplicates in known_scene_keys()";
  return set;
}

TEST(SceneFile, KnownKeysAreTheKeysTheParserAccepts) {
  // The resolved scenes of a full 2D and a full 3D scene write every key
  // (faces explicitly, so not boundary.default); they parse back, so each is
  // accepted.
  // A mesh needs a file: a tetrahedron.
  const std::filesystem::path obj = std::filesystem::temp_directory_path() /
                                    ("sablier_known_keys_" + std::to_string(::getpid()) + ".obj");
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  const std::string full3d = kBase3D + "[[sand]]\nshape = \"mesh\"\nfile = \"" + obj.string() +
                             "\"\nscale = 0.1\ntranslate = [0.38, 0.02, 0.02]\n"
                             "[[sand]]\nshape = \"box\"\nmin = [0, 0, 0]\nmax = [0.1, 0.1, 0.1]\n"
                             "[[boundary.opening]]\nface = \"zmin\"\nmin = [0.1, 0.1, 0]\n"
                             "max = [0.2, 0.2, 0]\n[material]\n"
                             "mu_i = { delta_mu = 0.26, I0 = 0.279, grain_diameter = 1e-3 }\n"
                             "[[obstacle]]\nshape = \"cylinder\"\ncenter = [0.45, 0.2, 0.0]\n"
                             "radius = 0.02\nheight = 0.1\n"
                             "[[obstacle]]\nshape = \"mesh\"\nfile = \"" +
                             obj.string() +
                             "\"\nscale = 0.05\ntranslate = [0.3, 0.02, 0.0]\n"
                             "[[obstacle]]\nshape = \"box\"\nmin = [0.05, 0.15, 0.15]\n"
                             "max = [0.1, 0.2, 0.2]\ndensity = 500\nangle = 10\naxis = [0, 1, 1]\n"
                             "spin = [0.0, 1.0, 0.0]\n";
  std::set<std::string> written{"boundary.default"};
  for (const std::string& text : {kFull2D, full3d}) {
    const std::string resolved = scene_to_toml(parse_scene(text, "full.toml"));
    collect_keys(toml::parse(resolved), "", written);
    EXPECT_NO_THROW(parse_scene(resolved, "resolved.toml"));
  }
  std::filesystem::remove(obj);
  EXPECT_EQ(written, known_set());
}

TEST(SceneFile, DocumentedKeysAreTheKnownKeys) {
  std::ifstream in(SABLIER_SOURCE_DIR "/docs/scenes.md");
  ASSERT_TRUE(in) << "docs/scenes.md";
  std::set<std::string> documented;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("| `", 0) != 0) continue;  // key rows: | `material.mu` | ...
    const std::size_t end = line.find('`', 3);
    ASSERT_NE(end, std::string::npos) << line;
    EXPECT_TRUE(documented.insert(line.substr(3, end - 3)).second) << "documented twice: " << line;
  }
  const std::set<std::string> known = known_set();
  for (const std::string& k : known) EXPECT_TRUE(documented.count(k)) << "undocumented: " << k;
  for (const std::string& k : documented) EXPECT_TRUE(known.count(k)) << "not a scene key: " << k;
}

TEST(SceneFile, DocumentedCompleteScenesParse) {
  std::ifstream in(SABLIER_SOURCE_DIR "/docs/scenes.md");
  std::string line, block;
  bool inside = false;
  int complete = 0;
  while (std::getline(in, line)) {
    if (!inside && line == "```toml") {
      inside = true;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      if (block.rfind("dimension =", 0) != 0 || block.find("[[sand]]") == std::string::npos)
        continue;  // a fragment, not a whole scene
      EXPECT_NO_THROW(parse_scene(block, "docs/scenes.md")) << block;
      ++complete;
    } else if (inside) {
      block += line + "\n";
    }
  }
  EXPECT_EQ(complete, 2);
}

}  // namespace
}  // namespace sablier
