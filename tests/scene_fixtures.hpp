// Shared fixtures of the scene-file tests (test_scene.cpp,
// test_scene_errors.cpp): base scenes, a scene with every key set, and
// helpers to edit scene text, catch the parser's message and compare two
// parsed scenes field by field.
#pragma once

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace sablier::test {

// Line numbers matter: the bad scenes below append lines from 9 on.
inline const std::string kBase2D = R"(dimension = 2
[grid]
size = [1.0, 0.5]
resolution = [40, 20]
[[sand]]
shape = "box"
min = [0.0, 0.0]
max = [0.2, 0.4]
)";

inline const std::string kBase3D = R"(dimension = 3
[grid]
size = [0.5, 0.25, 0.25]
resolution = [20, 10, 10]
[[sand]]
shape = "cylinder"
center = [0.25, 0.125, 0.0]
radius = 0.1
height = 0.2
)";

// Every key set, 2D: a disk, a box with its own material, a polygon, a spout,
// an orifice and the four 2D obstacle shapes (away from the sand but for the
// plane, which cuts nothing of it).
inline const std::string kFull2D = R"(dimension = 2
seed = 42
gravity = [1.5, -9.0]
[grid]
size = [2.0, 1.0]
resolution = [80, 40]
[time]
fps = 60
frames = 12
substeps = 4
cfl = 0.5
[material]
density = 1500
mu = 0.38
phi_max = 0.62
viscosity = 0.01
cohesion = 20.0
cohesion_decay = 3.0
mu_i = { delta_mu = 0.3, I0 = 0.3, grain_diameter = 2e-3 }
[solver]
tolerance = 1e-6
max_iterations = 300
anderson = 3
decompaction = "push"
decompaction_moves = 3
[boundary]
default = "stick"
xmax = "slip"
ymax = "free"
[[boundary.opening]]
face = "ymin"
min = [0.9, 0.0]
max = [1.1, 0.0]
[[sand]]
shape = "disk"
center = [0.5, 0.5]
radius = 0.25
particles_per_cell = 3
jitter = 0.5
velocity = [1.0, -0.5]
[[sand]]
shape = "box"
min = [1.0, 0.0]
max = [2.0, 0.5]
density = 2650
mu = 0.7
cohesion = 5.5
cohesion_decay = 0.25
mu_i = { delta_mu = 0.2, I0 = 0.4, grain_diameter = 5e-4 }
[[sand]]
shape = "polygon"
vertices = [[0.1, 0.8], [0.4, 0.8], [0.25, 0.95]]
[[spout]]
center = [1.5, 0.8]
radius = 0.05
velocity = [0.0, -2.0]
start = 0.1
stop = 0.5
particles_per_cell = 3
jitter = 0.25
[[obstacle]]
shape = "plane"
point = [0.0, 0.05]
normal = [0.1, 1.0]
mu = 0.3
velocity = [1.0, -0.1]
[[obstacle]]
shape = "box"
min = [0.8, 0.6]
max = [0.9, 0.7]
until = 0.5
[[obstacle]]
shape = "disk"
center = [1.7, 0.8]
radius = 0.05
mu = 0.0
[[obstacle]]
shape = "disk"
center = [1.2, 0.7]
radius = 0.04
density = 7800
velocity = [0.5, -1.0]
[[obstacle]]
shape = "polygon"
vertices = [[0.6, 0.1], [0.75, 0.1], [0.7, 0.2]]
)";

inline std::string replace(std::string s, const std::string& from, const std::string& to) {
  const std::size_t k = s.find(from);
  if (k == std::string::npos) throw std::logic_error("the fixture lacks " + from);
  return s.replace(k, from.size(), to);
}

// kBase2D with a disk of sand: center at line 7, radius at line 8.
inline std::string disk2d() {
  return replace(
      replace(replace(kBase2D, "\"box\"", "\"disk\""), "min = [0.0, 0.0]", "center = [0.5, 0.25]"),
      "max = [0.2, 0.4]", "radius = 0.1");
}

// A spout and no sand: the [[spout]] block at line 5, keys appended from line 9.
inline const std::string kSpout2D = R"(dimension = 2
[grid]
size = [1.0, 0.5]
resolution = [40, 20]
[[spout]]
center = [0.5, 0.4]
radius = 0.05
velocity = [0.0, -1.0]
)";

