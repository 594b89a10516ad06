// The sweep order's zones and separators (solver/zones.hpp): the layout
// must keep rows that share a velocity node apart exactly as the solver
// assumes, or parallel sweeps would race and results would depend on the
// thread count. Checked by brute force over every pair of rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "solver/zones.hpp"

namespace sablier {
namespace {

// Rows at coordinates a and b touch a common velocity node (stencils c - 1
// ... c + 1 on every axis).
template <int D>
bool share_a_node(const std::array<int, D>& a, const std::array<int, D>& b) {
  for (int k = 0; k < D; ++k)
    if (std::abs(a[k] - b[k]) > 2) return false;
  return true;
}

// Rows in an irregular blob of a box of `cells` nodes per axis (a random
// subset, as active nodes of a pile with holes), keyed by an x-first index.
template <int D>
void random_rows(std::mt19937& rng, const std::array<int, D>& cells, double fill,
                 std::vector<std::array<int, D>>& coords, std::vector<std::int64_t>& key) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::int64_t total = 1;
  for (int a = 0; a < D; ++a) total *= cells[a];
  for (std::int64_t i = 0; i < total; ++i) {
    if (unit(rng) > fill) continue;
    std::array<int, D> c;
    std::int64_t r = i;
    for (int a = 0; a < D; ++a) {
      c[a] = static_cast<int>(r % cells[a]);
      r /= cells[a];
    }
    coords.push_back(c);
    key.push_back(i);
  }
}

template <int D>
void check_layout(const std::array<int, D>& cells, double fill, int zone_rows, unsigned seed) {
  constexpr int NC = ipow(3, D);
  std::mt19937 rng(seed);
  std::vector<std::array<int, D>> coords;
  std::vector<std::int64_t> key;
  random_rows<D>(rng, cells, fill, coords, key);
  const int n = static_cast<int>(coords.size());
  const ZoneLayout L = zone_layout<D>(coords, key, zone_rows);
  const int Z = L.zones;
  ASSERT_EQ(static_cast<int>(L.run_start.size()), (2 * Z - 1) * NC + 1);
  ASSERT_EQ(L.run_start.back(), n);
  // A permutation of the rows.
  std::vector<int> sorted = L.order;
  std::sort(sorted.begin(), sorted.end());
  for (int j = 0; j < n; ++j) ASSERT_EQ(sorted[j], j);
  // Z: a power of two, at most rows / zone_rows, and not along x.
  EXPECT_EQ(Z & (Z - 1), 0);
  if (zone_rows == 0) {
    EXPECT_EQ(Z, 1);
  } else {
    EXPECT_LE(static_cast<std::int64_t>(Z) * zone_rows, std::max(n, zone_rows));
  }
  EXPECT_NE(L.axis, 0);
  // Each row's run, unit and colour.
  std::vector<int> run_of(n), unit_of(n);
  for (int r = 0; r + 1 < static_cast<int>(L.run_start.size()); ++r)
    for (int i = L.run_start[r]; i < L.run_start[r + 1]; ++i) {
      const int j = L.order[i];
      run_of[j] = r;
      unit_of[j] = r / NC;
      int colour = 0;
      for (int a = D - 1; a >= 0; --a) colour = colour * 3 + coords[j][a] % 3;
      ASSERT_EQ(colour, r % NC);
      if (i > L.run_start[r]) {
        ASSERT_LT(key[L.order[i - 1]], key[j]);  // by key within a run
      }
    }
  // Rows that share a node: same unit (swept in order by one thread), or a
  // zone and a separator next to it (the separators come after the zones).
  // Never two zones, two separators, or a zone and a separator further off.
  int pairs = 0;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      if (!share_a_node<D>(coords[a], coords[b])) continue;
      ++pairs;
      ASSERT_NE(run_of[a], run_of[b]) << "rows of one run share a node";
      const int ua = std::min(unit_of[a], unit_of[b]), ub = std::max(unit_of[a], unit_of[b]);
      if (ua == ub) continue;
      ASSERT_LT(ua, Z) << "two separators share a node";
      ASSERT_GE(ub, Z) << "two zones share a node";
      const int s = ub - Z;  // separator s lies between zones s and s + 1
      ASSERT_TRUE(ua == s || ua == s + 1) << "zone " << ua << " and separator " << s;
    }
  EXPECT_GT(pairs, 0);
}

TEST(Zones, LayoutKeepsRowsThatShareANodeInOrder2D) {
  check_layout<2>({200, 50}, 0.9, 500, 1);  // 4 zones
  check_layout<2>({200, 50}, 0.9, 100, 2);  // 32 zones would be too thin: fewer
  check_layout<2>({60, 12}, 0.7, 50, 3);
  check_layout<2>({40, 40}, 0.5, 0, 4);  // one zone
}

TEST(Zones, LayoutKeepsRowsThatShareANodeInOrder3D) {
  check_layout<3>({20, 10, 24}, 0.9, 500, 5);
  check_layout<3>({12, 30, 8}, 0.8, 100, 6);  // cut along y, the longest of y and z
}

// The zones hold about as many rows each, and as many as asked for.
TEST(Zones, ZonesShareTheRowsEvenly) {
  std::mt19937 rng(7);
  std::vector<std::array<int, 2>> coords;
  std::vector<std::int64_t> key;
  random_rows<2>(rng, {200, 64}, 1.0, coords, key);
  const ZoneLayout L = zone_layout<2>(coords, key, 1000);  // 12,800 rows: 8 zones
  ASSERT_EQ(L.zones, 8);
  EXPECT_EQ(L.axis, 1);
  const int NC = 9;
  for (int z = 0; z < L.zones; ++z) {
    const int rows = L.run_start[(z + 1) * NC] - L.run_start[z * NC];
    // 64 layers: 7 separators of 2 layers, 50 layers of zones, 6 or 7 each.
    EXPECT_GE(rows, 6 * 200) << "zone " << z;
    EXPECT_LE(rows, 7 * 200) << "zone " << z;
  }
}

}  // namespace
}  // namespace sablier
