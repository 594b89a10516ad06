#include "solver/cone_problem.hpp"

#include <cmath>

namespace sablier {

template <int D>
void ConeProblem<D>::resize_rows(int n) {
  node.resize(n);
  coupling.resize(n);
  volume.resize(n);
  k.resize(n);
  aperture.resize(n);
  cohesion.resize(n);
  lambda.resize(n);
  delassus.resize(n);
  state.resize(n);
}

namespace {

// (B u)_j: the symmetric part of sum_i u_i g_ji^T, in basis coordinates.
template <int D>
inline SymVec<D> apply_B(const ConeProblem<D>& p, int j) {
  const Vec<D>* u = p.velocity.data() + p.node[j];
  const auto& g = p.coupling[j];
  Mat<D> L = Mat<D>::Zero();
  for (int s = 0; s < ConeProblem<D>::NS; ++s) L.noalias() += u[p.stencil[s]] * g.col(s).transpose();
  return to_sym<D>(L);
}

// u_i += M_i^{-1} Lambda g_ji over row j's stencil.
template <int D>
inline void scatter_stress(ConeProblem<D>& p, int j, const SymVec<D>& dlambda) {
  const Mat<D> T = from_sym<D>(dlambda);
  Vec<D>* u = p.velocity.data() + p.node[j];
  const Vec<D>* im = p.inv_mass.data() + p.node[j];
  const auto& g = p.coupling[j];
  for (int s = 0; s < ConeProblem<D>::NS; ++s) {
    const std::int64_t o = p.stencil[s];
    u[o] += im[o].cwiseProduct(T * g.col(s));
  }
}

// One exact local update of row j.
template <int D>
inline void update_row(ConeProblem<D>& p, int j) {
  constexpr int SD = sym_size(D);
  using V = Eigen::Matrix<double, SD, 1>;
  const LocalDelassus<SD>& W = p.delassus[j];
  if (W.degenerate) {
    p.state[j] = DPCase::Inactive;
    return;
  }
  V y = apply_B<D>(p, j);
  y[0] += p.k[j];
  y /= p.volume[j];
  const V x_old = W.rotate(p.lambda[j]);
  V b = W.rotate(y) - W.apply_rotated(x_old);
  // Cohesion: the cone's apex sits at lambda = -shift e_0; solve for the
  // shifted stress lambda + shift e_0 (METHOD.md section 1).
  const double shift = p.cohesion[j];
  V e0 = V::Zero();
  e0[0] = shift;
  if (shift != 0.0) b -= W.apply_rotated(e0);
  V x;
  p.state[j] = solve_drucker_prager_rotated<SD>(W, b, p.aperture[j], x);
  x -= e0;
  const V dl = W.unrotate(x - x_old);
  if (dl.squaredNorm() == 0.0) return;
  scatter_stress<D>(p, j, dl);
  p.lambda[j] += dl;
}

// Sum of f(j) over rows in fixed blocks, then the block sums in order: the
// same floating-point result for any thread count.
template <class F>
double deterministic_sum(std::int64_t n, const F& f) {
  constexpr std::int64_t kBlock = 1024;
  const std::int64_t nb = (n + kBlock - 1) / kBlock;
  std::vector<double> partial(nb, 0.0);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < nb; ++b) {
    double s = 0.0;
    const std::int64_t end = std::min(n, (b + 1) * kBlock);
    for (std::int64_t j = b * kBlock; j < end; ++j) s += f(j);
    partial[b] = s;
  }
  double total = 0.0;
  for (double s : partial) total += s;
  return total;
}

}  // namespace

