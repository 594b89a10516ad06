// The order in which a Gauss-Seidel sweep updates the sand's stress rows:
// zones and separators (cone_problem.hpp, "Zones").
//
// A row at node coordinates c touches the velocity nodes c - 1 ... c + 1 on
// every axis, so two rows share a velocity node only if their coordinates
// differ by at most 2 on every axis. The rows are cut along one axis into
// Z zones separated by separators two node layers thick: rows of different
// zones are then at least 3 layers apart, and so are rows of different
// separators (each zone between two separators is at least 2 layers
// thick; we keep them at least kMinZoneLayers). A sweep updates every zone, each on one thread and
// in its own colour order (the rows of one colour of one zone are independent, which the batched
// slide solves need), then every separator likewise. Only rows of a zone and of the separators on
// either side of it touch the same velocities, and the separators always come after the zones:
// every thread count updates rows that share a velocity in the same order, so the result does not
// depend on it, and threads need to wait for each other only before the separators between them.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/tensor.hpp"

namespace sablier {

struct ZoneLayout {
  // The input rows in sweep order, and runs of them of one colour: run r
  // is order[run_start[r] .. run_start[r + 1]) and has colour r % 3^d (the
  // colour of ConeProblem: node coordinates mod 3). Every unit (a zone or a
  // separator) has its 3^d runs, empty or not: unit u is runs
  // [u 3^d, (u + 1) 3^d). Units [0, zones) are the zones, along `axis` in
  // increasing coordinate, and [zones, 2 zones - 1) the separators, the
  // separator zones + s lying between zones s and s + 1.
  std::vector<int> order;
  std::vector<int> run_start;
  int zones = 1;
  int axis = 0;
};

namespace zone_detail {

// The thinnest zone, in node layers. Two would keep separators apart, but
// the separators' rows (two layers each) would then be a large share of
// the rows, and whole layers of 3D rows are too coarse to balance thin
// zones (3D collapse, 17 layers in 4 zones of 2-4 layers: one thread got
// 14% more rows than the other).
constexpr int kMinZoneLayers = 4;

// First layer of each of the z - 1 separators over the layers' row counts
// `count`, so that each zone with half of each separator beside it holds
// about as many rows as the layers allow; false when the zones between them
// would be thinner than kMinZoneLayers.
inline bool place_separators(const std::vector<int>& count, int z, std::vector<int>& cut) {
  const int layers = static_cast<int>(count.size());
  std::int64_t total = 0;
  for (int c : count) total += c;
  cut.assign(z - 1, 0);
  std::int64_t before = 0;  // rows in layers [0, c)
  int c = 0;
  for (int s = 0; s < z - 1; ++s) {
    const std::int64_t target = total * (s + 1) / z;
    // The separator's middle (after its first layer c) at the target.
    while (c < layers && before + count[c] < target) before += count[c++];
    const int lowest = s == 0 ? kMinZoneLayers : cut[s - 1] + 2 + kMinZoneLayers;
    for (; c < lowest && c < layers; ++c) before += count[c];
    cut[s] = c;
  }
  return z == 1 || cut[z - 2] + 2 + kMinZoneLayers <= layers;
}

}  // namespace zone_detail

// The layout of rows at node coordinates coords[j], each run sorted by
// key[j] (distinct keys: the node index). The zones hold about zone_rows
// rows each: Z is the largest power of two up to rows / zone_rows (so that
// 2, 4, 8 ... threads share them evenly) that the extent along the longest
// axis allows; zone_rows = 0 or fewer than 2 zone_rows rows give one zone.
template <int D>
ZoneLayout zone_layout(const std::vector<std::array<int, D>>& coords,
                       const std::vector<std::int64_t>& key, int zone_rows) {
  constexpr int NC = ipow(3, D);
  const int n = static_cast<int>(coords.size());
  ZoneLayout layout;
  std::array<int, D> lo, hi;
  lo.fill(0);
  hi.fill(0);
  for (int j = 0; j < n; ++j)
    for (int a = 0; a < D; ++a) {
      lo[a] = j == 0 ? coords[j][a] : std::min(lo[a], coords[j][a]);
      hi[a] = j == 0 ? coords[j][a] : std::max(hi[a], coords[j][a]);
    }
  // Not along x: nodes are numbered x first, so the velocities that the
  // zones on either side of a separator write at the same time would share
  // cache lines (measured on the 2D collapse at 5 mm, cut along x: the
  // sweeps took 40% more cycles than cut along y).
  int axis = 1;
  for (int a = 2; a < D; ++a)
    if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
  std::vector<int> count(hi[axis] - lo[axis] + 1, 0);
  for (int j = 0; j < n; ++j) ++count[coords[j][axis] - lo[axis]];
  int z = 1;
  while (zone_rows > 0 && static_cast<std::int64_t>(2) * z * zone_rows <= n) z *= 2;
  std::vector<int> cut;
  while (!zone_detail::place_separators(count, z, cut)) z /= 2;
  layout.zones = z;
  layout.axis = axis;

  // Each row's unit and colour, then a counting sort by (unit, colour) and
  // the key within each run.
  const int units = 2 * z - 1;
  std::vector<int> run(n);
  std::vector<int> size(units * NC + 1, 0);
  for (int j = 0; j < n; ++j) {
    const int c = coords[j][axis] - lo[axis];
    int unit = z - 1;
    for (int s = 0; s < z - 1; ++s) {
      if (c < cut[s]) {
        unit = s;
        break;
      }
      if (c <= cut[s] + 1) {
        unit = z + s;
        break;
      }
    }
    int colour = 0;
    for (int a = D - 1; a >= 0; --a) colour = colour * 3 + coords[j][a] % 3;
    run[j] = unit * NC + colour;
    ++size[run[j] + 1];
  }
  for (int r = 0; r < units * NC; ++r) size[r + 1] += size[r];
  layout.run_start = size;
  layout.order.resize(n);
  for (int j = 0; j < n; ++j) layout.order[size[run[j]]++] = j;
  for (int r = 0; r < units * NC; ++r)
    std::sort(layout.order.begin() + layout.run_start[r],
              layout.order.begin() + layout.run_start[r + 1],
              [&](int a, int b) { return key[a] < key[b]; });
  return layout;
}

}  // namespace sablier
