// Node-to-node stabilisation of the cone problem (ConeProblem, cell rows):
// linear viscous rows on grid cells that resist motions alternating from
// node to node, which the Q1 stress rows hardly see (docs/method.md,
// "Node-to-node stabilisation").
//
// A cell's strain rate is the mean over the cell of the symmetric gradient
// of the bilinear (trilinear) velocity, eps_c = sym(sum_b u_b gbar_b^T) over
// its 2^d corners b, gbar_b the mean gradient of corner b's shape function
// ((2 b_a - 1) / (2^(d-1) h) along axis a). Its smooth part is the average
// of the cell and its 3^d - 1 neighbours with weights (1, 2, 1) / 4 per
// axis (the mean over the cell's corners of each corner's mean over its 2^d
// cells), and its node-to-node part
//   A_c u = eps_c - sum_o w_o eps_{c+o} = sym(sum_n u_n G_n^T)
// over the 4^d nodes n around the cell. A_c vanishes on every affine
// velocity field (the two means agree on a constant gradient), so the rows
// leave uniform flows, rigid motions and smooth shear to second order
// alone; on a strain rate alternating from cell to cell, which the stress
// rows average away, A_c is the cell's strain rate itself. Each row is a
// linear viscosity on it: the stress s_c = -2 eta A_c u (compression
// positive, as the stress rows' lambda) acting on the velocities as
// u += M^{-1} V_c A_c^T s_c, the minimiser of the kinetic energy plus the
// dissipation eta V_c |A_c u|^2 (it dissipates, never injects energy).
// Gauss-Seidel on a row with the others fixed: with y = A_c u and
// W_c = V_c A_c M^{-1} A_c^T, s' = -2 eta (I + 2 eta W_c)^{-1} (y - W_c s).
#pragma once

#include <cstdint>
#include <utility>

#include "core/tensor.hpp"
#include "solver/cone_problem.hpp"
#include "solver/stencil.hpp"
#include "solver/team.hpp"

namespace sablier {
namespace solver_detail {

// The cell rows' gradient table G (ConeProblem::cell_gradient) for cells of
// side h: column n = sum_a (n_a + 1) 4^a is node n (n_a = -1 ... 2 along
// axis a) of the footprint, relative to the cell's lowest corner.
template <int D>
Eigen::Matrix<double, D, ipow(4, D)> cell_gradient_table(double h) {
  constexpr int NF = ipow(4, D);
  Eigen::Matrix<double, D, NF> G = Eigen::Matrix<double, D, NF>::Zero();
  const double scale = 1.0 / (double(ipow(2, D - 1)) * h);
  // Neighbour cells o in {-1, 0, 1}^d, corners b in {0, 1}^d.
  for (int oi = 0; oi < ipow(3, D); ++oi) {
    int o[3] = {0, 0, 0};
    double w = 1.0;
    for (int a = 0, r = oi; a < D; ++a, r /= 3) {
      o[a] = r % 3 - 1;
      w *= o[a] == 0 ? 0.5 : 0.25;
    }
    const bool centre = o[0] == 0 && o[1] == 0 && o[2] == 0;
    const double coef = (centre ? 1.0 : 0.0) - w;
    for (int bi = 0; bi < ipow(2, D); ++bi) {
      int n = 0;
      Vec<D> g;
      for (int a = 0, stride = 1; a < D; ++a, stride *= 4) {
        const int b = bi >> a & 1;
        g[a] = (2 * b - 1) * scale;
        n += (o[a] + b + 1) * stride;
      }
      G.col(n) += coef * g;
    }
  }
  return G;
}

// y = A_c u at the sweeps' velocities.
template <int D>
inline SymVec<D> cell_strain(const ConeProblem<D>& p, int c) {
  Mat<D> L = Mat<D>::Zero();
  const std::int64_t base = p.cell_base[c];
  for (int n = 0; n < ConeProblem<D>::NF; ++n)
    L.noalias() += velocity_at<D>(p, base + p.cell_stencil[n]) * p.cell_gradient.col(n).transpose();
  return to_sym<D>(L);
}

// u_n += M_n^{-1} V_c S G_n over the cell's footprint, S the tensor of ds.
template <int D>
inline void scatter_cell(ConeProblem<D>& p, int c, const SymVec<D>& ds) {
  const Mat<D> S = p.cell_volume * from_sym<D>(ds);
  const std::int64_t base = p.cell_base[c];
  for (int n = 0; n < ConeProblem<D>::NF; ++n) {
    const std::int64_t i = base + p.cell_stencil[n];
    set_velocity_at<D>(
        p, i, velocity_at<D>(p, i) + p.inv_mass[i].cwiseProduct(S * p.cell_gradient.col(n)));
  }
}

// Each cell row's W_c and (I + 2 eta W_c)^{-1}.
template <int D>
void assemble_cells(ConeProblem<D>& p) {
  const int n = p.cells();
  p.cell_delassus.resize(n);
  p.cell_inverse.resize(n);
  p.cell_stress.resize(n, SymVec<D>::Zero());
#pragma omp parallel for schedule(static)
  for (int c = 0; c < n; ++c) {
    const Vec<D>* im = p.inv_mass.data() + p.cell_base[c];
    SymMat<D> W = p.cell_volume * local_delassus<D>(ConeProblem<D>::NF, [&](int f) {
                    return std::pair<Vec<D>, Vec<D>>(im[p.cell_stencil[f]], p.cell_gradient.col(f));
                  });
    W = (0.5 * (W + W.transpose())).eval();
    p.cell_delassus[c] = W;
    p.cell_inverse[c] = (SymMat<D>::Identity() + 2.0 * p.cell_viscosity * W).inverse();
  }
}

// f(c0, c1) on the thread's share of each colour of the cell rows (rows
// of one colour touch disjoint nodes, so the result does not depend on the
// team), then after_colour() on every thread. Colours without rows are
// skipped by every thread alike.
template <int D, class F, class A>
void walk_cells(const ConeProblem<D>& p, const Team& team, const F& f, const A& after_colour) {
  const int colours = static_cast<int>(p.cell_colour_start.size()) - 1;
  for (int k = 0; k < colours; ++k) {
    if (p.cell_colour_start[k] == p.cell_colour_start[k + 1]) continue;
    const auto [c0, c1] = team.split(p.cell_colour_start[k], p.cell_colour_start[k + 1]);
    if (c0 < c1) f(c0, c1);
    after_colour();
  }
}

// Adds every cell row's stress to the velocities (u += M^{-1} V_c A_c^T
// s_c), the team waiting after each colour.
template <int D>
void scatter_cell_stresses(ConeProblem<D>& p, const Team& team) {
  walk_cells<D>(
      p, team,
      [&](int c0, int c1) {
        for (int c = c0; c < c1; ++c) scatter_cell<D>(p, c, p.cell_stress[c]);
      },
      [&] { team.sync(); });
}

// One Gauss-Seidel pass over the cell rows, the team waiting after each
// colour.
template <int D>
void update_cells(ConeProblem<D>& p, const Team& team) {
  const double two_eta = 2.0 * p.cell_viscosity;
  walk_cells<D>(
      p, team,
      [&](int c0, int c1) {
        for (int c = c0; c < c1; ++c) {
          const SymVec<D> y = cell_strain<D>(p, c);
          const SymVec<D>& s = p.cell_stress[c];
          const SymVec<D> next = -two_eta * (p.cell_inverse[c] * (y - p.cell_delassus[c] * s));
          scatter_cell<D>(p, c, next - s);
          p.cell_stress[c] = next;
        }
      },
      [&] { team.sync(); });
}

}  // namespace solver_detail
}  // namespace sablier
