#include "core/distance_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace sablier {

DistanceGrid::DistanceGrid(std::shared_ptr<const SolidMesh> solid, const Point3& lo,
                           const Point3& hi, double spacing, double band)
    : mesh_(std::move(solid)), lo_(lo), h_(spacing), band_(band) {
  const SolidMesh& mesh = *mesh_;
  for (int a = 0; a < 3; ++a)
    n_[a] = std::max(2, static_cast<int>(std::ceil((hi[a] - lo[a]) / spacing)) + 1);
  const std::int64_t total = std::int64_t(n_[0]) * n_[1] * n_[2];
  values_.assign(static_cast<std::size_t>(total), 0.0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t k = 0; k < total; ++k) {
    const std::int64_t i = k % n_[0], j = (k / n_[0]) % n_[1],
                       l = k / (std::int64_t(n_[0]) * n_[1]);
    const Point3 p{lo[0] + i * spacing, lo[1] + j * spacing, lo[2] + l * spacing};
    const double d = mesh.distance(p, nullptr, band);
    values_[static_cast<std::size_t>(k)] = mesh.contains(p) ? -d : d;
  }
  mark_folds();
}

namespace {

// Whether triangle v (unit normal n) meets the cube of half side `half`
// about `centre`: the separating axis test of Akenine-Moller (2001), with
// the cube's three axes, the triangle's normal and the nine cross products
// of the cube's axes with the triangle's edges.
bool triangle_meets_box(const std::array<Point3, 3>& v, const Point3& n, const Point3& centre,
                        double half) {
  std::array<Point3, 3> p{};
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) p[k][a] = v[k][a] - centre[a];
  for (int a = 0; a < 3; ++a) {
    if (std::min({p[0][a], p[1][a], p[2][a]}) > half) return false;
    if (std::max({p[0][a], p[1][a], p[2][a]}) < -half) return false;
  }
  const double plane = n[0] * p[0][0] + n[1] * p[0][1] + n[2] * p[0][2];
  if (std::abs(plane) > half * (std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]))) return false;
  for (int e = 0; e < 3; ++e) {
    const Point3& a = p[e];
    const Point3& b = p[(e + 1) % 3];
    const Point3 f{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    for (int axis = 0; axis < 3; ++axis) {
      // The axis e_axis x f.
      Point3 u{0.0, 0.0, 0.0};
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      u[a1] = -f[a2];
      u[a2] = f[a1];
      double lo = HUGE_VAL, hi = -HUGE_VAL;
      for (const Point3& q : p) {
        const double s = u[0] * q[0] + u[1] * q[1] + u[2] * q[2];
        lo = std::min(lo, s);
        hi = std::max(hi, s);
      }
      const double r = half * (std::abs(u[0]) + std::abs(u[1]) + std::abs(u[2]));
      if (lo > r || hi < -r) return false;
    }
  }
  return true;
}

}  // namespace

