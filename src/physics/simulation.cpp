// The time step (METHOD.md section 2) and the simulation's diagnostics.
#include "physics/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "physics/emission.hpp"
#include "physics/shape.hpp"
#include "physics/viscosity.hpp"

namespace sablier {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

template <int D>
typename DenseGrid<D>::IVec grid_cells(const SceneConfig& scene) {
  typename DenseGrid<D>::IVec c;
  for (int a = 0; a < D; ++a) c[a] = scene.resolution[a];
  return c;
}

}  // namespace

template <int D>
Simulation<D>::Simulation(const SceneConfig& scene) : Simulation(scene, seed_particles<D>(scene)) {}

template <int D>
Simulation<D>::Simulation(const SceneConfig& scene, Particles<D> particles, ParticleOrder order)
    : scene_(scene),
      grid_(grid_cells<D>(scene), scene.cell_size()),
      particles_(std::move(particles)),
      rho0_(scene.material.density),
      phi_max_(scene.material.phi_max),
      materials_(material_table(scene)) {
  for (int a = 0; a < D; ++a) gravity_[a] = scene.gravity[a];
  // The transfers index the table without checks.
  for (const std::int32_t k : particles_.material)
    if (k < 0 || static_cast<std::size_t>(k) >= materials_.size())
      throw std::invalid_argument("particle material " + std::to_string(k) + " of " +
                                  std::to_string(materials_.size()));
  const std::int64_t nodes = grid_.node_count();
  node_grain_volume_.assign(nodes, 0.0);
  node_mass_.assign(nodes, 0.0);
  node_momentum_.assign(nodes, Vec<D>::Zero());
  row_of_node_.assign(nodes, -1);
  obstacles_ = make_obstacles<D>(scene);
  find_thin_solids();
  warm_lambda_.assign(obstacles_.empty() ? nodes : 2 * nodes, SymVec<D>::Zero());
  warm_case_.assign(warm_lambda_.size(), 0);
  problem_.velocity.assign(nodes, Vec<D>::Zero());
  problem_.inv_mass.assign(nodes, Vec<D>::Zero());
  problem_.stencil = grid_.stencil_offsets();
  init_boundaries();
  if (order == ParticleOrder::Sort) sort_particles();
}

// Velocity boundary conditions as projections inside M^{-1} (METHOD.md
// step 6): stick zeroes every component on a face's nodes, slip the normal
// one, free (and nodes inside an opening) nothing. Ghost nodes are fixed.
template <int D>
void Simulation<D>::init_boundaries() {
  free_mask_.assign(grid_.node_count(), Vec<D>::Zero());
  open_node_.assign(grid_.node_count(), 0);
  const double h = grid_.h();
  for (std::int64_t idx = 0; idx < grid_.node_count(); ++idx) {
    const auto n = grid_.node_coords(idx);
    if (!grid_.is_real_node(n)) continue;
    Vec<D> mask = Vec<D>::Ones();
    Vec<D> x;
    for (int a = 0; a < D; ++a) x[a] = n[a] * h;
    for (int a = 0; a < D; ++a) {
      for (int side = 0; side < 2; ++side) {
        if (n[a] != (side == 0 ? 0 : grid_.cells()[a])) continue;
        if (leaves_through_free_face(a, side, x)) {
          open_node_[idx] = 1;
          continue;
        }
        if (scene_.boundary.faces[2 * a + side] == BoundaryType::Stick) mask.setZero();
        if (scene_.boundary.faces[2 * a + side] == BoundaryType::Slip) mask[a] = 0.0;
      }
    }
    free_mask_[idx] = mask;
  }
}

