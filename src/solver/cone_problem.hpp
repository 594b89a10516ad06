// The reduced cone complementarity problem of one time step (METHOD.md
// section 2, steps 4-6) and its block Gauss-Seidel solver. The solver sees
// velocity unknowns, inverse masses, stress rows and cones: no particles.
//
// Notation. Velocity unknowns u_i (dense, ghost-padded node space) with
// inverse mass M_i^{-1} = dt / (rho m_i), per component, zero on constrained
// components (METHOD.md step 6). Stress row j couples to the 3^d velocity
// nodes of its stencil through vectors g_ji = sum_p V_p N_j(x_p) grad N_i(x_p),
// so that (B u)_j = sym(sum_i u_i g_ji^T) and the stress force on node i is
// f_i = sum_j Lambda_j g_ji (Lambda_j the tensor of lambda_j). Then
//   u      = u_f + M^{-1} f(lambda),
//   gamma_j = ((B u)_j + k_j e_0) / V_j,   (S gamma = B u + k, S_j = V_j)
// and gamma_j = W_jj lambda_j + b_j with the symmetric positive semi-definite
// diagonal block W_jj = (1/V_j) sum_i sym((M_i^{-1} Lambda g_ji) g_ji^T). The
// node-wise scaling by S^{1/2} of METHOD.md leaves each local problem's
// solution unchanged (cones are invariant under positive scaling), so rows are
// solved in physical units: lambda in Pa (per unit grain volume), gamma in 1/s.
// W = H H^T is never assembled: u is kept up to date and gamma_j read from it.
//
// Extra rows (frictional obstacles, METHOD.md section 3) have the same form
// gamma_RB = sym(vbar n^T) = sym(sum_i u_i (w_ji n)^T): a row with its own
// coupling vectors and aperture. Rigid bodies add velocity unknowns with their
// own inverse inertia (appended to `velocity`, below); both slot into this
// layout as further rows and unknowns.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/tensor.hpp"
#include "solver/drucker_prager.hpp"

namespace sablier {

struct SolveReport {
  int iterations = 0;     // Gauss-Seidel sweeps
  double residual = 0.0;  // relative velocity change of the last sweep (see below)
  bool hit_cap = false;   // stopped at max_iterations above tolerance
  int sliding = 0, sticking = 0, separated = 0;  // node cases after the solve
};

template <int D>
struct ConeProblem {
  static constexpr int SD = sym_size(D);
  static constexpr int NS = ipow(3, D);  // stencil size
  using Coupling = Eigen::Matrix<double, D, NS>;

  // Velocity unknowns.
  std::vector<Vec<D>> velocity;  // in: unconstrained velocity u_f; out: u
  std::vector<Vec<D>> inv_mass;  // dt / (rho m_i) on free components, else 0
  std::array<std::int64_t, NS> stencil{};  // velocity index offsets of a row's stencil

  // The sweeps' own copy of the velocities in 3D (solver/stencil.hpp): one
  // array per component (velocity_by_axis[c][i] = velocity[i][c]), so that
  // each line of a stencil, three nodes along x at consecutive indices, is
  // one four-lane load per component. The solver fills it from `velocity`
  // when it starts, and `velocity` from it when it ends; between the two the
  // sweeps read and write this copy only. Likewise the inverse masses by
  // component, and each sand row's coupling vectors by line, in single
  // precision (coupling_lines, kLineEntries per row: for each of the 9 lines
  // the x, y and z components of its three nodes; assemble_delassus fills it
  // and rounds `coupling` to the same values, stencil.hpp). Each
  // array has kLanePadding zeros past its end, read by the last line's
  // fourth lane. Empty in 2D, whose sweeps use `velocity` itself.
  static constexpr int kLineEntries = D * NS;
  static constexpr int kLanePadding = 4;
  std::array<std::vector<double>, D> velocity_by_axis, inv_mass_by_axis;
  std::vector<float> coupling_lines;

