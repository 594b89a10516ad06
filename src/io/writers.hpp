// Output writers. Every file is written atomically (temporary file in the
// same folder, then rename), so a crash never leaves a truncated file.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/grid_frame.hpp"
#include "io/particle_frame.hpp"
#include "io/vtk_xml.hpp"

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

// VTK XML PolyData (.vtp), binary appended data (zlib-compressed on
// request), one vertex per particle, point arrays: velocity, volume,
// pressure, phi, stress (symmetric tensor as the 9 components VTK expects),
// shear_rate, id (Int64), material (Int32).
std::string format_vtp(const ParticleFrame& frame,
                       VtkCompression compression = VtkCompression::None);
// CSV with header x,y[,z],vx,vy[,vz],volume,pressure,phi,sxx,syy[,szz],sxy[,sxz,syz]
std::string format_particle_csv(const ParticleFrame& frame);

// Binary PLY (binary_little_endian 1.0), one vertex per particle: float
// x, y, z (z = 0 in 2D), then doubles vx, vy, vz, volume, pressure, phi,
// shear_rate, id, material. A comment line in the header gives the
// dimension and time.
std::string format_ply(const ParticleFrame& frame);
constexpr std::size_t kPlyVertexBytes = 3 * 4 + 9 * 8;

// VTK XML ImageData (.vti) of the grid's real nodes, binary appended data
// (zlib-compressed on request): origin 0, spacing h, point arrays phi,
// velocity, pressure (Float64) and active (UInt8).
std::string format_vti(const GridFrame& grid, VtkCompression compression = VtkCompression::None);

// ParaView collection of frames: entries (time, relative file name).
struct SeriesEntry {
  double time;
  std::string file;
};
std::string format_pvd(const std::vector<SeriesEntry>& entries);

// Read back files written by format_vtp / format_vti, compressed or not
// (tests and tools). Throw IoError naming `source`.
ParticleFrame parse_vtp(const std::string& contents, const std::string& source);
GridFrame parse_vti(const std::string& contents, const std::string& source);

}  // namespace sablier
