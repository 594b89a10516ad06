// The `sablier plot` picture: a run's per-step statistics against time.
#pragma once

#include <string>
#include <vector>

#include "io/image.hpp"

namespace sablier {

// The columns of stats.csv that the plot shows, one entry per step.
struct StatsSeries {
  std::vector<double> time, kinetic_energy, potential_energy, iterations, residual, wall_seconds;
  // The grains' volume beyond phi_max, a fraction; empty for a file of a
  // build before the column.
  std::vector<double> overfill;
  // The scene's dimension when known (the run's scene.toml), else 0: 2D
  // energies are per metre of depth, and the energy panel says so.
  int dimension = 0;
};

// Reads stats.csv text, finding the columns by their header names (extra
// columns are ignored, so older and newer files both work). Throws IoError
// naming `source` and the line.
StatsSeries parse_stats_series(const std::string& csv, const std::string& source);

// Stacked panels against time: kinetic + potential and kinetic energy,
// solver iterations per step, residual (log scale), the grains' volume
// beyond phi_max in percent (when the file has the column), wall seconds
// per step.
Canvas plot_stats(const StatsSeries& stats, int width = 800, int height = 900);

// Tick positions for an axis over [lo, hi]: multiples of 1, 2 or 5 x 10^k,
// about `target` of them, the first <= lo and the last >= hi.
std::vector<double> nice_ticks(double lo, double hi, int target = 5);

}  // namespace sablier
