// The viscous part of the unconstrained velocity (METHOD.md step 3):
// (M + A) u_f = l with a(u, v) = sum_p V_p 2 eta D(u)(x_p) : D(v)(x_p),
// solved matrix-free by Jacobi-preconditioned conjugate gradients over the
// free velocity components of nodes holding mass. Next to thin solids the
// particles' stencils keep to their own side, as in the transfers.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/grid.hpp"
#include "core/particles.hpp"

namespace sablier {

template <int D>
struct ViscousSystem {
  const DenseGrid<D>& grid;
  const Particles<D>& particles;  // sorted by cell
  const std::vector<std::int64_t>& cell_start;
  const std::array<std::vector<std::int64_t>, ipow(2, D)>& cells_by_parity;
  const std::vector<double>& node_mass;  // m_i / rho_0, m^3 (per-particle densities summed in)
  const std::vector<Vec<D>>& free_mask;
  double rho_over_dt;  // rho_0 / dt: M_i = rho_0 node_mass_i / dt = m_i / dt
  double viscosity;    // eta, Pa s
  // Per particle, the corners of its cell across a thin solid (the
  // compatible transfer, physics/thin_solids.cpp); null when none.
  const std::uint8_t* across = nullptr;
};

// On entry u holds the inviscid velocity u0 (= M^{-1} l); on exit the
// solution of (M + A) u = M u0. Returns the CG iterations.
template <int D>
int solve_viscous(const ViscousSystem<D>& sys, std::vector<Vec<D>>& u);

}  // namespace sablier