// A cell is marked when two triangles pass within a sample of it (they
// meet its box enlarged by a sample on every side) with normals more than
// kFoldAngle apart. The enlargement matters: a thin part's two faces may
// cross neighbouring cells, one each, and the samples of both cells then
// read the distance to the nearer face, which interpolates to the wrong
// sign inside the part. A marked cell keeps the list of the triangles that
// meet its box enlarged by kListReach samples, each with its outward
// normal (outward by the winding number just off its centroid, so that
// either orientation of the mesh gives the same). Serial, in the tree's
// order of the triangles; the triangles met by every cell are counted in
// an array of one integer per cell, freed at the end.
void DistanceGrid::mark_folds() {
  const std::array<int, 3> cells{n_[0] - 1, n_[1] - 1, n_[2] - 1};
  const std::int64_t total = std::int64_t(cells[0]) * cells[1] * cells[2];
  const std::size_t count = mesh_->triangle_count();
  std::vector<Point3> normal(count, Point3{0.0, 0.0, 0.0});
  for (std::size_t t = 0; t < count; ++t) {
    const std::array<Point3, 3> v = mesh_->triangle(t);
    const Point3 n = cross(sub(v[1], v[0]), sub(v[2], v[0]));
    const double len = std::sqrt(dot(n, n));
    if (len > 0.0) normal[t] = {n[0] / len, n[1] / len, n[2] / len};
  }
  // f(t, k) on every cell k whose box, enlarged by `margin` on every side,
  // triangle t meets (t not degenerate).
  const auto each_meeting = [&](double margin, const auto& f) {
    for (std::size_t t = 0; t < count; ++t) {
      const std::array<Point3, 3> v = mesh_->triangle(t);
      const Point3& n = normal[t];
      if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0) continue;  // degenerate: no face
      std::array<int, 3> c0{}, c1{};
      bool outside = false;
      for (int a = 0; a < 3; ++a) {
        const double lo = std::min({v[0][a], v[1][a], v[2][a]}) - margin;
        const double hi = std::max({v[0][a], v[1][a], v[2][a]}) + margin;
        c0[a] = std::max(0, static_cast<int>(std::floor((lo - lo_[a]) / h_)));
        c1[a] = std::min(cells[a] - 1, static_cast<int>(std::floor((hi - lo_[a]) / h_)));
        outside = outside || c0[a] > c1[a];
      }
      if (outside) continue;
      for (int l = c0[2]; l <= c1[2]; ++l)
        for (int j = c0[1]; j <= c1[1]; ++j)
          for (int i = c0[0]; i <= c1[0]; ++i) {
            const Point3 centre{lo_[0] + (i + 0.5) * h_, lo_[1] + (j + 0.5) * h_,
                                lo_[2] + (l + 0.5) * h_};
            if (!triangle_meets_box(v, n, centre, 0.5 * h_ + margin)) continue;
            f(t, static_cast<std::size_t>((std::int64_t(l) * cells[1] + j) * cells[0] + i));
          }
    }
  };
  // Every cell's triangles within kListReach samples (compressed rows over
  // all cells).
  const double reach = kListReach * h_ * (1.0 + 1e-6);
  std::vector<std::int32_t> begin(static_cast<std::size_t>(total) + 1, 0);
  each_meeting(reach, [&](std::size_t, std::size_t k) { ++begin[k + 1]; });
  for (std::size_t k = 1; k < begin.size(); ++k) begin[k] += begin[k - 1];
  std::vector<std::int32_t> met(static_cast<std::size_t>(begin.back()));
  {
    std::vector<std::int32_t> fill(begin.begin(), begin.end() - 1);
    each_meeting(reach, [&](std::size_t t, std::size_t k) {
      met[static_cast<std::size_t>(fill[k]++)] = static_cast<std::int32_t>(t);
    });
  }
  // The marked cells and their lists, their triangles copied.
  const double cos_fold = std::cos(kFoldAngle);
  slot_.assign(static_cast<std::size_t>(total), -1);
  list_begin_.assign(1, 0);
  list_.clear();
  list_distance_.clear();
  triangles_.clear();
  std::vector<std::int32_t> local(count, -1);
  std::vector<Point3> near;
  std::vector<std::pair<double, std::int32_t>> order;  // a list's triangles by their distance
  for (std::size_t k = 0; k < static_cast<std::size_t>(total); ++k) {
    const std::int32_t b = begin[k], e = begin[k + 1];
    if (e - b < 2) continue;
    // The triangles within a sample of the cell, and whether two of them fold.
    const std::size_t i = k % static_cast<std::size_t>(cells[0]),
                      j = (k / static_cast<std::size_t>(cells[0])) %
                          static_cast<std::size_t>(cells[1]),
                      l = k /
                          (static_cast<std::size_t>(cells[0]) * static_cast<std::size_t>(cells[1]));
    const Point3 centre{lo_[0] + (double(i) + 0.5) * h_, lo_[1] + (double(j) + 0.5) * h_,
                        lo_[2] + (double(l) + 0.5) * h_};
    near.clear();
    for (std::int32_t x = b; x < e; ++x) {
      const std::size_t t = static_cast<std::size_t>(met[static_cast<std::size_t>(x)]);
      if (triangle_meets_box(mesh_->triangle(t), normal[t], centre, 1.5 * h_ * (1.0 + 1e-6)))
        near.push_back(normal[t]);
    }
    bool fold = false;
    for (std::size_t x = 0; x < near.size() && !fold; ++x)
      for (std::size_t y = x + 1; y < near.size() && !fold; ++y)
        fold = dot(near[x], near[y]) < cos_fold;
    if (!fold) continue;
    slot_[k] = static_cast<std::int32_t>(list_begin_.size()) - 1;
    for (std::int32_t x = b; x < e; ++x) {
      const std::size_t t = static_cast<std::size_t>(met[static_cast<std::size_t>(x)]);
      if (local[t] < 0) {
        const std::array<Point3, 3> v = mesh_->triangle(t);
        Point3 n = normal[t];
        const Point3 mid{(v[0][0] + v[1][0] + v[2][0]) / 3.0, (v[0][1] + v[1][1] + v[2][1]) / 3.0,
                         (v[0][2] + v[1][2] + v[2][2]) / 3.0};
        const double eps = 1e-6 * h_;
        if (mesh_->contains({mid[0] + eps * n[0], mid[1] + eps * n[1], mid[2] + eps * n[2]}))
          n = {-n[0], -n[1], -n[2]};
        double r2 = 0.0;
        for (const Point3& c : v) r2 = std::max(r2, dot(sub(c, mid), sub(c, mid)));
        std::array<double, 3> angle{};
        for (int c = 0; c < 3; ++c) {
          const Point3 x = sub(v[(c + 1) % 3], v[c]), y = sub(v[(c + 2) % 3], v[c]);
          angle[static_cast<std::size_t>(c)] =
              std::atan2(std::sqrt(dot(cross(x, y), cross(x, y))), dot(x, y));
        }
        local[t] = static_cast<std::int32_t>(triangles_.size());
        triangles_.push_back({v, n, mid, std::sqrt(r2), angle});
      }
      list_.push_back(local[t]);
    }
    // Nearest to the cell's centre first (ties by index), so that the
    // queries' bounds cut the rest early.
    order.clear();
    for (std::size_t x = static_cast<std::size_t>(list_begin_.back()); x < list_.size(); ++x) {
      const Tri& t = triangles_[static_cast<std::size_t>(list_[x])];
      const Point3 r = sub(centre, closest_on_triangle(centre, t.v[0], t.v[1], t.v[2]));
      order.emplace_back(dot(r, r), list_[x]);
    }
    std::sort(order.begin(), order.end());
    for (std::size_t x = 0; x < order.size(); ++x) {
      list_[static_cast<std::size_t>(list_begin_.back()) + x] = order[x].second;
      list_distance_.push_back(std::sqrt(order[x].first));
    }
    list_begin_.push_back(static_cast<std::int32_t>(list_.size()));
  }
}