// Per-row quantities of the forms (METHOD.md step 2): V_j, the phi_max term
// k_j, the friction and cohesion averaged over the row's particles, and the
// warm start. Where a node is over-full (Phi_j > phi_max V_j) METHOD.md step 5
// clamps k_j at zero rather than pushing grains apart in one step; a pure
// clamp lets transfer errors accumulate (measured: phi up to 1.1 in the 2D
// collapse, 3.4 in a frictionless dam break). By default (solver.decompaction
// = "move") the clamp is pure and the grains are moved apart after advection
// (decompaction.cpp). With "push" k_j keeps kOverfullRelaxation of the
// excess per step, pushing the grains apart through the cone problem; the
// energy this injects is reported (StepInfo::restoring_work) and bounded in
// the tests. "clamp" is METHOD.md's rule alone.
template <int D>
void Simulation<D>::build_rows(double dt) {
  ConeProblem<D>& P = problem_;
  const int rows = P.rows();
  const double inv_trace_dt = 1.0 / (trace_scale<D>() * dt);
  const int sand_rows = obstacle_row_start_;
  const bool with_obstacles = !obstacles_.empty();
  const bool pushing = scene_.solver.decompaction == Decompaction::Push;
#pragma omp parallel for schedule(static)
  for (int j = 0; j < sand_rows; ++j) {
    const std::int64_t node = P.node[j];
    const double vj = grid_.node_volume(grid_.node_coords(node));
    const double phi_j = node_grain_volume_[node];
    P.volume[j] = vj;
    // An obstacle's volume counts as grains (METHOD.md section 3): sand
    // cannot compact into it.
    const double solid = with_obstacles ? phi_max_ * vj * row_solid_[j] : 0.0;
    const double room = phi_max_ * vj - phi_j - solid;
    const double a = cone_aperture<D>(row_mu_sum_[j] / phi_j);
    P.aperture[j] = a;
    // Cohesion (the mean of the node's grains) acts only in the dense phase,
    // and a cohesive node does not compact (k_j = 0 rather than room > 0):
    // with room to compact, the separation case would put the node at the
    // apex of the shifted cone, a tension, while its grains move closer, and
    // that tension does positive work -lambda_N k_j (measured: c = 30 kPa
    // raised a block's energy from 46.0 to 57.1 J/m in 0.12 s). With k_j = 0
    // the step dissipates as without cohesion (lambda.gamma <= 0).
    const double c = row_cohesion_sum_[j] / phi_j;
    const bool cohesive = c > 0.0 && a > 0.0 && phi_j >= kCohesiveFill * phi_max_ * vj;
    P.cohesion[j] = cohesive ? c / a : 0.0;
    // Over-full: decompact only what the sand alone overfills. The solid's
    // share stops compaction but pushes no grain: the plane estimate of
    // solid_fraction and the particles' quadrature of Phi_j disagree by a
    // few percent, and counting that as over-fullness levitated a bed on a
    // plane 0.1 h above a node row (measured: rising at 4 mm/s, phi 0.64).
    const double excess = std::min(0.0, phi_max_ * vj - phi_j);
    const double push = pushing ? kOverfullRelaxation * excess : 0.0;
    P.k[j] = (room > 0.0 ? (cohesive ? 0.0 : room) : push) * inv_trace_dt;
    P.lambda[j] = warm_lambda_[node];
    // A node h/2 or more inside a solid: its dual cell holds no sand, and
    // its row sees only the slivers of grains within h/2 of the surface,
    // with weights N_j below 1/2, which the rows of the nodes outside see
    // too. Such a row is nearly singular, and inside a solid two cells thick
    // it joins the sand on both faces through the solid: in mixer2d's
    // paddle such rows carried 1e5 to 1.6e7 Pa against at most 7e4 for the
    // sand's (its weight at the floor is 2.2e3 Pa), and one stalled solve
    // threw grains out at 3.3 m/s (docs/method.md). The row is left out
    // (no coupling: the solver marks it inactive).
    if (with_obstacles && row_in_solid_[j]) {
      P.coupling[j].setZero();
      P.k[j] = 0.0;
      P.cohesion[j] = 0.0;
      P.lambda[j].setZero();
    }
  }
  // Obstacle rows: (lambda_RB ; gamma_RB) in DP(mu_RB) with gamma_RB =
  // sym(u n^T) / h, so coupling V_j n / h on the row's own node only, no
  // phi_max term and no cohesion. In the separation case u.n >= 0 (the sand
  // leaves the surface); otherwise u.n = 0 with Coulomb friction mu_RB
  // (supplement, section 3). The solver treats them as contact rows
  // (cone_problem.hpp): a Coulomb cone on the traction, aperture mu_RB.
  const double h = grid_.h();
  const std::int64_t nodes = grid_.node_count();
  constexpr int centre = ConeProblem<D>::NS / 2;
#pragma omp parallel for schedule(static)
  for (int j = sand_rows; j < rows; ++j) {
    const std::int64_t node = P.node[j];
    const int o = j - sand_rows;
    const bool wall = wall_gap_[o] >= 0.0;  // a ball against a wall (transfer.cpp)
    const double vj = wall ? std::pow(h, D) : grid_.node_volume(grid_.node_coords(node));
    P.volume[j] = vj;
    P.k[j] = 0.0;
    // Coulomb cone on the traction.
    P.aperture[j] = wall ? wall_mu_[o] : obstacles_[obstacle_index_[o]].mu;
    P.cohesion[j] = 0.0;
    P.coupling[j].setZero();
    P.coupling[j].col(centre) = (vj / h) * P.contact_frame[o].col(0);  // the normal
    P.lambda[j] = warm_lambda_[nodes + node];
  }
}

