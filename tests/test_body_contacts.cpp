// Rigid balls against the scene's obstacles and against each other
// (METHOD.md section 3; src/physics/transfer.cpp): a row on a ghost node
// with zero velocity, the normal from the ball to the other solid, the
// smaller friction of the two, and, against another ball, that ball's
// velocities as a second body of the same row (cone_problem.hpp). Sources:
// rigid-body mechanics (rolling and sliding down an incline, a perfectly
// inelastic collision: the model has no restitution) and the conservation
// of momentum.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

const testing::Environment* const kOneThread =
    testing::AddGlobalTestEnvironment(new test::OneThread);

using test::scene;

using test::kPi;
constexpr double kG = 9.81;
constexpr double kTolerance = 1e-6;  // a tenth of the shipped scenes' default

Vec3d vec3(double x, double y, double z = 0.0) { return Vec3d{x, y, z}; }

// The scene's sand as one small block in the top far corner, above every
// ramp and belt of these tests, which the balls never meet.
template <int D>
SceneConfig with_far_sand(const SceneConfig& base) {
  return test::small_block_only<D>(base, D == 2 ? vec3(0.44, 0.34) : vec3(0.44, 0.0, 0.29));
}

ObstacleConfig ball_config(const Vec3d& centre, double r, double mu, double density,
                           const Vec3d& velocity = Vec3d{0, 0, 0}) {
  ObstacleConfig b;
  b.shape = ObstacleShape::Ball;
  b.center = centre;
  b.radius = r;
  b.mu = mu;
  b.density = density;
  b.velocity = velocity;
  return b;
}

// A ball released from rest on a plane obstacle inclined at theta = 20
// degrees (falling along +x). With friction mu = min(ball, plane) above
// tan(theta) / (1 + m r^2 / J) it rolls without slipping and accelerates at
// g sin(theta) / (1 + J / (m r^2)): 2/3 of g sin(theta) for a disk, 5/7 for
// a sphere, with omega r = v; on a frictionless plane (the plane's mu = 0,
// the ball's 0.5: the smaller counts) it slides at g sin(theta) without
// spinning. Checked after 0.25 s: speed along the slope, spin, and the
// centre still r above the plane.
template <int D>
void ball_on_ramp(SceneConfig base, double plane_mu, double expected_fraction) {
  const double theta = 20.0 * kPi / 180.0, r = 0.04, T = 0.25, dt = 1.0 / 240;
  SceneConfig s = with_far_sand<D>(base);
  // The plane through (0, 0.25) (2D) or (0, 0, 0.25) (3D), normal
  // (sin theta, cos theta) in the x-up plane.
  ObstacleConfig plane;
  plane.shape = ObstacleShape::Plane;
  plane.point = D == 2 ? vec3(0.0, 0.25) : vec3(0.0, 0.0, 0.25);
  plane.normal =
      D == 2 ? vec3(std::sin(theta), std::cos(theta)) : vec3(std::sin(theta), 0.0, std::cos(theta));
  plane.mu = plane_mu;
  s.obstacles.push_back(plane);
  // Tangent to the plane above its point at x = 0.1.
  const double x0 = 0.1, surface = 0.25 - x0 * std::tan(theta);
  const Vec3d centre = D == 2
                           ? vec3(x0 + r * std::sin(theta), surface + r * std::cos(theta))
                           : vec3(x0 + r * std::sin(theta), 0.125, surface + r * std::cos(theta));
  s.obstacles.push_back(ball_config(centre, r, 0.5, 2500.0));
  Simulation<D> sim(s);
  while (sim.time() < T - 1e-12) sim.step(std::min(dt, T - sim.time()));
  const Obstacle<D>& b = sim.obstacles()[1];
  Vec<D> down = Vec<D>::Zero(), n = Vec<D>::Zero();  // along the slope, and the normal
  down[0] = std::cos(theta);
  down[D - 1] = -std::sin(theta);
  n[0] = std::sin(theta);
  n[D - 1] = std::cos(theta);
  const double expected = expected_fraction * kG * std::sin(theta) * T;
  const double speed = b.velocity.dot(down);
  // Spin about z (2D) or y (3D); rolling: V + omega x (-r n) = 0, that is
  // omega r = -speed in 2D (clockwise) and +speed about y in 3D.
  const double surface_speed = D == 2 ? -b.spin[0] * r : b.spin[1] * r;
  Vec<D> p0 = Vec<D>::Zero();
  p0[D - 1] = 0.25;
  const double height = (b.a - p0).dot(n);
  std::cout << D << "D ball on a ramp (plane mu " << plane_mu << "): speed " << speed
            << " m/s against " << expected << ", spin x r " << surface_speed << " m/s, height "
            << height << " m (r = " << r << ")\n";
  EXPECT_NEAR(speed, expected, 1e-6 * expected);
  EXPECT_NEAR(b.velocity.dot(n), 0.0, 1e-9);
  EXPECT_NEAR(surface_speed, plane_mu > 0.0 ? expected : 0.0, 1e-6 * expected);
  EXPECT_NEAR(height, r, 1e-9);
}

