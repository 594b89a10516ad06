// Under-relaxation of the rows whose case keeps flipping between stick and
// slide within one solve.
//
// Every row's local Drucker-Prager solve is exact, but a row whose block
// W_jj is nearly singular (its stencil's free velocities mostly on one side,
// as next to a stick floor) moves its stick candidate -W_jj^{-1} b by much
// for a small change of b. Across sweeps such a row can cross the cone's
// surface back and forth: the Gauss-Seidel iteration then cycles instead of
// converging, and the Anderson history restarts at every crossing. Measured
// on pile2d: one row next to the floor alternating between stick and slide
// for 1,900 sweeps, the residual wandering at 1e-4 to 1e-3 up to the
// iteration cap (docs/benchmarks.md). A row that keeps flipping (below)
// takes only the fraction ConeProblem::relaxation (solver.relaxation, 0.5 by
// default) of its local change, which damps the cycle: the under-relaxed
// nonlinear Gauss-Seidel of the nonsmooth contact dynamics solvers (Jean
// 1999, "The non-smooth contact dynamics method"), on those rows alone. The
// fixed points are the same: a row whose local solve returns its own stress
// has a zero change either way. The relaxed stress is projected back into
// the row's cone (it may start outside after Anderson mixing), so the
// solver's answer stays feasible.
#pragma once

#include <cmath>

#include "solver/cone_problem.hpp"

namespace sablier {

inline constexpr int kRelaxAfterFlips = 3;
inline constexpr int kCalmSweeps = 16;

// The Euclidean projection of x onto the cone |x_T| <= aperture x_N (x_N the
// coordinate 0, x_T the others; aperture > 0).
template <int S>
inline void project_onto_cone(Eigen::Matrix<double, S, 1>& x, double aperture) {
  const double t = x.template tail<S - 1>().norm();
  if (t <= aperture * x[0]) return;
  if (aperture * t <= -x[0]) {
    x.setZero();
    return;
  }
  const double n = (x[0] + aperture * t) / (1.0 + aperture * aperture);
  x.template tail<S - 1>() *= aperture * n / t;
  x[0] = n;
}

// Records sand row j's next case; true when the row is relaxed: it has
// flipped between stick and slide kRelaxAfterFlips times, with at most
// kCalmSweeps other updates between flips (a row that settles is no longer
// relaxed once it has been calm for longer: relaxing every row that has
// ever flipped slows the long solves that build a stress field from rest,
// where many rows change case a few times on the way, docs/benchmarks.md).
// Nothing is counted when the solver does not relax (relaxation = 1).
template <int D>
inline bool relaxed_row(ConeProblem<D>& p, int j, DPCase next) {
  if (p.relaxation >= 1.0) return false;
  const DPCase prev = p.state[j];
  const bool flip = (prev == DPCase::Stick && next == DPCase::Slide) ||
                    (prev == DPCase::Slide && next == DPCase::Stick);
  if (flip) {
    if (p.flips[j] < kRelaxAfterFlips) ++p.flips[j];
    p.calm[j] = 0;
  } else if (p.calm[j] <= kCalmSweeps && ++p.calm[j] > kCalmSweeps) {
    p.flips[j] = 0;
  }
  return p.flips[j] >= kRelaxAfterFlips;
}

// Relaxed row j's change for the local change dl: lambda + relaxation dl,
// projected into the row's cone (apex at -cohesion e_0), less lambda. Only
// rows with friction stick, so only they are relaxed: aperture > 0.
template <int D>
inline SymVec<D> relaxed_change(const ConeProblem<D>& p, int j, const SymVec<D>& dl) {
  SymVec<D> x = p.lambda[j] + p.relaxation * dl;
  x[0] += p.cohesion[j];
  project_onto_cone<sym_size(D)>(x, p.aperture[j]);
  x[0] -= p.cohesion[j];
  return x - p.lambda[j];
}

// Sand row j's local change dl as it goes to case `next`, relaxed if the
// row is (relaxed_row's bookkeeping: called once per update of the row).
template <int D>
inline void relax(ConeProblem<D>& p, int j, DPCase next, SymVec<D>& dl) {
  if (relaxed_row<D>(p, j, next)) dl = relaxed_change<D>(p, j, dl);
}

}  // namespace sablier