// Each rigid body's velocities become two entries of the cone problem's
// velocity vector past the grid's nodes (cone_problem.hpp): V_f = V + g dt
// and its angular velocity, with inverse masses dt / m and dt / J; its
// contact rows get the entry's index and their lever arms from the centre.
template <int D>
void Simulation<D>::attach_bodies(double dt) {
  ConeProblem<D>& P = problem_;
  const std::int64_t nodes = grid_.node_count();
  P.velocity.resize(nodes);
  P.inv_mass.resize(nodes);
  P.first_body_entry = nodes;
  P.spin_inverse.clear();
  P.spin_diagonal.clear();
  std::vector<std::int64_t> entry(obstacles_.size(), -1);
  for (std::size_t k = 0; k < obstacles_.size(); ++k) {
    const Obstacle<D>& o = obstacles_[k];
    if (!o.dynamic) continue;
    entry[k] = static_cast<std::int64_t>(P.velocity.size());
    P.velocity.push_back(o.velocity + dt * gravity_);
    // The spin after the gyroscopic torque: Euler's equations without
    // torque, J w' + w x J w = 0 in the body's axes, one implicit Euler step
    // taken by one Newton step from w (Catto 2015, "Physics for game
    // programmers: numerical methods"): J (w_f - w) + dt w_f x J w_f = 0,
    // linearised at w. Implicit, so it never adds energy (explicit steps
    // did: 8e-4 over 100 steps of a tumbling box). Zero for balls, whose J
    // is isotropic.
    const Mat<D> J_inv = spin_inverse(o, dt);
    Vec<D> spin = o.spin;
    if constexpr (D == 3) {
      if (o.shape != ObstacleShape::Ball) {
        const Mat<D>& J = o.inertia;
        const Vec<D> w = o.rotation.transpose() * o.spin;
        const auto skew = [](const Vec<D>& v) {
          Mat<D> m;
          m << 0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0;
          return m;
        };
        const Vec<D> Jw = J * w;
        const Mat<D> jacobian = J + dt * (skew(w) * J - skew(Jw));
        const Vec<D> w_f = w - jacobian.inverse() * (dt * w.cross(Jw));
        spin = o.rotation * w_f;
      }
    }
    P.velocity.push_back(spin);
    P.inv_mass.push_back(Vec<D>::Constant(dt / o.mass));
    // The spin's entry in the residual's weights: the tensor's diagonal (its
    // full form acts in the solve, P.spin_inverse).
    Vec<D> spin_weight = J_inv.diagonal();
    if constexpr (D == 2) spin_weight[1] = 0.0;  // 2D: one rotation, about z
    P.inv_mass.push_back(spin_weight);
    P.spin_inverse.push_back(J_inv);
    P.spin_diagonal.push_back(J_inv.isDiagonal(0.0));
  }
  const int contacts = P.rows() - P.first_contact;
  P.contact_body.assign(std::max(contacts, 0), -1);
  P.contact_arm.assign(std::max(contacts, 0), Vec<D>::Zero());
  P.contact_other_body.assign(std::max(contacts, 0), -1);
  P.contact_other_arm.assign(std::max(contacts, 0), Vec<D>::Zero());
  const double h = grid_.h();
  for (int j = std::max(P.first_body_row, P.first_contact); j < P.rows(); ++j) {
    const int c = j - P.first_contact;
    const int k = obstacle_index_[c];
    P.contact_body[c] = entry[k];
    if (wall_gap_[c] >= 0.0) {  // against a solid: the arms found with the row
      P.contact_arm[c] = contact_arm_[c];
      if (const int m = contact_other_[c]; m >= 0) {
        P.contact_other_body[c] = entry[m];
        P.contact_other_arm[c] = contact_other_arm_[c];
      }
      continue;
    }
    const auto n = grid_.node_coords(P.node[j]);
    for (int a = 0; a < D; ++a) P.contact_arm[c][a] = n[a] * h - obstacles_[k].a[a];
  }
}

