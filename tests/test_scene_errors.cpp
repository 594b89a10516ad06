// Scene files: good scenes parse to the expected values, --set overrides are
// checked like the file, the resolved scene round-trips, and every class of
// bad input gets a one-line error naming the file, line, key and what is
// allowed.
#include <gtest/gtest.h>

#include <string>

#include "scene/scene.hpp"

namespace sablier {
namespace {

const char* const kGood2D = R"(dimension = 2
[grid]
size = [1.0, 0.5]
resolution = [40, 20]
[[sand]]
shape = "box"
min = [0.0, 0.0]
max = [0.2, 0.4]
)";

const char* const kGood3D = R"(dimension = 3
gravity = [0, 0, -9.81]
[grid]
size = [0.5, 0.25, 0.25]
resolution = [20, 10, 10]
[material]
mu = 0.4
mu_i = { delta_mu = 0.26, I0 = 0.279, grain_diameter = 1e-3 }
[boundary]
default = "stick"
zmax = "free"
[[sand]]
shape = "cylinder"
center = [0.25, 0.125, 0.0]
radius = 0.1
height = 0.2
particles_per_cell = 3
jitter = 0.5
)";

TEST(Scene, Good2DWithDefaults) {
  const SceneConfig s = parse_scene(kGood2D, "good.toml");
  EXPECT_EQ(s.dimension, 2);
  EXPECT_EQ(s.resolution[0], 40);
  EXPECT_DOUBLE_EQ(s.cell_size(), 0.025);
  EXPECT_DOUBLE_EQ(s.gravity[1], -9.81);
  EXPECT_DOUBLE_EQ(s.material.mu, 0.5);
  EXPECT_DOUBLE_EQ(s.solver.tolerance, 1e-5);
  EXPECT_EQ(s.time.substeps, 0);
  EXPECT_EQ(s.boundary.faces[YMin], BoundaryType::Slip);
  ASSERT_EQ(s.sand.size(), 1u);
  EXPECT_EQ(s.sand[0].particles_per_cell, 2);
}

TEST(Scene, Good3D) {
  const SceneConfig s = parse_scene(kGood3D, "good3d.toml");
  EXPECT_EQ(s.dimension, 3);
  ASSERT_TRUE(s.material.mu_i.has_value());
  EXPECT_DOUBLE_EQ(s.material.mu_i->I0, 0.279);
  EXPECT_EQ(s.boundary.faces[XMin], BoundaryType::Stick);
  EXPECT_EQ(s.boundary.faces[ZMax], BoundaryType::Free);
  EXPECT_EQ(s.sand[0].shape, SandShape::Cylinder);
  EXPECT_DOUBLE_EQ(s.sand[0].height, 0.2);
}

TEST(Scene, OverridesApplyAndAreChecked) {
  const SceneConfig s = parse_scene(
      kGood2D, "good.toml",
      {"material.mu=0.3", "grid.resolution=[80,40]", "boundary.xmin=stick", "sand.0.jitter=0.25"});
  EXPECT_DOUBLE_EQ(s.material.mu, 0.3);
  EXPECT_EQ(s.resolution[0], 80);
  EXPECT_EQ(s.boundary.faces[XMin], BoundaryType::Stick);
  EXPECT_DOUBLE_EQ(s.sand[0].jitter, 0.25);
  for (const char* bad : {"material.mu=-1", "material.mue=0.3", "nokey", "=3", "sand.5.jitter=0",
                          "material.mu=[1,", "grid.size=[1]"}) {
    try {
      parse_scene(kGood2D, "good.toml", {bad});
      ADD_FAILURE() << "accepted --set " << bad;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("--set"), std::string::npos) << bad << ": " << e.what();
    }
  }
}

