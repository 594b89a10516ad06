// The inside test of a closed triangle mesh: the generalised winding number
// w(p) = sum over triangles of their solid angle at p / 4 pi (Jacobson et
// al. 2013), exactly +-1 inside and 0 outside a closed mesh, and robust to
// the edge and vertex hits that break ray-parity tests on lattice points.
// Summing every triangle costs O(triangles) per point; a tree of triangle
// clusters replaces each cluster far from p (distance > kFarRatio times its
// radius) by the first two terms of its multipole expansion (Barill et al.
// 2018), O(log triangles) per point. The truncation error decays as
// (radius / distance)^2; at kFarRatio = 3 it is far below the 1/2 margin
// between inside (1) and outside (0) except within a fraction of a
// triangle's size from the surface, where the sum is exact anyway.
#include "core/mesh.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

namespace sablier {
namespace {

constexpr double kFarRatio = 3.0;
constexpr int kLeafSize = 8;
constexpr int kMaxDepth = 60;  // median splits: depth <= log2(triangles) + 1
constexpr double kPi = 3.14159265358979323846;

double norm(const Point3& a) { return std::sqrt(dot(a, a)); }

// Solid angle of triangle (a, b, c) at the origin, positive when the origin
// sees it counter-clockwise (Van Oosterom & Strackee 1983).
double solid_angle(const Point3& a, const Point3& b, const Point3& c) {
  const double la = norm(a), lb = norm(b), lc = norm(c);
  const double det = dot(a, cross(b, c));
  const double div = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
  return 2.0 * std::atan2(det, div);
}

Point3 along(const Point3& a, double s, const Point3& u) {
  return {a[0] + s * u[0], a[1] + s * u[1], a[2] + s * u[2]};
}
double distance2(const Point3& a, const Point3& b) {
  const Point3 d = sub(a, b);
  return dot(d, d);
}

// The point of segment [a, b] nearest p (a itself for a zero-length one).
Point3 closest_on_segment(const Point3& p, const Point3& a, const Point3& b) {
  const Point3 ab = sub(b, a);
  const double len2 = dot(ab, ab);
  if (!(len2 > 0.0)) return a;
  return along(a, std::clamp(dot(sub(p, a), ab) / len2, 0.0, 1.0), ab);
}

}  // namespace

// The point of triangle (a, b, c) nearest p, by the Voronoi region of the
// triangle that p falls in (Ericson, Real-Time Collision Detection, 2005,
// 5.1.5): a vertex region when p lies behind both edges leaving that vertex,
// an edge region when p lies between the edge's two end regions and outside
// the edge (the projection of p is then on the line), else the face. The
// signed quantities va, vb, vc are the barycentric weights of p's
// projection onto the plane, each scaled by |ab x ac|^2; checking them in
// this order needs only the six dot products below.
Point3 closest_on_triangle(const Point3& p, const Point3& a, const Point3& b, const Point3& c,
                           TriangleFeature* feature) {
  const Point3 ab = sub(b, a), ac = sub(c, a);
  const Point3 ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    *feature = TriangleFeature::VertexA;
    return a;
  }
  const Point3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) {
    *feature = TriangleFeature::VertexB;
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    *feature = TriangleFeature::EdgeAB;
    return along(a, d1 / (d1 - d3), ab);
  }
  const Point3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) {
    *feature = TriangleFeature::VertexC;
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    *feature = TriangleFeature::EdgeCA;
    return along(a, d2 / (d2 - d6), ac);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    *feature = TriangleFeature::EdgeBC;
    return along(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(c, b));
  }
  const double sum = va + vb + vc;  // |ab x ac|^2: zero for a degenerate triangle
  if (!(sum > 0.0)) {
    // A sliver that round-off let through to the face case: its nearest
    // point is on one of its edges, and dividing by sum would give NaN.
    // (A degenerate triangle has no normal: its feature does not matter.)
    Point3 best = closest_on_segment(p, a, b);
    for (const Point3& q : {closest_on_segment(p, b, c), closest_on_segment(p, c, a)})
      if (distance2(p, q) < distance2(p, best)) best = q;
    *feature = TriangleFeature::EdgeAB;
    return best;
  }
  *feature = TriangleFeature::Face;
  const double v = vb / sum, w = vc / sum;
  return {a[0] + v * ab[0] + w * ac[0], a[1] + v * ab[1] + w * ac[1], a[2] + v * ab[2] + w * ac[2]};
}

Point3 closest_on_triangle(const Point3& p, const Point3& a, const Point3& b, const Point3& c) {
  TriangleFeature f;
  return closest_on_triangle(p, a, b, c, &f);
}

