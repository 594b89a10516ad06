// A heap: a right-angled wedge of sand 12 cm high against a frictionless
// wall, its flank at theta, on a rough floor (mu = 0.5, phi_max = 0.6), run
// for a while; then the flank's angle, a line fitted to the highest grain of
// each cell-wide column between 20% and 80% of the heap's height, the heap's
// height and its grains' median speed. tests/test_engine_physics.cpp (stands
// or slumps) and tests/validation_heap.cpp (converges in the grid) share it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "physics/simulation.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace sablier::test {

struct Heap {
  double angle_deg, height, median_speed;
};

// `rows` cells across the 0.15 m high box (30: 5 mm cells), four times as
// many along its 0.6 m; `grains` per cell and axis.
inline Heap heap_after(double theta_deg, double t, int rows = 30, int grains = 3) {
  const double h0 = 0.12, l0 = h0 / std::tan(theta_deg * M_PI / 180.0);
  const std::string text =
      "dimension = 2\ngravity = [0.0, -9.81]\n[grid]\nsize = [0.6, 0.15]\n"
      "resolution = [" +
      std::to_string(4 * rows) + ", " + std::to_string(rows) +
      "]\n[time]\nfps = 30\nframes = 45\n[material]\n"
      "density = 2500\nmu = 0.5\nphi_max = 0.6\n[boundary]\ndefault = \"slip\"\n"
      "ymin = \"stick\"\nymax = \"free\"\n[[sand]]\nshape = \"polygon\"\n"
      "particles_per_cell = " +
      std::to_string(grains) + "\nvertices = [[0.0, 0.0], [" + std::to_string(l0) +
      ", 0.0], [0.0, " + std::to_string(h0) + "]]\n";
  Simulation<2> sim(parse_scene(text, "heap.toml"));
  run_until(sim, t);
  const double h = sim.grid().h();
  std::vector<double> top(sim.grid().cells()[0], 0.0);
  std::vector<double> speed;
  for (std::size_t p = 0; p < sim.particles().size(); ++p) {
    const Vec<2>& x = sim.particles().position[p];
    double& column = top[std::min<std::size_t>(top.size() - 1, static_cast<std::size_t>(x[0] / h))];
    column = std::max(column, x[1]);
    speed.push_back(sim.particles().velocity[p].norm());
  }
  const double height = *std::max_element(top.begin(), top.end());
  std::vector<double> xs, ys;  // the flank's columns
  for (std::size_t c = 0; c < top.size(); ++c) {
    if (top[c] < 0.2 * height || top[c] > 0.8 * height) continue;
    xs.push_back((c + 0.5) * h);
    ys.push_back(top[c]);
  }
  double slope = 0.0, intercept = 0.0;
  fit_line(xs, ys, &slope, &intercept);
  std::nth_element(speed.begin(), speed.begin() + speed.size() / 2, speed.end());
  return {std::atan(-slope) * 180.0 / M_PI, height, speed[speed.size() / 2]};
}

}  // namespace sablier::test
