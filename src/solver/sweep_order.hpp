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
#include "solver/zones.hpp"

namespace sablier {
namespace solver_detail {

// The solve's team: one thread per zone, at most spinning_team_limit()
// (solver/team.hpp). Results do not depend on the team's size.
template <int D>
int team_size(const ConeProblem<D>& p) {
  return std::clamp(p.zones, 1, spinning_team_limit());
}

// A thread's part of the sweep order (solver/zones.hpp): the ranges of rows
// it updates, in order, and where it waits for the team. Its zones, then
// the separators between them; then, after the team's barrier, the
// separator after its last zone (between its zones and the next thread's,
// or the trailing one for the last thread); then its share of each colour
// of the contact rows, and the bodies' rows on the first thread. Every
// thread count updates rows that share a velocity in the same order, so
// results do not depend on it. (Before, the separators between threads
// were shared colour by colour, a barrier per colour, and the last thread
// had none: on the 3D bed on two threads they took a fifth of the sweep.)
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
  // Thread rank's first segment of the free velocities (free_velocities:
  // zone z is segment 2 z, the separator after it 2 z + 1).
  int first_segment(int rank) const { return 2 * zones_of(rank).first; }

  // f(j0, j1) on rank's ranges of rows in sweep order; done() after each
  // group of ranges whose rows are independent (rows of one colour of the
  // thread's zones or separators: the slide solves queued in a group are
  // done at its end), wait() where the team synchronises.
  template <class F, class G, class W>
  void walk(int rank, const F& f, const G& done, const W& wait) const {
    const std::vector<int>& cs = p.colour_start;
    // Colour c of the units first ... first + n - 1 (pairwise independent).
    const auto colour = [&](int c, int first, int n) {
      for (int u = first; u < first + n; ++u) {
        const int r = unit_start(u) + c;
        if (cs[r] < cs[r + 1]) f(cs[r], cs[r + 1]);
      }
      done();
    };
    const auto [z0, z1] = zones_of(rank);
    for (int c = 0; c < NC; ++c) colour(c, z0, z1 - z0);
    for (int c = 0; c < NC; ++c) colour(c, zones + z0, z1 - z0 - 1);
    wait();
    if (zones > 1) {
      for (int c = 0; c < NC; ++c) colour(c, zones + z1 - 1, 1);
      wait();
    }
    // The contact rows' colours; the bodies' rows on the first thread.
    const int ncol = static_cast<int>(cs.size()) - 1;
    for (int c = unit_start(sand_units(zones)); c < ncol; ++c) {
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
    for (int k = 0; k < rank; ++k)
      walk(
          k, [&](int j0, int j1) { n += j1 - j0; }, [] {}, [] {});
    return n;
  }
};

// The free velocity nodes (some component with inv_mass > 0) in the order of
// the threads that write them, and their blocks for the sums (anderson.hpp):
// the nodes of the rows of zone 0, separator 0, zone 1, ... separator Z - 1, each
// unit's by node index and in its own blocks (segment_block[s]: the first
// block of the s-th, SweepOrder::first_segment), then any other (the bodies' unknowns). A thread's
// zones and the separators after them are then consecutive, and so are the
// velocities its sweeps write: loops over free nodes hand few velocities
// between cores.
template <int D>
void free_velocities(const ConeProblem<D>& p, std::vector<std::int64_t>& free, SumBlocks& blocks,
                     std::vector<int>& segment_block) {
  constexpr int NC = ConeProblem<D>::NS;
  const std::int64_t nv = static_cast<std::int64_t>(p.velocity.size());
  const auto is_free = [&](std::int64_t i) { return p.inv_mass[i].maxCoeff() > 0.0; };
  const int zones = std::max(p.zones, 1);
  std::vector<char> seen(nv, 0);
  free.clear();
  const int units = sand_units(zones);
  segment_block.assign(units + 1, 0);
  for (int s = 0; s < units; ++s) {
    const int u = s % 2 == 0 ? s / 2 : zones + s / 2;
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
  segment_block[units] = blocks.count();
  for (std::int64_t i = 0; i < nv; ++i)
    if (!seen[i] && is_free(i)) free.push_back(i);
  blocks.add_segment(static_cast<std::int64_t>(free.size()));
}

}  // namespace solver_detail
}  // namespace sablier