std::int64_t DistanceGrid::exact_cells() const {
  return static_cast<std::int64_t>(list_begin_.size()) - 1;
}

// The distance in a marked cell (list `slot`) by its triangles: the
// nearest is the surface's nearest if it lies within kListReach samples of
// p (every triangle nearer than that is listed); its side by the angle-
// weighted pseudo-normal of the nearest point's feature (Baerentzen &
// Aanaes 2005): a face's normal, the sum of an edge's two faces' normals,
// or of a vertex's faces' normals weighted by their angles there. Returns
// false when the nearest triangle is further than that, or p lies on the
// surface, or the pseudo-normal leaves the side undecided. p lies
// `off_centre` from the cell's centre, so a triangle D from the centre is
// at least D - off_centre from p: the list, nearest to the centre first,
// is read only as far as a triangle could still be nearer than the best.
bool DistanceGrid::local_distance(std::int32_t slot, const Point3& p, double off_centre,
                                  double* distance, Point3* normal) const {
  const std::int32_t b = list_begin_[static_cast<std::size_t>(slot)],
                     e = list_begin_[static_cast<std::size_t>(slot) + 1];
  // Margins for the rounding of the listed distances and of off_centre.
  const double reach = off_centre * (1.0 + 1e-12) + 1e-12 * h_;
  double best2 = HUGE_VAL;
  Point3 q{};
  std::int32_t nearest = -1;
  TriangleFeature feature = TriangleFeature::Face;
  for (std::int32_t k = b; k < e; ++k) {
    const double beyond = list_distance_[static_cast<std::size_t>(k)] - reach;
    if (beyond > 0.0 && beyond * beyond > best2) break;  // these and the rest are farther
    const Tri& t = triangles_[static_cast<std::size_t>(list_[static_cast<std::size_t>(k)])];
    const double bound = std::sqrt(dot(sub(p, t.centre), sub(p, t.centre))) - t.radius;
    if (bound > 0.0 && bound * bound >= best2) continue;  // no nearer than the best
    TriangleFeature f;
    const Point3 c = closest_on_triangle(p, t.v[0], t.v[1], t.v[2], &f);
    const Point3 r = sub(p, c);
    const double d2 = dot(r, r);
    if (d2 < best2) best2 = d2, q = c, nearest = list_[static_cast<std::size_t>(k)], feature = f;
  }
  const double d = std::sqrt(best2);
  if (nearest < 0 || !(d < kListReach * h_) || !(d > 0.0)) return false;
  const Tri& t = triangles_[static_cast<std::size_t>(nearest)];
  Point3 m = t.n;
  if (feature != TriangleFeature::Face) {
    // The nearest point is a vertex, or on an edge (ends u, w): sum over
    // the listed triangles that have it.
    Point3 u = t.v[0], w = t.v[1];
    bool vertex = true;
    switch (feature) {
      case TriangleFeature::VertexA:
        u = t.v[0];
        break;
      case TriangleFeature::VertexB:
        u = t.v[1];
        break;
      case TriangleFeature::VertexC:
        u = t.v[2];
        break;
      case TriangleFeature::EdgeAB:
        u = t.v[0], w = t.v[1], vertex = false;
        break;
      case TriangleFeature::EdgeBC:
        u = t.v[1], w = t.v[2], vertex = false;
        break;
      default:
        u = t.v[2], w = t.v[0], vertex = false;
        break;
    }
    // A triangle that has q lies no farther from the cell's centre than q.
    const double q_reach =
        (std::sqrt(dot(sub(p, q), sub(p, q))) + off_centre) * (1.0 + 1e-12) + 1e-12 * h_;
    m = {0.0, 0.0, 0.0};
    for (std::int32_t k = b; k < e; ++k) {
      if (list_distance_[static_cast<std::size_t>(k)] > q_reach) break;
      const Tri& o = triangles_[static_cast<std::size_t>(list_[static_cast<std::size_t>(k)])];
      int iu = -1;
      bool has_w = false;
      for (int c = 0; c < 3; ++c) {
        if (o.v[c] == u) iu = c;
        has_w = has_w || o.v[c] == w;
      }
      if (iu < 0 || (!vertex && !has_w)) continue;
      // An edge's two faces count alike.
      const double weight = vertex ? o.angle[static_cast<std::size_t>(iu)] : 1.0;
      for (int c = 0; c < 3; ++c) m[c] += weight * o.n[c];
    }
  }
  const Point3 r = sub(p, q);
  const double side = dot(r, m);
  if (side == 0.0) return false;
  const double s = side > 0.0 ? 1.0 : -1.0;
  *distance = s * d;
  *normal = {s * r[0] / d, s * r[1] / d, s * r[2] / d};
  return true;
}

