// What the writers need of one frame of particles: plain arrays, no solver
// types. The simulation fills it; src/io writes it.
#pragma once

#include <cstddef>
#include <vector>

namespace sablier {

struct ParticleFrame {
  int dimension = 2;
  double time = 0.0;  // s
  std::size_t count = 0;
  // Interleaved per particle: position[p*dimension + a], velocity likewise (SI).
  std::vector<double> position;
  std::vector<double> velocity;
  std::vector<double> volume;    // grain volume V_p, m^3
  std::vector<double> pressure;  // bulk pressure phi Tr(lambda)/d, Pa, compression positive
  std::vector<double> phi;       // volume fraction at the particle
  // Bulk stress phi*lambda, compression positive, Cartesian components per
  // particle: 2D (xx, yy, xy), 3D (xx, yy, zz, xy, xz, yz).
  std::vector<double> stress;
  std::vector<double> shear_rate;  // equivalent shear rate sqrt(2 Dev D : Dev D), 1/s
  std::vector<double> id;          // stable particle id (as double for VTK simplicity)
  std::vector<double> material;    // material index: the [[sand]] block the particle came from

  int stress_components() const { return dimension == 2 ? 3 : 6; }
};

}  // namespace sablier
