// Closed triangle meshes as sand regions: reading OBJ and STL files
// (mesh_file.cpp), checking that a mesh is closed, the inside test by the
// generalised winding number (Jacobson et al. 2013), evaluated with a
// bounding-volume tree and a far-field expansion (Barill et al. 2018), and
// the distance to the surface over the same tree.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace sablier {

using Point3 = std::array<double, 3>;

// Point3 arithmetic, for the mesh's geometry (mesh.cpp, distance_grid.cpp).
inline Point3 sub(const Point3& a, const Point3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline double dot(const Point3& a, const Point3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// A mesh file that cannot be used: what() says why, without the file name
// (the caller names the file and the scene key).
struct MeshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An indexed triangle soup; vertices with equal coordinates are merged on
// reading, so that shared edges can be recognised.
struct TriangleMesh {
  std::vector<Point3> vertices;
  std::vector<std::array<std::int32_t, 3>> triangles;
};

// Reads an OBJ file (`v` and `f` lines; polygon faces are fan-triangulated,
// other lines ignored) or an STL file (binary, or ASCII `solid`), chosen by
// the extension (.obj, .stl, any case). Throws MeshError.
TriangleMesh read_mesh_file(const std::string& path);

// Edges not shared by exactly two triangles (0 for a closed mesh).
std::size_t open_edge_count(const TriangleMesh& mesh);

// An edge where a closed mesh's surface folds outward (convex, not flat):
// its ends, and its normal cone, the arc of the outward unit normals
// between its two triangles' (about `bisector`, unit, of half-angle
// acos(cos_half)). Rigid bodies meet other solids along such edges too
// (physics/edges.hpp).
struct FeatureEdge {
  Point3 from, to;
  Point3 bisector;
  double cos_half;
};

// The convex edges of a closed mesh whose two triangles are more than
// about a milliradian from coplanar (a face's diagonals are left out), each
// once; outward is the side the mesh's signed volume says, whichever way
// it is oriented. Edges not shared by exactly two triangles are skipped.
std::vector<FeatureEdge> feature_edges(const TriangleMesh& mesh);

// Whether two triangles of the mesh meet at a concave fold (the far corner
// of one above the other's plane, their normals more than about a
// milliradian apart).
bool has_concave_fold(const TriangleMesh& mesh);

// Each vertex's outward unit normal: the mean of its triangles' outward
// normals weighted by their angles there (Thurmer & Wuthrich 1998), outward
// by the signed volume as for feature_edges; zero where they cancel.
std::vector<Point3> vertex_normals(const TriangleMesh& mesh);

// The point of triangle (a, b, c) nearest p, and the part of the triangle
// it lies on (a vertex, the inside of an edge, or the inside of the face).
enum class TriangleFeature : unsigned char {
  Face,
  EdgeAB,
  EdgeBC,
  EdgeCA,
  VertexA,
  VertexB,
  VertexC
};
Point3 closest_on_triangle(const Point3& p, const Point3& a, const Point3& b, const Point3& c,
                           TriangleFeature* feature);
Point3 closest_on_triangle(const Point3& p, const Point3& a, const Point3& b, const Point3& c);

// The inside test of a closed mesh and the distance to its surface, built
// once; queries allocate nothing and may run concurrently.
class SolidMesh {
 public:
  explicit SolidMesh(const TriangleMesh& mesh);

  // Generalised winding number: the solid angle the surface subtends at p
  // over 4 pi; +-1 inside a closed mesh (the sign is the orientation), 0
  // outside, 1/2 on the surface.
  double winding_number(const Point3& p) const;
  // |winding number| > 1/2: meshes oriented either way fill the same.
  bool contains(const Point3& p) const;
  // Distance from p to the surface (m), and the surface's nearest point in
  // *closest when given: branch and bound over the tree (a node whose
  // bounding sphere is farther than the best distance so far is skipped),
  // exact up to round-off. Allocates nothing; may run concurrently. An
  // empty mesh is infinitely far (HUGE_VAL, *closest left as it was).
  // With a `limit`, a surface no nearer than it is reported at `limit`
  // (*closest left as it was): the search starts with that bound, so
  // points far from the surface cost almost nothing.
  double distance(const Point3& p, Point3* closest = nullptr, double limit = HUGE_VAL) const;

  // The distance from p to the surface, exact, for a corner of another
  // solid `towards` which that solid lies (physics/corners.hpp,
  // corner_distance), where p lies within `reach` of the surface (false
  // beyond). Within `slack` of it: the normal of the mesh's cone there (the
  // distinct normals of the triangles within `slack` of p) that follows
  // `towards`, as box_face_towards finds a box's (the normals weighted by
  // max(0, n . towards), summed and normalised; the nearest triangle's if
  // none faces it), and the same sum of their planes' signed distances
  // (negative on the inner side): a corner at an edge or corner of the mesh
  // takes the face it points into, or the edge's bisector. Beyond `slack`:
  // the distance to the nearest point, on the side of the nearest
  // triangle's plane, and the direction from that point.
  bool face_towards(const Point3& p, const Point3& towards, double slack, double reach,
                    double* distance, Point3* normal) const;

  // The faces that lie under p (physics/corners.hpp, faces_over): the
  // distinct planes of the triangles within `reach` of p onto which p
  // projects (its nearest point on the triangle is its projection, to a
  // part in 1e9 of `reach`), whose signed distance lies in [-slack, reach)
  // and which, where p lies within `slack` of the plane, face `towards`,
  // the direction into the solid p is a corner of (a corner at a convex
  // edge lies on the plane of the face beyond it too, which faces away
  // from it): their outward normals and distances, at most `max`, one per
  // distinct normal (the nearest of parallel planes). Near a concave fold
  // p lies over both of its faces, and must stay outside both planes; near
  // a convex one it lies behind the other face's plane. Returns their count.
  int faces_over(const Point3& p, const Point3& towards, double reach, double slack,
                 Point3* normals, double* distances, int max) const;

  const Point3& lower() const { return lo_; }
  const Point3& upper() const { return hi_; }
  double volume() const { return volume_; }  // enclosed volume, m^3 (by the divergence theorem)
  std::size_t triangle_count() const { return tri_.size(); }
  // The corners of triangle k (in the tree's order, not the file's).
  std::array<Point3, 3> triangle(std::size_t k) const { return {tri_[k].a, tri_[k].b, tri_[k].c}; }

 private:
  struct Tri {
    Point3 a, b, c;
  };
  // A node of the tree: its triangles are tri_[first, first + count); the
  // far field of its surface is the dipole sum `area_normal` at `centre`
  // plus the first-moment correction `moment` (row-major 3x3).
  struct Node {
    Point3 centre, area_normal;
    std::array<double, 9> moment;
    double radius;                           // every vertex within this distance of centre
    std::int32_t first, count, left, right;  // children -1 for a leaf
  };
  std::int32_t build(std::int32_t first, std::int32_t count, int depth);
  Point3 unit_normal(const Tri& t) const;
  template <class F>
  void within(const Point3& p, double reach, const F& f) const;
  void summarise(Node& n) const;

  bool concave_ = false;  // has_concave_fold: faces_over has something to find
  std::vector<Tri> tri_;
  std::vector<Node> nodes_;
  Point3 lo_{}, hi_{};
  double outward_ = 1.0;  // the triangles' orientation: +1 if (b - a) x (c - a) points out
  double volume_ = 0.0;
};

}  // namespace sablier
