// Parsing of [[obstacle]] blocks (docs/scenes.md): fixed solids that the sand
// slides on with Coulomb friction (physics/obstacle.hpp, METHOD.md section
// 3). scene_parse.cpp calls these; errors are one-line SceneErrors, like
// every scene error.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "scene/scene_reader.hpp"

namespace sablier {

// The [[obstacle]] blocks (none if absent).
void read_all_obstacles(TableReader& root, SceneConfig& s);

// Whether a fixed obstacle translates (obstacle[].velocity, other than a
// plane's along itself, which leaves its solid in place: a conveyor belt)
// or turns (a box, polygon or mesh with a spin): a solid driven into the
// sand.
bool moves_into_sand(const ObstacleConfig& o, int dimension);

// The scene file's name of a shape: Ball is "disk" in 2D, "sphere" in 3D.
const char* obstacle_shape_name(ObstacleShape shape, int dimension);

// Fixed solids thinner than this many cells are not resolved by the grid:
// with the grains' moves as decompaction, the sand flowing along them packs
// beyond phi_max (docs/scenes.md, "Thin solids"). A scene with one takes
// the projection when it names no decompaction, and `sablier check` and
// `sablier run` say so (or warn, under another decompaction).
inline constexpr double kThinSolidCells = 1.5;

// The thinnest part of an obstacle, when thinner than `below` (m): its
// thickness (m) and where it was measured (the middle of a face, in the
// coordinates its vertices or mesh file are given in, once scaled and
// translated). A box's least extent, a cylinder's height; a polygon's or
// mesh's least depth, over its faces (a polygon's edges, up to 5,000 of a
// mesh's triangles, evenly spread), at which the line into the solid from
// the face's middle along its normal leaves the solid again (marched in
// steps of 1/16 of `below`, then bisected). Planes and balls have none (a
// ball is small rather than thin).
struct ThinPart {
  double thickness = 0.0;
  Vec3d where{0, 0, 0};
};
bool thinnest_part(const ObstacleConfig& o, int dimension, double below, ThinPart* out);

// Measures every fixed obstacle of `s` (ObstacleConfig::thin and
// thin_at), once its mesh distances are sampled; a scene with one thinner
// than kThinSolidCells cells that names no decompaction takes the
// projection (scene/thin_solids.cpp).
void measure_thin_solids(SceneConfig& s);

// A message about a scene that is valid but may not do what its author
// expects: a note (the tool dealt with it; `sablier run --quiet` hides it)
// or a warning (always shown).
struct SceneMessage {
  bool warning = false;
  std::string text;  // without the "note: " or "warning: " that line() puts first
  std::string line() const { return (warning ? "warning: " : "note: ") + text; }
};

// One message for each fixed obstacle of `s` thinner than kThinSolidCells
// cells (ObstacleConfig::thin, measured when the scene was read): which,
// how thin, where, and what the decompaction does about it; a note under
// the projection, a warning under another decompaction.
std::vector<SceneMessage> thin_solid_messages(const SceneConfig& s);

// The keys these blocks take, as known_scene_keys() names them.
std::vector<std::string> obstacle_scene_keys();

}  // namespace sablier
