// Obstacles in particle pictures (docs/render.md): the scene's [[obstacle]]
// solids where they were at the frame's time, clipped to the domain box,
// in grey. 2D: filled behind the grains. 3D: ray-marched surfaces in the
// grains' depth buffer, so grains in front of a solid hide it and grains
// behind it are hidden.
#pragma once

#include <vector>

#include "io/render.hpp"

namespace sablier {

// Lambert factor in [0, 1] of a surface whose unit normal is `n` in screen
// coordinates (right, up, towards the viewer), under the pictures' light
// from the upper left: grains and obstacles share it.
double lambert(const double n[3]);

// 2D: fills the pixels whose centre lies inside an obstacle and the box with
// kObstacle, and those within `edge_px` pixels of the solids' boundary
// (not the box's) with kObstacleEdge. Draw before the grains.
void fill_obstacles_2d(Canvas& canvas, const std::vector<ObstacleConfig>& obstacles, double time,
                       const Box& box, const Camera& cam, int edge_px);

// 3D: per pixel, the nearest surface of the obstacles' union clipped to the
// box (where a solid reaches the box, its cut face), found by sphere
// tracing the signed distance along the view ray; drawn shaded where it is
// nearer than `zbuf` (depth per pixel, row-major), which it updates. The
// silhouettes, `edge_px` wide, are drawn with kObstacleEdge. Draw before
// the grains.
void draw_obstacles_3d(Canvas& canvas, std::vector<float>& zbuf,
                       const std::vector<ObstacleConfig>& obstacles, double time, const Box& box,
                       const Camera& cam, int edge_px);

}  // namespace sablier
