// Output writers. Every file is written atomically (temporary file in the
// same folder, then rename), so a crash never leaves a truncated file.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/particle_frame.hpp"

namespace sablier {

struct IoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Writes `contents` to `path` atomically. Throws IoError.
void write_file_atomic(const std::string& path, const std::string& contents);
// Creates a folder and its parents. Throws IoError.
void ensure_directory(const std::string& path);
// The whole contents of a file. Throws IoError.
std::string read_file(const std::string& path);

// VTK XML PolyData (.vtp), binary appended raw data, one vertex per particle,
// point arrays: velocity, volume, pressure, phi, stress (symmetric tensor as 6
// or 9 components as VTK expects), shear_rate, id.
std::string format_vtp(const ParticleFrame& frame);
// CSV with header x,y[,z],vx,vy[,vz],volume,pressure,phi,sxx,syy[,szz],sxy[,sxz,syz]
std::string format_particle_csv(const ParticleFrame& frame);

// Binary PLY (binary_little_endian 1.0), one vertex per particle: float
// x, y, z (z = 0 in 2D), then doubles vx, vy, vz, volume, pressure, phi,
// shear_rate, id. A comment line in the header gives the dimension and time.
std::string format_ply(const ParticleFrame& frame);
constexpr std::size_t kPlyVertexBytes = 3 * 4 + 8 * 8;

// ParaView collection of frames: entries (time, relative file name).
struct SeriesEntry {
  double time;
  std::string file;
};
std::string format_pvd(const std::vector<SeriesEntry>& entries);

// Reads back a .vtp written by format_vtp (tests and tools). Throws IoError.
ParticleFrame parse_vtp(const std::string& contents, const std::string& source);

}  // namespace sablier