std::size_t open_edge_count(const TriangleMesh& mesh) {
  std::vector<std::uint64_t> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const auto i = static_cast<std::uint32_t>(t[k]),
                 j = static_cast<std::uint32_t>(t[(k + 1) % 3]);
      edges.push_back(std::uint64_t(std::min(i, j)) << 32 | std::max(i, j));
    }
  std::sort(edges.begin(), edges.end());
  std::size_t open = 0;
  for (std::size_t k = 0; k < edges.size();) {
    std::size_t run = k;
    while (run < edges.size() && edges[run] == edges[k]) ++run;
    open += run - k != 2;
    k = run;
  }
  return open;
}

namespace {

// Each triangle's unit normal, turned outward by the sign of the volume
// (zero for a degenerate triangle).
std::vector<Point3> outward_normals(const TriangleMesh& mesh) {
  const auto& v = mesh.vertices;
  double six_v = 0.0;
  for (const auto& t : mesh.triangles) six_v += dot(v[t[0]], cross(v[t[1]], v[t[2]]));
  const double side = six_v < 0.0 ? -1.0 : 1.0;
  std::vector<Point3> normal;
  normal.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const Point3 n = cross(sub(v[t[1]], v[t[0]]), sub(v[t[2]], v[t[0]]));
    const double len = norm(n);
    normal.push_back(len > 0.0 ? Point3{side * n[0] / len, side * n[1] / len, side * n[2] / len}
                               : Point3{0, 0, 0});
  }
  return normal;
}

}  // namespace

std::vector<Point3> vertex_normals(const TriangleMesh& mesh) {
  const auto& v = mesh.vertices;
  const std::vector<Point3> normal = outward_normals(mesh);
  std::vector<Point3> out(v.size(), Point3{0, 0, 0});
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto& t = mesh.triangles[f];
      const Point3 a = sub(v[t[(k + 1) % 3]], v[t[k]]), b = sub(v[t[(k + 2) % 3]], v[t[k]]);
      const double la = norm(a), lb = norm(b);
      if (!(la > 0.0 && lb > 0.0)) continue;
      const double angle = std::acos(std::clamp(dot(a, b) / (la * lb), -1.0, 1.0));
      for (int c = 0; c < 3; ++c) out[t[k]][c] += angle * normal[f][c];
    }
  for (Point3& n : out) {
    const double len = norm(n);
    if (len > 0.0)
      for (double& c : n) c /= len;
  }
  return out;
}

namespace {

// f(a, b, n0, n1, convex) for each edge (a, b) that two triangles of outward
// normals n0 and n1 share, where they are not coplanar (normals more than
// about a milliradian apart); convex where the far corner of one triangle
// lies below the other's plane.
template <class F>
void for_each_fold(const TriangleMesh& mesh, const F& f) {
  const auto& v = mesh.vertices;
  const std::vector<Point3> normal = outward_normals(mesh);
  // (edge key, triangle, corner opposite the edge), sorted by key.
  struct Side {
    std::uint64_t key;
    std::int32_t tri, opposite;
  };
  std::vector<Side> sides;
  sides.reserve(mesh.triangles.size() * 3);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto& tr = mesh.triangles[t];
      const auto i = static_cast<std::uint32_t>(tr[k]),
                 j = static_cast<std::uint32_t>(tr[(k + 1) % 3]);
      sides.push_back({std::uint64_t(std::min(i, j)) << 32 | std::max(i, j),
                       static_cast<std::int32_t>(t), tr[(k + 2) % 3]});
    }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.key != y.key ? x.key < y.key : x.tri < y.tri;
  });
  constexpr double kFlat = 5e-7;  // 1 - cos of 1 mrad: coplanar triangles
  for (std::size_t k = 0; k < sides.size();) {
    std::size_t run = k;
    while (run < sides.size() && sides[run].key == sides[k].key) ++run;
    if (run - k == 2) {
      const Side &s0 = sides[k], &s1 = sides[k + 1];
      const Point3 &n0 = normal[s0.tri], &n1 = normal[s1.tri];
      const auto a = static_cast<std::int32_t>(s0.key >> 32),
                 b = static_cast<std::int32_t>(s0.key & 0xffffffffu);
      if (dot(n0, n1) < 1.0 - kFlat) f(a, b, n0, n1, dot(sub(v[s1.opposite], v[a]), n0) < 0.0);
    }
    k = run;
  }
}

}  // namespace

