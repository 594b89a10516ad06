// Rigid bodies' velocity unknowns in the cone solver (METHOD.md section 3,
// two-way coupling; src/solver/cone_problem.hpp). A body's linear and
// angular velocities are extra entries of the velocity vector with inverse
// masses dt / m and dt / J; its contact rows see the sand's velocity
// relative to the body's surface and push the body back. Checked on a body
// buried in a bed at rest: released from rest under gravity, the sand must
// hold it up (statics: the force of the sand on the body is its weight, and
// a still bed does not let it move), the momentum it gains must equal the
// impulse of its contact stresses, and the answer must not depend on the
// thread count (the body's rows are solved in order on one thread).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "physics/emission.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

const testing::Environment* const kOneThread =
    testing::AddGlobalTestEnvironment(new test::OneThread);

using test::scene;

using test::kPi;
constexpr double kTolerance = 1e-6;  // a tenth of the shipped scenes' default

struct BuriedBody {
  double mass = 0.0;   // kg (kg per metre of depth in 2D)
  double dt = 0.0;     // s
  std::int64_t v = 0;  // velocity index of the body's linear velocity
  Vec3d gravity{0, 0, 0};
};

// A ball of radius r and density 2500 buried in the middle of the shipped
// bed (its top 0.1 m below the surface), first as a fixed obstacle while the
// bed settles for 0.3 s; then the next step's problem, rebuilt with zero
// warm start (u_f = u - M^{-1} H^T lambda), gets the ball as a body released
// from rest: V_f = g dt, omega_f = 0.
template <int D>
ConeProblem<D> buried_body_problem(BuriedBody* body) {
  SceneConfig s = scene(D == 2 ? "bed2d.toml" : "bed3d.toml");
  const double r = 0.05;
  ObstacleConfig ball;
  ball.shape = ObstacleShape::Ball;
  ball.center = D == 2 ? Vec3d{0.5, 0.15, 0} : Vec3d{0.25, 0.125, 0.12};
  ball.radius = r;
  ball.mu = 0.5;
  s.obstacles.push_back(ball);
  Simulation<D> sim(s);
  while (sim.time() < 0.3 - 1e-12) sim.step(sim.adaptive_dt(0.3 - sim.time()));
  const double dt = sim.adaptive_dt(1.0 / 30);
  sim.step(dt);
  ConeProblem<D> q = sim.problem();
  for (auto& l : q.lambda) l = -l;
  apply_stress_to_velocity(q);
  for (auto& l : q.lambda) l.setZero();

  const double density = 2500.0;
  const double mass = D == 2 ? density * kPi * r * r : density * 4.0 / 3.0 * kPi * r * r * r;
  const double inertia = D == 2 ? 0.5 * mass * r * r : 0.4 * mass * r * r;
  Vec<D> g, centre;
  for (int a = 0; a < D; ++a) {
    g[a] = s.gravity[a];
    centre[a] = ball.center[a];
  }
  const std::int64_t v = static_cast<std::int64_t>(q.velocity.size());
  q.velocity.push_back(g * dt);
  q.velocity.push_back(Vec<D>::Zero());
  q.inv_mass.push_back(Vec<D>::Constant(dt / mass));
  Vec<D> spin = Vec<D>::Constant(dt / inertia);
  if (D == 2) spin[1] = 0.0;
  q.inv_mass.push_back(spin);
  q.first_body_entry = v;
  q.spin_inverse.assign(1, Mat<D>(spin.asDiagonal()));  // a ball's J is isotropic
  q.spin_diagonal.assign(1, 1);
  q.first_body_row = q.first_contact;
  const int contacts = q.rows() - q.first_contact;
  q.contact_body.assign(contacts, v);
  q.contact_arm.resize(contacts);
  const double h = sim.grid().h();
  for (int c = 0; c < contacts; ++c) {
    const auto n = sim.grid().node_coords(q.node[q.first_contact + c]);
    for (int a = 0; a < D; ++a) q.contact_arm[c][a] = n[a] * h - centre[a];
  }
  assemble_delassus(q);
  body->mass = mass;
  body->dt = dt;
  body->v = v;
  body->gravity = s.gravity;
  return q;
}

