// Bad scene files (issue 2, item 8): every class of bad input (missing
// keys, wrong types, NaN, negative sizes, unknown keys, sand outside the box,
// bad obstacles, bad --set overrides) gets a one-line error `<where>: <key>: <what is
// wrong>; <what is allowed>` (docs/scenes.md, "Errors").
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "scene/scene.hpp"
#include "scene_fixtures.hpp"

namespace sablier {
namespace {

using namespace sablier::test;

// ----------------------------------------------------------------- bad scenes

struct BadScene {
  const char* name;
  std::string text;
  std::string prefix;    // the message starts with "<where>: <key>"
  std::string fragment;  // and says what is wrong or allowed
};

std::string with(const std::string& extra) { return kBase2D + extra; }

std::vector<BadScene> syntax_and_top_level() {
  const std::string& g = kBase2D;
  return {
      {"syntax", with("mu = = 3\n"), "bad.toml:9: TOML syntax error", ""},
      {"unterminated string", replace(g, "\"box\"", "\"box"), "bad.toml:6: TOML syntax error", ""},
      {"duplicate key", replace(g, "dimension = 2", "dimension = 2\ndimension = 3"),
       "bad.toml:2: TOML syntax error", ""},
      {"no dimension", replace(g, "dimension = 2\n", ""), "bad.toml: dimension: missing",
       "required: an integer, 2 <= dimension <= 3"},
      {"dimension 4", replace(g, "dimension = 2", "dimension = 4"),
       "bad.toml:1: dimension: 4 is out of range", "2 <= dimension <= 3"},
      {"dimension float", replace(g, "dimension = 2", "dimension = 2.0"),
       "bad.toml:1: dimension: expected an integer, found the float 2.0", "2 <= dimension"},
      {"unknown top key", "gravty = [0, -9.81]\n" + g, "bad.toml:1: gravty: unknown key",
       "did you mean \"gravity\"?"},
      {"unknown table", with("[materail]\nmu = 0.3\n"), "bad.toml:9: materail: unknown key",
       "did you mean \"material\"?"},
      {"unknown far key", with("[output]\n"), "bad.toml:9: output: unknown key \"output\"",
       "allowed here: "},
      {"seed negative", "seed = -1\n" + g, "bad.toml:1: seed: -1 is out of range", "seed >= 0"},
      {"seed float", "seed = 1.5\n" + g, "bad.toml:1: seed: expected an integer", "seed >= 0"},
      {"gravity length", "gravity = [0, 0, -9.81]\n" + g,
       "bad.toml:1: gravity: expected 2 components", "2 finite numbers"},
      {"gravity inf", "gravity = [0, -inf]\n" + g, "bad.toml:1: gravity: -inf is not a finite",
       "finite numbers"},
  };
}

std::vector<BadScene> grid_errors() {
  const std::string& g = kBase2D;
  const std::string size = "size = [1.0, 0.5]", res = "resolution = [40, 20]";
  return {
      {"no grid", "dimension = 2\n[[sand]]\nshape = \"box\"\nmin = [0, 0]\nmax = [1, 1]\n",
       "bad.toml: grid.size: missing", "required: an array of 2 numbers, each size > 0"},
      {"grid not a table", "grid = 3\n" + replace(g, "[grid]\n" + size + "\n" + res + "\n", ""),
       "bad.toml:1: grid: expected a table, found the integer 3", "a [grid] table"},
      {"no size", replace(g, size + "\n", ""), "bad.toml:2: grid.size: missing", "size > 0"},
      {"no resolution", replace(g, res + "\n", ""), "bad.toml:2: grid.resolution: missing",
       "1 <= resolution <= 100000"},
      {"negative size", replace(g, size, "size = [-1.0, 0.5]"),
       "bad.toml:3: grid.size: component 0 (x) = -1 is out of range", "allowed: size > 0"},
      {"nan size", replace(g, size, "size = [nan, 0.5]"),
       "bad.toml:3: grid.size: nan is not a finite number", "size > 0"},
      {"size string", replace(g, size, "size = \"big\""),
       "bad.toml:3: grid.size: expected an array, found the string \"big\"", ""},
      {"size length", replace(g, size, "size = [1.0, 0.5, 0.5]"),
       "bad.toml:3: grid.size: expected 2 components (one per axis), found 3", ""},
      {"resolution zero", replace(g, res, "resolution = [0, 20]"),
       "bad.toml:4: grid.resolution: component 0 (x) = 0 is out of range", "1 <= resolution"},
      {"resolution fraction", replace(g, res, "resolution = [40.5, 20]"),
       "bad.toml:4: grid.resolution: expected an integer, found the float 40.5", "integers"},
      {"resolution integral float", replace(g, res, "resolution = [40.0, 20]"),
       "bad.toml:4: grid.resolution: expected an integer, found the float 40.0", ""},
      {"non-cubic cells", replace(g, res, "resolution = [40, 30]"),
       "bad.toml:4: grid.resolution: cells are not cubic",
       "allowed: grid.size / grid.resolution equal on every axis"},
      {"unknown grid key", replace(g, "[grid]\n", "[grid]\nsiz = 3\n"),
       "bad.toml:3: grid.siz: unknown key \"siz\"", "did you mean \"size\"?"},
  };
}

std::vector<BadScene> time_material_solver_errors() {
  return {
      {"time not a table", "time = 3\n" + kBase2D, "bad.toml:1: time: expected a table",
       "a [time] table"},
      {"fps zero", with("[time]\nfps = 0\n"), "bad.toml:10: time.fps: 0 is out of range",
       "allowed: fps > 0"},
      {"frames negative", with("[time]\nframes = -3\n"), "bad.toml:10: time.frames: -3",
       "frames >= 0"},
      {"substeps float", with("[time]\nsubsteps = 2.5\n"),
       "bad.toml:10: time.substeps: expected an integer, found the float 2.5", "substeps"},
      {"cfl too big", with("[time]\ncfl = 5\n"), "bad.toml:10: time.cfl: 5 is out of range",
       "0 < cfl <= 4"},
      {"mu negative", with("[material]\nmu = -0.2\n"),
       "bad.toml:10: material.mu: -0.2 is out of range; allowed: 0 <= mu <= 5", ""},
      {"mu string", with("[material]\nmu = \"high\"\n"),
       "bad.toml:10: material.mu: expected a number, found the string \"high\"", "0 <= mu <= 5"},
      {"mu nan", with("[material]\nmu = nan\n"), "bad.toml:10: material.mu: nan is not a finite",
       "0 <= mu <= 5"},
      {"density zero", with("[material]\ndensity = 0\n"), "bad.toml:10: material.density",
       "density > 0"},
      {"phi_max above 1", with("[material]\nphi_max = 1.2\n"), "bad.toml:10: material.phi_max",
       "0 < phi_max <= 1"},
      {"cohesion without friction", with("[material]\nmu = 0\ncohesion = 10\n"),
       "bad.toml:11: material.cohesion: 10 needs friction", "mu = 0"},
      {"cohesion_decay negative", with("[material]\ncohesion_decay = -2\n"),
       "bad.toml:10: material.cohesion_decay", "cohesion_decay >= 0"},
      {"misspelt mu", with("[material]\nmue = 0.3\n"), "bad.toml:10: material.mue: unknown key",
       "did you mean \"mu\"?"},
      {"mu_i incomplete", with("[material]\nmu_i = { delta_mu = 0.2 }\n"),
       "bad.toml:10: material.mu_i.I0: missing", "I0 > 0"},
      {"mu_i I0 zero", with("[material.mu_i]\ndelta_mu = 0.2\nI0 = 0\ngrain_diameter = 1e-3\n"),
       "bad.toml:11: material.mu_i.I0: 0 is out of range", "I0 > 0"},
      {"mu_i delta_mu negative",
       with("[material]\nmu_i = { delta_mu = -1, I0 = 0.3, grain_diameter = 1e-3 }\n"),
       "bad.toml:10: material.mu_i.delta_mu", "delta_mu >= 0"},
      {"mu_i unknown", with("[material.mu_i]\ndelta_mu=1\nI0=1\ngrain_diameter=1\nI_0=1\n"),
       "bad.toml:13: material.mu_i.I_0: unknown key", "did you mean \"I0\"?"},
      {"mu_i not a table", with("[material]\nmu_i = 0.3\n"),
       "bad.toml:10: material.mu_i: expected a table", "[material.mu_i]"},
      {"tolerance one", with("[solver]\ntolerance = 1.0\n"), "bad.toml:10: solver.tolerance",
       "0 < tolerance < 1"},
      {"iterations zero", with("[solver]\nmax_iterations = 0\n"),
       "bad.toml:10: solver.max_iterations", "max_iterations >= 1"},
      {"frames too large", with("[time]\nframes = 3000000000\n"),
       "bad.toml:10: time.frames: 3000000000 is too large", "frames <= 2147483647"},
      {"anderson too deep", with("[solver]\nanderson = 17\n"), "bad.toml:10: solver.anderson",
       "0 <= anderson <= 16"},
      {"zone rows negative", with("[solver]\nzone_rows = -1\n"), "bad.toml:10: solver.zone_rows",
       "zone_rows >= 0"},
      {"too many decompaction moves", with("[solver]\ndecompaction_moves = 17\n"),
       "bad.toml:10: solver.decompaction_moves", "1 <= decompaction_moves <= 16"},
      {"no decompaction moves", with("[solver]\ndecompaction_moves = 0\n"),
       "bad.toml:10: solver.decompaction_moves", "1 <= decompaction_moves <= 16"},
      {"decompaction enum", with("[solver]\ndecompaction = \"spread\"\n"),
       "bad.toml:10: solver.decompaction", "allowed: \"move\", \"push\", \"clamp\""},
      {"iterations float", with("[solver]\nmax_iterations = 1e3\n"),
       "bad.toml:10: solver.max_iterations: expected an integer", ""},
  };
}

std::vector<BadScene> boundary_errors() {
  const std::string opening = "[[boundary.opening]]\nface = \"ymin\"\n";
  return {
      {"boundary enum", with("[boundary]\nxmin = \"sticky\"\n"),
       "bad.toml:10: boundary.xmin: \"sticky\" is not allowed",
       "allowed: \"stick\", \"slip\", \"free\""},
      {"boundary not a string", with("[boundary]\nxmin = 1\n"),
       "bad.toml:10: boundary.xmin: expected a string", "\"stick\", \"slip\", \"free\""},
      {"default enum", with("[boundary]\ndefault = \"open\"\n"), "bad.toml:10: boundary.default",
       "\"stick\", \"slip\", \"free\""},
      {"zmin in 2D", with("[boundary]\nzmin = \"stick\"\n"),
       "bad.toml:10: boundary.zmin: only valid in 3D", "xmin, xmax, ymin, ymax"},
      {"misspelt face", with("[boundary]\nxmn = \"stick\"\n"), "bad.toml:10: boundary.xmn",
       "did you mean \"xmin\"?"},
      {"opening zmin in 2D", with("[[boundary.opening]]\nface = \"zmin\"\n"),
       "bad.toml:10: boundary.opening[0].face: \"zmin\" is only valid in 3D",
       "\"xmin\", \"xmax\", \"ymin\", \"ymax\""},
      {"opening bad face", with("[[boundary.opening]]\nface = \"bottom\"\n"),
       "bad.toml:10: boundary.opening[0].face: \"bottom\" is not allowed", "\"ymin\""},
      {"opening no face", with("[[boundary.opening]]\nmin = [0, 0]\nmax = [1, 0]\n"),
       "bad.toml:9: boundary.opening[0].face: missing", "one of \"xmin\""},
      {"opening no min", with(opening + "max = [0.1, 0]\n"),
       "bad.toml:9: boundary.opening[0].min: missing", "2 finite numbers"},
      {"opening off face", with(opening + "min = [0.9, 0]\nmax = [1.5, 0]\n"),
       "bad.toml:12: boundary.opening[0].max: [0.9, 1.5] on x leaves the face", "within [0, 1]"},
      {"opening reversed", with(opening + "min = [0.6, 0]\nmax = [0.5, 0]\n"),
       "bad.toml:12: boundary.opening[0].max: 0.5 on x is below min", "min <= max"},
      {"opening length", with(opening + "min = [0.5]\nmax = [0.6, 0]\n"),
       "bad.toml:11: boundary.opening[0].min: expected 2 components", ""},
      {"opening unknown key", with(opening + "min = [0, 0]\nmax = [0.1, 0]\nwidth = 3\n"),
       "bad.toml:13: boundary.opening[0].width: unknown key", "allowed here: "},
      {"opening not blocks", with("[boundary]\nopening = 3\n"),
       "bad.toml:10: boundary.opening: expected [[boundary.opening]] blocks", ""},
  };
}

std::vector<BadScene> sand_errors() {
  const std::string& g = kBase2D;
  const std::string& c = kBase3D;
  const std::string disk = disk2d();
  return {
      {"no sand", "dimension = 2\n[grid]\nsize = [1.0, 0.5]\nresolution = [40, 20]\n",
       "bad.toml: sand: missing", "at least one [[sand]] block"},
      {"empty sand list", "dimension = 2\nsand = []\n[grid]\nsize = [1, 1]\nresolution = [4, 4]\n",
       "bad.toml:2: sand: empty", "at least one [[sand]] block"},
      {"sand not blocks", "dimension = 2\nsand = 3\n[grid]\nsize = [1, 1]\nresolution = [4, 4]\n",
       "bad.toml:2: sand: expected [[sand]] blocks", ""},
      {"sand above the box", replace(g, "max = [0.2, 0.4]", "max = [0.2, 0.6]"),
       "bad.toml:8: sand[0].max: the sand region [0, 0.6] on y leaves the box", "[0, 0.5]"},
      {"sand below the box", replace(g, "min = [0.0, 0.0]", "min = [-0.1, 0.0]"),
       "bad.toml:7: sand[0].min: the sand region [-0.1, 0.2] on x leaves the box", "[0, 1]"},
      {"empty box", replace(g, "max = [0.2, 0.4]", "max = [0.0, 0.4]"),
       "bad.toml:8: sand[0].max: empty box", "min < max"},
      {"no shape", replace(g, "shape = \"box\"\n", ""), "bad.toml:5: sand[0].shape: missing",
       "one of \"box\", \"disk\""},
      {"bad shape", replace(g, "\"box\"", "\"cone\""),
       "bad.toml:6: sand[0].shape: \"cone\" is not allowed", "\"box\", \"disk\""},
      {"cylinder in 2D", replace(g, "\"box\"", "\"cylinder\""),
       "bad.toml:6: sand[0].shape: \"cylinder\" is only valid in 3D", "\"box\", \"disk\""},
      {"disk in 3D", replace(c, "\"cylinder\"", "\"disk\""),
       "bad.toml:6: sand[0].shape: \"disk\" is only valid in 2D", "\"box\", \"cylinder\""},
      {"misspelt ppc", with("particles_per_cel = 2\n"),
       "bad.toml:9: sand[0].particles_per_cel: unknown key",
       "did you mean \"particles_per_cell\"?"},
      {"ppc zero", with("particles_per_cell = 0\n"), "bad.toml:9: sand[0].particles_per_cell",
       "1 <= particles_per_cell <= 8"},
      {"jitter above one", with("jitter = 2\n"), "bad.toml:9: sand[0].jitter: 2 is out of range",
       "0 <= jitter <= 1"},
      {"velocity length", with("velocity = [1.0]\n"), "bad.toml:9: sand[0].velocity: expected 2",
       ""},
      {"center in a box", with("center = [0.1, 0.1]\n"),
       "bad.toml:9: sand[0].center: not used by shape \"box\"", "allowed: min, max"},
      {"disk outside", replace(disk, "center = [0.5, 0.25]", "center = [0.05, 0.25]"),
       "bad.toml:7: sand[0].center: the sand region [-0.05, 0.15", "within [0, 1]"},
      {"disk radius zero", replace(disk, "radius = 0.1", "radius = 0"),
       "bad.toml:8: sand[0].radius: 0 is out of range", "radius > 0"},
      {"disk height", disk + "height = 0.1\n", "bad.toml:9: sand[0].height: only used by 3D",
       "center, radius"},
      {"min in a disk", disk + "min = [0, 0]\n", "bad.toml:9: sand[0].min: not used by shape",
       "center, radius"},
      {"cylinder too tall", replace(c, "height = 0.2", "height = 0.3"),
       "bad.toml:9: sand[0].height: the sand region [0, 0.3] on z leaves the box", "[0, 0.25]"},
      {"cylinder no height", replace(c, "height = 0.2\n", ""),
       "bad.toml:5: sand[0].height: missing", "height > 0"},
      {"second block bad", with("[[sand]]\nshape = \"box\"\nmin = [0, 0]\nmax = [0, 0.1]\n"),
       "bad.toml:12: sand[1].max: empty box", "min < max"},
      {"3D zmax enum", c + "[boundary]\nzmax = \"open\"\n",
       "bad.toml:11: boundary.zmax: \"open\" is not allowed", "\"free\""},
  };
}

// [[obstacle]] blocks after kBase2D's lines (the block at line 9) or
// kBase3D's (line 10).
std::vector<BadScene> obstacle_errors() {
  const std::string block = "[[obstacle]]\nshape = ";
  const std::string plane = block + "\"plane\"\npoint = [0.5, 0.1]\n";
  const std::string disk = block + "\"disk\"\ncenter = [0.5, 0.25]\n";
  const std::string box = block + "\"box\"\nmin = [0.5, 0.1]\n";
  return {
      {"obstacle shape unknown", with(block + "\"cone\"\n"),
       "bad.toml:10: obstacle[0].shape: \"cone\" is not allowed", "\"plane\", \"box\", \"disk\""},
      {"obstacle no shape", with("[[obstacle]]\nmu = 0.3\n"),
       "bad.toml:9: obstacle[0].shape: missing", "one of \"plane\""},
      {"obstacle sphere in 2D", with(block + "\"sphere\"\n"),
       "bad.toml:10: obstacle[0].shape: \"sphere\" is only valid in 3D", "\"disk\""},
      {"obstacle disk in 3D", kBase3D + block + "\"disk\"\n",
       "bad.toml:11: obstacle[0].shape: \"disk\" is only valid in 2D",
       "\"plane\", \"box\", \"sphere\", \"cylinder\""},
      {"obstacle zero normal", with(plane + "normal = [0.0, 0]\n"),
       "bad.toml:12: obstacle[0].normal: zero", "a nonzero vector, pointing from the solid"},
      {"obstacle no normal", with(plane), "bad.toml:9: obstacle[0].normal: missing",
       "2 finite numbers"},
      {"obstacle normal length", with(plane + "normal = [0, 0, 1]\n"),
       "bad.toml:12: obstacle[0].normal: expected 2 components", ""},
      {"obstacle negative radius", with(disk + "radius = -0.1\n"),
       "bad.toml:12: obstacle[0].radius: -0.1 is out of range", "radius > 0"},
      {"obstacle empty box", with(box + "max = [0.6, 0.1]\n"),
       "bad.toml:12: obstacle[0].max: empty box: max = 0.1 on y", "min < max"},
      {"obstacle mu above the bound", with(disk + "radius = 0.1\nmu = 5.5\n"),
       "bad.toml:13: obstacle[0].mu: 5.5 is out of range; allowed: 0 <= mu <= 5", ""},
      {"obstacle moving box with the moves",
       with(box + "max = [0.6, 0.2]\nvelocity = [0.1, 0]\n[solver]\ndecompaction = \"move\"\n"),
       "bad.toml:13: obstacle[0].velocity: a box moving into the sand needs "
       "solver.decompaction = \"project\"",
       "a plane moving along itself"},
      {"obstacle angle on a plane", with(plane + "normal = [0, 1]\nangle = 30\n"),
       "bad.toml:13: obstacle[0].angle: a plane does not turn",
       "on a box, polygon, or a rigid body"},
      {"obstacle spin on a plane", with(plane + "normal = [0, 1]\nspin = 3\n"),
       "bad.toml:13: obstacle[0].spin: a plane does not turn", "spin on a disk (a roller)"},
      {"obstacle spin vector in 2D", with(disk + "radius = 0.1\ndensity = 500\nspin = [0, 0, 3]\n"),
       "bad.toml:14: obstacle[0].spin: expected a number", ""},
      {"obstacle axis in 2D",
       with(box + "max = [0.6, 0.2]\ndensity = 500\nangle = 30\naxis = [1, 0]\n"),
       "bad.toml:15: obstacle[0].axis: 2D bodies turn about z", "axis in 3D scenes only"},
      {"obstacle angle out of range", with(box + "max = [0.6, 0.2]\ndensity = 500\nangle = 400\n"),
       "bad.toml:14: obstacle[0].angle: 400 is out of range", "angle <= 360"},
      {"obstacle box body outside the box",
       with("[[obstacle]]\nshape = \"box\"\nmin = [0.5, 0.3]\nmax = [0.9, 0.5]\ndensity = "
            "500\nangle = 45\n"),
       "bad.toml:11: obstacle[0].min: the rigid body spans [0.18786", "a body that starts inside"},
      {"obstacle zero density", with(disk + "radius = 0.1\ndensity = 0\n"),
       "bad.toml:13: obstacle[0].density: 0 is out of range", "density <= 100000"},
      {"obstacle density string", with(disk + "radius = 0.1\ndensity = \"heavy\"\n"),
       "bad.toml:13: obstacle[0].density: expected a number", ""},
      {"body leaving the box",
       with(block + "\"disk\"\ncenter = [0.95, 0.25]\nradius = 0.1\ndensity = 2500\n"),
       "bad.toml:11: obstacle[0].center: the rigid body spans [0.85", "starts inside the box"},
      {"body inside a box obstacle",
       with(box + "max = [0.6, 0.2]\n" + block +
            "\"disk\"\ncenter = [0.55, 0.25]\nradius = 0.1\ndensity = 2500\n"),
       "bad.toml:15: obstacle[1].center: overlaps obstacle[0] (a box) by 0.05",
       "rigid bodies clear of the other obstacles and bodies"},
      {"bodies overlapping",
       with(disk + "radius = 0.1\ndensity = 2500\n" + block +
            "\"disk\"\ncenter = [0.65, 0.25]\nradius = 0.1\ndensity = 1000\n"),
       "bad.toml:16: obstacle[1].center: overlaps obstacle[0] (a rigid disk) by 0.0",
       "touching is clear"},
      {"obstacle plane moving along its normal with the push",
       with(plane + "normal = [0, 1]\nvelocity = [0.1, 0.2]\n[solver]\ndecompaction = \"push\"\n"),
       "bad.toml:13: obstacle[0].velocity: a plane moving into the sand needs",
       "velocity . normal = 0"},
      {"obstacle mu negative", with(disk + "radius = 0.1\nmu = -0.1\n"),
       "bad.toml:13: obstacle[0].mu: -0.1 is out of range", "0 <= mu <= 5"},
      {"obstacle mu string", with(disk + "radius = 0.1\nmu = \"rough\"\n"),
       "bad.toml:13: obstacle[0].mu: expected a number", "0 <= mu <= 5"},
      {"obstacle min in a disk", with(disk + "radius = 0.1\nmin = [0, 0]\n"),
       "bad.toml:13: obstacle[0].min: not used by shape \"disk\"", "allowed: center, radius"},
      {"obstacle radius in a plane", with(plane + "normal = [0, 1]\nradius = 0.1\n"),
       "bad.toml:13: obstacle[0].radius: not used by shape \"plane\"", "point, normal"},
      {"obstacle height in 2D", with(disk + "radius = 0.1\nheight = 0.1\n"),
       "bad.toml:13: obstacle[0].height: not used by shape \"disk\"", "center, radius"},
      {"obstacle misspelt", with(disk + "radius = 0.1\nmue = 0.1\n"),
       "bad.toml:13: obstacle[0].mue: unknown key", "did you mean \"mu\"?"},
      {"obstacle no height",
       kBase3D + block + "\"cylinder\"\ncenter = [0.4, 0.1, 0]\nradius = 0.02\n",
       "bad.toml:10: obstacle[0].height: missing", "height > 0"},
      {"obstacle outside the box",
       with(disk + "radius = 0.1\n" + disk + "radius = 0.1\n" + block +
            "\"disk\"\ncenter = [1.25, 0.25]\nradius = 0.125\n"),
       "bad.toml:19: obstacle[2].center: the obstacle spans [1.125, 1.375] on x, outside the box",
       "reaches into or touches the box"},
      {"obstacle polygon in 3D", kBase3D + block + "\"polygon\"\n",
       "bad.toml:11: obstacle[0].shape: \"polygon\" is only valid in 2D", "\"mesh\""},
      {"obstacle mesh in 2D", with(block + "\"mesh\"\n"),
       "bad.toml:10: obstacle[0].shape: \"mesh\" is only valid in 3D", "\"polygon\""},
      {"obstacle polygon of two corners",
       with(block + "\"polygon\"\nvertices = [[0.1, 0.1], [0.2, 0.2]]\n"),
       "bad.toml:11: obstacle[0].vertices: 2 vertices", "at least 3 points"},
      {"obstacle polygon outside the box",
       with(block + "\"polygon\"\nvertices = [[1.1, 0.1], [1.2, 0.1], [1.2, 0.2]]\n"),
       "bad.toml:11: obstacle[0].vertices: the obstacle spans [1.1, 1.2] on x, outside the box",
       "reaches into or touches the box"},
      {"obstacle plane with a density", with(plane + "normal = [0, 1]\ndensity = 2500\n"),
       "bad.toml:13: obstacle[0].density: a plane cannot be a rigid body",
       "density on a disk, box or polygon"},
      {"obstacle cylinder with a density",
       kBase3D + block +
           "\"cylinder\"\ncenter = [0.2, 0.1, 0.0]\nradius = 0.02\nheight = "
           "0.05\ndensity = 2500\n",
       "bad.toml:15: obstacle[0].density: a cylinder cannot be a rigid body",
       "density on a sphere, box or mesh"},
      {"obstacle rigid polygon crossing itself",
       with(block + "\"polygon\"\nvertices = [[0.5, 0.1], [0.7, 0.2], [0.7, 0.1], [0.5, 0.25]]\n"
                    "density = 2500\n"),
       "bad.toml:11: obstacle[0].vertices: edges 0 and 2 of the rigid polygon meet",
       "does not cross or touch itself"},
      {"obstacle mesh file missing", kBase3D + block + "\"mesh\"\nfile = \"no_such_mesh.obj\"\n",
       "bad.toml:12: obstacle[0].file: cannot use the mesh file", "closed triangle mesh"},
      {"obstacle until zero", with(box + "max = [0.6, 0.2]\nuntil = 0\n"),
       "bad.toml:13: obstacle[0].until: 0 is out of range", "until > 0"},
      {"obstacle until on a body", with(disk + "radius = 0.1\ndensity = 2500\nuntil = 0.5\n"),
       "bad.toml:14: obstacle[0].until: a rigid body cannot be taken away", "fixed obstacles"},
      {"obstacle vertices in a disk", with(disk + "radius = 0.1\nvertices = [[0, 0]]\n"),
       "bad.toml:13: obstacle[0].vertices: not used by shape \"disk\"", "center, radius"},
      {"obstacle box under the floor",
       with(block + "\"box\"\nmin = [0.1, -0.3]\nmax = [0.6, -0.1]\n"),
       "bad.toml:12: obstacle[0].max: the obstacle spans [-0.3, -0.1] on y", "[0, grid.size]"},
      {"obstacle plane misses the box",
       with(block + "\"plane\"\npoint = [0, -1]\nnormal = [0, 1]\n"),
       "bad.toml:11: obstacle[0].point: the plane misses the box", "cuts or touches the box"},
      {"obstacle plane covers the box",
       with(block + "\"plane\"\npoint = [0, 1]\nnormal = [0, 1]\n"),
       "bad.toml:12: obstacle[0].normal: the whole box is on the plane's solid side",
       "part of the box on the side its normal points to"},
      {"sand inside an obstacle", with(block + "\"box\"\nmin = [-0.1, -0.1]\nmax = [0.3, 0.45]\n"),
       "bad.toml:6: sand[0].shape: the region holds no particle: it lies inside [[obstacle]]",
       "room for particles outside the obstacles"},
      {"obstacle not blocks", "obstacle = 3\n" + kBase2D,
       "bad.toml:1: obstacle: expected [[obstacle]] blocks", ""},
  };
}

// A required key or table misspelt: the misspelling is reported, at its
// line, with the missing key it stands for; a missing key with no unknown
// key like it is still "missing".
std::vector<BadScene> misspelt_required_keys() {
  const std::string& g = kBase2D;
  return {
      {"misspelt grid table", replace(g, "[grid]", "[gird]"),
       "bad.toml:2: gird: unknown key \"gird\"; did you mean \"grid\"? (grid.size is missing;",
       "an array of 2 numbers"},
      {"misspelt dimension", replace(g, "dimension = 2", "dimenson = 2"),
       "bad.toml:1: dimenson: unknown key \"dimenson\"; did you mean \"dimension\"?",
       "(dimension is missing; required: an integer"},
      {"misspelt sand blocks", replace(g, "[[sand]]", "[[Sand]]"),
       "bad.toml:5: Sand: unknown key \"Sand\"; did you mean \"sand\"?", "(sand is missing;"},
      {"misspelt shape", replace(g, "shape =", "shpe ="),
       "bad.toml:6: sand[0].shpe: unknown key \"shpe\"; did you mean \"shape\"?",
       "(sand[0].shape is missing; required: one of \"box\""},
      {"misspelt radius", replace(disk2d(), "radius =", "radus ="),
       "bad.toml:8: sand[0].radus: unknown key \"radus\"; did you mean \"radius\"?", "radius > 0"},
      {"misspelt max", replace(g, "max =", "mx ="),
       "bad.toml:8: sand[0].mx: unknown key \"mx\"; did you mean \"max\"?",
       "(sand[0].max is missing"},
      {"misspelt vertices",
       with("[[obstacle]]\nshape = \"polygon\"\nvertice = [[0.5, 0.1], [0.7, 0.1], [0.6, 0.2]]\n"),
       "bad.toml:11: obstacle[0].vertice: unknown key", "did you mean \"vertices\"?"},
      {"misspelt spout key", replace(kSpout2D, "radius =", "raduis ="),
       "bad.toml:7: spout[0].raduis: unknown key", "did you mean \"radius\"?"},
      {"missing max beside min", replace(g, "max = [0.2, 0.4]\n", ""),
       "bad.toml:5: sand[0].max: missing", "2 finite numbers"},
  };
}

// Sources that yield no particle in the run.
std::vector<BadScene> empty_sources() {
  return {
      {"spout opening after the run", kSpout2D + "start = 10\n",
       "bad.toml:9: spout[0].start: the spout opens at 10 s, too late",
       "run ends at 1 s (time.frames / time.fps), so it emits nothing; allowed: start <= 0.995 s"},
      {"spout in a run of no frames", kSpout2D + "[time]\nframes = 0\n",
       "bad.toml:5: spout[0].start: the spout opens at 0 s", "a run longer than 0.005 s"},
      {"bowtie polygon",
       replace(replace(kBase2D, "\"box\"", "\"polygon\""), "min = [0.0, 0.0]\nmax = [0.2, 0.4]",
               "vertices = [[0.1, 0.1], [0.3, 0.3], [0.3, 0.1], [0.1, 0.3]]"),
       "bad.toml:7: sand[0].vertices: the polygon crosses itself (edges 0 and 2 meet)",
       "a simple polygon"},
  };
}

TEST(SceneFile, BadScenesGetOneLineErrorsWithKeyLineAndAllowed) {
  std::vector<BadScene> cases;
  for (auto part :
       {syntax_and_top_level(), grid_errors(), time_material_solver_errors(), boundary_errors(),
        sand_errors(), obstacle_errors(), misspelt_required_keys(), empty_sources()})
    cases.insert(cases.end(), part.begin(), part.end());
  EXPECT_GE(cases.size(), 80u);
  std::set<std::string> names;
  for (const BadScene& c : cases) {
    EXPECT_TRUE(names.insert(c.name).second) << "duplicate case " << c.name;
    const std::string msg = error_of(c.text);
    EXPECT_EQ(msg.rfind(c.prefix, 0), 0u) << c.name << ": " << msg;
    EXPECT_NE(msg.find(c.fragment), std::string::npos) << c.name << ": " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << c.name << ": not one line: " << msg;
    if (msg.find("syntax") == std::string::npos) {
      EXPECT_NE(msg.find("; "), std::string::npos) << c.name << ": says nothing allowed: " << msg;
    }
  }
}

TEST(SceneFile, LoadSceneNamesTheFile) {
  EXPECT_EQ(error_of(kBase2D + "[[sand]]\nshape = \"cone\"\n").rfind("bad.toml:10:", 0), 0u);
  const std::string path = testing::TempDir() + "/sablier_scene_errors_bad.toml";
  std::ofstream(path) << kBase2D << "[material]\nmu = -1\n";
  try {
    load_scene(path);
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ":10: material.mu:", 0), 0u) << e.what();
  }
  std::filesystem::remove(path);
  for (const std::string missing : {"/nonexistent/scene.toml", "no_such_scene.toml"}) {
    try {
      load_scene(missing);
      FAIL() << "accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(missing + ": cannot open the scene file", 0), 0u)
          << e.what();
    }
  }
  EXPECT_THROW(load_scene(SABLIER_SOURCE_DIR "/scenes"), SceneError);
}

}  // namespace
}  // namespace sablier
