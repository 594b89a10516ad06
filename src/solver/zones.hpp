// The order in which a Gauss-Seidel sweep updates the sand's stress rows:
// zones and separators (cone_problem.hpp, "Zones").
//
// A row at node coordinates c touches the velocity nodes c - 1 ... c + 1 on
// every axis, so two rows share a velocity node only if their coordinates
// differ by at most 2 on every axis. The rows are cut along one axis into
// Z zones, each followed by a separator: those between zones are two node
// layers and two lines thick (the cuts fall between lines of rows along x,
// zone_layout), so rows of different zones differ by 3 or more on one axis,
// and so do rows of different separators (each zone is at least
// kMinZoneLayers layers thick); the last one takes the rows after the last
// zone. A sweep updates every zone, each on one thread and in its own
// colour order (the rows of one colour of one zone are independent, which
// the batched slide solves need), then every separator likewise. Only rows
// of a zone and of the separators on either side of it touch the same
// velocities, and the separators always come after the zones: every thread
// count updates rows that share a velocity in the same order, so the result
// does not depend on it. Each thread's zones and separators cost about as
// much as the others' (rows weighted by the caller's estimate of their
// time), so the threads wait for each other little, and only twice a sweep
// (before the separators, and after them).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/tensor.hpp"
#include "solver/drucker_prager.hpp"