  // Stress rows, in runs of rows with pairwise disjoint stencils (rows of
  // one colour: node coordinates mod 3), rows [colour_start[c],
  // colour_start[c+1]). The sand's rows come first, laid out in zones
  // (solver/zones.hpp): 2 x zones units (the zones, then the separator
  // after each) of 3^d runs each, one per colour, which a sweep updates
  // one unit per thread, each in its own order; the contact rows' colours
  // follow, each shared by the team. With zones = 1 the sand's rows are one
  // unit: 3^d colours swept in order.
  std::vector<int> colour_start;
  int zones = 1;
  std::vector<std::int64_t> node;     // velocity index of the row's centre node
  std::vector<Coupling> coupling;     // g_ji, columns in stencil order
  std::vector<double> volume;         // V_j, m^3
  std::vector<double> inv_volume;     // 1 / V_j of the sand rows (assemble_delassus)
  std::vector<double> k;              // (phi_max V_j - Phi_j)^+ / (sqrt(2d) dt), m^3/s
  std::vector<double> aperture;       // cone aperture (METHOD.md section 4)
  std::vector<double> cohesion;       // apex shift along e_0, Pa (cone on lambda + shift e_0)
  std::vector<SymVec<D>> lambda;      // in: warm start; out: the solution, Pa
  std::vector<LocalDelassus<SD>> delassus;
  // Per sand row, its block's first row and inverse unrotated
  // (LocalDelassus::unrotated; assemble_delassus fills it): the sweeps try
  // separation and stick with these, without rotating the row's stress and
  // strain rate, and read `delassus` only for rows that slide.
  struct Unrotated {
    SymVec<D> first_row;
    Eigen::Matrix<double, SD, SD> inverse;
    bool degenerate;  // as delassus[j].degenerate
  };
  std::vector<Unrotated> unrotated;
  std::vector<DPCase> state;
  std::vector<double> beta;           // plastic multiplier of the last local solve (guess for the next)
  // Under-relaxation of the rows that cycle between stick and slide
  // (solver/relaxation.hpp): the fraction of its local change such a row
  // takes (1: none, the plain update), and each row's recent flips and
  // updates since its last flip, kept by the solver.
  double relaxation = 1.0;
  std::vector<unsigned char> flips, calm;

  // Contact rows (frictional obstacles, METHOD.md section 3): rows
  // [first_contact, rows()) act on their own node only (coupling: the centre
  // column w n, n the obstacle's normal pointing into the sand) and are solved
  // as a Coulomb problem on the traction r = (r_N, r_T) in the orthonormal
  // frame contact_frame (first column n): |r_T| <= aperture r_N with
  // aperture = mu_RB itself. Their stress is Lambda(r) = r_N I + t n^T + n t^T
  // (t = sum_k r_Tk f_k), whose traction Lambda n is r; for it the cone of
  // DP(mu_RB) is exactly Coulomb's, |Dev Lambda| = |t| <= mu_RB r_N (METHOD.md
  // section 4), and no stress component is left in the coupling's null space
  // for the local solve to choose.
  int first_contact = std::numeric_limits<int>::max();  // none unless set
  std::vector<Mat<D>> contact_frame;              // per contact row j - first_contact
  std::vector<LocalDelassus<D>> contact_delassus;  // per contact row: w F^T M^{-1} F
  std::vector<Vec<D>> contact_velocity;  // per contact row: the obstacle's velocity (u is relative to it)

  // Rigid bodies (METHOD.md section 3, two-way coupling). A body's velocity
  // unknowns are two entries of `velocity` past the grid's nodes: at index
  // v its linear velocity V, at v + 1 its angular velocity about world axes
  // (2D: (omega, 0); 3D: omega). The linear entry's inverse mass is dt / m
  // per component; the angular one acts through dt J^-1, J the inertia
  // tensor about world axes (spin_inverse, one per body from
  // first_body_entry on, two entries per body; in 2D its (0, 0) entry, about
  // z), and its inv_mass entry holds that tensor's diagonal (0 on the unused
  // component in 2D), the weights of the residual's norm. Being ordinary
  // velocity entries, they enter the residual and the Anderson mixing
  // unchanged.
  // Contact rows [first_body_row, rows()) touch a body: contact_body gives
  // the index v of their body's entries, contact_arm the lever arm x_node -
  // centre (m). Their relative velocity is u_node - (V + omega x arm), and
  // their stress pushes the body back with the opposite force. Rows that
  // share a body are not independent, so the solver updates these rows one
  // after the other, in order, on one thread (results stay independent of
  // the thread count); they must come last.
  // A row may pair its body with a second one instead of a sand node (two
  // balls touching): contact_other_body gives that body's index (or -1; an
  // empty vector means none anywhere) and contact_other_arm its lever arm.
  // The row's node is then one with zero velocity and inverse mass, and its
  // relative velocity u_node + (V' + omega' x arm') - (V + omega x arm); the
  // second body takes the force the row puts on the node.
  int first_body_row = std::numeric_limits<int>::max();  // none unless set
  std::int64_t first_body_entry = std::numeric_limits<std::int64_t>::max();
  std::vector<Mat<D>> spin_inverse;        // per body: dt J^-1 about world axes
  std::vector<char> spin_diagonal;         // per body: spin_inverse is diagonal (inv_mass holds it)
  std::vector<std::int64_t> contact_body;  // per contact row: the body's velocity index, or -1
  std::vector<Vec<D>> contact_arm;         // per contact row: node position - body centre, m
  std::vector<std::int64_t> contact_other_body;  // per contact row: a second body, or -1
  std::vector<Vec<D>> contact_other_arm;         // per contact row: its lever arm, m

