// The gather and scatter of src/solver/stencil.hpp compiled with their
// plain loops only (tests/stencil_loops.cpp), for tests/test_stencil.cpp.
#pragma once

#include "solver/cone_problem.hpp"

namespace sablier::stencil_loops {

template <int D>
SymVec<D> apply_B(const ConeProblem<D>& p, int j);
template <int D>
void scatter_stress(ConeProblem<D>& p, int j, const SymVec<D>& dlambda);

}  // namespace sablier::stencil_loops
