// Parsing of the sand sources beyond boxes, disks and cylinders (spheres,
// polygons, triangle meshes) and of [[spout]] blocks; scene_parse.cpp calls
// these. Errors are one-line SceneErrors, like every scene error.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "scene/scene_reader.hpp"

namespace sablier {

// Shapes of the other dimension, for "only valid in 3D" messages.
std::vector<std::string> shapes_of_other_dimension(int dimension);

// Rejects the keys of one shape in a block of another, for the keys and
// shapes that the box/disk/cylinder reader does not already cover.
void reject_other_shape_keys(TableReader& t, const std::string& shape);

// "sphere" (3D), "polygon" (2D) or "mesh" (3D).
void read_source_shape(TableReader& t, const std::string& shape, SandConfig& c,
                       const SceneConfig& s);

// [lo, hi] on `axis` must lie in the box [0, grid.size]: else `key` fails,
// `with` the other keys (and grid.size) that [lo, hi] came from.
void check_inside(TableReader& t, const SceneConfig& s, const std::string& key, double lo,
                  double hi, int axis, std::vector<std::string> with,
                  const char* what = "the sand region");

// Whether two edges of the polygon `v` that are not neighbours meet (cross
// or touch): the first two such, by index.
bool polygon_edges_meet(const std::vector<Vec3d>& v, std::size_t* first, std::size_t* second);

// A polygon's `vertices` (of a [[sand]] or [[obstacle]] block): at least 3
// finite points [x, y] enclosing a positive area (z is 0).
std::vector<Vec3d> read_polygon_vertices(TableReader& t);

// A mesh's `file` (relative to the scene file's folder), `scale` and
// `translate`: read, checked closed, transformed.
struct MeshKeys {
  std::string file, file_path;
  double scale = 1.0;
  Vec3d translate{0, 0, 0};
  std::shared_ptr<const SolidMesh> mesh;
  std::shared_ptr<const TriangleMesh> surface;  // the same triangles, transformed
};
MeshKeys read_mesh_keys(TableReader& t, const SceneConfig& s);

// The [[spout]] blocks (none if absent).
void read_all_spouts(TableReader& root, SceneConfig& s);

// Every [[sand]] block must seed at least one particle (physics/seeding.cpp).
void check_regions_seed(TableReader& root, const SceneConfig& s);

// The keys these blocks add, as known_scene_keys() names them.
std::vector<std::string> source_scene_keys();

}  // namespace sablier