TEST(BodyContacts, DiskRollsDownARampAtTwoThirdsOfGSinTheta2D) {
  ball_on_ramp<2>(scene("drop2d.toml"), 0.5, 2.0 / 3.0);
}
TEST(BodyContacts, SphereRollsDownARampAtFiveSeventhsOfGSinTheta3D) {
  ball_on_ramp<3>(scene("bed3d.toml"), 0.5, 5.0 / 7.0);
}
TEST(BodyContacts, DiskSlidesDownAFrictionlessRamp2D) {
  ball_on_ramp<2>(scene("drop2d.toml"), 0.0, 1.0);
}

// A ball at rest on a horizontal conveyor-belt plane (an obstacle moving
// along itself at v_b = 1 m/s, friction 0.5). Friction drags it and spins
// it up until its contact point moves with the belt, V + omega x (-r n) =
// v_b; from then on it rolls at v_b J / (J + m r^2): v_b / 3 for a disk
// (after v_b / (3 mu g) = 0.068 s) and 2 v_b / 7 for a sphere. Checked at
// 0.2 s, to 1e-6.
template <int D>
void ball_on_belt(SceneConfig base, double expected_fraction) {
  const double r = 0.04, vb = 1.0, dt = 1.0 / 240;
  SceneConfig s = with_far_sand<D>(base);
  ObstacleConfig belt;
  belt.shape = ObstacleShape::Plane;
  belt.point = D == 2 ? vec3(0.0, 0.05) : vec3(0.0, 0.0, 0.05);
  belt.normal = D == 2 ? vec3(0.0, 1.0) : vec3(0.0, 0.0, 1.0);
  belt.velocity = vec3(vb, 0.0);
  belt.mu = 0.5;
  s.obstacles.push_back(belt);
  s.obstacles.push_back(
      ball_config(D == 2 ? vec3(0.1, 0.05 + r) : vec3(0.1, 0.125, 0.05 + r), r, 0.5, 2500.0));
  Simulation<D> sim(s);
  while (sim.time() < 0.2 - 1e-12) sim.step(dt);
  const Obstacle<D>& b = sim.obstacles()[1];
  // Spin about z (2D) or y (3D); the contact point's velocity is
  // V + omega x (-r n): V_x - omega r in 2D, V_x + omega_y r in 3D.
  const double surface = D == 2 ? -b.spin[0] * r : b.spin[1] * r;
  std::cout << D << "D ball on a belt at " << vb << " m/s: speed " << b.velocity[0]
            << " m/s against " << expected_fraction * vb << ", contact point "
            << b.velocity[0] - surface << " m/s\n";
  EXPECT_NEAR(b.velocity[0], expected_fraction * vb, 1e-6);
  EXPECT_NEAR(b.velocity[0] - surface, vb, 1e-6);
  EXPECT_NEAR(b.a[D - 1], 0.05 + r, 1e-9);
}

TEST(BodyContacts, DiskOnABeltRollsAtAThirdOfItsSpeed2D) {
  ball_on_belt<2>(scene("drop2d.toml"), 1.0 / 3.0);
}
TEST(BodyContacts, SphereOnABeltRollsAtTwoSeventhsOfItsSpeed3D) {
  ball_on_belt<3>(scene("bed3d.toml"), 2.0 / 7.0);
}

