// The scene's fixed obstacles as geometry for other tools: a Wavefront OBJ
// file (ParaView, Blender and Houdini read it) that `sablier run` writes
// once, as obstacles.obj, beside the particle frames.
#pragma once

#include <string>
#include <vector>

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

// A rigid body's [[obstacle]] block `start` moved to a pose: its centre (m),
// and its orientation from the scene's, as an angle (2D, rad,
// counter-clockwise) or a unit quaternion (3D, w x y z), as bodies.csv
// gives them. The result is the block as if the scene had started it there
// (`angle`, `axis` set from the orientation).
ObstacleConfig posed_body(const ObstacleConfig& start, const double centre[3], double angle,
                          const double quaternion[4], int dimension);

// The rigid bodies among `obstacles` (posed: posed_body) and the solids
// driven into the sand (a turning one posed likewise, one that only
// translates moved here to where it is at `time`, s) as VTK XML
// PolyData (ASCII) for ParaView: 3D surfaces as polygons, 2D outlines as
// closed lines in the z = 0 plane, each cell with the solid's obstacle
// index (cell array `obstacle`). A turned body's surface is turned with it
// (a ball's tessellation too, so that its rolling shows).
std::string format_bodies_vtp(const std::vector<ObstacleConfig>& obstacles,
                              const SceneConfig& scene, double time = 0.0);

}  // namespace sablier