// The solve gave each body its velocities at the end of the step; it moves
// with them (the same semi-implicit Euler step as the grains) and turns by
// its spin times dt.
template <int D>
void Simulation<D>::move_bodies(double dt) {
  const ConeProblem<D>& P = problem_;
  std::int64_t v = grid_.node_count();
  for (Obstacle<D>& o : obstacles_) {
    if (!o.dynamic) continue;
    o.velocity = P.velocity[v];
    o.spin = P.velocity[v + 1];
    o.a += dt * o.velocity;
    if constexpr (D == 2) {
      o.angle += dt * o.spin[0];
    } else {
      const double turn = dt * o.spin.norm();
      if (turn > 0.0) {
        const auto& q = o.quaternion;
        const Eigen::Quaterniond r =
            (Eigen::Quaterniond(Eigen::AngleAxisd(turn, o.spin.normalized())) *
             Eigen::Quaterniond(q[0], q[1], q[2], q[3]))
                .normalized();
        o.quaternion = {r.w(), r.x(), r.y(), r.z()};
      }
    }
    set_orientation(o);
    v += 2;
  }
}

// u_f = (M + A)^{-1} l (METHOD.md step 3) and the inverse masses dt / m_i,
// m_i = rho_0 node_mass_ = sum_p rho_p V_p N_i; a division per node without
// viscosity, conjugate gradients with it.
template <int D>
int Simulation<D>::unconstrained_velocity(double dt) {
  ConeProblem<D>& P = problem_;
  const std::int64_t nodes = grid_.node_count();
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nodes; ++i) {
    const double m = node_mass_[i];
    if (m > 0.0) {
      P.velocity[i] = (node_momentum_[i] / m + dt * gravity_).cwiseProduct(free_mask_[i]);
      P.inv_mass[i] = free_mask_[i] * (dt / (rho0_ * m));
    } else {
      P.velocity[i].setZero();
      P.inv_mass[i].setZero();
    }
  }
  if (scene_.material.viscosity <= 0.0) return 0;
  ViscousSystem<D> sys{grid_,      particles_, cell_start_, cells_by_parity_,
                       node_mass_, free_mask_, rho0_ / dt,  scene_.material.viscosity};
  if (!thin_solids_.empty()) sys.across = across_.data();  // P2G's positions
  return solve_viscous(sys, P.velocity);
}