std::vector<FeatureEdge> feature_edges(const TriangleMesh& mesh) {
  std::vector<FeatureEdge> out;
  for_each_fold(mesh, [&](std::int32_t a, std::int32_t b, const Point3& n0, const Point3& n1,
                          bool convex) {
    const Point3 sum{n0[0] + n1[0], n0[1] + n1[1], n0[2] + n1[2]};
    const double len = norm(sum);
    if (convex && len > 0.0) {
      const Point3 bisector{sum[0] / len, sum[1] / len, sum[2] / len};
      out.push_back({mesh.vertices[a], mesh.vertices[b], bisector, dot(n0, bisector)});
    }
  });
  return out;
}

bool has_concave_fold(const TriangleMesh& mesh) {
  bool concave = false;
  for_each_fold(mesh, [&](std::int32_t, std::int32_t, const Point3&, const Point3&, bool convex) {
    concave = concave || !convex;
  });
  return concave;
}

SolidMesh::SolidMesh(const TriangleMesh& mesh) : concave_(has_concave_fold(mesh)) {
  tri_.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    tri_.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
  lo_ = hi_ = mesh.vertices.empty() ? Point3{0, 0, 0} : mesh.vertices[0];
  for (const Point3& v : mesh.vertices)
    for (int a = 0; a < 3; ++a) lo_[a] = std::min(lo_[a], v[a]), hi_[a] = std::max(hi_[a], v[a]);
  double six_v = 0.0;  // divergence theorem: V = sum a.(b x c) / 6
  for (const Tri& t : tri_) six_v += dot(t.a, cross(t.b, t.c));
  volume_ = std::abs(six_v) / 6.0;
  outward_ = six_v < 0.0 ? -1.0 : 1.0;
  if (!tri_.empty()) build(0, static_cast<std::int32_t>(tri_.size()), 0);
}

// Splits at the median centroid along the longest axis of the centroids'
// box; nth_element is deterministic, so the tree (and every sum) is too.
std::int32_t SolidMesh::build(std::int32_t first, std::int32_t count, int depth) {
  const auto index = static_cast<std::int32_t>(nodes_.size());
  nodes_.push_back(Node{});
  Node n{};
  n.first = first;
  n.count = count;
  n.left = n.right = -1;
  summarise(n);
  if (count > kLeafSize && depth < kMaxDepth) {
    const auto centroid = [](const Tri& t, int a) { return t.a[a] + t.b[a] + t.c[a]; };
    Point3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (std::int32_t k = first; k < first + count; ++k)
      for (int a = 0; a < 3; ++a)
        lo[a] = std::min(lo[a], centroid(tri_[k], a)),
        hi[a] = std::max(hi[a], centroid(tri_[k], a));
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    const std::int32_t half = count / 2;
    std::nth_element(
        tri_.begin() + first, tri_.begin() + first + half, tri_.begin() + first + count,
        [&](const Tri& x, const Tri& y) { return centroid(x, axis) < centroid(y, axis); });
    n.left = build(first, half, depth + 1);
    n.right = build(first + half, count - half, depth + 1);
  }
  nodes_[index] = n;
  return index;
}

// The node's expansion centre (area-weighted centroid), its summed area
// vectors N = sum A_t n_t, the first moment M_ij = sum (A_t n_t)_i
// (centroid_t - centre)_j, and its radius.
void SolidMesh::summarise(Node& n) const {
  double area = 0.0;
  Point3 weighted{0, 0, 0}, normal{0, 0, 0};
  for (std::int32_t k = n.first; k < n.first + n.count; ++k) {
    const Tri& t = tri_[k];
    const Point3 an = cross(sub(t.b, t.a), sub(t.c, t.a));  // 2 A n
    const double a = 0.5 * norm(an);
    for (int i = 0; i < 3; ++i) {
      normal[i] += 0.5 * an[i];
      weighted[i] += a * (t.a[i] + t.b[i] + t.c[i]) / 3.0;
    }
    area += a;
  }
  n.centre = tri_[n.first].a;
  if (area > 0.0)
    for (int i = 0; i < 3; ++i) n.centre[i] = weighted[i] / area;
  n.area_normal = normal;
  n.moment.fill(0.0);
  n.radius = 0.0;
  for (std::int32_t k = n.first; k < n.first + n.count; ++k) {
    const Tri& t = tri_[k];
    const Point3 an = cross(sub(t.b, t.a), sub(t.c, t.a));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        n.moment[3 * i + j] += 0.5 * an[i] * ((t.a[j] + t.b[j] + t.c[j]) / 3.0 - n.centre[j]);
    for (const Point3* v : {&t.a, &t.b, &t.c})
      n.radius = std::max(n.radius, norm(sub(*v, n.centre)));
  }
}

