// Solids driven into the sand (obstacle[].velocity on a fixed obstacle)
// with the projection as decompaction (solver.decompaction = "project",
// decompaction.cpp): the grains a solid crowds are moved by the gradient of
// node potentials that take every node back to phi_max. Checked against
// kinematics (a rising floor lifts a bed at rest as a block), the phi_max
// bound, Rankine's passive thrust on a ploughing blade, and thread
// independence.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "io/writers.hpp"
#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "scene/scene_reader.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

const testing::Environment* const kOneThread =
    testing::AddGlobalTestEnvironment(new test::OneThread);

using test::run_until;
using test::scene;

// The largest volume fraction the grains see (G2P's interpolated phi).
template <int D>
double largest_phi(const Simulation<D>& sim) {
  double most = 0.0;
  for (double p : sim.particles().phi) most = std::max(most, p);
  return most;
}

// A 10 cm bed (jittered grains) resting on a plane floor 5 cm above the
// box's floor that rises at 0.1 m/s. Source: kinematics. The floor cannot
// be crossed and the sand above it has nowhere else to go, so the bed must
// rise with it as a block: every grain at the floor's speed, the sand
// neither compacted beyond phi_max nor left behind. With the grains' moves
// (the default decompaction without moving solids) the grains crossed the
// nodes a layer at a time and their velocities formed a checkerboard
// (docs/method.md); with the projection, measured (2D, 0.5 s): mean
// vertical velocity 0.0993 m/s, slowest grain 0.093, largest phi 0.601.
template <int D>
void rising_floor_lifts_the_bed() {
  const double up = 0.1;
  SceneConfig s = scene(
      D == 2 ? "bed2d.toml" : "bed3d.toml",
      D == 2 ? std::vector<std::string>{"grid.size=[0.2,0.4]", "grid.resolution=[20,40]",
                                        "sand.0.min=[0.0,0.05]", "sand.0.max=[0.2,0.15]",
                                        "sand.0.jitter=0.3", "sand.0.particles_per_cell=3"}
             : std::vector<std::string>{"grid.size=[0.1,0.1,0.25]", "grid.resolution=[10,10,25]",
                                        "sand.0.min=[0.0,0.0,0.03]", "sand.0.max=[0.1,0.1,0.1]",
                                        "sand.0.jitter=0.3", "sand.0.particles_per_cell=3"});
  ObstacleConfig floor;
  floor.shape = ObstacleShape::Plane;
  floor.point = D == 2 ? Vec3d{0, 0.05, 0} : Vec3d{0, 0, 0.03};
  floor.normal = D == 2 ? Vec3d{0, 1, 0} : Vec3d{0, 0, 1};
  floor.velocity = D == 2 ? Vec3d{0, up, 0} : Vec3d{0, 0, up};
  floor.mu = 0.5;
  s.obstacles.push_back(floor);
  s.solver.decompaction = Decompaction::Project;
  Simulation<D> sim(s);
  const std::size_t grains = sim.particles().size();
  const double duration = D == 2 ? 0.5 : 0.3;
  run_until(sim, duration, 1.0 / 60);
  double mean = 0.0, slowest = 1e300, fastest = -1e300, lowest = 1e300;
  for (std::size_t p = 0; p < sim.particles().size(); ++p) {
    const double v = sim.particles().velocity[p][D - 1];
    mean += v;
    slowest = std::min(slowest, v);
    fastest = std::max(fastest, v);
    lowest = std::min(lowest, sim.particles().position[p][D - 1]);
  }
  mean /= static_cast<double>(sim.particles().size());
  const double floor_now = floor.point[D - 1] + up * duration;
  std::cout << D << "D rising floor: mean vertical velocity " << mean << " m/s (slowest " << slowest
            << ", fastest " << fastest << "), largest phi " << largest_phi(sim) << ", lowest grain "
            << lowest - floor_now << " m above the floor\n";
  EXPECT_EQ(sim.particles().size(), grains);
  EXPECT_NEAR(mean / up, 1.0, 0.02);
  EXPECT_GT(slowest, 0.85 * up);
  EXPECT_LT(fastest, 1.15 * up);
  EXPECT_LT(largest_phi(sim), 0.61);
  EXPECT_GT(lowest, floor_now - 1e-9);
}

