// The scene's fixed obstacles as geometry for other tools: a Wavefront OBJ
// file (ParaView, Blender and Houdini read it) that `sablier run` writes
// once, as obstacles.obj, beside the particle frames.
#pragma once

#include <string>

#include "scene/scene.hpp"

namespace sablier {

// One object (`o obstacle_K`, K the block's index in the scene) per fixed
// obstacle, in metres. 3D: triangulated surfaces (a plane as its cut through
// the box, boxes, spheres and cylinders tessellated, a mesh's own
// triangles, transformed). 2D, in the z = 0 plane: closed outlines as `l`
// polylines (a plane as its segment across the box). Rigid bodies move and
// are left out: bodies.csv has their track. Empty ("") when no obstacle is
// fixed.
std::string format_obstacles_obj(const SceneConfig& scene);

}  // namespace sablier