double SolidMesh::winding_number(const Point3& p) const {
  if (nodes_.empty()) return 0.0;
  double omega = 0.0;
  std::int32_t stack[2 * kMaxDepth + 4];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    const Point3 r = sub(n.centre, p);
    const double d2 = dot(r, r);
    if (d2 > kFarRatio * kFarRatio * n.radius * n.radius) {
      // Omega ~ N.r / |r|^3 + sum_ij J_ij M_ij, J = grad (r / |r|^3)
      // = I / |r|^3 - 3 r r^T / |r|^5.
      const double inv = 1.0 / std::sqrt(d2), inv3 = inv * inv * inv, inv5 = inv3 * inv * inv;
      double rmr = 0.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) rmr += r[i] * n.moment[3 * i + j] * r[j];
      const double trace = n.moment[0] + n.moment[4] + n.moment[8];
      omega += dot(n.area_normal, r) * inv3 + trace * inv3 - 3.0 * rmr * inv5;
    } else if (n.left < 0) {
      for (std::int32_t k = n.first; k < n.first + n.count; ++k)
        omega += solid_angle(sub(tri_[k].a, p), sub(tri_[k].b, p), sub(tri_[k].c, p));
    } else {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  return omega / (4.0 * kPi);
}

bool SolidMesh::contains(const Point3& p) const {
  for (int a = 0; a < 3; ++a)
    if (p[a] < lo_[a] || p[a] > hi_[a]) return false;
  return std::abs(winding_number(p)) > 0.5;
}

// Depth-first branch and bound: a node's triangles are no nearer p than its
// bounding sphere, max(0, |p - centre| - radius), so a node whose bound is
// not below the best distance found so far cannot improve it. The nearer
// child goes on top of the stack, so that a good best is found early and
// most of the tree is cut; each entry keeps its bound, checked again when
// popped since the best may have shrunk meanwhile.
double SolidMesh::distance(const Point3& p, Point3* closest, double limit) const {
  if (nodes_.empty()) return limit;
  const auto bound = [&](const Node& n) {
    return std::max(0.0, norm(sub(p, n.centre)) - n.radius);
  };
  // Each level pops one entry and pushes at most two, and a node is at
  // depth <= kMaxDepth, so the stack never holds more than kMaxDepth + 1.
  constexpr std::size_t kStack = 128;
  static_assert(kStack >= kMaxDepth + 2, "the traversal stack must hold the deepest path");
  std::array<std::int32_t, kStack> stack;
  std::array<double, kStack> lower;
  std::size_t top = 0;
  stack[top] = 0;
  lower[top++] = bound(nodes_[0]);
  double best = limit, best2 = limit * limit;  // distance and its square
  bool found = false;
  Point3 nearest{};
  while (top > 0) {
    --top;
    if (lower[top] >= best) continue;
    const Node& n = nodes_[stack[top]];
    if (n.left < 0) {
      for (std::int32_t k = n.first; k < n.first + n.count; ++k) {
        const Point3 q = closest_on_triangle(p, tri_[k].a, tri_[k].b, tri_[k].c);
        const double d2 = distance2(p, q);
        if (d2 < best2) best2 = d2, best = std::sqrt(d2), nearest = q, found = true;
      }
      continue;
    }
    std::int32_t nearer = n.left, farther = n.right;
    double near_lb = bound(nodes_[nearer]), far_lb = bound(nodes_[farther]);
    if (far_lb < near_lb) std::swap(nearer, farther), std::swap(near_lb, far_lb);
    assert(top + 2 <= kStack);
    if (far_lb < best) stack[top] = farther, lower[top++] = far_lb;
    if (near_lb < best) stack[top] = nearer, lower[top++] = near_lb;
  }
  if (closest && found) *closest = nearest;
  return best;
}

// Triangle t's outward unit normal (zero for a triangle of no area).
Point3 SolidMesh::unit_normal(const Tri& t) const {
  const Point3 n = cross(sub(t.b, t.a), sub(t.c, t.a));
  const double len = norm(n);
  return len > 0.0 ? Point3{outward_ * n[0] / len, outward_ * n[1] / len, outward_ * n[2] / len}
                   : Point3{0, 0, 0};
}