TEST(MovingSolids, RisingFloorLiftsTheBedAsABlock2D) { rising_floor_lifts_the_bed<2>(); }
TEST(MovingSolids, RisingFloorLiftsTheBedAsABlock3D) { rising_floor_lifts_the_bed<3>(); }

// The shipped plough (scenes/plough2d.toml): a smooth blade pushed at 0.1
// m/s into a 10 cm bed on a rough floor. Source: Rankine (1857), the
// passive earth pressure on a smooth vertical wall pushed into a horizontal
// cohesionless backfill, F_p = K_p rho phi_max g H^2 / 2 with K_p = (1 +
// sin phi) / (1 - sin phi) = 3 for sin phi = mu (the 2D Mohr-Coulomb angle
// of METHOD.md section 4): 220.7 N/m for H = 0.1 m. Rankine's state is the
// associated material's collapse; our flow rule is non-associated (no
// dilatancy, METHOD.md section 1), which lowers collapse loads (Drescher &
// Detournay 1993), and the mound grows as the blade moves. Measured: mean
// force over 0.05-0.3 s 220.2 N/m (-0.2%) with the 5 grains per cell and
// axis the scene seeds since the thirty-sixth session; with 3 (shipped
// until then) 186 N/m (-16%), the particle quadrature letting the pushed
// sand compact and the projection undoing it without a force (198 and 191
// N/m under earlier projections). The test asks for the mean within 10% of
// F_p, which the 3-grain seeding fails. The sand stays at phi_max:
// after the first step the largest phi any grain sees is 0.6006 (with the
// grains' moves instead, in the same box with a slip floor, 10% of the
// grains were at phi 0.70 or more after 1.2 s, docs/method.md).
TEST(MovingSolids, PloughPushesWithRankinesPassiveThrust2D) {
  const SceneConfig s = scene("plough2d.toml");
  ASSERT_EQ(s.solver.decompaction, Decompaction::Project);  // chosen for the moving blade
  Simulation<2> sim(s);
  const std::size_t grains = sim.particles().size();
  double impulse = 0.0, span = 0.0, most_phi = 0.0;
  while (sim.time() < 0.3 - 1e-12) {
    const StepInfo info = sim.step(sim.adaptive_dt(std::min(1.0 / 30, 0.3 - sim.time())));
    if (sim.time() > 0.05 + 1e-12) {
      impulse += -info.obstacle_force[0][0] * info.dt;
      span += info.dt;
    }
    // From the second step on: the first step's phi is the jittered
    // seeding's own (up to 0.627), before any projection.
    if (sim.steps() > 1) most_phi = std::max(most_phi, largest_phi(sim));
  }
  const double rankine = 3.0 * s.material.density * s.material.phi_max * 9.81 * 0.1 * 0.1 / 2.0;
  std::cout << "plough: mean force " << impulse / span << " N/m against Rankine's passive "
            << rankine << " N/m, largest phi " << most_phi << "\n";
  EXPECT_NEAR(impulse / span / rankine, 1.0, 0.10);
  EXPECT_LT(most_phi, 0.61);
  EXPECT_EQ(sim.particles().size(), grains);
}