std::int32_t DistanceGrid::slot_of(const std::array<int, 3>& c) const {
  return slot_[static_cast<std::size_t>((std::int64_t(c[2]) * (n_[1] - 1) + c[1]) * (n_[0] - 1) +
                                        c[0])];
}

bool DistanceGrid::exact_at(const Point3& p) const {
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const double u = (p[a] - lo_[a]) / h_;
    if (!(u >= 0.0 && u <= n_[a] - 1)) return false;  // beyond the sampled box
    c[a] = std::min(static_cast<int>(u), n_[a] - 2);
  }
  return slot_of(c) >= 0;
}

double DistanceGrid::signed_distance(const Point3& p, Point3* normal) const {
  // The nearest point of the sampled box, and the cell holding it.
  double extra2 = 0.0;
  std::array<int, 3> c{};
  std::array<double, 3> t{};
  for (int a = 0; a < 3; ++a) {
    const double top = lo_[a] + (n_[a] - 1) * h_;
    const double q = std::clamp(p[a], lo_[a], top);
    extra2 += (p[a] - q) * (p[a] - q);
    const double u = (q - lo_[a]) / h_;
    c[a] = std::min(static_cast<int>(u), n_[a] - 2);
    t[a] = u - c[a];
  }
  const auto at = [&](int i, int j, int l) {
    return values_[static_cast<std::size_t>((std::int64_t(c[2] + l) * n_[1] + (c[1] + j)) * n_[0] +
                                            (c[0] + i))];
  };
  double v = 0.0;
  std::array<double, 3> g{0.0, 0.0, 0.0};
  for (int l = 0; l < 2; ++l)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const double w[3] = {i ? t[0] : 1.0 - t[0], j ? t[1] : 1.0 - t[1], l ? t[2] : 1.0 - t[2]};
        const double s[3] = {i ? 1.0 : -1.0, j ? 1.0 : -1.0, l ? 1.0 : -1.0};
        const double f = at(i, j, l);
        v += w[0] * w[1] * w[2] * f;
        g[0] += s[0] * w[1] * w[2] * f;
        g[1] += w[0] * s[1] * w[2] * f;
        g[2] += w[0] * w[1] * s[2] * f;
      }
  const double len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  if (len > 0.0) {
    *normal = {g[0] / len, g[1] / len, g[2] / len};
  } else {
    *normal = {0.0, 0.0, 1.0};
  }
  const std::int32_t slot = extra2 > 0.0 ? -1 : slot_of(c);
  if (slot >= 0) {
    // A marked cell: the exact distance, by its own triangles if it can,
    // else by the whole mesh's tree; on the surface itself (d = 0) the
    // interpolated normal stands.
    const Point3 centre{lo_[0] + (c[0] + 0.5) * h_, lo_[1] + (c[1] + 0.5) * h_,
                        lo_[2] + (c[2] + 0.5) * h_};
    double d = 0.0;
    if (local_distance(slot, p, std::sqrt(dot(sub(p, centre), sub(p, centre))), &d, normal))
      return d;
    Point3 q{};
    d = mesh_->distance(p, &q, band_);
    if (!(d < band_)) return v;
    const double s = mesh_->contains(p) ? -1.0 : 1.0;
    if (d > 0.0) *normal = {s * (p[0] - q[0]) / d, s * (p[1] - q[1]) / d, s * (p[2] - q[2]) / d};
    return s * d;
  }
  return v + std::sqrt(extra2);
}

}  // namespace sablier