// f(k, q, d2) for each triangle k within `reach` of p, q its point nearest
// p and d2 their squared distance: the tree's nodes whose bounding spheres
// come within `reach`, each level popping one entry and pushing at most two
// (as distance()).
template <class F>
void SolidMesh::within(const Point3& p, double reach, const F& f) const {
  if (nodes_.empty()) return;
  constexpr std::size_t kStack = 128;
  std::array<std::int32_t, kStack> stack;
  std::size_t top = 0;
  stack[top++] = 0;
  const double reach2 = reach * reach;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (norm(sub(p, n.centre)) - n.radius > reach) continue;
    if (n.left >= 0) {
      assert(top + 2 <= kStack);
      stack[top++] = n.right;
      stack[top++] = n.left;
      continue;
    }
    for (std::int32_t k = n.first; k < n.first + n.count; ++k) {
      const Tri& t = tri_[k];
      const Point3 q = closest_on_triangle(p, t.a, t.b, t.c);
      const double d2 = distance2(p, q);
      if (d2 <= reach2) f(k, q, d2);
    }
  }
}

bool SolidMesh::face_towards(const Point3& p, const Point3& towards, double slack, double reach,
                             double* distance, Point3* normal) const {
  if (nodes_.empty()) return false;
  double nearest2 = HUGE_VAL;
  std::int32_t nearest = -1;
  Point3 nearest_point{};
  // The distinct face normals within `slack` facing `towards` (coplanar
  // triangles count once, so that how a face is split does not weigh),
  // their weights and plane distances.
  constexpr int kFaces = 16;
  std::array<Point3, kFaces> face_normal;
  std::array<double, kFaces> face_weight, face_plane;
  int faces = 0;
  const double slack2 = slack * slack;
  within(p, reach, [&](std::int32_t k, const Point3& q, double d2) {
    const Tri& t = tri_[k];
    if (d2 < nearest2) nearest2 = d2, nearest = k, nearest_point = q;
    if (!(d2 <= slack2)) return;
    const Point3 m = unit_normal(t);
    const double w = dot(m, towards);
    if (!(w > 0.0)) return;
    bool seen = false;
    for (int f = 0; f < faces && !seen; ++f) seen = distance2(face_normal[f], m) < 1e-18;
    if (seen || faces == kFaces) return;
    face_normal[faces] = m;
    face_weight[faces] = w;
    face_plane[faces++] = dot(m, sub(p, t.a));
  });
  if (nearest < 0) return false;
  if (nearest2 > slack2) {
    // Off the surface by more than `slack`: the exact distance to the
    // nearest point, on the side the nearest triangle's plane gives.
    const Point3 m = unit_normal(tri_[nearest]);
    const Point3 d = sub(p, nearest_point);
    const double len = std::sqrt(nearest2), side = dot(m, d) < 0.0 ? -1.0 : 1.0;
    *normal = len > 0.0 ? Point3{side * d[0] / len, side * d[1] / len, side * d[2] / len} : m;
    *distance = side * len;
    return true;
  }
  // The normals facing the corner, weighted as box_face_towards weighs a
  // box's (physics/corners.hpp); none facing it: the nearest triangle's.
  Point3 sum{0, 0, 0};
  double wd = 0.0;
  for (int f = 0; f < faces; ++f) {
    for (int c = 0; c < 3; ++c) sum[c] += face_weight[f] * face_normal[f][c];
    wd += face_weight[f] * face_plane[f];
  }
  const double len = norm(sum);
  if (len > 0.0) {
    *normal = {sum[0] / len, sum[1] / len, sum[2] / len};
    *distance = wd / len;
  } else {
    *normal = unit_normal(tri_[nearest]);
    *distance = dot(*normal, sub(p, tri_[nearest].a));
  }
  return true;
}

int SolidMesh::faces_over(const Point3& p, const Point3& towards, double reach, double slack,
                          Point3* normals, double* distances, int max) const {
  // Outside a convex solid a point lies over one face at most, the nearest.
  if (!concave_) return 0;
  int count = 0;
  const double inside2 = 1e-18 * reach * reach;
  within(p, reach, [&](std::int32_t k, const Point3& q, double) {
    const Tri& t = tri_[k];
    const Point3 m = unit_normal(t);
    if (!(dot(m, m) > 0.0)) return;  // a triangle of no area
    const double d = dot(m, sub(p, t.a));
    if (!(d >= -slack && d < reach)) return;
    const Point3 foot{p[0] - d * m[0], p[1] - d * m[1], p[2] - d * m[2]};
    if (!(distance2(foot, q) <= inside2)) return;                  // p is not over the triangle
    if (std::abs(d) <= slack && !(dot(m, towards) > 0.0)) return;  // on it, facing away
    int f = 0;
    while (f < count && !(distance2(normals[f], m) < 1e-18)) ++f;
    if (f < count) {
      distances[f] = std::min(distances[f], d);
    } else if (count < max) {
      normals[count] = m;
      distances[count++] = d;
    }
  });
  return count;
}

}  // namespace sablier