TEST(Scene, ResolvedSceneRoundTrips) {
  for (const char* text : {kGood2D, kGood3D}) {
    const SceneConfig a = parse_scene(text, "a.toml", {"material.mu=0.123456789012345"});
    const SceneConfig b = parse_scene(scene_to_toml(a), "a.toml");
    EXPECT_EQ(scene_to_toml(a), scene_to_toml(b));
    EXPECT_EQ(b.material.mu, 0.123456789012345);
    EXPECT_EQ(a.sand[0].jitter, b.sand[0].jitter);
  }
}

TEST(Scene, MissingFileNamesThePath) {
  try {
    load_scene("/nonexistent/scene.toml");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.toml"), std::string::npos);
  }
}

struct BadScene {
  const char* name;
  std::string text;
  const char* expect_key;   // the dotted key the message must name
  const char* expect_text;  // and a fragment saying what is wrong or allowed
};

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const std::size_t k = s.find(from);
  if (k == std::string::npos) throw std::logic_error("fixture lacks " + from);
  return s.replace(k, from.size(), to);
}

std::vector<BadScene> bad_scenes() {
  const std::string g = kGood2D;
  return {
      {"syntax", g + "mu = = 3\n", "", "syntax error"},
      {"no dimension", replace(g, "dimension = 2\n", ""), "dimension", "missing"},
      {"dimension 4", replace(g, "dimension = 2", "dimension = 4"), "dimension", "allowed"},
      {"dimension float", replace(g, "dimension = 2", "dimension = 2.0"), "dimension", "integer"},
      {"no grid", replace(replace(replace(g, "[grid]\n", ""), "size = [1.0, 0.5]\n", ""),
                          "resolution = [40, 20]\n", ""),
       "grid", "missing"},
      {"no size", replace(g, "size = [1.0, 0.5]\n", ""), "grid.size", "missing"},
      {"negative size", replace(g, "size = [1.0, 0.5]", "size = [-1.0, 0.5]"), "grid.size", "out of range"},
      {"zero size", replace(g, "size = [1.0, 0.5]", "size = [0.0, 0.5]"), "grid.size", "out of range"},
      {"nan size", replace(g, "size = [1.0, 0.5]", "size = [nan, 0.5]"), "grid.size", "finite"},
      {"inf size", replace(g, "size = [1.0, 0.5]", "size = [inf, 0.5]"), "grid.size", "finite"},
      {"size string", replace(g, "size = [1.0, 0.5]", "size = \"big\""), "grid.size", "array"},
      {"size length", replace(g, "size = [1.0, 0.5]", "size = [1.0, 0.5, 0.5]"), "grid.size", "2 numbers"},
      {"resolution zero", replace(g, "resolution = [40, 20]", "resolution = [0, 20]"), "grid.resolution", "out of range"},
      {"resolution fraction", replace(g, "resolution = [40, 20]", "resolution = [40.5, 20]"), "grid.resolution", "whole"},
      {"non-cubic cells", replace(g, "resolution = [40, 20]", "resolution = [40, 30]"), "grid.resolution", "cubic"},
      {"unknown grid key", replace(g, "[grid]\n", "[grid]\nsiz = 3\n"), "grid.siz", "did you mean \"size\""},
      {"unknown top key", "gravty = [0, -9.81]\n" + g, "gravty", "did you mean \"gravity\""},
      {"unknown table", g + "[materail]\nmu = 0.3\n", "materail", "did you mean \"material\""},
      {"mu negative", g + "[material]\nmu = -0.2\n", "material.mu", "0 <= value <= 5"},
      {"mu string", g + "[material]\nmu = \"high\"\n", "material.mu", "expected a number"},
      {"mu nan", g + "[material]\nmu = nan\n", "material.mu", "finite"},
      {"density zero", g + "[material]\ndensity = 0\n", "material.density", "0 < value"},
      {"phi_max above 1", g + "[material]\nphi_max = 1.2\n", "material.phi_max", "<= 1"},
      {"cohesion without friction", g + "[material]\nmu = 0\ncohesion = 10\n", "material.cohesion", "mu > 0"},
      {"mu_i incomplete", g + "[material]\nmu_i = { delta_mu = 0.2 }\n", "material.mu_i.I0", "missing"},
      {"fps zero", g + "[time]\nfps = 0\n", "time.fps", "0 < value"},
      {"frames negative", g + "[time]\nframes = -3\n", "time.frames", "out of range"},
      {"substeps float", g + "[time]\nsubsteps = 2.5\n", "time.substeps", "integer"},
      {"tolerance one", g + "[solver]\ntolerance = 1.0\n", "solver.tolerance", "< 1"},
      {"iterations zero", g + "[solver]\nmax_iterations = 0\n", "solver.max_iterations", "1 <= value"},
      {"boundary enum", g + "[boundary]\nxmin = \"sticky\"\n", "boundary.xmin", "\"stick\", \"slip\", \"free\""},
      {"zmin in 2D", g + "[boundary]\nzmin = \"stick\"\n", "boundary.zmin", "unknown key"},
      {"opening bad face", g + "[[boundary.opening]]\nface = \"zmin\"\nmin = [0, 0]\nmax = [0.1, 0]\n",
       "boundary.opening[0].face", "allowed"},
      {"opening off face", g + "[[boundary.opening]]\nface = \"ymin\"\nmin = [0.9, 0]\nmax = [1.5, 0]\n",
       "boundary.opening[0].min", "leaves the face"},
      {"no sand", replace(replace(replace(replace(g, "[[sand]]\n", ""), "shape = \"box\"\n", ""),
                                  "min = [0.0, 0.0]\n", ""), "max = [0.2, 0.4]\n", ""),
       "sand", "at least one"},
      {"sand outside", replace(g, "max = [0.2, 0.4]", "max = [0.2, 0.6]"), "sand[0].min", "leaves the box"},
      {"sand negative", replace(g, "min = [0.0, 0.0]", "min = [-0.1, 0.0]"), "sand[0].min", "leaves the box"},
      {"sand empty box", replace(g, "max = [0.2, 0.4]", "max = [0.0, 0.4]"), "sand[0].max", "min < max"},
      {"sand shape", replace(g, "shape = \"box\"", "shape = \"cylinder\""), "sand[0].shape", "\"box\", \"disk\""},
      {"sand unknown key", replace(g, "shape = \"box\"", "shape = \"box\"\nparticles_per_cel = 2"),
       "sand[0].particles_per_cel", "did you mean \"particles_per_cell\""},
      {"ppc zero", replace(g, "shape = \"box\"", "shape = \"box\"\nparticles_per_cell = 0"),
       "sand[0].particles_per_cell", "out of range"},
      {"jitter above one", replace(g, "shape = \"box\"", "shape = \"box\"\njitter = 2"),
       "sand[0].jitter", "<= 1"},
      {"disk outside", replace(replace(replace(g, "shape = \"box\"", "shape = \"disk\""),
                                       "min = [0.0, 0.0]", "center = [0.05, 0.2]"),
                               "max = [0.2, 0.4]", "radius = 0.1"),
       "sand[0].center", "leaves the box"},
      {"gravity length", "gravity = [0, 0, -9.81]\n" + g, "gravity", "2 numbers"},
      {"sand not array of tables", g + "sand = 3\n", "sand", ""},
  };
}

TEST(Scene, BadScenesGetClearErrors) {
  const auto cases = bad_scenes();
  EXPECT_GE(cases.size(), 40u);
  for (const BadScene& c : cases) {
    try {
      parse_scene(c.text, "bad.toml");
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const SceneError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind("bad.toml", 0), 0u) << c.name << ": " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << c.name << ": not one line: " << msg;
      EXPECT_NE(msg.find(c.expect_key), std::string::npos) << c.name << ": " << msg;
      EXPECT_NE(msg.find(c.expect_text), std::string::npos) << c.name << ": " << msg;
    }
  }
}

TEST(Scene, ErrorsGiveTheLine) {
  try {
    parse_scene(std::string(kGood2D) + "[material]\nmu = -1\n", "bad.toml");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:10: material.mu"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sablier