// The diagonal block of each body contact row (assemble_delassus) against
// the velocity change it must describe, worked out here from the
// definitions: a traction r in the contact frame F puts f = w F r on the
// node (w = |g_jj|) and -f on the body at lever arm a (V -= M_b^{-1} f,
// omega -= J^{-1} (a x f)), and the relative velocity
// u_node - (V + omega x a), seen in the contact frame, must change by W r.
template <int D>
void check_body_delassus(const ConeProblem<D>& q, const BuriedBody& body) {
  constexpr int centre = ConeProblem<D>::NS / 2;
  for (int j = q.first_body_row; j < q.rows(); ++j) {
    const int c = j - q.first_contact;
    const Mat<D>& F = q.contact_frame[c];
    const LocalDelassus<D>& W = q.contact_delassus[c];
    const Vec<D>& a = q.contact_arm[c];
    const double w = q.coupling[j].col(centre).norm();
    for (int k = 0; k < D; ++k) {
      const Vec<D> r = Vec<D>::Unit(k);
      const Vec<D> f = w * F * r;
      const Vec<D> du = q.inv_mass[q.node[j]].cwiseProduct(f);
      const Vec<D> dV = -q.inv_mass[body.v].cwiseProduct(f);
      Vec<D> dpoint;
      if constexpr (D == 2) {
        const double dw = -q.inv_mass[body.v + 1][0] * (a[0] * f[1] - a[1] * f[0]);
        dpoint = dV + dw * Vec<D>(-a[1], a[0]);
      } else {
        const Vec<D> dw = -q.inv_mass[body.v + 1].cwiseProduct(a.cross(f));
        dpoint = dV + dw.cross(a);
      }
      const Vec<D> expected = F.transpose() * (du - dpoint);
      const Vec<D> stored = W.unrotate(W.apply_rotated(W.rotate(r)));
      ASSERT_LT((stored - expected).norm(), 1e-9 * expected.norm())
          << "row " << j << " direction " << k;
    }
  }
}

template <int D>
void body_held_by_bed() {
  BuriedBody body;
  ConeProblem<D> q = buried_body_problem<D>(&body);
  const int contacts = q.rows() - q.first_contact;
  ASSERT_GT(contacts, 0);
  check_body_delassus<D>(q, body);
  ConeProblem<D> p2 = q;  // the same solve on 2 threads, below
  const SolveReport rep = solve_gauss_seidel(q, kTolerance, 20000, 5);
  EXPECT_FALSE(rep.hit_cap) << "residual " << rep.residual;
  const Vec<D> V = q.velocity[body.v];
  const Vec<D> spin = q.velocity[body.v + 1];
  double g = 0.0;
  for (int a = 0; a < D; ++a) g += body.gravity[a] * body.gravity[a];
  g = std::sqrt(g);
  // The momentum the body gained is the impulse of its contact stresses
  // (push_body): m (V - V_f) = -dt sum_j Lambda_j g_jj.
  Vec<D> force = Vec<D>::Zero();
  constexpr int centre = ConeProblem<D>::NS / 2;
  for (int j = q.first_body_row; j < q.rows(); ++j)
    force += from_sym<D>(q.lambda[j]) * q.coupling[j].col(centre);
  Vec<D> g_vec;
  for (int a = 0; a < D; ++a) g_vec[a] = body.gravity[a];
  const Vec<D> momentum = body.mass * (V - g_vec * body.dt);
  const Vec<D> impulse = -body.dt * force;
  std::cout << D << "D ball buried in a bed, " << contacts << " contact rows, " << rep.iterations
            << " sweeps: speed " << V.norm() << " m/s after a step of free fall " << g * body.dt
            << " m/s; spin " << spin.norm() << " rad/s; force of the sand on the ball "
            << -force.transpose() << " N against weight " << body.mass * g << " N\n";
  EXPECT_LT((momentum - impulse).norm(), 1e-9 * body.mass * g * body.dt);
  // Statics: the bed carries the ball's weight and the ball stays put (to
  // the solver's tolerance: 1e-3 of the speed a free fall would reach).
  EXPECT_LT(V.norm(), 1e-3 * g * body.dt);
  EXPECT_NEAR(-force[D - 1], body.mass * g, 1e-3 * body.mass * g);
  EXPECT_LT(spin.norm() * 0.05, 1e-3 * g * body.dt);  // surface speed r omega
  // Same answer on 2 threads, to the bit.
  omp_set_num_threads(2);
  solve_gauss_seidel(p2, kTolerance, 20000, 5);
  omp_set_num_threads(1);
  for (std::size_t i = 0; i < q.velocity.size(); ++i) ASSERT_EQ(q.velocity[i], p2.velocity[i]) << i;
}

