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

// Rows of unit u (runs [u 3^d, (u + 1) 3^d)).
template <int D>
int unit_rows(const ZoneLayout& L, int u) {
  constexpr int NC = ipow(3, D);
  return L.run_start[(u + 1) * NC] - L.run_start[u * NC];
}

// The summed cost of unit u's rows.
template <int D>
std::int64_t unit_cost(const ZoneLayout& L, const std::vector<int>& cost, int u) {
  constexpr int NC = ipow(3, D);
  std::int64_t c = 0;
  for (int i = L.run_start[u * NC]; i < L.run_start[(u + 1) * NC]; ++i) c += cost[L.order[i]];
  return c;
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
  ASSERT_EQ(static_cast<int>(L.run_start.size()), sand_units(Z) * NC + 1);
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

// The zones hold about as many rows each, and as many as asked for: each
// zone with the separator after it (a thread's share of a sweep) holds the
// rows divided by the zones, and each separator as many as the others, to
// within a line of rows along x (the cuts fall between lines, here single
// nodes, not only between layers).
TEST(Zones, ZonesShareTheRowsEvenly) {
  std::mt19937 rng(7);
  std::vector<std::array<int, 2>> coords;
  std::vector<std::int64_t> key;
  random_rows<2>(rng, {200, 64}, 1.0, coords, key);
  const ZoneLayout L = zone_layout<2>(coords, key, 1000);  // 12,800 rows: 8 zones
  ASSERT_EQ(L.zones, 8);
  EXPECT_EQ(L.axis, 1);
  for (int z = 0; z < L.zones; ++z) {
    EXPECT_NEAR(unit_rows<2>(L, z) + unit_rows<2>(L, L.zones + z), 12800 / 8, 1) << "zone " << z;
    // Two layers and two nodes between zones; the trailing one as many.
    EXPECT_EQ(unit_rows<2>(L, L.zones + z), 402) << "separator " << z;
  }
}

// A 3D bed of 51 x 11 x 15 nodes (the benchmark's Bed3DPaperSize): two
// zones cut along z, 15 layers of 11 lines of 51 rows. Whole layers gave
// the threads 3,927 + 561 and 3,366 + 561 rows (the separator between them
// shared); cut between lines, each thread's zone and separator differ
// from the other's by at most a line.
TEST(Zones, BedSplitsToALine3D) {
  std::mt19937 rng(8);
  std::vector<std::array<int, 3>> coords;
  std::vector<std::int64_t> key;
  random_rows<3>(rng, {51, 11, 15}, 1.0, coords, key);
  const ZoneLayout L = zone_layout<3>(coords, key, 500);
  ASSERT_EQ(L.zones, 2);
  EXPECT_EQ(L.axis, 2);
  EXPECT_EQ(unit_rows<3>(L, 2), 51 * (2 * 11 + 2));   // between the zones
  EXPECT_EQ(unit_rows<3>(L, 3), unit_rows<3>(L, 2));  // the trailing one
  EXPECT_LE(std::abs(unit_rows<3>(L, 0) - unit_rows<3>(L, 1)), 51);
}

// The cuts balance costs, not rows: the same bed with its top three layers
// costing 2 per row and the others 5 (the solver's costs of rows that start
// without stress and with it, solver/zones.hpp, zone_row_cost). Each thread's zone and
// separator then cost the same to within a line's cost (51 x 5), and so do
// the two separators, the trailing one (at the top) holding more rows.
TEST(Zones, CutsBalanceCosts3D) {
  std::mt19937 rng(8);
  std::vector<std::array<int, 3>> coords;
  std::vector<std::int64_t> key;
  random_rows<3>(rng, {51, 11, 15}, 1.0, coords, key);
  std::vector<int> cost(coords.size());
  for (std::size_t j = 0; j < coords.size(); ++j) cost[j] = coords[j][2] >= 12 ? 2 : 5;
  const ZoneLayout L = zone_layout<3>(coords, key, 500, cost);
  ASSERT_EQ(L.zones, 2);
  const std::int64_t line = 51 * 5;
  EXPECT_LE(std::abs((unit_cost<3>(L, cost, 0) + unit_cost<3>(L, cost, 2)) -
                     (unit_cost<3>(L, cost, 1) + unit_cost<3>(L, cost, 3))),
            line);
  EXPECT_LE(std::abs(unit_cost<3>(L, cost, 2) - unit_cost<3>(L, cost, 3)), line);
  EXPECT_EQ(unit_rows<3>(L, 2), 51 * (2 * 11 + 2));
  EXPECT_GT(unit_rows<3>(L, 3), unit_rows<3>(L, 2));
  // Without costs the two separators hold the same rows (BedSplitsToALine3D).
}

// 2D rows weigh by the case they ended the last solve in (zone_row_cost):
// a 200 x 64 block whose upper half slid and lower half stuck, in two
// zones. The thread with the sliding half gets fewer rows, and each
// thread's zone and separator cost the same to within a row's cost (the
// cuts fall between single nodes in 2D), and so do the two separators.
// 3D counts stressed rows alike whatever their case (the twenty-fourth
// session's rule, kept).
TEST(Zones, SlidingRowsWeighMore2D) {
  std::mt19937 rng(9);
  std::vector<std::array<int, 2>> coords;
  std::vector<std::int64_t> key;
  random_rows<2>(rng, {200, 64}, 1.0, coords, key);
  std::vector<int> cost(coords.size());
  for (std::size_t j = 0; j < coords.size(); ++j)
    cost[j] = zone_row_cost<2>(true, coords[j][1] >= 32 ? DPCase::Slide : DPCase::Stick);
  const ZoneLayout L = zone_layout<2>(coords, key, 4000, cost);
  ASSERT_EQ(L.zones, 2);
  const int slide = zone_row_cost<2>(true, DPCase::Slide);
  EXPECT_GT(slide, 2 * zone_row_cost<2>(true, DPCase::Stick));
  EXPECT_GT(zone_row_cost<2>(true, DPCase::Separation),
            zone_row_cost<2>(false, DPCase::Separation));
  EXPECT_LE(std::abs((unit_cost<2>(L, cost, 0) + unit_cost<2>(L, cost, 2)) -
                     (unit_cost<2>(L, cost, 1) + unit_cost<2>(L, cost, 3))),
            slide);
  EXPECT_LE(std::abs(unit_cost<2>(L, cost, 2) - unit_cost<2>(L, cost, 3)), slide);
  EXPECT_GT(unit_rows<2>(L, 0) + unit_rows<2>(L, 2),
            unit_rows<2>(L, 1) + unit_rows<2>(L, 3) + 2000);
  EXPECT_EQ(zone_row_cost<3>(true, DPCase::Slide), zone_row_cost<3>(true, DPCase::Stick));
  EXPECT_LT(zone_row_cost<3>(false, DPCase::Separation),
            zone_row_cost<3>(true, DPCase::Separation));
}

}  // namespace
}  // namespace sablier
