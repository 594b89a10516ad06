// One simulation: particles, grid, and the time step of METHOD.md section 2.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/grid.hpp"
#include "core/particles.hpp"
#include "io/grid_frame.hpp"
#include "io/particle_frame.hpp"
#include "physics/material.hpp"
#include "physics/obstacle.hpp"
#include "physics/shape.hpp"
#include "scene/scene.hpp"
#include "solver/cone_problem.hpp"

namespace sablier {

// Wall-clock seconds spent in each stage of a step.
struct StepTimings {
  double transfer = 0.0;   // sort, P2G, node quantities
  double assembly = 0.0;   // unconstrained velocity, viscosity, Delassus blocks
  double solve = 0.0;      // warm start and Gauss-Seidel sweeps
  double advection = 0.0;  // G2P, rheology state, advection, boundaries
  double total() const { return transfer + assembly + solve + advection; }
};

struct StepInfo {
  double dt = 0.0;
  SolveReport solve;
  StepTimings timings;
  int active_nodes = 0;  // stress rows (= velocity nodes of cells holding particles)
  int viscous_iterations = 0;
  // J: bound on the energy the decompaction of over-full nodes may add this
  // step: 2 dt sum_j max(0, -lambda_N k_j) over k_j < 0 when the cone
  // problem pushes them apart; the work against gravity of the grains
  // lifted when they are moved instead (solver.decompaction = "move").
  double restoring_work = 0.0;
  // solver.decompaction = "project": the largest excess of a node's grain
  // volume over its capacity left after the step's projection, in units of
  // phi_max V_j (above 1e-3 only where the grains cannot get out of the
  // way: sand confined by a solid pressing on it).
  double crowding = 0.0;
  // The grains' volume beyond phi_max at the end of the step (after the
  // decompaction), as a fraction of all of it: sum_j max(0, Phi_j -
  // phi_max V_j) / sum_j Phi_j, Phi_j the grain volume at node j (Q1
  // weights). A percent or two where the decompaction keeps up; it grows
  // when the steps crowd grains faster than the moves spread them (a
  // `time.cfl` above 1 on fine grids), or under solver.decompaction =
  // "clamp".
  double overfill = 0.0;
  // Force the sand exerts on each [[obstacle]] over the step (N; N/m in 2D),
  // the reaction to the obstacle rows' stresses.
  std::vector<Vec3d> obstacle_force;
};

// Fraction of a node's excess volume fraction removed per step (see build_rows).
constexpr double kOverfullRelaxation = 0.1;
// A node whose grain volume is at least this fraction of phi_max V_j belongs
// to the dense phase: it carries its grains' cohesion and does not compact
// (see build_rows). A node on a flat free surface is half full, one at a
// convex corner a quarter full.
constexpr double kCohesiveFill = 0.4;
// A node whose grain volume is below this fraction of its volume is nearly
// empty: its velocity is no motion of sand, and the grains' shear rate
// takes their own velocity there (transfer_to_particles; their affine
// matrix does not). One grain of a 2D cell at 5 per axis is 0.024 of it at
// phi_max 0.6, of a 3D cell at 3 per axis 0.022: this is under half of
// that (docs/validation.md, "Shear rate of sand at rest").
constexpr double kEmptyNodePhi = 1e-2;

// Particles created from the scene's [[sand]] regions (METHOD.md step 1:
// n particles per cell and per axis, V_p = phi_max h^d / n^d).
// `region_counts`, if given, receives the particles of each [[sand]] block.
template <int D>
Particles<D> seed_particles(const SceneConfig& scene,
                            std::vector<std::size_t>* region_counts = nullptr);

// Whether a Simulation built from given particles sorts them by cell (and
// drops those outside the box) at once, or leaves that to its first step:
// a run resumed from a checkpoint must choose its next step's length from
// the same grains as the run it continues.
enum class ParticleOrder { Sort, AsGiven };

template <int D>
class Simulation {
 public:
  explicit Simulation(const SceneConfig& scene);
  Simulation(const SceneConfig& scene, Particles<D> particles,
             ParticleOrder order = ParticleOrder::Sort);

