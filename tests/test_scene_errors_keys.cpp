// Bad scene files, continued (docs/scenes.md, "Errors"): an unknown key's
// message lists exactly the keys its block takes; an error across keys that
// --set changed names the overrides; an override that cannot be applied
// says what would be.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "scene_fixtures.hpp"

namespace sablier {
namespace {

using namespace sablier::test;

std::string with(const std::string& extra) { return kBase2D + extra; }

// An unknown key's message lists, or suggests, exactly the keys its block
// takes, for its shape and dimension.
TEST(SceneFile, UnknownKeysListTheKeysTheirBlockTakes) {
  const std::string obstacle = "[[obstacle]]\nshape = ";
  const std::string disk = obstacle + "\"disk\"\ncenter = [0.5, 0.25]\nradius = 0.1\n";
  const std::string plane = obstacle + "\"plane\"\npoint = [0, 0.02]\nnormal = [0, 1]\n";
  const std::string box3d = obstacle + "\"box\"\nmin = [0.4, 0.1, 0]\nmax = [0.45, 0.2, 0.1]\n";
  const std::string bogus = "bogus_key=1";
  const auto allowed = [](const std::string& msg) { return msg.substr(msg.find("allowed here")); };
  EXPECT_EQ(allowed(error_of(with(disk), {"obstacle.0." + bogus})),
            "allowed here: center, density, mu, radius, shape, spin, until, velocity");
  EXPECT_EQ(allowed(error_of(with(disk + "density = 500\n"), {"obstacle.0." + bogus})),
            "allowed here: angle, center, density, mu, radius, shape, spin, velocity");
  EXPECT_EQ(allowed(error_of(with(plane), {"obstacle.0." + bogus})),
            "allowed here: mu, normal, point, shape, until, velocity");
  EXPECT_EQ(allowed(error_of(kBase3D + box3d, {"obstacle.0." + bogus})),
            "allowed here: angle, axis, density, max, min, mu, shape, spin, until, velocity");
  EXPECT_EQ(allowed(error_of(kSpout2D, {"spout.0." + bogus})),
            "allowed here: center, jitter, particles_per_cell, radius, start, stop, velocity");
  const struct {
    std::string scene, set, guess;
  } misspelt[] = {
      {with(disk), "obstacle.0.densty=1", "density"},
      {with(disk), "obstacle.0.untl=1", "until"},
      {kBase3D + box3d, "obstacle.0.axsi=[0,0,1]", "axis"},
      {kSpout2D, "spout.0.stopp=1", "stop"},
      {kBase2D, "material.mu_j=1", "mu_i"},
      {kBase2D, "time.fr=1", "frames"},  // the only key it begins
      {kBase2D, "solver.tol=1", "tolerance"},
  };
  for (const auto& c : misspelt)
    EXPECT_NE(error_of(c.scene, {c.set}).find("did you mean \"" + c.guess + "\"?"),
              std::string::npos)
        << c.set << " -> " << error_of(c.scene, {c.set});
  // A one-letter key is no misspelling of a longer one ("f" was taken for
  // "cfl"): the keys are listed.
  EXPECT_EQ(allowed(error_of(kBase2D, {"time.f=1"})), "allowed here: cfl, fps, frames, substeps");
  EXPECT_EQ(error_of(kBase2D, {"material.m=1"}).find("did you mean"), std::string::npos);
}

// A check across keys blames a line of the file; the keys it read that
// --set gave are named after the message.
TEST(SceneFile, ErrorsAcrossKeysNameTheOverridesTheyRead) {
  const std::string opening =
      "[[boundary.opening]]\nface = \"ymin\"\nmin = [0.4, 0]\nmax = [0.5, 0]\n";
  const std::string box = "[[obstacle]]\nshape = \"box\"\nmin = [0.5, 0.1]\nmax = [0.6, 0.2]\n";
  const struct {
    std::string scene;
    std::vector<std::string> sets;
    std::string prefix, suffix;
  } cases[] = {
      {disk2d(),
       {"sand.0.radius=0.3"},
       "bad.toml:7: sand[0].center: the sand region",
       "(grid.size) (with --set sand.0.radius=0.3)"},
      {with(opening),
       {"boundary.opening.0.min=[0.6,0]"},
       "bad.toml:12: boundary.opening[0].max: 0.5 on x is below min = 0.6",
       "min <= max (with --set boundary.opening.0.min=[0.6,0])"},
      {with(box + "velocity = [0.1, 0]\n"),
       {"solver.decompaction=move"},
       "bad.toml:13: obstacle[0].velocity: a box moving into the sand",
       "(with --set solver.decompaction=move)"},
      {with(box + "spin = 1.0\n"),
       {"solver.decompaction=move", "time.frames=3"},
       "bad.toml:13: obstacle[0].spin: a box moving into the sand",
       "conveyor belt) (with --set solver.decompaction=move)"},
      {kBase2D,
       {"grid.size=[0.5,0.25]", "material.mu=0.3"},
       "bad.toml:8: sand[0].max: the sand region [0, 0.4] on y leaves the box",
       "(with --set grid.size=[0.5,0.25])"},
      {kBase2D,
       {"dimension=3"},
       "bad.toml:3: grid.size: expected 3 components",
       "(with --set dimension=3)"},
      {kSpout2D,
       {"time.frames=0"},
       "bad.toml:5: spout[0].start: the spout opens at 0 s",
       "(with --set time.frames=0)"},
      // The blamed key's own override is named in front; unrelated ones and
      // tables --set created (holding defaults) are not named.
      {disk2d(),
       {"sand.0.center=[0.5,0.05]", "sand.0.jitter=0.5"},
       "--set sand[0].center: the sand region",
       "within [0, 0.5] (grid.size)"},
      {with("max_x = 1\n"),
       {"material.mu=0.3"},
       "bad.toml:9: sand[0].max_x: unknown key",
       "did you mean \"max\"?"},
      {with(box + "velocity = [0.1, 0]\n[solver]\ndecompaction = \"move\"\n"),
       {"time.fps=60"},
       "bad.toml:13: obstacle[0].velocity: a box moving into the sand",
       "conveyor belt)"},
      {with(box + "velocity = [0.1, 0]\n"),
       {"solver.tolerance=1e-3", "solver.decompaction=push"},
       "bad.toml:13: obstacle[0].velocity",
       "(with --set solver.decompaction=push)"},
  };
  for (const auto& c : cases) {
    const std::string msg = error_of(c.scene, c.sets);
    EXPECT_EQ(msg.rfind(c.prefix, 0), 0u) << msg;
    ASSERT_GE(msg.size(), c.suffix.size()) << msg;
    EXPECT_EQ(msg.substr(msg.size() - c.suffix.size()), c.suffix) << msg;
    EXPECT_EQ(msg.find(", --set"), std::string::npos) << msg;  // one named, at most
  }
}

// Overrides that cannot be applied say what would be.
TEST(SceneFile, BadOverridesSayWhatWouldWork) {
  EXPECT_EQ(
      error_of(kBase2D, {"sand.0={shape=\"box\"}"})
          .rfind("--set sand.0={shape=\"box\"}: a whole [[sand]] block cannot be set; set its "
                 "keys one by one, e.g. --set sand.0.KEY=VALUE;",
                 0),
      0u);
  EXPECT_EQ(error_of(kBase3D, {"sand.0.file=sub/rock.obj"})
                .rfind("--set sand.0.file=sub/rock.obj: \"sub/rock.obj\" is not a TOML value (a "
                       "string other than a bare word needs quotes: --set "
                       "'sand.0.file=\"sub/rock.obj\"');",
                       0),
            0u);
  // Broken arrays and strings get no such hint.
  for (const char* set : {"material.mu=[1,", "sand.0.file=\"a"})
    EXPECT_EQ(error_of(kBase2D, {set}).find("needs quotes"), std::string::npos) << set;
}

}  // namespace
}  // namespace sablier