// A blade whose faces lie on walls: the plough's blade resting on the floor
// (2D), and in 3D across the whole box, on the floor and between the side
// walls. A grain the blade runs into goes back out through the front face,
// not through the wall that its nearest face lies on, so the box keeps
// every grain (mass conservation: walls let none out) and none is left
// inside the blade. Before, grains near the blade's lower face went out
// through the floor: the 2D plough on the floor lost 38 of 8,370 grains in
// 1 s, the 3D blade 533 of 43,740 in 0.4 s.
template <int D>
void blade_on_walls_keeps_every_grain(const SceneConfig& s, double t) {
  Simulation<D> sim(s);
  const std::size_t grains = sim.particles().size();
  double deepest = 0.0;
  while (sim.time() < t - 1e-12) {
    sim.step(sim.adaptive_dt(std::min(1.0 / 30, t - sim.time())));
    const Obstacle<D> blade = sim.obstacles_at(sim.time())[0];
    for (const Vec<D>& x : sim.particles().position) {
      Vec<D> n;
      deepest = std::min(deepest, signed_distance(blade, x, &n));
    }
  }
  std::cout << D << "D blade on the walls: " << sim.particles().size() << " of " << grains
            << " grains left after " << t << " s, deepest inside the blade " << deepest << " m\n";
  EXPECT_EQ(sim.particles().size(), grains);
  EXPECT_GE(deepest, 0.0);
}

TEST(MovingSolids, BladeOnTheFloorKeepsEveryGrain2D) {
  blade_on_walls_keeps_every_grain<2>(scene("plough2d.toml", {"obstacle.0.min=[0.05,0.0]"}), 1.0);
}

TEST(MovingSolids, BladeAcrossTheBoxKeepsEveryGrain3D) {
  blade_on_walls_keeps_every_grain<3>(
      scene("plough3d.toml", {"obstacle.0.min=[0.04,0.0,0.0]", "obstacle.0.max=[0.06,0.3,0.2]"}),
      0.4);
}

// A blade half a cell thick (5 mm at 1 cm cells) driven through the bed:
// no grain gets behind it (it reaches above the box and below the floor,
// so none can go around). A grain the blade runs into is put back where
// its path relative to the blade entered the blade; put back through the
// nearest face instead, grains past the blade's middle went out behind it:
// 16 of 8,370 by 0.67 s, 17 by 1 s. And it pushes as the shipped 2 cm
// blade does (the test above, same source: here within 10% of Rankine's
// passive thrust over a longer time, in which the mound grows), keeping
// the sand at phi_max, since the grains in front of it keep to the nodes
// on their side (the compatible transfer, at the blade's place at each
// step): measured 236 N/m over 0.05-0.7 s (+7%) with the scene's 5 grains
// per cell and axis, 208 N/m (-6%) with 3, largest phi 0.6007. All the
// figures that follow are with 3. Without that transfer (the sand in front sharing the
// nodes behind the blade) it pushed with 157 N/m (-29%); a 3 mm blade over
// 0.05-0.6 s with 118 N/m and 190 N/m with it (the 2 cm blade 210), its
// sand at phi 0.688 and 0.605 (frames from the second on).
TEST(MovingSolids, ThinBladeLetsNoGrainBehind2D) {
  const SceneConfig s = scene("plough2d.toml", {"obstacle.0.min=[0.065,-0.05]"});
  Simulation<2> sim(s);
  std::size_t behind = 0;
  double impulse = 0.0, span = 0.0, most_phi = 0.0;
  while (sim.time() < 0.7 - 1e-12) {
    const StepInfo info = sim.step(sim.adaptive_dt(std::min(1.0 / 30, 0.7 - sim.time())));
    const Obstacle<2> blade = sim.obstacles_at(sim.time())[0];
    for (const Vec<2>& x : sim.particles().position) behind += x[0] < blade.a[0];  // a: min corner
    if (sim.time() > 0.05 + 1e-12) {
      impulse += -info.obstacle_force[0][0] * info.dt;
      span += info.dt;
    }
    if (sim.steps() > 1) most_phi = std::max(most_phi, largest_phi(sim));
  }
  const double rankine = 3.0 * s.material.density * s.material.phi_max * 9.81 * 0.1 * 0.1 / 2.0;
  std::cout << "thin blade: " << behind << " grain-steps behind it, mean force " << impulse / span
            << " N/m against Rankine's " << rankine << ", largest phi " << most_phi << "\n";
  EXPECT_EQ(behind, 0u);
  EXPECT_NEAR(impulse / span / rankine, 1.0, 0.10);
  EXPECT_LT(most_phi, 0.61);
}

