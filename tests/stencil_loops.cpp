// src/solver/stencil.hpp without its AVX2 paths (SABLIER_STENCIL_LOOPS), its
// namespace renamed so that these inline functions do not stand in for the
// solver's at link time (tests/test_stencil.cpp compares the two).
#include "stencil_loops.hpp"

#define SABLIER_STENCIL_LOOPS 1
#define solver_detail solver_detail_loops
#include "solver/stencil.hpp"
#undef solver_detail

namespace sablier::stencil_loops {

template <int D>
SymVec<D> apply_B(const ConeProblem<D>& p, int j) {
  return solver_detail_loops::apply_B<D>(p, j);
}
template <int D>
void scatter_stress(ConeProblem<D>& p, int j, const SymVec<D>& dlambda) {
  solver_detail_loops::scatter_stress<D>(p, j, dlambda);
}

template SymVec<2> apply_B<2>(const ConeProblem<2>&, int);
template SymVec<3> apply_B<3>(const ConeProblem<3>&, int);
template void scatter_stress<2>(ConeProblem<2>&, int, const SymVec<2>&);
template void scatter_stress<3>(ConeProblem<3>&, int, const SymVec<3>&);

}  // namespace sablier::stencil_loops
