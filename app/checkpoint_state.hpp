// Between a Simulation<D> and the plain arrays of checkpoint.bin.
#pragma once

#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "physics/simulation.hpp"

namespace sablier {
namespace detail {

// Appends the coefficients of fixed-size Eigen values to `out` (column-major).
template <class T>
void flatten(const std::vector<T>& values, std::vector<double>& out) {
  out.reserve(out.size() + values.size() * T::SizeAtCompileTime);
  for (const T& v : values)
    for (Eigen::Index k = 0; k < T::SizeAtCompileTime; ++k) out.push_back(v.data()[k]);
}

template <class T>
std::vector<T> unflatten(const std::vector<double>& in) {
  std::vector<T> out(in.size() / T::SizeAtCompileTime);
  for (std::size_t i = 0; i < out.size(); ++i)
    for (Eigen::Index k = 0; k < T::SizeAtCompileTime; ++k)
      out[i].data()[k] = in[i * T::SizeAtCompileTime + k];
  return out;
}

}  // namespace detail

// The simulation's part of a checkpoint into `c`, whose arrays keep their
// storage from one frame to the next (a 3D checkpoint of 69,120 grains is
// 16.5 MB, and fresh arrays cost page faults at every frame); the caller
// adds the run's part (scene hash, frame, substep, formats, frame times).
template <int D>
void capture_checkpoint(const Simulation<D>& sim, Checkpoint* c) {
  const Particles<D>& p = sim.particles();
  c->version = Checkpoint::kFormatVersion;
  c->dimension = D;
  c->steps = sim.steps();
  c->time = sim.time();
  c->particles = p.size();
  for (auto* v : {&c->position, &c->velocity, &c->affine, &c->stress, &c->warm_stress}) v->clear();
  detail::flatten(p.position, c->position);
  detail::flatten(p.velocity, c->velocity);
  detail::flatten(p.affine, c->affine);
  c->volume = p.volume;
  c->cohesion = p.cohesion;
  c->inertial = p.inertial;
  c->id = p.id;
  c->material.assign(p.material.begin(), p.material.end());
  detail::flatten(p.stress, c->stress);
  c->phi = p.phi;
  c->shear_rate = p.shear_rate;
  c->nodes = sim.warm_start().size();
  detail::flatten(sim.warm_start(), c->warm_stress);
  c->warm_case = sim.warm_cases();
}

template <int D>
Checkpoint capture_checkpoint(const Simulation<D>& sim) {
  Checkpoint c;
  capture_checkpoint(sim, &c);
  return c;
}

// The simulation a checkpoint describes (decode_checkpoint checked the
// arrays' sizes), its particles as the checkpoint holds them: not sorted,
// so that the grains that left the box in the last step are still there
// when the next step's length is chosen, as in the run that was not
// interrupted (its next step drops them when it sorts). No frame is
// written before that step, since an interrupt in a frame's last step
// writes the frame before its checkpoint (run_command.cpp). Throws
// CheckpointError naming `source` when the checkpoint's grid is not the
// scene's.
template <int D>
Simulation<D> restore_simulation(const SceneConfig& scene, const Checkpoint& c,
                                 const std::string& source) {
  Particles<D> p;
  p.position = detail::unflatten<Vec<D>>(c.position);
  p.velocity = detail::unflatten<Vec<D>>(c.velocity);
  p.affine = detail::unflatten<Mat<D>>(c.affine);
  p.volume = c.volume;
  p.cohesion = c.cohesion;
  p.inertial = c.inertial;
  p.id = c.id;
  p.material.resize(c.material.size());
  const auto materials = static_cast<std::int64_t>(material_table(scene).size());
  for (std::size_t k = 0; k < c.material.size(); ++k) {
    if (c.material[k] < 0 || c.material[k] >= materials)
      throw CheckpointError(source + ": particle material " + std::to_string(c.material[k]) +
                            " but the scene has " + std::to_string(materials) +
                            " materials; cannot resume");
    p.material[k] = static_cast<std::int32_t>(c.material[k]);
  }
  p.stress = detail::unflatten<SymVec<D>>(c.stress);
  p.phi = c.phi;
  p.shear_rate = c.shear_rate;
  Simulation<D> sim(scene, std::move(p), ParticleOrder::AsGiven);
  // One warm-start stress per grid node, and one more per node with obstacles.
  const auto nodes = static_cast<std::uint64_t>(sim.warm_start().size());
  if (c.nodes != nodes)
    throw CheckpointError(source + ": holds " + std::to_string(c.nodes) +
                          " warm-start stresses, the scene's grid needs " + std::to_string(nodes) +
                          "; cannot resume");
  sim.restore_clock(c.time, c.steps, detail::unflatten<SymVec<D>>(c.warm_stress), c.warm_case);
  return sim;
}

}  // namespace sablier