// The projection's sums are in particle order and its Gauss-Seidel colours
// independent (decompaction.cpp): the same bits on 1 and 2 threads (the
// plough, 12 steps).
TEST(MovingSolids, ProjectionGivesTheSameBitsOnAnyThreadCount) {
  test::expect_same_bits_on_1_and_2_threads<2>(scene("plough2d.toml"), 12);
}

// The same in 3D (plough3d, whose blade the sand flows around), 6 steps.
TEST(MovingSolids, ProjectionGivesTheSameBitsOnAnyThreadCount3D) {
  test::expect_same_bits_on_1_and_2_threads<3>(scene("plough3d.toml"), 6);
}

// Three threads split the decompaction's scatters in three ranges of nodes,
// each starting at the cell of a grain (scatter_by_ranges), and the solve's
// team stays at the processors' count: still the bits of one thread
// (collapse3d on a coarse grid, jittered grains, 6 steps).
TEST(MovingSolids, DecompactionGivesTheSameBitsOnThreeThreads3D) {
  const SceneConfig s =
      scene("collapse3d.toml", {"grid.resolution=[40,4,10]", "sand.0.jitter=0.5", "seed=3"});
  const int threads = omp_get_max_threads();
  std::vector<std::vector<Vec<3>>> positions;
  for (int t : {1, 3}) {
    omp_set_num_threads(t);
    Simulation<3> sim(s);
    for (int i = 0; i < 6; ++i) sim.step(sim.adaptive_dt(1.0 / s.time.fps));
    positions.push_back(sim.particles().position);
  }
  omp_set_num_threads(threads);
  EXPECT_EQ(positions[0], positions[1]);
}

// Without a moving solid the projection leaves a bed at rest alone: bed2d
// (frictionless side walls) with decompaction = "project" stays below 1e-3
// m/s after 1 s, as with the moves (METHOD.md section 5's bed test).
TEST(MovingSolids, ProjectionLeavesABedAtRest2D) {
  Simulation<2> sim(scene("bed2d.toml", {"solver.decompaction=\"project\""}));
  run_until(sim, 1.0, 1.0 / 30);
  double fastest = 0.0;
  for (const Vec<2>& u : sim.particles().velocity) fastest = std::max(fastest, u.norm());
  std::cout << "bed2d with the projection: fastest grain after 1 s " << fastest
            << " m/s, largest phi " << largest_phi(sim) << "\n";
  EXPECT_LT(fastest, 1e-3);
  EXPECT_LT(largest_phi(sim), 0.61);
}

// Sand at rest in a vee of two fixed planes sloping at 30 degrees, under
// the projection: a bed at rest has nothing to decompact, so the work of the
// projection's lifts (StepInfo::restoring_work) must stay at the level of
// the quadrature's noise. Fixed solids take no share of a node's capacity
// (project_capacities): when they did, the plane estimate of that share
// and the grains' quadrature disagreed next to the walls and the grains
// were moved off them at every step (measured over 0.5 s: 0.188 J/m, 1.1e-3
// of the bed's potential energy; 6.0e-4 J/m, 3.5e-6, without the share).
// Bound: 1e-4 of the potential energy.
TEST(MovingSolids, ProjectionLeavesSandOnFixedSlopesAlone2D) {
  SceneConfig s = scene("bed2d.toml",
                        {"grid.size=[0.4,0.3]", "grid.resolution=[40,30]", "sand.0.max=[0.4,0.25]",
                         "boundary.default=\"stick\"", "solver.decompaction=\"project\""});
  for (double side : {-1.0, 1.0}) {
    ObstacleConfig plane;
    plane.shape = ObstacleShape::Plane;
    plane.point = Vec3d{0.2, 0.0, 0.0};
    plane.normal = Vec3d{0.5 * side, std::sqrt(3.0) / 2, 0.0};
    s.obstacles.push_back(plane);
  }
  Simulation<2> sim(s);
  const double energy = std::abs(sim.potential_energy());
  double work = 0.0;
  while (sim.time() < 0.5 - 1e-12) work += sim.step(sim.adaptive_dt(1.0 / 30)).restoring_work;
  double fastest = 0.0;
  for (const Vec<2>& u : sim.particles().velocity) fastest = std::max(fastest, u.norm());
  std::cout << "sand in a vee with the projection: lift work " << work << " J/m over 0.5 s ("
            << work / energy << " of the potential energy), fastest grain " << fastest << " m/s\n";
  EXPECT_LT(work, 1e-4 * energy);
  EXPECT_LT(fastest, 1e-3);
}