  // Advances by dt (s).
  StepInfo step(double dt);
  // The adaptive step for at most `remaining` seconds: a particle (or a
  // rigid body's surface) travels at most time.cfl cells, accounting for one
  // step of gravity.
  double adaptive_dt(double remaining) const;

  double time() const { return time_; }
  std::int64_t steps() const { return steps_; }
  const SceneConfig& scene() const { return scene_; }
  const DenseGrid<D>& grid() const { return grid_; }
  const Particles<D>& particles() const { return particles_; }
  // Per grain, the lower bound on its distance to the solids that the last
  // step kept (clearance_; 0 where unknown).
  const std::vector<double>& clearances() const { return clearance_; }
  Particles<D>& particles() { return particles_; }
  const ConeProblem<D>& problem() const { return problem_; }

  const std::vector<Material>& materials() const { return materials_; }
  // Fixed and kinematic obstacles as at t = 0; rigid bodies as they are now.
  const std::vector<Obstacle<D>>& obstacles() const { return obstacles_; }
  std::vector<Obstacle<D>> obstacles_at(double t) const {
    std::vector<Obstacle<D>> out;
    for (const Obstacle<D>& o : obstacles_) out.push_back(at_time(o, t));
    return out;
  }
  // Sets rigid body k's state (the [[obstacle]] of index k, which must have
  // a density): a resumed run takes it from bodies.csv.
  // `angle` (2D, rad) or `quaternion` (3D, w x y z) is its orientation.
  void set_body_state(std::size_t k, const Vec<D>& centre, const Vec<D>& velocity,
                      const Vec<D>& spin, double angle, const std::array<double, 4>& quaternion) {
    Obstacle<D>& o = obstacles_.at(k);
    if (!o.dynamic) throw std::invalid_argument("obstacle " + std::to_string(k) + " is not a body");
    o.a = centre;
    o.velocity = velocity;
    o.spin = spin;
    o.angle = angle;
    o.quaternion = quaternion;
    set_orientation(o);
  }
  // First stress row of the obstacles (rows before it are the sand's nodes).
  int first_obstacle_row() const { return obstacle_row_start_; }

  // Diagnostics (SI), from the particles, each with its own density rho_p.
  double kinetic_energy() const;    // sum 1/2 rho_p V_p |u_p|^2
  double potential_energy() const;  // -sum rho_p V_p g.x_p (zero at the origin)
  double affine_energy() const;     // APIC: 1/2 sum_p rho_p V_p sum_i N_i |B_p (x_i - x_p)|^2
  double max_speed() const;
  double grain_mass() const;  // sum rho_p V_p

  // Bulk stress phi lambda of row j, Cartesian tensor (compression positive).
  Mat<D> row_bulk_stress(int j) const;

  ParticleFrame frame() const;
  GridFrame grid_frame() const;  // grid nodes for the .vti writer (physics/grid_frame.cpp)

  // Checkpointing (app/checkpoint_state.hpp). Besides the scene and the
  // particles, the future depends on the clock and on the warm start of the
  // next solve: last step's stresses per grid node (then, with obstacles,
  // the obstacle rows' stresses per grid node), and the case (DPCase) each
  // node's sand row ended that solve in, which sets the next step's zones
  // (transfer.cpp). Everything else is rebuilt from these at the start of
  // each step. `cases` may be empty (a checkpoint of format 3): no case
  // known, as before a first step.
  const std::vector<SymVec<D>>& warm_start() const { return warm_lambda_; }
  const std::vector<std::uint8_t>& warm_cases() const { return warm_case_; }
  void restore_clock(double time, std::int64_t steps, std::vector<SymVec<D>> warm_start,
                     std::vector<std::uint8_t> cases) {
    time_ = time;
    steps_ = steps;
    warm_lambda_ = std::move(warm_start);
    if (cases.size() == warm_lambda_.size())
      warm_case_ = std::move(cases);
    else
      warm_case_.assign(warm_lambda_.size(), 0);
  }

  // For tests and diagnostics: when set, called once per step with the
  // step's assembled cone problem, just before it is solved (a test records
  // a problem the solver finds hard and solves it again under variants).
  std::function<void(const ConeProblem<D>&)> before_solve;