TEST(Bodies, BuriedBallIsHeldByTheBed2D) { body_held_by_bed<2>(); }
TEST(Bodies, BuriedBallIsHeldByTheBed3D) { body_held_by_bed<3>(); }

// A ball of density 2500 thrown down at 1 m/s onto a bed whose surface is at
// `surface`, run for `duration` s (the whole simulation: scene keys, the
// body's rows, its motion). Sources: the body's momentum balance, step by
// step, m (V_n - V_{n-1}) = (F_n + m g) dt_n with F_n the force of the sand
// on it (the solver gives the body V_f = V + g dt plus the impulse of its
// rows); and statics once it has stopped: over the second half of the run
// the sand carries its weight (the mean force, weighted by dt, equals m g to
// 1%), it has stopped (below 5 cm/s, from 1 m/s) and it rests in the
// surface: sunk, but by less than its radius.
template <int D>
void dropped_ball(const SceneConfig& s, double surface, double duration) {
  Simulation<D> sim(s);
  ASSERT_TRUE(sim.obstacles()[0].dynamic);
  const double m = sim.obstacles()[0].mass, r = sim.obstacles()[0].radius;
  Vec<D> g;
  for (int a = 0; a < D; ++a) g[a] = s.gravity[a];
  const test::BodyBalance run = test::run_body_balance(sim, duration);
  const double worst = run.worst;
  const Obstacle<D>& b = sim.obstacles()[0];
  const double weight = m * g.norm();
  std::cout << D << "D ball dropped on a bed: after " << duration << " s centre height "
            << b.a[D - 1] << " m (surface " << surface << ", radius " << r << "), speed "
            << b.velocity.norm() << " m/s, mean force of the sand over the second half "
            << run.mean_force << " N against weight " << weight << " N; momentum balance to "
            << worst << "\n";
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(run.mean_force, weight, 0.01 * weight);
  EXPECT_LT(b.velocity.norm(), 0.05);
  EXPECT_LT(b.a[D - 1], surface + r);
  EXPECT_GT(b.a[D - 1], surface - r);
}

TEST(Bodies, DroppedDiskIsCaughtByTheBed2D) {
  dropped_ball<2>(scene("drop2d.toml", {"time.frames=30"}), 0.15, 1.0);
}

TEST(Bodies, DroppedSphereIsCaughtByTheBed3D) {
  SceneConfig s = scene("bed3d.toml");
  ObstacleConfig ball;
  ball.shape = ObstacleShape::Ball;
  ball.center = Vec3d{0.25, 0.125, 0.32};
  ball.radius = 0.05;
  ball.density = 2500.0;
  ball.velocity = Vec3d{0, 0, -1.0};
  s.obstacles.push_back(ball);
  dropped_ball<3>(s, 0.25, 0.4);
}

