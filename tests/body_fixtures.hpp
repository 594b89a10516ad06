// Helpers shared by the rigid-body tests (test_box_bodies.cpp,
// test_shaped_bodies.cpp): scene text and a body's measured acceleration.
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>

#include "physics/simulation.hpp"
#include "test_support.hpp"

namespace sablier::test {

// A number as scene text, to the last bit.
inline std::string num(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

// A block of sand far from everything: a scene needs one [[sand]] block.
inline const std::string kSpeck2D =
    "[[sand]]\nshape = \"box\"\nmin = [0.9, 0.4]\nmax = [0.95, 0.45]\n";
inline const std::string kSpeck3D =
    "[[sand]]\nshape = \"box\"\nmin = [0.5, 0.0, 0.25]\nmax = [0.55, 0.05, 0.3]\n";

// The acceleration of body k along its velocity between 0.1 and 0.25 s, and
// in *spin the largest spin seen at those two times.
template <int D>
double body_acceleration(Simulation<D>& sim, std::size_t k, double* spin) {
  run_until(sim, 0.1);
  const double v1 = sim.obstacles()[k].velocity.norm(), t1 = sim.time();
  *spin = sim.obstacles()[k].spin.norm();
  run_until(sim, 0.25);
  const double v2 = sim.obstacles()[k].velocity.norm(), t2 = sim.time();
  *spin = std::max(*spin, sim.obstacles()[k].spin.norm());
  return (v2 - v1) / (t2 - t1);
}

}  // namespace sablier::test