  // Node-to-node stabilisation (solver/cell_rows.hpp): linear viscous rows
  // on grid cells, each resisting its cell's node-to-node strain rate
  // (A_c u) with the stress s_c = -2 eta A_c u. A_c u = sym(sum_n u_n G_n^T)
  // over the 4^d nodes around the cell (cell_stencil, offsets from its
  // lowest corner node cell_base), G the same for every cell
  // (cell_gradient). The rows come in 4^d colours (cell coordinates mod 4:
  // rows of one colour touch disjoint nodes), rows [cell_colour_start[c],
  // cell_colour_start[c + 1]). None when cell_base is empty.
  static constexpr int NF = ipow(4, D);
  std::array<std::int64_t, NF> cell_stencil{};
  Eigen::Matrix<double, D, NF> cell_gradient = Eigen::Matrix<double, D, NF>::Zero();  // 1/m
  std::vector<std::int64_t> cell_base;
  std::vector<int> cell_colour_start;
  double cell_viscosity = 0.0;           // eta, Pa s
  double cell_volume = 0.0;              // V_c = h^d, m^3
  std::vector<SymVec<D>> cell_stress;    // s_c, Pa: warm start in, solution out
  std::vector<SymMat<D>> cell_delassus;  // W_c = V_c A_c M^{-1} A_c^T (1/(Pa s))
  std::vector<SymMat<D>> cell_inverse;   // (I + 2 eta W_c)^{-1}
  int cells() const { return static_cast<int>(cell_base.size()); }

  // The second body of contact row c (index past first_contact), or -1.
  std::int64_t other_body(int c) const {
    return contact_other_body.empty() ? -1 : contact_other_body[c];
  }

  int rows() const { return static_cast<int>(node.size()); }
  void resize_rows(int n);
};

// Builds each row's diagonal block W_jj (METHOD.md step 5).
template <int D>
void assemble_delassus(ConeProblem<D>& p);

// Adds M^{-1} f(lambda) to the velocities.
template <int D>
void apply_stress_to_velocity(ConeProblem<D>& p);

// Block Gauss-Seidel with coloured parallel sweeps, warm-started from the
// rows' lambda (on entry `velocity` holds u_f; the warm start's M^{-1} f is
// added here). Residual after sweep k, in the kinetic-energy norm
// |a|_M^2 = sum_i a_i . M_i a_i:
//   r_k = |u^k - u^{k-1}|_M / |u^k - u_f|_M,
// the velocity change of the last sweep relative to the whole correction the
// stresses make. It is dimensionless (independent of the scene's size,
// density and gravity), zero exactly at a fixed point, and blind to the
// stress components in the null space of W = H H^T (lambda has d(d+1)/2
// components per node against d velocities, so the stress field is not
// unique; those components never move a grain). Plus what the rows of
// bodies against solids (on ghost nodes) traded: per body, the sum of the
// norms of the changes each such row made to its velocities in the sweep
// less the norm of their sum, squared, added to the numerator
// (contact_rows.hpp, BodyMoves). Several such rows at one point (a corner
// at a concave fold, faces_over) can trade stress so that their body ends
// the sweep where it began while each row still moves it (a cube in a
// V-groove passed the test on its fourth sweep with its rows 3% from their
// own solutions, and the next sweep's r was 2.8e-3). Stops when r <=
// tolerance or after max_iterations sweeps. Bit-identical whatever the
// thread count.
// With anderson_depth m > 0 the sweeps are accelerated by Anderson mixing of
// the last m sweeps (cone_problem.cpp, AndersonMixer); m = 0 is plain
// Gauss-Seidel.
// A solve that reaches the cap returns the best iterate of its second half:
// the stresses and velocities after the sweep, among sweeps
// max_iterations / 2 ... max_iterations, with the smallest residual (each
// such iterate follows a plain sweep, so it is feasible, and its residual is
// the one reported). Solves that stall wander (docs/benchmarks.md, "Steps at
// the cap"); the last iterate may sit on a spike.
// The sweeps run on one OpenMP thread per zone, at most
// omp_get_max_threads() and the machine's processors; a thread waits for the
// others only before the separators between its zones and theirs, after
// them, and around each colour of contact rows. The result does not depend
// on the thread count.
// `history`, when given, receives every sweep's residual.
template <int D>
SolveReport solve_gauss_seidel(ConeProblem<D>& p, double tolerance, int max_iterations,
                               int anderson_depth = 0, std::vector<double>* history = nullptr);

}  // namespace sablier