// A piston (a plane moving down at 0.05 m/s) closing a box whose bottom
// half is full of sand. Source: incompressibility: sand at phi_max in a
// closed box cannot make room for the piston once it touches (at 1 s), so
// the projection must leave it over-full and say so (StepInfo::crowding,
// which `sablier run` reports), while before the touch nothing is left
// over. Measured: 0.0010 at most before (the projection's slack), 0.26 of
// phi_max by 1.3 s.
TEST(MovingSolids, ConfinedSandIsReportedOverFull2D) {
  SceneConfig s = scene("bed2d.toml",
                        {"grid.size=[0.2,0.3]", "grid.resolution=[20,30]", "sand.0.max=[0.2,0.15]",
                         "sand.0.jitter=0.3", "boundary.ymax=\"stick\""});
  ObstacleConfig piston;
  piston.shape = ObstacleShape::Plane;
  piston.point = {0.0, 0.2, 0.0};
  piston.normal = {0.0, -1.0, 0.0};
  piston.velocity = {0.0, -0.05, 0.0};
  s.obstacles.push_back(piston);
  s.solver.decompaction = Decompaction::Project;
  Simulation<2> sim(s);
  double before = 0.0, after = 0.0;
  while (sim.time() < 1.3 - 1e-12) {
    const StepInfo info = sim.step(sim.adaptive_dt(std::min(1.0 / 30, 1.3 - sim.time())));
    (sim.time() < 0.95 ? before : after) =
        std::max(sim.time() < 0.95 ? before : after, info.crowding);
  }
  std::cout << "piston: crowding left " << before << " before the touch, " << after << " after\n";
  EXPECT_LE(before, 1e-3);
  EXPECT_GT(after, 0.01);
}

// ParaView sees a moving solid where it is: `sablier run` writes its
// surface at each frame to frames/bodies_NNNNN.vtp (with the rigid
// bodies'), moved by its velocity times the frame's time, and leaves it out
// of obstacles.obj (the fixed solids' surfaces).
TEST(MovingSolids, FramesShowTheBladeWhereItIs) {
  const auto dir = test::fresh_dir("moving_solid_frames");
  const test::Result r = test::sablier("run " + test::scene_file("plough2d.toml") + " --out " +
                                       dir.string() + " --quiet --set time.frames=3");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string first = read_file((dir / "frames/bodies_00000.vtp").string());
  const std::string last = read_file((dir / "frames/bodies_00003.vtp").string());
  // The blade's lower left corner: (0.05, -0.05) at 0 s, 0.1 m/s x 0.1 s further at frame 3.
  EXPECT_NE(first.find("0.050000000000000003 -0.050000000000000003 0\n"), std::string::npos)
      << first;
  EXPECT_NE(last.find("0.060000000000000005 -0.050000000000000003 0\n"), std::string::npos) << last;
  EXPECT_FALSE(std::filesystem::exists(dir / "obstacles.obj"));
}

}  // namespace
}  // namespace sablier
