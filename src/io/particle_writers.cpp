// Particle files: VTK XML PolyData (binary appended), CSV, and the ParaView
// collection that lists the frames.
#include <fmt/format.h>

#include <cstdint>

#include "io/vtk_xml.hpp"
#include "io/writers.hpp"

namespace sablier {
namespace {

// Value i of the 3-component vectors made of d-component interleaved ones
// (z = 0 in 2D).
struct As3D {
  const std::vector<double>& v;
  int d;
  double operator()(std::size_t i) const {
    const std::size_t p = i / 3, a = i % 3;
    return static_cast<int>(a) < d ? v[d * p + a] : 0.0;
  }
};

// Value i of the full 3x3 tensors (row-major) made of the compact components.
struct AsTensor9 {
  const ParticleFrame& f;
  double operator()(std::size_t i) const {
    // Compact component of each of the nine entries, -1 for a zero.
    static constexpr int k2[9] = {0, 2, -1, 2, 1, -1, -1, -1, -1};
    static constexpr int k3[9] = {0, 3, 4, 3, 1, 5, 4, 5, 2};
    const std::size_t p = i / 9;
    const int k = (f.dimension == 2 ? k2 : k3)[i % 9];
    return k < 0 ? 0.0 : f.stress[f.stress_components() * p + k];
  }
};

}  // namespace

std::string format_vtp(const ParticleFrame& f, VtkCompression compression) {
  const std::size_t n = f.count;
  VtkAppended app(compression);
  // The arrays below, raw: 180 bytes per grain, 8 per array's header.
  if (compression == VtkCompression::None) app.reserve(180 * n + 8 * 16 + 64);
  std::string field, point;
  field += vtk_field_tag("Float64", "TIME", 1, app.add(std::vector<double>{f.time}));
  field += vtk_field_tag("Int32", "DIMENSION", 1, app.add(std::vector<std::int32_t>{f.dimension}));
  const auto scalar = [&](const char* name, const std::vector<double>& v) {
    if (v.size() == n) point += vtk_array_tag("Float64", name, 1, app.add(v));
  };
  point += vtk_array_tag("Float64", "velocity", 3,
                         app.add_generated<double>(3 * n, As3D{f.velocity, f.dimension}));
  scalar("volume", f.volume);
  scalar("pressure", f.pressure);
  scalar("phi", f.phi);
  point += vtk_array_tag("Float64", "stress", 9, app.add_generated<double>(9 * n, AsTensor9{f}));
  scalar("shear_rate", f.shear_rate);
  // Integers, so that ParaView colours them by category and selects exactly.
  if (f.id.size() == n) {
    const auto id = [&f](std::size_t p) { return static_cast<std::int64_t>(f.id[p]); };
    point += vtk_array_tag("Int64", "id", 1, app.add_generated<std::int64_t>(n, id));
  }
  if (f.material.size() == n) {
    const auto material = [&f](std::size_t p) { return static_cast<std::int32_t>(f.material[p]); };
    point += vtk_array_tag("Int32", "material", 1, app.add_generated<std::int32_t>(n, material));
  }
  const std::string points = vtk_array_tag(
      "Float64", "Points", 3, app.add_generated<double>(3 * n, As3D{f.position, f.dimension}));
  const auto conn = [](std::size_t p) { return static_cast<std::int64_t>(p); };
  const auto offs = [](std::size_t p) { return static_cast<std::int64_t>(p + 1); };
  const std::string verts =
      vtk_array_tag("Int64", "connectivity", 1, app.add_generated<std::int64_t>(n, conn)) +
      vtk_array_tag("Int64", "offsets", 1, app.add_generated<std::int64_t>(n, offs));
  return vtk_file(
      "PolyData",
      fmt::format("<PolyData>\n<FieldData>{}</FieldData>\n"
                  "<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" "
                  "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<PointData>{}</PointData>\n"
                  "<Points>{}</Points>\n<Verts>{}</Verts>\n</Piece>\n</PolyData>\n",
                  field, n, n, point, points, verts),
      app);
}

std::string format_particle_csv(const ParticleFrame& f) {
  const int d = f.dimension;
  const int sc = f.stress_components();
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "{}\n",
                 d == 2 ? "x,y,vx,vy,volume,pressure,phi,sxx,syy,sxy"
                        : "x,y,z,vx,vy,vz,volume,pressure,phi,sxx,syy,szz,sxy,sxz,syz");
  for (std::size_t p = 0; p < f.count; ++p) {
    for (int a = 0; a < d; ++a)
      fmt::format_to(std::back_inserter(out), "{},", f.position[d * p + a]);
    for (int a = 0; a < d; ++a)
      fmt::format_to(std::back_inserter(out), "{},", f.velocity[d * p + a]);
    fmt::format_to(std::back_inserter(out), "{},{},{}", f.volume[p], f.pressure[p], f.phi[p]);
    for (int k = 0; k < sc; ++k)
      fmt::format_to(std::back_inserter(out), ",{}", f.stress[sc * p + k]);
    out.push_back('\n');
  }
  return fmt::to_string(out);
}

std::string format_pvd(const std::vector<SeriesEntry>& entries) {
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" "
      "byte_order=\"LittleEndian\">\n<Collection>\n";
  for (const SeriesEntry& e : entries)
    out += fmt::format("<DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time,
                       e.file);
  return out + "</Collection>\n</VTKFile>\n";
}

ParticleFrame parse_vtp(const std::string& s, const std::string& source) {
  std::map<std::string, VtkArray> arrays = read_vtk_arrays(s, source);
  for (const char* name : {"TIME", "DIMENSION", "Points", "velocity", "stress"})
    if (!arrays.count(name)) throw IoError(source + ": missing array " + name);
  const auto values = [&](const char* name) -> std::vector<double>& { return arrays[name].values; };
  ParticleFrame f;
  f.time = values("TIME").at(0);
  f.dimension = static_cast<int>(values("DIMENSION").at(0));
  const int d = f.dimension;
  if (d != 2 && d != 3) throw IoError(source + ": dimension is not 2 or 3");
  f.count = values("Points").size() / 3;
  if (values("velocity").size() != 3 * f.count || values("stress").size() != 9 * f.count)
    throw IoError(source + ": arrays of different lengths");
  for (std::size_t p = 0; p < f.count; ++p)
    for (int a = 0; a < d; ++a) {
      f.position.push_back(values("Points")[3 * p + a]);
      f.velocity.push_back(values("velocity")[3 * p + a]);
    }
  f.volume = values("volume");
  f.pressure = values("pressure");
  f.phi = values("phi");
  f.shear_rate = values("shear_rate");
  f.id = values("id");
  f.material = values("material");
  const int idx2[] = {0, 4, 1}, idx3[] = {0, 4, 8, 1, 2, 5};
  for (std::size_t p = 0; p < f.count; ++p)
    for (int k = 0; k < f.stress_components(); ++k)
      f.stress.push_back(values("stress")[9 * p + (d == 2 ? idx2[k] : idx3[k])]);
  return f;
}

}  // namespace sablier
