// The contact rows of the cone problem (ConeProblem, frictional obstacles
// and rigid bodies, METHOD.md section 3): their diagonal blocks, their exact
// local update, and the bodies' reaction to them (cone_problem.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/tensor.hpp"
#include "solver/cone_problem.hpp"
#include "solver/drucker_prager.hpp"
#include "solver/stencil.hpp"

namespace sablier {
namespace solver_detail {

// Velocity of a body's point at `arm` from its centre: V + omega x arm. The
// bodies' entries stay in `velocity` during a solve (stencil.hpp,
// velocity_at).
template <int D>
inline Vec<D> body_point_velocity(const ConeProblem<D>& p, std::int64_t v, const Vec<D>& arm) {
  const Vec<D>& V = p.velocity[v];
  const Vec<D>& w = p.velocity[v + 1];
  if constexpr (D == 2) {
    return V + w[0] * Vec<D>(-arm[1], arm[0]);
  } else {
    return V + w.cross(arm);
  }
}

// The body's reaction to force f (the force its contact stress puts on the
// sand node at `arm`): V -= M^{-1} f, omega -= J^{-1} (arm x f), with the
// inverse masses already multiplied by dt (cone_problem.hpp); per component
// where J is diagonal (balls).
template <int D>
inline void push_body(ConeProblem<D>& p, std::int64_t v, const Vec<D>& arm, const Vec<D>& f) {
  p.velocity[v] -= p.inv_mass[v].cwiseProduct(f);
  if constexpr (D == 2) {
    p.velocity[v + 1][0] -= p.inv_mass[v + 1][0] * (arm[0] * f[1] - arm[1] * f[0]);
  } else {
    const std::int64_t b = (v - p.first_body_entry) / 2;
    if (p.spin_diagonal[b]) {
      p.velocity[v + 1] -= p.inv_mass[v + 1].cwiseProduct(arm.cross(f));
    } else {
      p.velocity[v + 1] -= p.spin_inverse[b] * arm.cross(f);
    }
  }
}

// The force a contact row's stress change dl puts on its node, Lambda g_jj.
template <int D>
inline Vec<D> contact_force(const ConeProblem<D>& p, int j, const SymVec<D>& dl) {
  return from_sym<D>(dl) * p.coupling[j].col(ConeProblem<D>::NS / 2);
}

// u_j += M_j^{-1} f for the force f = Lambda g_jj of contact row j
// (contact_force): a contact row's stress moves its own node only (its
// coupling is zero elsewhere). Its stencil is not visited: the rows of a ball
// against a wall or another solid sit on a ghost node beyond the grid's last
// layer, whose stencil leaves the velocity storage.
template <int D>
inline void move_contact_node(ConeProblem<D>& p, int j, const Vec<D>& f) {
  const std::int64_t i = p.node[j];
  Vec<D> u = velocity_at<D>(p, i);
  u += p.inv_mass[i].cwiseProduct(f);
  set_velocity_at<D>(p, i, u);
}

// How much the rows of bodies against solids (on ghost nodes) moved each
// body in a sweep, against how far it moved: per body, the sum of the
// kinetic-energy norms (the residual's, cone_problem.hpp) of the changes
// each row made to its velocities, and those changes' sum. Several rows at
// one point (a corner at a concave fold) can trade stress so that the body
// ends the sweep where it began while each row still moves it; `traded`
// measures that.
template <int D>
struct BodyMoves {
  std::int64_t first = 0;     // the bodies' first velocity entry
  std::vector<Vec<D>> net;    // per entry (V, omega of each body): the summed changes
  std::vector<double> moved;  // per body: the sum of the changes' norms

  void reset(const ConeProblem<D>& p) {
    first = p.first_body_entry;
    const std::int64_t entries = static_cast<std::int64_t>(p.velocity.size()) - first;
    net.assign(entries > 0 ? entries : 0, Vec<D>::Zero());
    moved.assign(net.size() / 2, 0.0);
  }
  // Body v's change from `before` (its entries v, v + 1).
  void add(const ConeProblem<D>& p, std::int64_t v, const Vec<D> (&before)[2]) {
    const Vec<D> d[2] = {p.velocity[v] - before[0], p.velocity[v + 1] - before[1]};
    net[v - first] += d[0];
    net[v - first + 1] += d[1];
    moved[(v - first) / 2] += norm(p, v, d);
  }
  // The sum over bodies of (sum of the norms - norm of the sum)^2, zero
  // where every row moved its body the same way; then starts over.
  double traded(const ConeProblem<D>& p) {
    double t = 0.0;
    for (std::size_t b = 0; b < moved.size(); ++b) {
      if (!(moved[b] > 0.0)) continue;
      Vec<D>* const sum = &net[2 * b];
      const double gap = moved[b] - norm(p, first + 2 * static_cast<std::int64_t>(b), sum);
      t += gap * gap;
      sum[0].setZero();
      sum[1].setZero();
      moved[b] = 0.0;
    }
    return t;
  }

