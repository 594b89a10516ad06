// The transient of a mu(I) layer on an infinite incline (a 1D problem,
// integrated to convergence) and the speeds of the grains in the middle of
// a channel, by depth, to compare with it: tests/test_mui_layer.cpp (2D,
// incline_mui2d) and tests/validation_mui_layer.cpp (3D).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "physics/simulation.hpp"
#include "scene/scene.hpp"

namespace sablier::test {

// The velocity profile of an infinite layer of depth H on a rough bed,
// started from rest, under mu(I) (METHOD.md section 1; the pressure and
// the inertial number as Sablier forms them: bulk pressure p = phi_max
// sigma_zz, I = gamma_dot d / sqrt(p / rho) with rho the grains' density,
// and mu the simple-shear friction coefficient, METHOD.md section 4). In
// simple shear the stress's deviator is the shear tau on the layer's planes
// and p = rho phi_max g_n (H - z) is fixed by the weight above, so
//   du/dt = g_t + d tau / dz / (rho phi_max),   tau = mu(I) p,
// with u = 0 at the bed and tau = 0 at the surface (g_t and g_n gravity's
// components along and into the slope). With g_t > mu_s g_n no part of the
// layer can move as a rigid plug (a plug above z accelerates at g_t less
// its base's mu g_n, and holding it together would need a shear mu p >
// mu_s p inside it), so every plane shears downhill, gamma_dot >= 0, and
// tau is mu(I) p with mu -> mu_s as gamma_dot -> 0 (negative rounding is
// taken as 0). Finite volumes of H / cells, explicit steps within a fifth
// of the diffusive limit (the diffusivity d tau / d gamma_dot / (rho
// phi_max) is at most (delta_mu / I0) d sqrt(g_n H / phi_max)). Returns the
// cells' speeds at each of `times` (increasing).
inline std::vector<std::vector<double>> infinite_layer(const MaterialConfig& m, double g_t,
                                                       double g_n, double depth, int cells,
                                                       const std::vector<double>& times) {
  const double dz = depth / cells, rho = m.density, phi = m.phi_max;
  const MuIConfig& r = *m.mu_i;
  const double diffusivity = r.delta_mu / r.I0 * r.grain_diameter * std::sqrt(g_n * depth / phi);
  const double max_dt = 0.2 * dz * dz / diffusivity;
  std::vector<double> u(cells, 0.0), tau(cells + 1, 0.0), pressure(cells);
  for (int i = 0; i < cells; ++i) pressure[i] = rho * phi * g_n * (depth - i * dz);  // face i
  std::vector<std::vector<double>> out;
  double t = 0.0;
  for (double until : times) {
    while (t < until - 1e-12) {
      const double dt = std::min(max_dt, until - t);
      for (int i = 0; i < cells; ++i) {  // face i, below cell i
        const double rate = std::max(0.0, i == 0 ? u[0] / (dz / 2) : (u[i] - u[i - 1]) / dz);
        const double inertial = rate * r.grain_diameter / std::sqrt(pressure[i] / rho);
        const double mu = inertial > 0.0 ? m.mu + r.delta_mu / (1.0 + r.I0 / inertial) : m.mu;
        tau[i] = mu * pressure[i];
      }
      for (int i = 0; i < cells; ++i) u[i] += dt * (g_t + (tau[i + 1] - tau[i]) / (rho * phi * dz));
      t += dt;
    }
    out.push_back(u);
  }
  return out;
}

// The speeds of the grains within 2.5 cm of x = `middle` along the channel:
// their mean (element 0), then their mean in each of `bands` layers of the
// initial depth, from the bed up (grains above the initial surface count
// in the top one; the last axis is the height).
template <int D>
std::vector<double> middle_speeds(const Simulation<D>& sim, double middle, double depth,
                                  int bands) {
  std::vector<double> sum(bands + 1, 0.0), count(bands + 1, 0.0);
  const Particles<D>& p = sim.particles();
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (std::abs(p.position[k][0] - middle) >= 0.025) continue;
    const int band =
        std::clamp(static_cast<int>(p.position[k][D - 1] / depth * bands), 0, bands - 1);
    const double speed = p.velocity[k].norm();
    sum[0] += speed, count[0] += 1;
    sum[band + 1] += speed, count[band + 1] += 1;
  }
  for (int b = 0; b <= bands; ++b) sum[b] = count[b] > 0 ? sum[b] / count[b] : 0.0;
  return sum;
}

// The same for the 1D layer's cells.
inline std::vector<double> layer_speeds(const std::vector<double>& u, int bands) {
  const int cells = static_cast<int>(u.size()), per_band = cells / bands;
  std::vector<double> out(bands + 1, 0.0);
  for (int i = 0; i < cells; ++i) {
    out[0] += u[i] / cells;
    out[1 + i / per_band] += u[i] / per_band;
  }
  return out;
}

}  // namespace sablier::test