 private:
  void init_boundaries();
  void sort_particles();
  void transfer_to_grid(double dt);
  void build_rows(double dt);
  void build_cells(double dt);
  int unconstrained_velocity(double dt);
  // Rigid bodies (METHOD.md section 3): their velocity unknowns in the cone
  // problem, and their motion over the step once it is solved.
  void attach_bodies(double dt);
  void move_bodies(double dt);
  void transfer_to_particles(double dt);
  // solver.decompaction = "move", and "project" before its projection:
  // moves grains out of over-full nodes after advection (decompaction.cpp);
  // returns the work done against gravity, J (J/m in 2D).
  double move_grains_apart(int moves, double dt);
  // solver.decompaction = "project", after move_grains_apart: grains moved
  // by the gradient of node potentials that take every node back to its
  // capacity (decompaction.cpp); returns the work done against gravity, as
  // move_grains_apart.
  double project_grains_apart(int rounds, double dt);
  // Its steps (decompaction.cpp): capacities (returns the largest excess),
  // the matrix L and the colours, the potentials, the grains' moves.
  double project_capacities(const std::vector<Obstacle<D>>& moving);
  void project_assemble();
  void project_potentials();
  void project_move(const std::vector<Obstacle<D>>& obstacles_end, double dt);
  void restore_braked_momentum(const std::vector<Obstacle<D>>& obstacles_end);
  // Phi_i at the grains' present positions into move_excess_ (and each
  // grain's cell base node into move_base_, -1 outside the box, and its
  // place in that cell into move_local_).
  void grain_volume_at_positions();
  // stencil_of(p) at the positions of the last grain_volume_at_positions,
  // for a grain inside the box, from its place in its cell kept there: the
  // decompaction's passes over the same positions divide by h once.
  Q1Stencil<D> stencil_at_move_base(std::int64_t p) const {
    return stencil_in_cell(p, move_local_[p]);
  }
  // StepInfo::overfill from the Phi_j that grain_volume_at_positions left.
  double overfill() const;
  void emit_from_spouts(double start);  // sources: particles entering during the step
  bool leaves_through_free_face(int axis, int side, const Vec<D>& x) const;
  bool kept_by_walls(const Vec<D>& x) const;
  // A point beyond a wall of the box put back just inside it (1e-6 of a
  // cell); beyond a free face or an opening it stays (its grain leaves at
  // the next sort). Advection's rule and the projection's moves'.
  void put_inside_walls(Vec<D>& x) const {
    const double h = grid_.h();
    for (int a = 0; a < D; ++a) {
      const double upper = grid_.cells()[a] * h;
      if (x[a] < 0.0 && !leaves_through_free_face(a, 0, x)) x[a] = 1e-6 * h;
      if (x[a] > upper && !leaves_through_free_face(a, 1, x)) x[a] = upper - 1e-6 * h;
    }
  }
  // A grain inside a solid put back just outside it, the box's walls
  // permitting, on the side of `from` (where it came from) when given
  // (solid_exit.cpp).
  // Returns true, and the surface's outward normal in `held`, when it holds
  // the grain on the side of a thin part it came from. `clearance`, when
  // given, receives a lower bound on x's distance to the solids when the
  // call returns (0 where it put or held x on a surface; +inf without
  // solids).
  bool put_outside_solids(const std::vector<Obstacle<D>>& solids, Vec<D>& x,
                          const Vec<D>* from = nullptr, Vec<D>* held = nullptr,
                          double* clearance = nullptr) const;
  // Grain p's move from x to y within a step, after advection (the
  // decompaction's moves): y put outside the solids as put_outside_solids
  // does, `from` x. The grain's clearance (clearance_) skips the query
  // where it shows that y is outside every solid and its path crosses
  // none: the same answer (docs/method.md, "Frictional obstacles").
  // Returns y as put_outside_solids leaves it; clearance_[p] then holds for
  // y if the caller takes y.
  void move_outside_solids(const std::vector<Obstacle<D>>& solids, std::int64_t p, const Vec<D>& x,
                           Vec<D>& y, double* clearance_at_y) const;
  // Whether grain p's clearance shows that a step of length `step` from
  // where it holds ends outside every solid and crosses none, which is the
  // distance query's own answer (solid_exit.cpp): the skip of advection
  // and of the moves.
  bool clear_of_solids(std::int64_t p, double step) const {
    return clearance_[p] >= 2.0 * step + 1e-9 * grid_.h();
  }
  // (rho_p / rho_0) V_p: particle p's mass in units of rho_0, m^3.
  double mass_volume(std::size_t p) const {
    return materials_[particles_.material[p]].mass_ratio * particles_.volume[p];
  }
  // The Q1 shape functions at grain p's position, in its cell, and that
  // cell's base node; next to a thin solid, its own side's (across_, which
  // find_own_sides must have computed at the grain's present position).
  Q1Stencil<D> stencil_of(std::int64_t p, std::int64_t* base) const {
    const Vec<D>& x = particles_.position[p];
    const auto cc = grid_.cell_of(x);
    *base = grid_.cell_base_node(cc);
    return stencil_in_cell(p, place_in_cell(x, cc));
  }
  // (x - the origin of cell cc) / h: where x lies in that cell, in [0, 1]^d.
  Vec<D> place_in_cell(const Vec<D>& x, const typename DenseGrid<D>::IVec& cc) const {
    const double h = grid_.h();
    Vec<D> local;
    for (int a = 0; a < D; ++a) local[a] = (x[a] - cc[a] * h) / h;
    return local;
  }
  // The shape functions of grain p at `local` in its cell, its own side's
  // next to a thin solid.
  Q1Stencil<D> stencil_in_cell(std::int64_t p, const Vec<D>& local) const {
    Q1Stencil<D> s = q1_stencil<D>(local, grid_.h());
    if (!thin_solids_.empty()) keep_corners<D>(across_[p], s);
    return s;
  }
  // The fixed solids thinner than kThinSolidCells cells (the scene's
  // measure), and each node's distance to them where they are at time t
  // (thin_solids.cpp).
  void find_thin_solids();
  void place_thin_solids(double t);
  // The compatible transfer next to them (thin_solids.cpp): a grain's
  // shape functions limited to the corners of its cell on its own side of
  // every fixed solid thinner than the cells resolve, renormalised
  // (keep_corners, shape.hpp). corners_across gives the corners of the
  // cell with base node `base` that lie across such a solid from x (bit a
  // for corner a; 0 when the stencil stays whole); find_own_sides keeps it
  // per grain in across_, for the grains' present positions (after the
  // sort of a step, and at each round of the decompaction), so that P2G,
  // the viscosity, G2P and the decompaction's passes over the same
  // positions query the solids' distance once.
  std::uint8_t corners_across(const Vec<D>& x, std::int64_t base) const;
  void find_own_sides();
  // The fixed solids thinner than kThinSolidCells (their indices in
  // obstacles_), whether each moves or is taken away (driven) and whether
  // one does, and whether thin_solids_ (where they are) and the nodes'
  // distances are set, for which time.
  std::vector<std::size_t> thin_index_;
  std::vector<std::uint8_t> thin_driven_;
  bool thin_move_ = false;
  bool thin_placed_ = false;
  double thin_time_ = 0.0;
  std::vector<Obstacle<D>> thin_solids_;
  std::vector<double> thin_node_distance_;      // per node: signed distance to them, m
  std::vector<Vec<D>> thin_node_normal_;        // and its unit gradient
  std::vector<std::uint8_t> thin_node_driven_;  // the nearest moves or is taken away
  std::vector<std::uint8_t> across_;            // per grain: corners_across at its position