 private:
  // The kinetic-energy norm of a change d of body v's two entries.
  static double norm(const ConeProblem<D>& p, std::int64_t v, const Vec<D>* d) {
    double e = 0.0;
    for (int k = 0; k < 2; ++k)
      for (int c = 0; c < D; ++c)
        if (p.inv_mass[v + k][c] > 0.0) e += d[k][c] * d[k][c] / p.inv_mass[v + k][c];
    return std::sqrt(e);
  }
};

// One exact local update of contact row j (cone_problem.hpp): the Coulomb
// problem y = W r + b, y = F^T u the node's velocity in the contact frame.
// With `moves`, a row between a body and a solid (its node a ghost's, of
// zero inverse mass) records there the changes it made to its bodies.
template <int D>
inline void update_contact_row(ConeProblem<D>& p, int j, BodyMoves<D>* moves = nullptr) {
  const int c = j - p.first_contact;
  const LocalDelassus<D>& W = p.contact_delassus[c];
  if (W.degenerate) {
    p.state[j] = DPCase::Inactive;
    return;
  }
  const Mat<D>& F = p.contact_frame[c];
  const Vec<D> n = F.col(0);
  const Vec<D> r_old = F.transpose() * (from_sym<D>(p.lambda[j]) * n);
  const Vec<D> x_old = W.rotate(r_old);
  const std::int64_t body = j >= p.first_body_row ? p.contact_body[c] : -1;
  const std::int64_t other = j >= p.first_body_row ? p.other_body(c) : -1;
  Vec<D> relative = velocity_at<D>(p, p.node[j]) - p.contact_velocity[c];
  if (body >= 0) relative -= body_point_velocity<D>(p, body, p.contact_arm[c]);
  if (other >= 0) relative += body_point_velocity<D>(p, other, p.contact_other_arm[c]);
  const Vec<D> b = W.rotate(F.transpose() * relative) - W.apply_rotated(x_old);
  Vec<D> x;
  p.state[j] = solve_drucker_prager_rotated<D>(W, b, p.aperture[j], x, p.beta[j]);
  const Vec<D> dr = W.unrotate(x - x_old);
  if (dr.squaredNorm() == 0.0) return;
  const Vec<D> t = F.template rightCols<D - 1>() * dr.template tail<D - 1>();
  const Mat<D> dL = dr[0] * Mat<D>::Identity() + t * n.transpose() + n * t.transpose();
  const SymVec<D> dl = to_sym<D>(dL);
  const Vec<D> f = contact_force<D>(p, j, dl);
  move_contact_node<D>(p, j, f);
  const bool measure = moves && body >= 0 && !(p.inv_mass[p.node[j]].maxCoeff() > 0.0);
  Vec<D> was[2], other_was[2];
  if (measure) {
    was[0] = p.velocity[body], was[1] = p.velocity[body + 1];
    if (other >= 0) other_was[0] = p.velocity[other], other_was[1] = p.velocity[other + 1];
  }
  if (body >= 0) push_body<D>(p, body, p.contact_arm[c], f);
  if (other >= 0) push_body<D>(p, other, p.contact_other_arm[c], -f);
  if (measure) {
    moves->add(p, body, was);
    if (other >= 0) moves->add(p, other, other_was);
  }
  p.lambda[j] += dl;
}

// Each contact row's block (ConeProblem::contact_delassus): W_c = w F^T M^{-1} F
// on the row's own node, w = |g_jj|, and its bodies' shares (below).
template <int D>
void assemble_contacts(ConeProblem<D>& p) {
  const int n = p.rows();
  const int first = std::min(p.first_contact, n);
  p.contact_delassus.resize(n - first);
  constexpr int centre = ConeProblem<D>::NS / 2;
#pragma omp parallel for schedule(static)
  for (int j = first; j < n; ++j) {
    const Mat<D>& F = p.contact_frame[j - first];
    const double w = p.coupling[j].col(centre).norm();
    // Velocity change of the node relative to the contact per unit force:
    // the node's inverse mass, plus the body's (push_body, above):
    // M_b^{-1} + [a]x^T J^{-1} [a]x in 3D, M_b^{-1} + a_perp a_perp^T / J in 2D.
    Mat<D> Wc = w * F.transpose() * p.inv_mass[p.node[j]].asDiagonal() * F;
    const auto add_body = [&](std::int64_t v, const Vec<D>& a) {
      Mat<D> K = p.inv_mass[v].asDiagonal();
      if constexpr (D == 2) {
        const Vec<D> perp(-a[1], a[0]);
        K += p.inv_mass[v + 1][0] * perp * perp.transpose();
      } else {
        Mat<D> A;
        A << 0, -a[2], a[1], a[2], 0, -a[0], -a[1], a[0], 0;  // [a]x
        if (p.spin_diagonal[(v - p.first_body_entry) / 2]) {
          K += A.transpose() * p.inv_mass[v + 1].asDiagonal() * A;
        } else {
          K += A.transpose() * p.spin_inverse[(v - p.first_body_entry) / 2] * A;
        }
      }
      Wc += w * F.transpose() * K * F;
    };
    if (j >= p.first_body_row) {
      const int c = j - first;
      if (p.contact_body[c] >= 0) add_body(p.contact_body[c], p.contact_arm[c]);
      if (p.other_body(c) >= 0) add_body(p.other_body(c), p.contact_other_arm[c]);
    }
    p.contact_delassus[j - first].set(0.5 * (Wc + Wc.transpose()));
  }
}

}  // namespace solver_detail
}  // namespace sablier
