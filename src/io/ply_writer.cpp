// Binary PLY particle files (Stanford polygon format, vertices only), read by
// ParaView, MeshLab, CloudCompare, Blender and Houdini: positions as float
// x, y, z, because that is what most readers expect of a point cloud, and the
// particle quantities as doubles.
#include <fmt/format.h>

#include "io/bytes.hpp"
#include "io/writers.hpp"

namespace sablier {

namespace {
const char* const kPlyProperties[] = {"vx",  "vy",         "vz", "volume",  "pressure",
                                      "phi", "shear_rate", "id", "material"};
}  // namespace

std::string format_ply(const ParticleFrame& f) {
  const std::size_t n = f.count;
  const int d = f.dimension;
  std::string header = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment sablier frame, dimension {}, time {} s\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
      d, f.time, n);
  for (const char* name : kPlyProperties) header += fmt::format("property double {}\n", name);
  header += "end_header\n";

  ByteWriter out;
  out.data().reserve(header.size() + n * kPlyVertexBytes);
  out.put_bytes(header);
  for (std::size_t p = 0; p < n; ++p) {
    for (int a = 0; a < 3; ++a) out.put(a < d ? static_cast<float>(f.position[p * d + a]) : 0.0f);
    for (int a = 0; a < 3; ++a) out.put(a < d ? f.velocity[p * d + a] : 0.0);
    out.put(f.volume[p]);
    out.put(f.pressure[p]);
    out.put(f.phi[p]);
    out.put(f.shear_rate[p]);
    out.put(f.id[p]);
    // Frames built by hand (tests, tools) may leave the material out.
    out.put(f.material.size() == n ? f.material[p] : 0.0);
  }
  return std::move(out.data());
}

}  // namespace sablier
