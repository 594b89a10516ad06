// Spouts ([[spout]] blocks, docs/scenes.md): grains entering the box
// through a cross-section at the spout's velocity, with volume fraction
// phi_max, so a mass rate of rho phi_max |v| A.
//
// Emission is stateless, a function of the clock alone, so a resumed run
// emits exactly what the uninterrupted one does with no checkpoint field:
// the material that crossed the section by time t is L(t) = floor(|v| (t -
// start) / s) layers of particles (s = h / particles_per_cell, t capped at
// stop). A step from t0 to t1 appends the layers L(t0) .. L(t1) - 1, each a
// lattice of the cross-section with spacing s, layer j at its travelled
// distance |v| (t1 - start) - (j + 1/2) s downstream of the centre, moving at
// the spout's velocity. Jitter comes from a counter-based hash of (seed,
// spout, layer, point, axis), the particle id is (spout + 1) 2^40 + layer
// 2^20 + point: unique with at most 2^20 - 1 points per layer and layers per
// spout (the scene parser checks both).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/particles.hpp"
#include "physics/obstacle.hpp"
#include "scene/scene.hpp"

namespace sablier {

constexpr std::int64_t kSpoutIdBits = 20;  // bits for the point and the layer of an id
constexpr std::int64_t kSpoutIdLimit = std::int64_t(1) << kSpoutIdBits;

// Particle spacing of a spout, m.
double spout_spacing(const SceneConfig& scene, const SpoutConfig& spout);

// Points per layer: 2D, round(2 radius / s) points across the segment; 3D,
// the points of the square lattice (i + 1/2, j + 1/2) s within the disk.
std::size_t spout_layer_size(int dimension, double radius, double spacing);

// Layers emitted by time t (0 before start).
std::int64_t spout_layers(const SpoutConfig& spout, double spacing, double t);
// Particles emitted by time t: the layers times the layer's points.
std::int64_t spout_particles(const SceneConfig& scene, const SpoutConfig& spout, double t);

// Mass rates: nominal rho phi_max |v| A (A = 2 radius in 2D, per metre of
// depth, kg/(m s); pi radius^2 in 3D, kg/s), and that of the lattice
// actually emitted (A rounded to whole particles: layer size s^(d-1)).
double spout_nominal_rate(const SceneConfig& scene, const SpoutConfig& spout);
double spout_lattice_rate(const SceneConfig& scene, const SpoutConfig& spout);

// Fastest spout still open at time t (0 if none): the adaptive step must
// resolve grains that enter at that speed.
double open_spout_speed(const SceneConfig& scene, double t);

// The material index of spout grains: [material], the entry after the
// [[sand]] blocks' (physics/material.hpp).
std::int32_t spout_material_index(const SceneConfig& scene);

// Appends the particles every spout emits between t0 and t1 (t0 < t1).
// Points that would lie outside the box or inside an [[obstacle]] are
// skipped (the others keep their ids). The scene's rigid bodies move with
// the run, so they are not taken from the scene: `bodies`, when given, are
// the bodies where they are at t1 (Simulation::obstacles()), and points
// inside them are skipped too.
template <int D>
void emit_spout_particles(const SceneConfig& scene, double t0, double t1, Particles<D>& p,
                          const std::vector<Obstacle<D>>* bodies = nullptr);

}  // namespace sablier