template <int D>
StepInfo Simulation<D>::step(double dt) {
  StepInfo info;
  info.dt = dt;
  auto t0 = Clock::now();
  sort_particles();
  transfer_to_grid(dt);
  build_rows(dt);
  build_cells(dt);
  info.timings.transfer = seconds_since(t0);

  t0 = Clock::now();
  info.viscous_iterations = unconstrained_velocity(dt);
  attach_bodies(dt);
  assemble_delassus(problem_);
  info.timings.assembly = seconds_since(t0);

  t0 = Clock::now();
  problem_.relaxation = scene_.solver.relaxation;
  if (before_solve) before_solve(problem_);
  info.solve = solve_gauss_seidel(problem_, scene_.solver.tolerance, scene_.solver.max_iterations,
                                  scene_.solver.anderson);
  info.timings.solve = seconds_since(t0);
  // Work the decompaction of over-full nodes may do: 2 dt sum max(0,
  // -lambda_N k_j) over k_j < 0. Nodes with room (k_j > 0) do no work:
  // lambda_N >= 0 there, cohesive nodes having k_j = 0 (build_rows).
  for (int j = 0; j < problem_.rows(); ++j)
    if (problem_.k[j] < 0.0)
      info.restoring_work += 2.0 * dt * std::max(0.0, -problem_.lambda[j][0] * problem_.k[j]);

  t0 = Clock::now();
  std::fill(warm_lambda_.begin(), warm_lambda_.end(), SymVec<D>::Zero());
  std::fill(warm_case_.begin(), warm_case_.end(), std::uint8_t(0));
  for (int j = 0; j < obstacle_row_start_; ++j) {
    warm_lambda_[problem_.node[j]] = problem_.lambda[j];
    warm_case_[problem_.node[j]] = static_cast<std::uint8_t>(problem_.state[j]);
  }
  // The obstacles feel the opposite of the force their rows put on the sand,
  // f = Lambda_j g_j (cone_problem.hpp).
  info.obstacle_force.assign(obstacles_.size(), Vec3d{0, 0, 0});
  const std::int64_t nodes = grid_.node_count();
  constexpr int centre = ConeProblem<D>::NS / 2;
  for (int j = obstacle_row_start_; j < problem_.rows(); ++j) {
    warm_lambda_[nodes + problem_.node[j]] = problem_.lambda[j];
    if (wall_gap_[j - obstacle_row_start_] >= 0.0) continue;  // the wall's push, not the sand's
    const Vec<D> f = from_sym<D>(problem_.lambda[j]) * problem_.coupling[j].col(centre);
    Vec3d& total = info.obstacle_force[obstacle_index_[j - obstacle_row_start_]];
    for (int a = 0; a < D; ++a) total[a] -= f[a];
  }
  move_bodies(dt);
  transfer_to_particles(dt);
  const bool moves = scene_.solver.decompaction == Decompaction::Move;
  if (moves) info.restoring_work += move_grains_apart(scene_.solver.decompaction_moves, dt);
  if (scene_.solver.decompaction == Decompaction::Project) {
    // The moves first, then the projection of what they leave (docs/method.md,
    // "The moves before the projection"): the moves spread local crowding
    // without touching velocities, so the projection's braking acts only on
    // the rest (hourglass2d: 27 steps at the solver's cap of 566, against
    // 128 of 572 with the projection alone).
    info.restoring_work += move_grains_apart(scene_.solver.decompaction_moves, dt);
    info.restoring_work += project_grains_apart(scene_.solver.decompaction_moves, dt);
    info.crowding = project_left_;
  }
  // Moves that stopped early found no node over-full; the projection ends
  // with Phi at the grains' final positions.
  if (moves && moves_settled_) {
    info.overfill = 0.0;
  } else {
    if (scene_.solver.decompaction != Decompaction::Project) grain_volume_at_positions();
    info.overfill = overfill();
  }
  info.timings.advection = seconds_since(t0);

  info.active_nodes = obstacle_row_start_;  // sand nodes (obstacle rows are extra)
  const double start = time_;
  time_ += dt;
  ++steps_;
  emit_from_spouts(start);
  return info;
}

// The source hook, at the end of a step: the layers the spouts emitted
// between `start` and now (emission.hpp), a function of the clock alone so
// that a resumed run emits the same. Appended unsorted: the next step's
// sort (stable) puts them in place, as the constructor's does on a resume.
template <int D>
void Simulation<D>::emit_from_spouts(double start) {
  if (scene_.spouts.empty()) return;
  emit_spout_particles<D>(scene_, start, time_, particles_, &obstacles_);
  clearance_.resize(particles_.size(), 0.0);  // the new grains' is unknown
}