namespace sablier {

struct ZoneLayout {
  // The input rows in sweep order, and runs of them of one colour: run r
  // is order[run_start[r] .. run_start[r + 1]) and has colour r % 3^d (the
  // colour of ConeProblem: node coordinates mod 3). Every unit (a zone or a
  // separator) has its 3^d runs, empty or not: unit u is runs
  // [u 3^d, (u + 1) 3^d). Units [0, zones) are the zones, along `axis` in
  // increasing coordinate, and [zones, 2 zones) the separators, the
  // separator zones + s lying between zones s and s + 1, and the last one
  // (zones + zones - 1) after the last zone; with one zone, that zone is the
  // only unit (sand_units).
  std::vector<int> order;
  std::vector<int> run_start;
  int zones = 1;
  int axis = 0;
};

// Units of the sand's rows: the zones and their separators, or the one zone.
inline int sand_units(int zones) { return zones > 1 ? 2 * zones : 1; }

namespace zone_detail {

// The thinnest zone, in node layers. Two would keep separators apart, but
// the separators' rows would then be a large share of the rows (3D
// collapse, 17 layers: 4 zones of 2-4 layers).
constexpr int kMinZoneLayers = 4;

// The separators' lines over the lines' costs `count` (the sums of their
// rows' costs): separator s is lines [first[s], last[s]), `width` lines for
// s < z - 1 (between zones s and s + 1), the trailing one (s = z - 1) the
// lines after the last zone. Each zone with the separator after it costs
// about n / z (n the total) and each separator about as much as the others
// (z = 1: nothing), so that the threads' zones and their separators balance
// as the lines allow. A zone holds at least `min_zone` lines; false when z
// zones do not fit.
inline bool place_separators(const std::vector<std::int64_t>& count, int z, int width, int min_zone,
                             std::vector<int>& first, std::vector<int>& last) {
  const int lines = static_cast<int>(count.size());
  std::vector<std::int64_t> before(lines + 1, 0);  // rows in lines [0, k)
  for (int k = 0; k < lines; ++k) before[k + 1] = before[k] + count[k];
  const std::int64_t n = before[lines];
  first.assign(z, lines);
  last.assign(z, lines);
  std::int64_t separated = 0;  // rows of the separators between zones
  for (int s = 0; s + 1 < z; ++s) {
    // The separator ending nearest (s + 1) n / z: rows before its end grow
    // with its first line c.
    const std::int64_t target = n * (s + 1) / z;
    const int lowest = s == 0 ? min_zone : last[s - 1] + min_zone;
    if (lowest + width > lines) return false;
    int c = lowest;
    while (c + width < lines && before[c + width + 1] <= target) ++c;
    if (c + width < lines && before[c + width + 1] - target < target - before[c + width]) ++c;
    first[s] = c;
    last[s] = c + width;
    separated += before[last[s]] - before[first[s]];
  }
  if (z == 1) return true;
  // The trailing separator: the lines after the last zone holding the mean
  // of the others' rows.
  const std::int64_t mean = separated / (z - 1);
  const int lowest = last[z - 2] + min_zone;
  if (lowest > lines) return false;
  int c = lines;
  while (c > lowest && n - before[c - 1] <= mean) --c;
  first[z - 1] = c;
  return true;
}

}  // namespace zone_detail

// What a sand row costs a sweep, for the zones' cuts (zone_layout), by
// what is known before the solve: [0] no warm-start stress (a row that
// stays separated skips its scatter, the larger half of its time); with
// one, the case the row ended the last solve in: [1] separated or none
// known, [2] stick, [3] slide.
// 3D: 2 without stress and 5 with, whatever the case (on the benchmark's
// 3D bed, whose top layers separate, counting rows alone left the thread
// whose separator held them idle for about 7% of a sweep; twenty-fourth
// session). 2D: the cycles a row update took by case (one thread, 5 mm
// collapse: separated 49, stick 60, slide 285, rotated problem and batched
// slide solve) plus the mixing's per row (about 30), in tens of cycles: a
// slide costs three times a stick, and with the old 3D rule the upper zones
// of the 5 mm collapse, which slide, took 20-35% more cycles than the lower
// ones (time-stamp counter, either thread on either core), and their thread
// kept the other waiting; with these costs a sweep took 4-5% less time
// (docs/benchmarks.md, twenty-sixth session). In 3D the same rule made no
// difference that the guest's noise let us see.
template <int D>
constexpr int kZoneCost[4] = {2, 5, 5, 5};
template <>
constexpr int kZoneCost<2>[4] = {8, 9, 10, 28};
template <int D>
constexpr int zone_row_cost(bool stressed, DPCase last) {
  return kZoneCost<D>[!stressed ? 0 : last == DPCase::Stick ? 2 : last == DPCase::Slide ? 3 : 1];
}

// The layout of rows at node coordinates coords[j], each run sorted by
// key[j] (distinct keys: the node index). The zones hold about zone_rows
// rows each: Z is the largest power of two up to rows / zone_rows (so that
// 2, 4, 8 ... threads share them evenly) that the extent along the longest
// axis allows; zone_rows = 0 or fewer than 2 zone_rows rows give one zone.
// The cuts balance the rows' costs cost[j] (positive; empty: each row
// costs 1), the time a sweep spends on them as far as the caller can tell.
template <int D>
ZoneLayout zone_layout(const std::vector<std::array<int, D>>& coords,
                       const std::vector<std::int64_t>& key, int zone_rows,
                       const std::vector<int>& cost = {}) {
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
  // The cuts fall between lines of rows along x, not only between layers:
  // a row's line is its coordinate along `axis` times the lines per layer
  // plus its coordinate along `across` (the other axis that is not x in 3D;
  // x itself in 2D), so that zones balance to a line (whole layers left
  // the bed's two zones 3,927 and 3,366 rows). Two rows share a velocity
  // node only if both coordinates differ by at most 2, so their lines
  // differ by at most 2 per_layer + 2; a separator of 2 per_layer + 2 lines
  // puts the lines of two zones' rows at least 2 per_layer + 3 apart.
  const int across = D == 3 ? 3 - axis : 0;
  const int per_layer = hi[across] - lo[across] + 1;
  const auto line_of = [&](int j) {
    return (coords[j][axis] - lo[axis]) * per_layer + (coords[j][across] - lo[across]);
  };
  const int width = 2 * per_layer + 2;
  const int min_zone = zone_detail::kMinZoneLayers * per_layer;
  std::vector<std::int64_t> count((hi[axis] - lo[axis] + 1) * per_layer, 0);
  for (int j = 0; j < n; ++j) count[line_of(j)] += cost.empty() ? 1 : cost[j];
  int z = 1;
  while (zone_rows > 0 && static_cast<std::int64_t>(2) * z * zone_rows <= n) z *= 2;
  std::vector<int> first, last;
  while (!zone_detail::place_separators(count, z, width, min_zone, first, last)) z /= 2;
  layout.zones = z;
  layout.axis = axis;

  // Each row's unit and colour, then a counting sort by (unit, colour) and
  // the key within each run.
  const int units = sand_units(z);
  std::vector<int> run(n);
  std::vector<int> size(units * NC + 1, 0);
  for (int j = 0; j < n; ++j) {
    const int c = line_of(j);
    int unit = units - 1;  // every row breaks out below (one zone: first[0] = lines)
    for (int s = 0; s < z; ++s) {
      if (c < first[s]) {
        unit = s;
        break;
      }
      if (c < last[s]) {
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