  SceneConfig scene_;
  DenseGrid<D> grid_;
  Particles<D> particles_;
  double time_ = 0.0;
  std::int64_t steps_ = 0;
  double rho0_, phi_max_;            // reference density rho_0 = [material].density (material.hpp)
  std::vector<Material> materials_;  // one per [[sand]] block, by particles_.material
  Vec<D> gravity_;

  // Particles sorted by cell: particles of cell c are [cell_start_[c], cell_start_[c+1]).
  std::vector<std::int64_t> cell_start_;
  std::vector<std::int64_t> active_cells_;  // sorted
  std::array<std::vector<std::int64_t>, ipow(2, D)> cells_by_parity_;

  // Dense node fields (ghost-padded).
  // Grain volume Phi_i = sum_p V_p N_i, m^3: the phi_max constraint and phi.
  std::vector<double> node_grain_volume_;
  // Mass in units of rho_0: m_i / rho_0 = sum_p (rho_p / rho_0) V_p N_i, m^3
  // (equal to Phi_i when every grain has density rho_0).
  std::vector<double> node_mass_;
  std::vector<Vec<D>> node_momentum_;  // q_i / rho_0, m^4/s
  std::vector<Vec<D>> free_mask_;      // 1 on free velocity components, 0 on constrained
  // 1 on a node of a free face or an opening (grains leave the box there),
  // else 0: the projection does not bound the grain volume there.
  std::vector<std::uint8_t> open_node_;
  std::vector<int> row_of_node_;        // stress row index or -1
  std::vector<SymVec<D>> warm_lambda_;  // last step's stresses, for the warm start
  // Per warm_lambda_ entry, the case its sand row ended the last solve in
  // (a DPCase; 0, separation, where there was none): the zones' costs.
  std::vector<std::uint8_t> warm_case_;
  std::vector<double> row_mu_sum_, row_cohesion_sum_;  // sum_p V_p N_j (mu_p, c_p)
  // move_grains_apart (decompaction.cpp): per node, the relative excess; per
  // grain, the lift and its cell's base node.
  std::vector<double> move_excess_, move_lift_;
  // Per grain: a lower bound on its distance to the solids where they end
  // the step, set at advection (or, where no solid moves, kept from the
  // last step less the advection's length) and kept through its moves (each
  // takes its length off); 0 where unknown. Only where every solid's
  // distance is exact (1-Lipschitz: not a mesh's sampled one). Follows the
  // grains through sort_particles.
  std::vector<double> clearance_, sorted_clearance_;  // the latter: sort_particles' scratch
  std::vector<std::int64_t> move_base_;
  std::vector<Vec<D>> move_local_;  // (x_p - cell origin) / h, as stencil_of takes it
  bool moves_settled_ = false;      // the last moves stopped with no node over-full
  // project_grains_apart: per node, its 3^d row of L (node to node,
  // sum_p V_p grad N_j . grad N_k), its capacity and potential; the nodes
  // holding grains, by colour (coordinate parities).
  std::vector<double> project_L_, project_full_, project_capacity_, project_q_;
  // Per grain, the velocity the braking took (project_move); per node, the
  // momentum it took and the grains' mass there, in units of rho_0.
  std::vector<Vec<D>> brake_velocity_, brake_momentum_;
  std::vector<double> brake_mass_;
  // Per node: its cell's clump, -1 for a cell without grains.
  std::vector<std::int64_t> brake_root_;
  std::vector<std::uint8_t> brake_flags_;  // per clump root: it touches a wall or a solid; braked
  double project_left_ = 0.0;  // the last projection's largest excess left (StepInfo::crowding)
  std::array<std::vector<std::int64_t>, ipow(2, D)> project_nodes_;

  // Obstacles (METHOD.md section 3): rows [obstacle_row_start_, rows) are
  // nodes within one cell of an obstacle (their normals are the first
  // columns of problem_.contact_frame); the sand rows' nodes carry the
  // solid's share of their volume.
  std::vector<Obstacle<D>> obstacles_;
  int obstacle_row_start_ = 0;
  std::vector<int> obstacle_index_;  // per obstacle row: which [[obstacle]]
  // Per obstacle row: a rigid ball against a wall, an obstacle or another
  // ball (gap >= 0, m, and the friction there; contact_other_ the other
  // ball's [[obstacle]] index, else -1), or a row with the sand (gap -1).
  std::vector<double> wall_gap_, wall_mu_;
  std::vector<int> contact_other_;
  // Rows of a body against a solid: the lever arms of the touching points
  // from the body's centre and from the other body's (m).
  std::vector<Vec<D>> contact_arm_, contact_other_arm_;
  std::vector<double> row_solid_;  // per sand row: solid fraction of V_j
  // Per sand row: the node lies h/2 or more inside a solid (build_rows).
  std::vector<char> row_in_solid_;
  std::vector<char> touched_;  // per node: a solid touches it (build_cells)

  ConeProblem<D> problem_;
};

}  // namespace sablier