// A ball launched along a rough floor (stick wall, friction mu = 0.5, the
// ball's own) with speed v0 and no spin. Source: rigid-body mechanics. It
// slides while friction mu m g decelerates it and spins it up, then rolls
// without slipping at v0 / (1 + J / (m r^2)): 2/3 v0 for a disk, 5/7 v0 for
// a sphere, from t = (v0 - v_roll) / (mu g) on. Checked: the speed after
// the first step (deceleration mu g), the rolling speed and spin at the
// end, and that it stays on the floor (height r). Sand: a small block in
// a far corner, which the ball never meets.
// With backspin (scene key `spin`, b = r omega_0 / v0 against the rolling
// sense), the angular momentum about the contact point is kept while it
// slides, so it ends rolling at v0 (1 - k b) / (1 + k), k = J / (m r^2):
// backwards when k b > 1.
template <int D>
void ball_rolls(SceneConfig s, double k, double backspin = 0.0) {
  const double r = 0.04, v0 = 1.0, mu = 0.5, g = 9.81;
  const double rolling_fraction = (1.0 - k * backspin) / (1.0 + k);
  // (In 2D the block is in the far corner: a disk sent back by its
  // backspin would otherwise meet the block's collapsing grains.)
  s = test::small_block_only<D>(std::move(s), D == 2 ? Vec3d{0.45, 0, 0} : Vec3d{0, 0, 0});
  ObstacleConfig ball;
  ball.shape = ObstacleShape::Ball;
  ball.center = D == 2 ? Vec3d{0.1, r, 0} : Vec3d{0.1, 0.125, r};
  ball.radius = r;
  ball.mu = mu;
  ball.density = 2500.0;
  ball.velocity = Vec3d{v0, 0, 0};
  const double w0 = backspin * v0 / r;  // counter-clockwise in 2D, about -y in 3D
  ball.spin = D == 2 ? Vec3d{0, 0, w0} : Vec3d{0, -w0, 0};
  s.obstacles.push_back(ball);
  Simulation<D> sim(s);
  const double dt = 1.0 / 240, end = backspin > 0.0 ? 0.4 : 0.2;
  sim.step(dt);
  EXPECT_NEAR(sim.obstacles()[0].velocity[0], v0 - mu * g * dt, 1e-9) << "sliding";
  while (sim.time() < end - 1e-12) sim.step(std::min(dt, end - sim.time()));
  const Obstacle<D>& b = sim.obstacles()[0];
  const double spin = D == 2 ? b.spin[0] : b.spin[1];  // about z (2D) or y (3D)
  const double expected = rolling_fraction * v0;
  std::cout << D << "D ball on a rough floor, backspin " << backspin << ": speed " << b.velocity[0]
            << " m/s against " << expected << ", spin " << spin << " rad/s, height " << b.a[D - 1]
            << " m\n";
  EXPECT_NEAR(b.velocity[0], expected, 1e-6);
  // Rolling: the contact point is still, v + omega x (-r e_up) = 0.
  EXPECT_NEAR(D == 2 ? -spin * r : spin * r, expected, 1e-6);
  EXPECT_NEAR(b.a[D - 1], r, 1e-9);
}

TEST(Bodies, DiskRollsAtTwoThirdsOfItsSpeed2D) { ball_rolls<2>(scene("drop2d.toml"), 0.5); }
TEST(Bodies, SphereRollsAtFiveSeventhsOfItsSpeed3D) { ball_rolls<3>(scene("bed3d.toml"), 0.4); }
// Backspin b = 3: the disk comes back at -1/3 v0, the sphere at -1/7 v0.
TEST(Bodies, DiskWithBackspinComesBack2D) { ball_rolls<2>(scene("drop2d.toml"), 0.5, 3.0); }
TEST(Bodies, SphereWithBackspinComesBack3D) { ball_rolls<3>(scene("bed3d.toml"), 0.4, 3.0); }

// A spout pouring onto a rigid disk (scenes/drop2d.toml's): the body is
// where the run has taken it, not where the scene put it, so the grains
// that would appear inside the body as given are not emitted (the others
// keep their ids), and the scene's own starting position blocks nothing.
TEST(Bodies, SpoutsSeeBodiesWhereTheRunTookThem) {
  SceneConfig s = scene("drop2d.toml");
  SpoutConfig spout;
  spout.center = Vec3d{0.25, 0.35, 0};
  spout.radius = 0.05;
  spout.velocity = Vec3d{0, -0.5, 0};
  spout.jitter = 0.5;
  s.spouts = {spout};
  SceneConfig bare = s;
  bare.obstacles.clear();
  std::vector<Obstacle<2>> bodies = make_obstacles<2>(s);
  ASSERT_TRUE(bodies[0].dynamic);
  const Vec<2> moved_to(0.25, 0.18);
  bodies[0].a = moved_to;
  Particles<2> all, moved, unmoved;
  emit_spout_particles<2>(bare, 0.0, 0.4, all);
  emit_spout_particles<2>(s, 0.0, 0.4, moved, &bodies);
  emit_spout_particles<2>(s, 0.0, 0.4, unmoved);  // no bodies given
  std::vector<std::int64_t> ids;
  for (std::size_t k = 0; k < all.size(); ++k)
    if ((all.position[k] - moved_to).norm() >= bodies[0].radius) ids.push_back(all.id[k]);
  EXPECT_LT(ids.size(), all.size());
  EXPECT_EQ(moved.id, ids);
  EXPECT_EQ(unmoved.id, all.id);
}

}  // namespace
}  // namespace sablier
