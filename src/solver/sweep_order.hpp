// The order of a Gauss-Seidel sweep over the threads (cone_problem.cpp):
// which rows each thread updates, in which order, where the team waits, and
// which free velocities each thread owns in the loops over them.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "solver/anderson.hpp"
#include "solver/cone_problem.hpp"
#include "solver/team.hpp"

namespace sablier {
namespace solver_detail {

// The solve's team: one thread per zone, at most the run's thread count.
template <int D>
int team_size(const ConeProblem<D>& p) {
  return std::clamp(p.zones, 1, std::max(1, omp_get_max_threads()));
}

// A thread's part of the sweep order (solver/zones.hpp): the ranges of rows
// it updates, in order, and where it waits for the team. Its zones, then
// the separators between them (halves, then middles); after the team's
// barrier, the first half of the separator between its zones and the next
// thread's and the second half of the one below; after another, the middle
// of the first; then its share of each colour of the contact rows, and the
// bodies' rows on the first thread. Every thread count updates rows that
// share a velocity in the same order, so results do not depend on it.
template <int D>
struct SweepOrder {
  static constexpr int NC = ConeProblem<D>::NS;  // runs (colours) per unit
  const ConeProblem<D>& p;
  int size;   // the team
  int zones;  // Z

  SweepOrder(const ConeProblem<D>& problem, int team)
      : p(problem), size(team), zones(std::max(problem.zones, 1)) {}
  Team as(int rank) const { return Team{rank, size, nullptr}; }
  std::pair<int, int> zones_of(int rank) const { return as(rank).split(0, zones); }
  static int unit_start(int u) { return u * NC; }
  // Separator s's units (zones.hpp): first half, second half, middle.
  int half(int s, int which) const { return zones + 3 * s + which; }
  int middle(int s) const { return zones + 3 * s + 2; }
  // The separator between thread k's zones and thread k + 1's.
  int boundary(int k) const { return zones_of(k).second - 1; }
  // The free velocities' segments (free_velocities) start with thread
  // rank's at this one: zone z is segment 4 z, separator s's first half,
  // middle and second half 4 s + 1, 4 s + 2 and 4 s + 3.
  int first_segment(int rank) const {
    const int z0 = zones_of(rank).first;
    return z0 == 0 ? 0 : 4 * z0 - 1;
  }

  // f(j0, j1) on rank's ranges of rows in sweep order; done() after each
  // group of ranges whose rows are independent (rows of one colour of the
  // thread's zones or separators: the slide solves queued in a group are
  // done at its end), wait() where the team synchronises.
  template <class F, class G, class W>
  void walk(int rank, const F& f, const G& done, const W& wait) const {
    const std::vector<int>& cs = p.colour_start;
    // Colour by colour, the n pairwise independent units unit(0) ... unit(n - 1).
    const auto colours = [&](int n, const auto& unit) {
      for (int c = 0; c < NC; ++c) {
        for (int i = 0; i < n; ++i) {
          const int r = unit_start(unit(i)) + c;
          if (cs[r] < cs[r + 1]) f(cs[r], cs[r + 1]);
        }
        done();
      }
    };
    const auto [z0, z1] = zones_of(rank);
    const int inner = z1 - z0 - 1;  // separators between this thread's zones
    colours(z1 - z0, [&](int i) { return z0 + i; });
    colours(2 * inner, [&](int i) { return half(z0 + i / 2, i % 2); });
    colours(inner, [&](int i) { return middle(z0 + i); });
    wait();
    if (size > 1) {
      const bool above = rank + 1 < size, below = rank > 0;
      if constexpr (D == 3) {  // 2D separators are all middle (zones.hpp)
        colours(int(above) + int(below), [&](int i) {
          return i == 0 && above ? half(boundary(rank), 0) : half(boundary(rank - 1), 1);
        });
        wait();
      }
      if (above) colours(1, [&](int) { return middle(boundary(rank)); });
      wait();
    }
    // The contact rows' colours; the bodies' rows on the first thread.
    const int ncol = static_cast<int>(cs.size()) - 1;
    for (int c = unit_start(zones + 3 * (zones - 1)); c < ncol; ++c) {
      const int begin = cs[c], end = cs[c + 1];
      const int split = std::clamp(p.first_body_row, begin, end);
      const auto [c0, c1] = as(rank).split(begin, split);
      if (c0 < c1) f(c0, c1);
      done();
      wait();
      if (split < end) {
        if (rank == 0) f(split, end);
        done();
        wait();
      }
    }
  }
  // The rows of the threads before `rank`.
  int rows_before(int rank) const {
    int n = 0;
    for (int k = 0; k < rank; ++k) walk(k, [&](int j0, int j1) { n += j1 - j0; }, [] {}, [] {});
    return n;
  }
};

// The free velocity nodes (some component with inv_mass > 0) in the order of
// the threads that write them, and their blocks for the sums (anderson.hpp):
// the nodes of the rows of zone 0, separator 0 (first half, middle, second
// half), zone 1, ... zone Z - 1, each segment's by node index and in its own
// blocks (segment_block[s]: the first block of segment s,
// SweepOrder::first_segment), then any other (the bodies' unknowns). A
// thread's segments are then consecutive, and so are the velocities its
// sweeps write: loops over free nodes hand few velocities between cores.
template <int D>
void free_velocities(const ConeProblem<D>& p, std::vector<std::int64_t>& free, SumBlocks& blocks,
                     std::vector<int>& segment_block) {
  constexpr int NC = ConeProblem<D>::NS;
  const std::int64_t nv = static_cast<std::int64_t>(p.velocity.size());
  const auto is_free = [&](std::int64_t i) { return p.inv_mass[i].maxCoeff() > 0.0; };
  const int zones = std::max(p.zones, 1);
  const int segments = 4 * zones - 3;
  std::vector<char> seen(nv, 0);
  free.clear();
  segment_block.assign(segments + 1, 0);
  for (int s = 0; s < segments; ++s) {
    const int z = s / 4, part = s % 4;  // part 0: zone z; 1, 2, 3: separator z
    const int u = part == 0 ? z : zones + 3 * z + (part == 1 ? 0 : part == 2 ? 2 : 1);
    const std::size_t from = free.size();
    for (int j = p.colour_start[u * NC]; j < p.colour_start[(u + 1) * NC]; ++j) {
      const std::int64_t i = p.node[j];
      if (seen[i] || !is_free(i)) continue;
      seen[i] = 1;
      free.push_back(i);
    }
    std::sort(free.begin() + static_cast<std::ptrdiff_t>(from), free.end());
    segment_block[s] = blocks.count();
    blocks.add_segment(static_cast<std::int64_t>(free.size()));
  }
  segment_block[segments] = blocks.count();
  for (std::int64_t i = 0; i < nv; ++i)
    if (!seen[i] && is_free(i)) free.push_back(i);
  blocks.add_segment(static_cast<std::int64_t>(free.size()));
}

}  // namespace solver_detail
}  // namespace sablier
