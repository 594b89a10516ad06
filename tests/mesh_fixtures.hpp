// Meshes shared by the mesh tests (test_sources.cpp, test_mesh_distance.cpp,
// test_shaped_obstacles.cpp, test_thin_parts.cpp): a subdivided icosahedron
// and an axis-aligned box.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/mesh.hpp"

namespace sablier::test {

using Tri = std::array<Point3, 3>;

// A unit icosahedron whose faces are split in four `levels` times, the new
// vertices pushed out onto the unit sphere: 20 * 4^levels triangles.
inline std::vector<Tri> icosphere(int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const std::vector<Point3> v{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                              {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                              {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                        {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                        {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                        {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  const auto unit = [](const Point3& p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return Point3{p[0] / n, p[1] / n, p[2] / n};
  };
  std::vector<Tri> tris;
  for (const auto& k : f) tris.push_back({unit(v[k[0]]), unit(v[k[1]]), unit(v[k[2]])});
  for (int l = 0; l < levels; ++l) {
    std::vector<Tri> finer;
    for (const Tri& x : tris) {
      const auto mid = [&](int i, int j) {
        return unit({(x[i][0] + x[j][0]) / 2, (x[i][1] + x[j][1]) / 2, (x[i][2] + x[j][2]) / 2});
      };
      const Point3 ab = mid(0, 1), bc = mid(1, 2), ca = mid(2, 0);
      finer.insert(finer.end(), {{x[0], ab, ca}, {ab, x[1], bc}, {ca, bc, x[2]}, {ab, bc, ca}});
    }
    tris = finer;
  }
  return tris;
}

// A triangle soup as a mesh (shared corners repeated, not merged: the
// winding number and the distance do not need them merged).
inline TriangleMesh soup(const std::vector<Tri>& tris) {
  TriangleMesh mesh;
  for (const Tri& t : tris) {
    std::array<std::int32_t, 3> idx;
    for (int k = 0; k < 3; ++k) {
      idx[k] = static_cast<std::int32_t>(mesh.vertices.size());
      mesh.vertices.push_back(t[k]);
    }
    mesh.triangles.push_back(idx);
  }
  return mesh;
}

// The box [lo, hi] as a closed mesh, two outward triangles per face (corner
// index bits: x = 1, y = 2, z = 4).
inline TriangleMesh box_mesh(const Point3& lo, const Point3& hi) {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back({k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]});
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

// Writes a mesh to an OBJ file to the last bit.
inline void write_exact_obj(const std::filesystem::path& path, const TriangleMesh& m) {
  std::ofstream out(path);
  out.precision(17);
  for (const Point3& v : m.vertices) out << "v " << v[0] << " " << v[1] << " " << v[2] << "\n";
  for (const auto& t : m.triangles)
    out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
}

// Writes meshes to one OBJ file (`v` and `f` lines), their vertices
// numbered one after the other.
inline void write_obj(const std::filesystem::path& path, const std::vector<TriangleMesh>& meshes) {
  std::ofstream out(path);
  int base = 1;
  for (const TriangleMesh& m : meshes) {
    for (const Point3& v : m.vertices) out << "v " << v[0] << " " << v[1] << " " << v[2] << "\n";
    for (const auto& t : m.triangles)
      out << "f " << t[0] + base << " " << t[1] + base << " " << t[2] + base << "\n";
    base += static_cast<int>(m.vertices.size());
  }
}

}  // namespace sablier::test
