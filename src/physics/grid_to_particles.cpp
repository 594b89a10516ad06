// Grid to particles (METHOD.md section 2, step 7): G2P with the lagged
// rheology state, advection and the domain's faces. The way there, sorting
// and P2G, is transfer.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "physics/shape.hpp"
#include "physics/simulation.hpp"

namespace sablier {

template <int D>
void Simulation<D>::transfer_to_particles(double dt) {
  constexpr int NC = ipow(2, D);
  const auto corner = grid_.corner_offsets();
  const Material* mats = materials_.data();
  const ConeProblem<D>& P = problem_;
  const std::int64_t n = static_cast<std::int64_t>(particles_.size());
  std::int64_t bad = std::numeric_limits<std::int64_t>::max();
  const std::vector<Obstacle<D>> obstacles_end =
      obstacles_at(time_ + dt);  // where the step leaves them
  // Where the step found them, for the grains near a fixed solid that
  // moves: a grain's start carried along with that solid, so that its path
  // is followed relative to it (put_outside_solids).
  const std::vector<Obstacle<D>> obstacles_start = obstacles_at(time_);
  bool driven = false, in_place = true;
  for (const Obstacle<D>& o : obstacles_start) {
    driven |= !o.dynamic && moves_into_sand(o);
    in_place &= !o.dynamic && !moves_into_sand(o);
  }
#pragma omp parallel for schedule(static) reduction(min : bad)
  for (std::int64_t p = 0; p < n; ++p) {
    Vec<D>& x = particles_.position[p];
    std::int64_t base = 0;
    const Q1Stencil<D> s = stencil_of(p, &base);  // P2G's positions: across_ stands
    Vec<D> u = Vec<D>::Zero();
    Mat<D> grad = Mat<D>::Zero();
    SymVec<D> lambda = SymVec<D>::Zero();
    const Material& mp = mats[particles_.material[p]];
    const bool decays = mp.cohesion_decay > 0.0;
    double phi = 0.0, left_out = 0.0, yielding = 0.0;  // yielding: only where cohesion decays
    unsigned empty_corners = 0;  // corners whose node is nearly empty (kEmptyNodePhi)
    for (int a = 0; a < NC; ++a) {
      const std::int64_t node = base + corner[a];
      const Vec<D>& ui = P.velocity[node];
      u += s.w[a] * ui;
      grad.noalias() += ui * s.grad[a].transpose();
      const int row = row_of_node_[node];
      if (node_grain_volume_[node] < kEmptyNodePhi * P.volume[row]) empty_corners |= 1u << a;
      if (row_in_solid_[row]) {
        left_out += s.w[a];
      } else {
        lambda += s.w[a] * P.lambda[row];
        if (decays && P.state[row] != DPCase::Stick) yielding += s.w[a];
      }
      phi += s.w[a] * node_grain_volume_[node] / P.volume[row];
    }
    // A grain next to a solid reads its stress from the rows of the sand
    // around it, not from those left out inside the solid (build_rows).
    if (left_out > 0.0 && left_out < 1.0) {
      lambda /= 1.0 - left_out;
      yielding /= 1.0 - left_out;
    }
    if (!u.allFinite()) bad = std::min(bad, p);
    particles_.velocity[p] = u;
    particles_.affine[p] = grad;  // APIC's B_p = grad u(x_p) (METHOD.md step 7)
    particles_.stress[p] = lambda;
    particles_.phi[p] = phi;
    // The sand's own velocity gradient, for its rheology: a nearly empty
    // node's velocity is no motion of sand, so such nodes take the grain's
    // own velocity (the grad N_a sum to zero, so a velocity shared by all
    // corners adds nothing; docs/validation.md, "Shear rate of sand at rest").
    // The affine matrix keeps every node: leaving them out of it too made
    // the draining scenes' solves harder (docs/benchmarks.md, fortieth).
    // (A pass of its own: products shared with the loop above would change
    // how the compiler rounds the affine matrix.)
    if (empty_corners) {
      Vec<D> empty_grad = Vec<D>::Zero();
      Mat<D> empty_term = Mat<D>::Zero();
      for (int a = 0; a < NC; ++a) {
        if (!(empty_corners >> a & 1u)) continue;
        empty_grad += s.grad[a];
        empty_term.noalias() += P.velocity[base + corner[a]] * s.grad[a].transpose();
      }
      grad += u * empty_grad.transpose() - empty_term;
    }
    // Equivalent shear rate: 2 |Dev D| in the paper's norm (the simple-shear
    // rate for simple shear), used by mu(I) and by the cohesion decay.
    const double shear = 2.0 * deviatoric_norm<D>(to_sym<D>(grad));
    particles_.shear_rate[p] = shear;
    if (mp.has_mu_i) {
      // Lagged inertial number I = shear d_p / sqrt(P / rho_p), P the bulk
      // pressure, d_p and rho_p the particle's own grains.
      const double pressure = phi * trace_of<D>(lambda) / D;
      particles_.inertial[p] =
          pressure > 0.0 ? shear * mp.mu_i.grain_diameter / std::sqrt(pressure / mp.density)
                         : std::numeric_limits<double>::infinity();
    }
    // Cohesion decays with the plastic shear: the shear where the grain's
    // stress nodes do not stick (docs/method.md, "Conventions").
    if (decays) particles_.cohesion[p] *= std::exp(-mp.cohesion_decay * shear * yielding * dt);
    // Advection and the domain's faces: a particle crossing a free face (or
    // an opening) is left outside and dropped at the next sort; on walls it
    // is put back just inside (it can only overshoot when cfl > 1).
    const Vec<D> from = x;
    x += dt * u;
    put_inside_walls(x);
    // A grain the interpolated velocity carried into an obstacle (or that a
    // moving obstacle ran into) is put back on its surface: the grid
    // velocity keeps nodes out, not points between them.
    Vec<D> carried = from;
    if (driven) {
      Vec<D> n;
      int k = 0;
      obstacle_distance(obstacles_start, from, &n, &k);
      const Obstacle<D>& s0 = obstacles_start[k];
      const Obstacle<D>& s1 = obstacles_end[k];
      if (!s0.dynamic && moves_into_sand(s0))
        carried = s0.posed ? Vec<D>(s1.a + s1.rotation * (s0.rotation.transpose() * (from - s0.a)))
                           : Vec<D>(from + (s1.a - s0.a));
    }
    // A grain held on the side of a thin part it came from keeps no
    // velocity into the part, relative to its surface, and no velocity
    // gradient: the grid does not resolve the part (its nodes beyond it
    // fall freely), and carried on by APIC that would grow step after step
    // (measured: a grain held at a wedge's tip reached 7 m/s in 1 s).
    // Where every solid stays where the last step left it, the grain's
    // clearance less the step's length still bounds its distance; where
    // that shows the step ending outside every solid and crossing none,
    // that is the query's answer (move_outside_solids).
    Vec<D> held;
    const double step = (x - from).norm();
    if (in_place && clear_of_solids(p, step)) {
      clearance_[p] -= step;
    } else if (put_outside_solids(obstacles_end, x, &carried, &held, &clearance_[p])) {
      Vec<D> n;
      int k = 0;
      obstacle_distance(obstacles_end, x, &n, &k);
      Vec<D>& v = particles_.velocity[p];
      const double into = (v - surface_velocity(obstacles_end[k], x)).dot(held);
      if (into < 0.0) v -= into * held;
      particles_.affine[p].setZero();
    }
  }
  if (bad != std::numeric_limits<std::int64_t>::max())
    throw std::runtime_error("non-finite velocity at step " + std::to_string(steps_) +
                             ", particle id " + std::to_string(particles_.id[bad]) +
                             ", stage G2P (grid to particles)");
}

template void Simulation<2>::transfer_to_particles(double);
template void Simulation<3>::transfer_to_particles(double);

}  // namespace sablier