// Two balls on a slip floor (frictionless), the first launched at v0 = 1
// m/s straight at the second, at rest 1 cm away. The contact has no
// restitution, so the collision is perfectly inelastic: momentum is
// conserved at every step, and afterwards both move at m_1 v0 / (m_1 +
// m_2), touching. Different densities make the masses differ (3D: 2500 and
// 7500 kg/m^3, so the pair ends at v0 / 4). Then a box obstacle stops the
// pair: the balls must come to rest against it, the front one touching it.
template <int D>
void balls_collide(SceneConfig base, double density2) {
  const double r = 0.04, v0 = 1.0, dt = 1.0 / 240;
  SceneConfig s = with_far_sand<D>(base);
  s.boundary.faces[2 * (D - 1)] = BoundaryType::Slip;  // the floor
  const double y = 0.125;
  s.obstacles.push_back(
      ball_config(D == 2 ? vec3(0.1, r) : vec3(0.1, y, r), r, 0.5, 2500.0, vec3(v0, 0.0)));
  s.obstacles.push_back(ball_config(
      D == 2 ? vec3(0.1 + 2 * r + 0.01, r) : vec3(0.1 + 2 * r + 0.01, y, r), r, 0.5, density2));
  // A fixed box the pair runs into, its face at x = 0.35.
  ObstacleConfig box;
  box.shape = ObstacleShape::Box;
  box.min = D == 2 ? vec3(0.35, 0.0) : vec3(0.35, 0.0, 0.0);
  box.max = D == 2 ? vec3(0.4, 0.1) : vec3(0.4, 0.25, 0.1);
  box.mu = 0.5;
  s.obstacles.push_back(box);
  s.solver.tolerance = kTolerance;
  Simulation<D> sim(s);
  const double m1 = sim.obstacles()[0].mass, m2 = sim.obstacles()[1].mass;
  const double expected = m1 * v0 / (m1 + m2);
  // Until the pair reaches the box (the front ball's face at x = 0.35).
  double worst = 0.0;
  while (sim.time() < 0.1 - 1e-12) {
    sim.step(dt);
    const double p = m1 * sim.obstacles()[0].velocity[0] + m2 * sim.obstacles()[1].velocity[0];
    worst = std::max(worst, std::abs(p - m1 * v0));
  }
  const Obstacle<D>& a = sim.obstacles()[0];
  const Obstacle<D>& b = sim.obstacles()[1];
  std::cout << D << "D collision: speeds " << a.velocity[0] << " and " << b.velocity[0]
            << " m/s against " << expected << ", gap " << (b.a[0] - a.a[0] - 2 * r)
            << " m, worst momentum error " << worst << " kg m/s (of " << m1 * v0 << ")\n";
  EXPECT_LT(worst, 1e-9 * m1 * v0);
  EXPECT_NEAR(a.velocity[0], expected, 1e-6 * v0);
  EXPECT_NEAR(b.velocity[0], expected, 1e-6 * v0);
  EXPECT_NEAR(b.a[0] - a.a[0], 2 * r, 1e-9);
  // On to the box: at rest against it. The rows of the two balls hang
  // together (floor, pair, box), so the stop is exact only to the solver's
  // tolerance, a relative velocity change per sweep of 1e-6 of the step's
  // correction, about g dt: the bound on the speeds left after it, which
  // carry the balls across gaps of that order until the rows close them.
  while (sim.time() < 1.0 - 1e-12) sim.step(dt);
  const double still = kTolerance * kG * dt;
  std::cout << D << "D pair against the box: speeds " << a.velocity.norm() << ", "
            << b.velocity.norm() << " m/s (bound " << still << "), front ball's face at "
            << b.a[0] + r << " m, gap between the balls " << (b.a[0] - a.a[0] - 2 * r) << " m\n";
  EXPECT_LT(a.velocity.norm(), still);
  EXPECT_LT(b.velocity.norm(), still);
  EXPECT_NEAR(b.a[0] + r, 0.35, 0.5 * still);
  EXPECT_NEAR(b.a[0] - a.a[0], 2 * r, 0.5 * still);
}

TEST(BodyContacts, EqualDisksCollideInelastically2D) {
  balls_collide<2>(scene("drop2d.toml"), 2500.0);
}
TEST(BodyContacts, UnequalSpheresCollideInelastically3D) {
  balls_collide<3>(scene("bed3d.toml"), 7500.0);
}

}  // namespace
}  // namespace sablier
