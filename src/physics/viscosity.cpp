#include "physics/viscosity.hpp"

#include <cmath>

#include "physics/shape.hpp"

namespace sablier {
namespace {

// sum_i a_i . b_i over nodes, in fixed blocks (thread-count independent).
template <int D>
double dot(const std::vector<Vec<D>>& a, const std::vector<Vec<D>>& b) {
  constexpr std::int64_t kBlock = 4096;
  const std::int64_t n = static_cast<std::int64_t>(a.size());
  const std::int64_t nb = (n + kBlock - 1) / kBlock;
  std::vector<double> partial(nb);
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < nb; ++k) {
    double s = 0.0;
    for (std::int64_t i = k * kBlock; i < std::min(n, (k + 1) * kBlock); ++i) s += a[i].dot(b[i]);
    partial[k] = s;
  }
  double total = 0.0;
  for (double s : partial) total += s;
  return total;
}

// out = (M + A) u on free components.
template <int D>
void apply_operator(const ViscousSystem<D>& sys, const std::vector<Vec<D>>& u,
                    std::vector<Vec<D>>& out) {
  constexpr int NC = ipow(2, D);
  const std::int64_t nodes = static_cast<std::int64_t>(u.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nodes; ++i) out[i] = sys.rho_over_dt * sys.node_mass[i] * u[i];
  const auto corner = sys.grid.corner_offsets();
  const double h = sys.grid.h();
  for (const auto& cells : sys.cells_by_parity) {
    const std::int64_t nc = static_cast<std::int64_t>(cells.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t ci = 0; ci < nc; ++ci) {
      const auto cc = sys.grid.cell_coords(cells[ci]);
      const std::int64_t base = sys.grid.cell_base_node(cc);
      for (std::int64_t p = sys.cell_start[cells[ci]]; p < sys.cell_start[cells[ci] + 1]; ++p) {
        Vec<D> local;
        for (int a = 0; a < D; ++a) local[a] = sys.particles.position[p][a] / h - cc[a];
        Q1Stencil<D> s = q1_stencil<D>(local, h);
        if (sys.across != nullptr) keep_corners<D>(sys.across[p], s);
        Mat<D> grad = Mat<D>::Zero();
        for (int c = 0; c < NC; ++c) grad.noalias() += u[base + corner[c]] * s.grad[c].transpose();
        const Mat<D> stress =
            (sys.viscosity * sys.particles.volume[p]) * (grad + grad.transpose());  // 2 eta V D
        for (int c = 0; c < NC; ++c) out[base + corner[c]] += stress * s.grad[c];
      }
    }
  }
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nodes; ++i) out[i] = out[i].cwiseProduct(sys.free_mask[i]);
}

}  // namespace

template <int D>
int solve_viscous(const ViscousSystem<D>& sys, std::vector<Vec<D>>& u) {
  const std::int64_t nodes = static_cast<std::int64_t>(u.size());
  std::vector<Vec<D>> r(nodes), z(nodes), d(nodes), q(nodes);
  // Right-hand side M u0, residual r = b - (M + A) u0 (u0 as the first guess).
  apply_operator(sys, u, q);
  std::vector<double> inv_diag(nodes, 0.0);
  for (std::int64_t i = 0; i < nodes; ++i) {
    const double m = sys.rho_over_dt * sys.node_mass[i];
    r[i] = (m * u[i]).cwiseProduct(sys.free_mask[i]) - q[i];
    inv_diag[i] = m > 0.0 ? 1.0 / m : 0.0;
    z[i] = inv_diag[i] * r[i];
    d[i] = z[i];
  }
  const double b_norm = std::sqrt(dot<D>(r, z));  // scale for the stopping test
  double rz = dot<D>(r, z);
  int it = 0;
  for (; it < 500 && rz > 1e-20 * b_norm * b_norm + 1e-300; ++it) {
    apply_operator(sys, d, q);
    const double alpha = rz / dot<D>(d, q);
    for (std::int64_t i = 0; i < nodes; ++i) {
      u[i] += alpha * d[i];
      r[i] -= alpha * q[i];
      z[i] = inv_diag[i] * r[i];
    }
    const double rz_new = dot<D>(r, z);
    const double beta = rz_new / rz;
    rz = rz_new;
    for (std::int64_t i = 0; i < nodes; ++i) d[i] = z[i] + beta * d[i];
  }
  return it;
}

template int solve_viscous<2>(const ViscousSystem<2>&, std::vector<Vec<2>>&);
template int solve_viscous<3>(const ViscousSystem<3>&, std::vector<Vec<3>>&);

}  // namespace sablier
