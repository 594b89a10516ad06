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
#include <cmath>

namespace sablier {
namespace {

constexpr double kFarRatio = 3.0;
constexpr int kLeafSize = 8;
constexpr int kMaxDepth = 60;  // median splits: depth <= log2(triangles) + 1
constexpr double kPi = 3.14159265358979323846;

Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Point3& a) { return std::sqrt(dot(a, a)); }

// Solid angle of triangle (a, b, c) at the origin, positive when the origin
// sees it counter-clockwise (Van Oosterom & Strackee 1983).
double solid_angle(const Point3& a, const Point3& b, const Point3& c) {
  const double la = norm(a), lb = norm(b), lc = norm(c);
  const double det = dot(a, cross(b, c));
  const double div = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
  return 2.0 * std::atan2(det, div);
}

}  // namespace

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

SolidMesh::SolidMesh(const TriangleMesh& mesh) {
  tri_.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    tri_.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
  lo_ = hi_ = mesh.vertices.empty() ? Point3{0, 0, 0} : mesh.vertices[0];
  for (const Point3& v : mesh.vertices)
    for (int a = 0; a < 3; ++a) lo_[a] = std::min(lo_[a], v[a]), hi_[a] = std::max(hi_[a], v[a]);
  double six_v = 0.0;  // divergence theorem: V = sum a.(b x c) / 6
  for (const Tri& t : tri_) six_v += dot(t.a, cross(t.b, t.c));
  volume_ = std::abs(six_v) / 6.0;
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

}  // namespace sablier
