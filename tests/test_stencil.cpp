// The sweeps' gather and scatter (src/solver/stencil.hpp): the AVX2 paths
// give the same bits as the plain loops (so results do not depend on the
// build's instruction set), and both give B u and its transpose's product
// as defined (cone_problem.hpp: (B u)_j = sym(sum_s u_s g_s^T), and the
// stress change's u_s += M_s^{-1} dLambda g_s).
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "solver/stencil.hpp"
#include "stencil_loops.hpp"

namespace sablier {
namespace {

// A grid of n nodes per axis with random velocities and inverse masses (a
// quarter of the components fixed: zero), and a row on every node whose
// stencil stays on the grid, the last of them reaching its last node.
template <int D>
ConeProblem<D> random_problem(unsigned seed) {
  constexpr int n = 6;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ConeProblem<D> p;
  std::int64_t stride[3] = {1, n, n * n};
  int nodes = 1;
  for (int a = 0; a < D; ++a) nodes *= n;
  p.velocity.resize(nodes);
  p.inv_mass.resize(nodes);
  for (auto& v : p.velocity)
    for (int a = 0; a < D; ++a) v[a] = u(rng);
  for (auto& m : p.inv_mass)
    for (int a = 0; a < D; ++a) m[a] = u(rng) > -0.5 ? 1.5 + u(rng) : 0.0;
  for (int k = 0; k < ConeProblem<D>::NS; ++k) {
    int r = k;
    std::int64_t o = 0;
    for (int a = 0; a < D; ++a) {
      o += (r % 3 - 1) * stride[a];
      r /= 3;
    }
    p.stencil[k] = o;
  }
  std::vector<std::int64_t> rows;
  for (int i = 0; i < nodes; ++i) {
    bool inside = true;
    for (int a = 0, r = i; a < D; ++a, r /= n) inside = inside && r % n > 0 && r % n < n - 1;
    if (inside) rows.push_back(i);
  }
  p.resize_rows(static_cast<int>(rows.size()));
  for (std::size_t j = 0; j < rows.size(); ++j) {
    p.node[j] = rows[j];
    for (int e = 0; e < p.coupling[j].size(); ++e) p.coupling[j].data()[e] = u(rng);
  }
  // The sweeps' copies (3D: velocities and inverse masses by component,
  // couplings by stencil line), as the solver makes them.
  solver_detail::velocities_to_axes<D>(p);
  solver_detail::pack_coupling_lines<D>(p, p.rows());
  return p;
}

template <int D>
bool same_bits(const Eigen::Matrix<double, D, 1>& a, const Eigen::Matrix<double, D, 1>& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * D) == 0;
}

template <int D>
void check_paths() {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    ConeProblem<D> lanes = random_problem<D>(seed), loops = lanes;
    std::mt19937 rng(100 + seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    // Rows in turn, each gathering what the rows before it scattered.
    for (int pass = 0; pass < 2; ++pass)
      for (int j = 0; j < lanes.rows(); ++j) {
        const SymVec<D> a = solver_detail::apply_B<D>(lanes, j);
        const SymVec<D> b = stencil_loops::apply_B<D>(loops, j);
        ASSERT_TRUE(same_bits<sym_size(D)>(a, b)) << "gather, row " << j << ", seed " << seed;
        // B u as defined, to round-off.
        Mat<D> L = Mat<D>::Zero();
        for (int s = 0; s < ConeProblem<D>::NS; ++s)
          L += solver_detail::velocity_at<D>(lanes, lanes.node[j] + lanes.stencil[s]) *
               lanes.coupling[j].col(s).transpose();
        EXPECT_LE((a - to_sym<D>(L)).norm(), 1e-13 * (1.0 + L.norm()));
        SymVec<D> dl;
        for (int e = 0; e < sym_size(D); ++e) dl[e] = u(rng);
        std::vector<Vec<D>> before(lanes.velocity.size());
        for (std::size_t i = 0; i < before.size(); ++i)
          before[i] = solver_detail::velocity_at<D>(lanes, std::int64_t(i));
        solver_detail::scatter_stress<D>(lanes, j, dl);
        stencil_loops::scatter_stress<D>(loops, j, dl);
        const Mat<D> T = from_sym<D>(dl);
        for (int s = 0; s < ConeProblem<D>::NS; ++s) {
          const std::int64_t i = lanes.node[j] + lanes.stencil[s];
          const Vec<D> expected =
              before[i] + lanes.inv_mass[i].cwiseProduct(T * lanes.coupling[j].col(s));
          EXPECT_LE((solver_detail::velocity_at<D>(lanes, i) - expected).norm(),
                    1e-13 * (1.0 + expected.norm()));
        }
      }
    for (std::size_t i = 0; i < lanes.velocity.size(); ++i)
      ASSERT_TRUE(same_bits<D>(solver_detail::velocity_at<D>(lanes, std::int64_t(i)),
                               solver_detail::velocity_at<D>(loops, std::int64_t(i))))
          << "scatter, node " << i << ", seed " << seed;
  }
}

TEST(Stencil, LanesMatchLoopsBitForBit2D) { check_paths<2>(); }
TEST(Stencil, LanesMatchLoopsBitForBit3D) { check_paths<3>(); }

}  // namespace
}  // namespace sablier
