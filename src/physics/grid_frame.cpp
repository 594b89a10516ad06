// The grid fields of a frame for the .vti writer (io/grid_frame.hpp): what
// the last step's solve saw and produced on each real node.
#include "io/grid_frame.hpp"

#include "physics/shape.hpp"
#include "physics/simulation.hpp"

namespace sablier {
namespace {

// Position of real node n in the frame's arrays (x fastest, as VTK stores
// ImageData points).
template <int D>
std::size_t frame_index(const typename DenseGrid<D>::IVec& n, const GridFrame& g) {
  std::size_t i = 0;
  for (int a = D - 1; a >= 0; --a) i = i * g.nodes[a] + n[a];
  return i;
}

// Grain volume per node, sum_p V_p N_i(x_p), splatted from the particles as
// the next step's transfer will: for frames before any solve.
template <int D>
void splat_volume(const Particles<D>& particles, const DenseGrid<D>& grid, GridFrame& g) {
  const double h = grid.h();
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const Vec<D>& x = particles.position[p];
    bool outside = false;  // left through a free face: the next sort drops it
    for (int a = 0; a < D; ++a) outside |= !(x[a] >= 0.0 && x[a] <= grid.cells()[a] * h);
    if (outside) continue;
    const auto cell = grid.cell_of(x);
    Vec<D> local;
    for (int a = 0; a < D; ++a) local[a] = x[a] / h - cell[a];
    const Q1Stencil<D> s = q1_stencil<D>(local, h);
    for (int c = 0; c < Q1Stencil<D>::NC; ++c) {
      auto n = cell;
      for (int a = 0; a < D; ++a) n[a] += (c >> a) & 1;
      g.phi[frame_index<D>(n, g)] += particles.volume[p] * s.w[c];
    }
  }
}

}  // namespace

// phi, velocity and pressure come from the last step's grid (its transfer,
// rows and solve), so that pressure = phi Tr(lambda)/d holds node by node
// with the phi written; a frame before any solve gets phi from the
// particles and no velocity or stress.
template <int D>
GridFrame Simulation<D>::grid_frame() const {
  GridFrame g;
  g.dimension = D;
  g.time = time_;
  g.spacing = grid_.h();
  for (int a = 0; a < D; ++a) g.nodes[a] = grid_.cells()[a] + 1;
  const std::size_t n = g.node_count();
  g.phi.assign(n, 0.0);
  g.velocity.assign(n * D, 0.0);
  g.pressure.assign(n, 0.0);
  g.active.assign(n, 0);
  g.regime.assign(n, kNoRow);

  const bool solved = problem_.rows() > 0;
  if (solved) {
    for (std::int64_t idx = 0; idx < grid_.node_count(); ++idx) {
      const auto c = grid_.node_coords(idx);
      if (grid_.is_real_node(c)) g.phi[frame_index<D>(c, g)] = node_mass_[idx];
    }
  } else {
    splat_volume<D>(particles_, grid_, g);
  }
  for (std::int64_t idx = 0; idx < grid_.node_count(); ++idx) {
    const auto c = grid_.node_coords(idx);
    if (grid_.is_real_node(c)) g.phi[frame_index<D>(c, g)] /= grid_.node_volume(c);
  }
  // problem_.node[j] is the velocity index of row j's node: rows sit on the
  // corners of cells holding particles, so always on real nodes.
  for (int j = 0; j < obstacle_row_start_; ++j) {  // sand rows
    const std::int64_t node = problem_.node[j];
    const std::size_t i = frame_index<D>(grid_.node_coords(node), g);
    g.active[i] = 1;
    for (int a = 0; a < D; ++a) g.velocity[i * D + a] = problem_.velocity[node][a];
    g.pressure[i] = row_bulk_stress(j).trace() / D;
    switch (problem_.state[j]) {
      case DPCase::Stick:
        g.regime[i] = kSticking;
        break;
      case DPCase::Slide:
        g.regime[i] = kSliding;
        break;
      default:  // separated, or a row too empty to carry a stress
        g.regime[i] = kSeparated;
        break;
    }
  }
  return g;
}

template GridFrame Simulation<2>::grid_frame() const;
template GridFrame Simulation<3>::grid_frame() const;

}  // namespace sablier