template <int D>
void assemble_delassus(ConeProblem<D>& p) {
  constexpr int SD = sym_size(D);
  const int n = p.rows();
#pragma omp parallel for schedule(static)
  for (int j = 0; j < n; ++j) {
    const auto& g = p.coupling[j];
    const Vec<D>* im = p.inv_mass.data() + p.node[j];
    SymMat<D> W = SymMat<D>::Zero();
    for (int c = 0; c < SD; ++c) {
      SymVec<D> e = SymVec<D>::Zero();
      e[c] = 1.0;
      const Mat<D> T = from_sym<D>(e);
      Mat<D> L = Mat<D>::Zero();
      for (int s = 0; s < ConeProblem<D>::NS; ++s) {
        const Vec<D> du = im[p.stencil[s]].cwiseProduct(T * g.col(s));
        L.noalias() += du * g.col(s).transpose();
      }
      W.col(c) = to_sym<D>(L) / p.volume[j];
    }
    p.delassus[j].set(0.5 * (W + W.transpose()));
  }
}

template <int D>
void apply_stress_to_velocity(ConeProblem<D>& p) {
  const int ncol = static_cast<int>(p.colour_start.size()) - 1;
  for (int c = 0; c < ncol; ++c) {
#pragma omp parallel for schedule(static)
    for (int j = p.colour_start[c]; j < p.colour_start[c + 1]; ++j) {
      if (!p.delassus[j].degenerate && p.lambda[j].squaredNorm() > 0.0)
        scatter_stress<D>(p, j, p.lambda[j]);
    }
  }
}

template <int D>
SolveReport solve_gauss_seidel(ConeProblem<D>& p, double tolerance, int max_iterations) {
  SolveReport report;
  const int n = p.rows();
  if (n == 0) return report;
  const int ncol = static_cast<int>(p.colour_start.size()) - 1;
  const std::int64_t nv = static_cast<std::int64_t>(p.velocity.size());
  // Velocities before any stress acts (u_f) and before the current sweep.
  const std::vector<Vec<D>> u_free = p.velocity;
  std::vector<Vec<D>> u_prev;
  apply_stress_to_velocity(p);  // warm start
  // |a|_M^2 = sum over free components of a^2 / inv_mass (kinetic-energy norm).
  const auto mass_norm2 = [&](const Vec<D>& a, std::int64_t i) {
    double s = 0.0;
    for (int c = 0; c < D; ++c)
      if (p.inv_mass[i][c] > 0.0) s += a[c] * a[c] / p.inv_mass[i][c];
    return s;
  };
  for (int it = 1; it <= max_iterations; ++it) {
    u_prev = p.velocity;
    for (int c = 0; c < ncol; ++c) {
#pragma omp parallel for schedule(static)
      for (int j = p.colour_start[c]; j < p.colour_start[c + 1]; ++j) update_row<D>(p, j);
    }
    const double change = deterministic_sum(
        nv, [&](std::int64_t i) { return mass_norm2(p.velocity[i] - u_prev[i], i); });
    const double correction = deterministic_sum(
        nv, [&](std::int64_t i) { return mass_norm2(p.velocity[i] - u_free[i], i); });
    report.iterations = it;
    report.residual = correction > 0.0 ? std::sqrt(change / correction) : 0.0;
    if (report.residual <= tolerance) break;
  }
  report.hit_cap = report.residual > tolerance;
  for (int j = 0; j < n; ++j) {
    switch (p.state[j]) {
      case DPCase::Slide: ++report.sliding; break;
      case DPCase::Stick: ++report.sticking; break;
      default: ++report.separated; break;
    }
  }
  return report;
}

template <int D>
SymVec<D> row_strain_rate(const ConeProblem<D>& p, int j) {
  SymVec<D> y = apply_B<D>(p, j);
  y[0] += p.k[j];
  return y / p.volume[j];
}

#define SABLIER_INSTANTIATE(D)                                                          \
  template struct ConeProblem<D>;                                                       \
  template void assemble_delassus<D>(ConeProblem<D>&);                                  \
  template void apply_stress_to_velocity<D>(ConeProblem<D>&);                           \
  template SolveReport solve_gauss_seidel<D>(ConeProblem<D>&, double, int);             \
  template SymVec<D> row_strain_rate<D>(const ConeProblem<D>&, int);
SABLIER_INSTANTIATE(2)
SABLIER_INSTANTIATE(3)
#undef SABLIER_INSTANTIATE

}  // namespace sablier
