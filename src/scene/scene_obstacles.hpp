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

// The keys these blocks take, as known_scene_keys() names them.
std::vector<std::string> obstacle_scene_keys();

}  // namespace sablier
