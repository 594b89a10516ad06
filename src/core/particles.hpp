// Material points, structure of arrays (one array per field), kept sorted by
// cell after every step so that transfers walk memory in order.
#pragma once

#include <cstdint>
#include <vector>

#include "core/tensor.hpp"

namespace sablier {

template <int D>
struct Particles {
  // State.
  std::vector<Vec<D>> position;   // m
  std::vector<Vec<D>> velocity;   // m/s
  std::vector<Mat<D>> affine;     // APIC matrix B_p = grad u(x_p), 1/s
  std::vector<double> volume;     // grain volume V_p, m^3 (mass rho V_p)
  std::vector<double> cohesion;   // current cohesion, Pa (decays with shear)
  std::vector<double> inertial;   // lagged inertial number I (mu(I) rheology)
  std::vector<std::int64_t> id;   // stable identity, for outputs
  // Index into the material table (physics/material.hpp): the [[sand]]
  // block the grain came from, or the [material] entry after them (spouts).
  std::vector<std::int32_t> material;
  // Diagnostics of the last step, interpolated from the grid (outputs only).
  std::vector<SymVec<D>> stress;  // lambda(x_p), Pa per unit grain volume
  std::vector<double> phi;        // volume fraction
  std::vector<double> shear_rate; // sqrt(2 Dev D : Dev D), 1/s

  std::size_t size() const { return position.size(); }

  void resize(std::size_t n) {
    position.resize(n);
    velocity.resize(n);
    affine.resize(n);
    volume.resize(n);
    cohesion.resize(n);
    inertial.resize(n);
    id.resize(n);
    material.resize(n);
    stress.resize(n);
    phi.resize(n);
    shear_rate.resize(n);
  }

  // Reorders every field: new particle k is old particle order[k]
  // (order may be shorter than size(): the others are dropped).
  void permute(const std::vector<std::int64_t>& order) {
    apply(position, order);
    apply(velocity, order);
    apply(affine, order);
    apply(volume, order);
    apply(cohesion, order);
    apply(inertial, order);
    apply(id, order);
    apply(material, order);
    apply(stress, order);
    apply(phi, order);
    apply(shear_rate, order);
  }

 private:
  template <class T>
  static void apply(std::vector<T>& v, const std::vector<std::int64_t>& order) {
    std::vector<T> out(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) out[k] = v[order[k]];
    v.swap(out);
  }
};

}  // namespace sablier
