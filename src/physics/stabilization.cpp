// The node-to-node stabilisation's cell rows (solver.stabilization;
// solver/cell_rows.hpp, docs/method.md): which cells get one, each step.
#include <algorithm>
#include <cmath>
#include <vector>

#include "physics/simulation.hpp"
#include "solver/cell_rows.hpp"

namespace sablier {
namespace {

// A corner holds sand at rest when full to this fraction of phi_max and
// slower than kStabilizedSpeed sqrt(|g| h) (build_cells).
constexpr double kStabilizedFill = 0.98;
constexpr double kStabilizedSpeed = 0.1;

}  // namespace

// The cell rows of the node-to-node stabilisation (solver/cell_rows.hpp):
// every cell whose 4^d footprint nodes all carry sand rows outside the
// solids (the sand's interior, a cell in from its surface and the box)
// and whose corners hold sand at rest: full (grain volume at least
// kStabilizedFill phi_max V_j: where grains may still compact, node-to-node
// motion is the compaction itself; stabilising it kept beds settling onto
// planes moving at 1.2-4.6 mm/s) and slower than kStabilizedSpeed
// sqrt(|g| h) (stabilising flowing sand slowed silo2d's discharge by 21%;
// docs/method.md). In 4^d colours by cell coordinates mod 4, each colour
// by cell index.
// eta = solver.stabilization rho_0 phi_max h^2 / dt: the rows' damping of
// a node-to-node motion relative to its inertia, 2 eta W_c, does not depend
// on the cell size, the step or the density.
template <int D>
void Simulation<D>::build_cells(double dt) {
  ConeProblem<D>& P = problem_;
  P.cell_base.clear();
  P.cell_colour_start.clear();
  P.cell_stress.clear();
  const double c = scene_.solver.stabilization;
  if (!(c > 0.0)) return;
  const double h = grid_.h();
  P.cell_viscosity = c * rho0_ * phi_max_ * h * h / dt;
  P.cell_volume = std::pow(h, D);
  P.cell_gradient = solver_detail::cell_gradient_table<D>(h);
  // The 4^d nodes around the cell, from one before its lowest corner.
  P.cell_stencil = grid_.template block_offsets<4>(-1);
  constexpr int NF = ConeProblem<D>::NF;
  // Nodes a solid touches (a contact row, or part of the node's volume
  // inside a solid): sand at rest that a solid loads or pushes deforms from
  // node to node there (a box dropped on a bed rested 4 mm above the
  // surface with them stabilised, and sank 0.4 mm into it without).
  touched_.assign(grid_.node_count(), 0);
  for (int j = obstacle_row_start_; j < P.rows(); ++j) touched_[P.node[j]] = 1;
  const auto sand_node = [&](std::int64_t node) {
    const int r = row_of_node_[node];
    if (r < 0 || r >= obstacle_row_start_ || touched_[node]) return false;
    return !row_in_solid_[r] && !(row_solid_[r] > 0.0);
  };
  const double rest_speed = kStabilizedSpeed * std::sqrt(gravity_.norm() * h);
  const auto full_node = [&](std::int64_t node) {
    return node_grain_volume_[node] >= kStabilizedFill * phi_max_ * P.volume[row_of_node_[node]] &&
           node_momentum_[node].norm() <= rest_speed * node_mass_[node];
  };
  const auto corner = grid_.corner_offsets();
  constexpr int colours = ipow(4, D);
  std::vector<std::vector<std::int64_t>> by_colour(colours);
  for (int j = 0; j < obstacle_row_start_; ++j) {
    const std::int64_t base = P.node[j];
    const auto cell = grid_.node_coords(base);
    bool inside = true;
    for (int a = 0; a < D; ++a) inside = inside && cell[a] >= 0 && cell[a] < grid_.cells()[a];
    for (int n = 0; inside && n < NF; ++n) inside = sand_node(base + P.cell_stencil[n]);
    for (int b = 0; inside && b < (1 << D); ++b) inside = full_node(base + corner[b]);
    if (!inside) continue;
    int colour = 0;
    for (int a = D - 1; a >= 0; --a) colour = 4 * colour + cell[a] % 4;
    by_colour[colour].push_back(base);
  }
  P.cell_colour_start.push_back(0);
  for (auto& v : by_colour) {
    std::sort(v.begin(), v.end());
    P.cell_base.insert(P.cell_base.end(), v.begin(), v.end());
    P.cell_colour_start.push_back(static_cast<int>(P.cell_base.size()));
  }
  P.cell_stress.assign(P.cell_base.size(), SymVec<D>::Zero());
}

template void Simulation<2>::build_cells(double);
template void Simulation<3>::build_cells(double);

}  // namespace sablier