template <int D>
double Simulation<D>::adaptive_dt(double remaining) const {
  // Travel (v + g dt) dt <= cfl h, solved for dt.
  const double reach = scene_.time.cfl * grid_.h();
  // Grains a spout is about to emit move too (emission.hpp), and so do the
  // rigid bodies' surfaces (at most |V| + |omega| r), which must not skip
  // over the grains they meet.
  double v = std::max(max_speed(), open_spout_speed(scene_, time_));
  for (const Obstacle<D>& o : obstacles_)
    if (o.dynamic || moves_into_sand(o))  // a body, or a solid driven through the sand
      v = std::max(v, o.velocity.norm() + o.spin.norm() * bounding_radius(o));
  const double g = gravity_.norm();
  double dt = remaining;
  if (g > 0.0) {
    dt = std::min(dt, (-v + std::sqrt(v * v + 4.0 * g * reach)) / (2.0 * g));
  } else if (v > 0.0) {
    dt = std::min(dt, reach / v);
  }
  // Equal sub-steps to the end of the frame.
  const double n = std::ceil(remaining / dt * (1.0 - 1e-12));
  return remaining / std::max(1.0, n);
}

// The energies sum (rho_p / rho_0) V_p terms and multiply by rho_0 once, as
// the grid's masses do (material.hpp): exact with a single material.
template <int D>
double Simulation<D>::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t p = 0; p < particles_.size(); ++p)
    e += mass_volume(p) * particles_.velocity[p].squaredNorm();
  return 0.5 * rho0_ * e;
}

template <int D>
double Simulation<D>::potential_energy() const {
  double e = 0.0;
  for (std::size_t p = 0; p < particles_.size(); ++p)
    e -= mass_volume(p) * gravity_.dot(particles_.position[p]);
  return rho0_ * e;
}

template <int D>
double Simulation<D>::affine_energy() const {
  constexpr int NC = ipow(2, D);
  const double h = grid_.h();
  double e = 0.0;
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    const Vec<D>& x = particles_.position[p];
    const Vec<D> local = place_in_cell(x, grid_.cell_of(x));
    const Q1Stencil<D> s = q1_stencil<D>(local, h);
    for (int c = 0; c < NC; ++c) {
      Vec<D> offset;
      for (int a = 0; a < D; ++a) offset[a] = (((c >> a) & 1) - local[a]) * h;
      e += mass_volume(p) * s.w[c] * (particles_.affine[p] * offset).squaredNorm();
    }
  }
  return 0.5 * rho0_ * e;
}

template <int D>
double Simulation<D>::max_speed() const {
  double v2 = 0.0;
  for (const Vec<D>& v : particles_.velocity) v2 = std::max(v2, v.squaredNorm());
  return std::sqrt(v2);
}

template <int D>
double Simulation<D>::grain_mass() const {
  double m = 0.0;
  for (std::size_t p = 0; p < particles_.size(); ++p) m += mass_volume(p);
  return rho0_ * m;
}

template <int D>
Mat<D> Simulation<D>::row_bulk_stress(int j) const {
  const double phi = node_grain_volume_[problem_.node[j]] / problem_.volume[j];
  return phi * from_sym<D>(problem_.lambda[j]);
}

template <int D>
ParticleFrame Simulation<D>::frame() const {
  const std::size_t n = particles_.size();
  constexpr int SD = sym_size(D);
  ParticleFrame f;
  f.dimension = D;
  f.time = time_;
  f.count = n;
  f.position.resize(n * D);
  f.velocity.resize(n * D);
  f.volume = particles_.volume;
  f.pressure.resize(n);
  f.phi = particles_.phi;
  f.stress.resize(n * SD);
  f.shear_rate = particles_.shear_rate;
  f.id.resize(n);
  f.material.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    for (int a = 0; a < D; ++a) {
      f.position[p * D + a] = particles_.position[p][a];
      f.velocity[p * D + a] = particles_.velocity[p][a];
    }
    // Outputs are bulk values phi lambda (METHOD.md section 4).
    const double phi = particles_.phi[p];
    f.pressure[p] = phi * trace_of<D>(particles_.stress[p]) / D;
    const SymVec<D> s = phi * cartesian_components<D>(particles_.stress[p]);
    for (int k = 0; k < SD; ++k) f.stress[p * SD + k] = s[k];
    f.id[p] = static_cast<double>(particles_.id[p]);
    f.material[p] = static_cast<double>(particles_.material[p]);
  }
  return f;
}

template class Simulation<2>;
template class Simulation<3>;

}  // namespace sablier
