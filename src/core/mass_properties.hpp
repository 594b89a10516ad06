// Mass properties of uniform solids per unit density: a simple polygon (2D)
// and a closed, consistently oriented triangle mesh (3D), by the divergence
// theorem over signed triangles and tetrahedra from the origin. Either
// orientation gives the same (positive) result.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "core/mesh.hpp"

namespace sablier {

struct MassProperties {
  double measure = 0.0;  // area (m^2) or volume (m^3)
  Point3 centroid{0, 0, 0};
  // About the centroid along the input's axes, per unit density (m^4 in 2D,
  // m^5 in 3D); in 2D only [2][2], about z.
  std::array<std::array<double, 3>, 3> inertia{};
};

// A polygon's corners in order (either orientation; it must not cross
// itself): area A = 1/2 sum c_i, c_i = x_i y_i+1 - x_i+1 y_i, centroid
// sum (p_i + p_i+1) c_i / (6 A), polar moment about the origin
// sum c_i (x_i^2 + x_i x_i+1 + x_i+1^2 + y_i^2 + y_i y_i+1 + y_i+1^2) / 12,
// moved to the centroid by the parallel-axis theorem.
inline MassProperties polygon_mass_properties(const std::vector<std::array<double, 2>>& p) {
  MassProperties m;
  double a2 = 0.0, cx = 0.0, cy = 0.0, j = 0.0;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % n];
    const double c = u[0] * v[1] - v[0] * u[1];
    a2 += c;
    cx += (u[0] + v[0]) * c;
    cy += (u[1] + v[1]) * c;
    j += c * (u[0] * u[0] + u[0] * v[0] + v[0] * v[0] + u[1] * u[1] + u[1] * v[1] + v[1] * v[1]);
  }
  const double area = 0.5 * a2;
  m.centroid = {cx / (3.0 * a2), cy / (3.0 * a2), 0.0};
  const double sign = area < 0.0 ? -1.0 : 1.0;
  m.measure = sign * area;
  const double r2 = m.centroid[0] * m.centroid[0] + m.centroid[1] * m.centroid[1];
  m.inertia[2][2] = sign * (j / 12.0 - area * r2);
  return m;
}

// A closed mesh: volume sum d / 6 over its triangles (a, b, c), d = a . (b x
// c); centroid sum d (a + b + c) / 24 / V; second moments about the origin
// C = sum d / 120 (a a^T + b b^T + c c^T + s s^T), s = a + b + c, moved to
// the centroid (C - V x x^T), and the inertia tensor tr(C) I - C.
inline MassProperties mesh_mass_properties(const TriangleMesh& mesh) {
  MassProperties m;
  double volume = 0.0, c[3] = {0, 0, 0}, C[3][3] = {};
  for (const auto& t : mesh.triangles) {
    const Point3& a = mesh.vertices[t[0]];
    const Point3& b = mesh.vertices[t[1]];
    const Point3& e = mesh.vertices[t[2]];
    const double d = a[0] * (b[1] * e[2] - b[2] * e[1]) - a[1] * (b[0] * e[2] - b[2] * e[0]) +
                     a[2] * (b[0] * e[1] - b[1] * e[0]);
    volume += d / 6.0;
    double s[3];
    for (int k = 0; k < 3; ++k) {
      s[k] = a[k] + b[k] + e[k];
      c[k] += d * s[k] / 24.0;
    }
    for (int r = 0; r < 3; ++r)
      for (int q = 0; q < 3; ++q)
        C[r][q] += d / 120.0 * (a[r] * a[q] + b[r] * b[q] + e[r] * e[q] + s[r] * s[q]);
  }
  const double sign = volume < 0.0 ? -1.0 : 1.0;
  for (int k = 0; k < 3; ++k) m.centroid[k] = c[k] / volume;
  m.measure = sign * volume;
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) C[r][q] = sign * (C[r][q] - volume * m.centroid[r] * m.centroid[q]);
  const double trace = C[0][0] + C[1][1] + C[2][2];
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) m.inertia[r][q] = (r == q ? trace : 0.0) - C[r][q];
  return m;
}

}  // namespace sablier
