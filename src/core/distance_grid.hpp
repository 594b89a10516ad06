// The signed distance to a closed triangle mesh, sampled once on a regular
// grid and interpolated, for mesh obstacles (physics/obstacle.hpp). The
// simulation asks for it at every grain and node of every step (and four
// times per grain in the moves), where an exact query through the mesh's
// tree would cost microseconds; the sampled one costs a trilinear
// interpolation. Sampled at half the simulation's cell size it is exact on
// flat faces and rounds edges and corners over about a sample, below what
// the grid of the simulation resolves.
#pragma once

#include <array>
#include <vector>

#include "core/mesh.hpp"

namespace sablier {

class DistanceGrid {
 public:
  // Samples the signed distance to `mesh` (negative inside, by its winding
  // number) at the corners of a grid of spacing `spacing` covering [lo, hi]
  // (OpenMP over the samples; the values do not depend on the threads),
  // each cut to [-band, band]: the simulation looks a cell or two from the
  // surface, and the cut spares the distance queries of far samples.
  DistanceGrid(const SolidMesh& mesh, const Point3& lo, const Point3& hi, double spacing,
               double band);

  // The interpolated signed distance at p (m) and its unit gradient, the
  // outward normal: exactly interpolated within band - spacing of the
  // surface, beyond that a value of at least about band - spacing in
  // magnitude, of the right sign. Beyond the sampled box: the value at the
  // nearest point of the box plus the distance to it. Allocates nothing.
  double signed_distance(const Point3& p, Point3* normal) const;

 private:
  Point3 lo_{};
  double h_ = 0.0;
  std::array<int, 3> n_{};      // samples per axis
  std::vector<double> values_;  // x fastest
};

}  // namespace sablier
