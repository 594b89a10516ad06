// The material table: one entry per [[sand]] block (docs/scenes.md), looked
// up by each particle's `material` index in the transfers. phi_max and the
// viscosity are not in it: they stay scene-wide (docs/method.md).
#pragma once

#include <vector>

#include "scene/scene.hpp"

namespace sablier {

struct Material {
  double density = 2500.0;  // rho_p, kg/m^3
  // rho_p / rho_0, rho_0 = [material].density: the grid's masses are kept in
  // units of rho_0 (Simulation::node_mass_), so that with one material this
  // ratio is exactly 1 and the products with it are exact (bit-identical to
  // a single-density code).
  double mass_ratio = 1.0;
  double mu = 0.5;              // simple-shear friction coefficient
  double cohesion = 0.0;        // initial cohesion, Pa (particles carry the current value)
  double cohesion_decay = 0.0;  // per unit shear strain
  bool has_mu_i = false;
  MuIConfig mu_i;

  // Friction at the lagged inertial number I (METHOD.md section 1):
  // mu + delta_mu / (1 + I0 / I), or mu without mu(I).
  double friction(double inertial) const {
    if (!has_mu_i || !(inertial > 0.0)) return mu;
    return mu + mu_i.delta_mu / (1.0 + mu_i.I0 / inertial);
  }
};

// One entry per [[sand]] block, in block order; then [material] itself, at
// index sand.size(), for the grains of [[spout]] blocks (emission.hpp) and
// for a scene without blocks (a hand-made particle set: index 0).
inline std::vector<Material> material_table(const SceneConfig& scene) {
  std::vector<Material> table;
  const bool plain = scene.sand.empty() || !scene.spouts.empty();
  const std::size_t entries = scene.sand.size() + (plain ? 1 : 0);
  for (std::size_t k = 0; k < entries; ++k) {
    const MaterialConfig m = k < scene.sand.size() ? sand_material(scene, k) : scene.material;
    Material e;
    e.density = m.density;
    e.mass_ratio = m.density / scene.material.density;
    e.mu = m.mu;
    e.cohesion = m.cohesion;
    e.cohesion_decay = m.cohesion_decay;
    e.has_mu_i = m.mu_i.has_value();
    if (m.mu_i) e.mu_i = *m.mu_i;
    table.push_back(e);
  }
  return table;
}

}  // namespace sablier
