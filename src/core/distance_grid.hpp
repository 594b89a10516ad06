// The signed distance to a closed triangle mesh, sampled once on a regular
// grid and interpolated, for mesh obstacles (physics/obstacle.hpp). The
// simulation asks for it at every grain and node of every step (and four
// times per grain in the moves), where an exact query through the mesh's
// tree would cost microseconds; the sampled one costs a trilinear
// interpolation. Sampled at half the simulation's cell size it is exact on
// flat faces and rounds edges and corners over about a sample, below what
// the grid of the simulation resolves.
//
// Interpolation cannot see a part of the mesh thinner than a sample (a
// plate, a blade, a very sharp wedge's tip: both its faces between the
// same samples, every sample outside). So the cells of the sampling grid
// that two faces turned more than kFoldAngle from each other pass near are
// marked when the grid is built, and in those cells the distance is the
// mesh's exact one, from the triangles near the cell (their nearest point,
// and the side by its pseudo-normal), or failing that from the mesh's tree
// (nearest point and winding number). Flat faces and gentle tessellations
// stay interpolated.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/mesh.hpp"

namespace sablier {

class DistanceGrid {
 public:
  // Two faces within a sample of a cell whose normals differ by more than
  // this (radians) make it a cell of exact distances: 150 degrees, a thin
  // part's faces (opposed, 180 degrees) and a wedge sharper than 30
  // degrees, whose part thinner than a sample reaches more than about two
  // samples from its tip. Blunter folds stay interpolated, rounded over
  // about a sample: at 120 degrees `hopper3d`'s 49-degree lip was marked,
  // and grains flowing around its now sharp tip were held there by the
  // put-back that follows their paths (physics/solid_exit.cpp) until they
  // clumped (phi 3.5 at 1 s; docs/method.md).
  static constexpr double kFoldAngle = 2.6179938779914944;
  // A marked cell lists the triangles within this many samples of it: its
  // exact distances come from them up to that distance, beyond it from the
  // mesh's tree. A point of a marked cell lies within 1 + sqrt(3) = 2.73
  // samples of the faces that marked it, so with 3 the tree is asked only
  // on the surface itself (with 1 a fifth of hopper3d's queries went to
  // the tree when its lip was marked; with 2, 5% of a 3 mm funnel shell's,
  // and they took a fifth of its run). The lists are read nearest first
  // and only as far as a triangle could be nearer (local_distance), so
  // their length costs little.
  static constexpr double kListReach = 3.0;

  // Samples the signed distance to `mesh` (negative inside, by its winding
  // number) at the corners of a grid of spacing `spacing` covering [lo, hi]
  // (OpenMP over the samples; the values do not depend on the threads),
  // each cut to [-band, band]: the simulation looks a cell or two from the
  // surface, and the cut spares the distance queries of far samples. Marks
  // the cells of exact distances (above).
  DistanceGrid(std::shared_ptr<const SolidMesh> mesh, const Point3& lo, const Point3& hi,
               double spacing, double band);

  // The signed distance at p (m) and its unit gradient, the outward normal:
  // in a marked cell the mesh's own; elsewhere interpolated, exactly so
  // within band - spacing of the surface, beyond that a value of at least
  // about band - spacing in magnitude, of the right sign. Beyond the sampled
  // box: the value at the nearest point of the box plus the distance to it.
  // Allocates nothing.
  double signed_distance(const Point3& p, Point3* normal) const;

  // The mesh it samples (its exact queries).
  const SolidMesh& mesh() const { return *mesh_; }

  // How many cells of the sampling grid take the exact distance, and
  // whether p lies in one.
  std::int64_t exact_cells() const;
  bool exact_at(const Point3& p) const;

 private:
  struct Tri {
    std::array<Point3, 3> v;
    Point3 n;       // unit, outward
    Point3 centre;  // of the corners; every corner within `radius` of it
    double radius;
    std::array<double, 3> angle;  // at each corner, radians (pseudo-normals' weights)
  };
  void mark_folds();
  // The list of cell c (coordinates in cells), or -1 when unmarked.
  std::int32_t slot_of(const std::array<int, 3>& c) const;
  bool local_distance(std::int32_t slot, const Point3& p, double off_centre, double* distance,
                      Point3* normal) const;

  std::shared_ptr<const SolidMesh> mesh_;
  Point3 lo_{};
  double h_ = 0.0, band_ = 0.0;
  std::array<int, 3> n_{};      // samples per axis
  std::vector<double> values_;  // x fastest
  // Per cell (n_ - 1 per axis, x fastest): -1, or the marked cell's list,
  // list_[list_begin_[slot], list_begin_[slot + 1]) into triangles_, the
  // nearest to the cell's centre first, and their distances from it
  // (list_distance_, m).
  std::vector<std::int32_t> slot_;
  std::vector<std::int32_t> list_begin_{0};
  std::vector<std::int32_t> list_;
  std::vector<double> list_distance_;
  std::vector<Tri> triangles_;
};

}  // namespace sablier