// The message of the SceneError that parsing throws ("" if none).
inline std::string error_of(const std::string& text,
                            const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, "bad.toml", overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// ---------------------------------------------------------------- good scenes

// Field by field, doubles exactly.
inline void expect_same(const SceneConfig& a, const SceneConfig& b) {
  EXPECT_EQ(a.dimension, b.dimension);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.size, b.size);
  EXPECT_EQ(a.resolution, b.resolution);
  EXPECT_EQ(a.gravity, b.gravity);
  EXPECT_EQ(a.time.fps, b.time.fps);
  EXPECT_EQ(a.time.frames, b.time.frames);
  EXPECT_EQ(a.time.substeps, b.time.substeps);
  EXPECT_EQ(a.time.cfl, b.time.cfl);
  const MaterialConfig &m = a.material, &n = b.material;
  EXPECT_EQ(m.density, n.density);
  EXPECT_EQ(m.mu, n.mu);
  EXPECT_EQ(m.phi_max, n.phi_max);
  EXPECT_EQ(m.viscosity, n.viscosity);
  EXPECT_EQ(m.cohesion, n.cohesion);
  EXPECT_EQ(m.cohesion_decay, n.cohesion_decay);
  ASSERT_EQ(m.mu_i.has_value(), n.mu_i.has_value());
  if (m.mu_i) {
    EXPECT_EQ(m.mu_i->delta_mu, n.mu_i->delta_mu);
    EXPECT_EQ(m.mu_i->I0, n.mu_i->I0);
    EXPECT_EQ(m.mu_i->grain_diameter, n.mu_i->grain_diameter);
  }
  EXPECT_EQ(a.solver.tolerance, b.solver.tolerance);
  EXPECT_EQ(a.solver.max_iterations, b.solver.max_iterations);
  EXPECT_EQ(a.solver.anderson, b.solver.anderson);
  EXPECT_EQ(a.solver.zone_rows, b.solver.zone_rows);
  EXPECT_EQ(a.solver.decompaction, b.solver.decompaction);
  EXPECT_EQ(a.solver.decompaction_moves, b.solver.decompaction_moves);
  EXPECT_EQ(a.boundary.faces, b.boundary.faces);
  ASSERT_EQ(a.boundary.openings.size(), b.boundary.openings.size());
  for (std::size_t k = 0; k < a.boundary.openings.size(); ++k) {
    EXPECT_EQ(a.boundary.openings[k].face, b.boundary.openings[k].face);
    EXPECT_EQ(a.boundary.openings[k].min, b.boundary.openings[k].min);
    EXPECT_EQ(a.boundary.openings[k].max, b.boundary.openings[k].max);
  }
  ASSERT_EQ(a.sand.size(), b.sand.size());
  for (std::size_t k = 0; k < a.sand.size(); ++k) {
    const SandConfig &p = a.sand[k], &q = b.sand[k];
    EXPECT_EQ(p.shape, q.shape);
    EXPECT_EQ(p.min, q.min);
    EXPECT_EQ(p.max, q.max);
    EXPECT_EQ(p.center, q.center);
    EXPECT_EQ(p.radius, q.radius);
    EXPECT_EQ(p.height, q.height);
    EXPECT_EQ(p.particles_per_cell, q.particles_per_cell);
    EXPECT_EQ(p.jitter, q.jitter);
    EXPECT_EQ(p.velocity, q.velocity);
    EXPECT_EQ(p.vertices, q.vertices);
    EXPECT_EQ(p.file_path, q.file_path);
    EXPECT_EQ(p.scale, q.scale);
    EXPECT_EQ(p.translate, q.translate);
    EXPECT_EQ(p.material.density, q.material.density);
    EXPECT_EQ(p.material.mu, q.material.mu);
    EXPECT_EQ(p.material.cohesion, q.material.cohesion);
    EXPECT_EQ(p.material.cohesion_decay, q.material.cohesion_decay);
    ASSERT_EQ(p.material.mu_i.has_value(), q.material.mu_i.has_value());
    if (p.material.mu_i) {
      EXPECT_EQ(p.material.mu_i->delta_mu, q.material.mu_i->delta_mu);
      EXPECT_EQ(p.material.mu_i->I0, q.material.mu_i->I0);
      EXPECT_EQ(p.material.mu_i->grain_diameter, q.material.mu_i->grain_diameter);
    }
  }
  ASSERT_EQ(a.spouts.size(), b.spouts.size());
  for (std::size_t k = 0; k < a.spouts.size(); ++k) {
    const SpoutConfig &p = a.spouts[k], &q = b.spouts[k];
    EXPECT_EQ(p.center, q.center);
    EXPECT_EQ(p.radius, q.radius);
    EXPECT_EQ(p.velocity, q.velocity);
    EXPECT_EQ(p.start, q.start);
    EXPECT_EQ(p.stop, q.stop);
    EXPECT_EQ(p.particles_per_cell, q.particles_per_cell);
    EXPECT_EQ(p.jitter, q.jitter);
  }
  ASSERT_EQ(a.obstacles.size(), b.obstacles.size());
  for (std::size_t k = 0; k < a.obstacles.size(); ++k) {
    const ObstacleConfig &p = a.obstacles[k], &q = b.obstacles[k];
    EXPECT_EQ(p.shape, q.shape);
    EXPECT_EQ(p.point, q.point);
    EXPECT_EQ(p.normal, q.normal);
    EXPECT_EQ(p.min, q.min);
    EXPECT_EQ(p.max, q.max);
    EXPECT_EQ(p.density, q.density);
    EXPECT_EQ(p.center, q.center);
    EXPECT_EQ(p.radius, q.radius);
    EXPECT_EQ(p.height, q.height);
    EXPECT_EQ(p.mu, q.mu);
    EXPECT_EQ(p.velocity, q.velocity);
    EXPECT_EQ(p.until, q.until);
    EXPECT_EQ(p.vertices, q.vertices);
    EXPECT_EQ(p.file_path, q.file_path);
    EXPECT_EQ(p.scale, q.scale);
    EXPECT_EQ(p.translate, q.translate);
    EXPECT_EQ(p.polygon != nullptr, q.polygon != nullptr);
    EXPECT_EQ(p.distance != nullptr, q.distance != nullptr);
  }
}

inline Vec3d v(double x, double y, double z = 0) { return {x, y, z}; }
}  // namespace sablier::test
