#include "core/distance_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sablier {

DistanceGrid::DistanceGrid(const SolidMesh& mesh, const Point3& lo, const Point3& hi,
                           double spacing, double band)
    : lo_(lo), h_(spacing) {
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
  return v + std::sqrt(extra2);
}

}  // namespace sablier
