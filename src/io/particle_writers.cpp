// Particle files: VTK XML PolyData (binary appended), CSV, and the ParaView
// collection that lists the frames.
#include <fmt/format.h>

#include <cstdint>

#include "io/vtk_xml.hpp"
#include "io/writers.hpp"

namespace sablier {
namespace {

// 3-component vectors from d-component interleaved ones (z = 0 in 2D).
std::vector<double> as_3d(const std::vector<double>& v, int d, std::size_t n) {
  std::vector<double> out(3 * n, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (int a = 0; a < d; ++a) out[3 * p + a] = v[d * p + a];
  return out;
}

// Full 3x3 tensors (row-major) from the compact components.
std::vector<double> as_tensor9(const ParticleFrame& f) {
  const std::size_t n = f.count;
  const int sc = f.stress_components();
  std::vector<double> out(9 * n, 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    const double* s = &f.stress[sc * p];
    double* t = &out[9 * p];
    if (f.dimension == 2) {
      t[0] = s[0], t[4] = s[1], t[1] = t[3] = s[2];
    } else {
      t[0] = s[0], t[4] = s[1], t[8] = s[2];
      t[1] = t[3] = s[3], t[2] = t[6] = s[4], t[5] = t[7] = s[5];
    }
  }
  return out;
}

}  // namespace

std::string format_vtp(const ParticleFrame& f, VtkCompression compression) {
  const std::size_t n = f.count;
  VtkAppended app(compression);
  std::string field, point;
  field += vtk_field_tag("Float64", "TIME", 1, app.add(std::vector<double>{f.time}));
  field += vtk_field_tag("Int32", "DIMENSION", 1, app.add(std::vector<std::int32_t>{f.dimension}));
  const auto scalar = [&](const char* name, const std::vector<double>& v) {
    if (v.size() == n && n > 0) point += vtk_array_tag("Float64", name, 1, app.add(v));
  };
  point += vtk_array_tag("Float64", "velocity", 3, app.add(as_3d(f.velocity, f.dimension, n)));
  scalar("volume", f.volume);
  scalar("pressure", f.pressure);
  scalar("phi", f.phi);
  point += vtk_array_tag("Float64", "stress", 9, app.add(as_tensor9(f)));
  scalar("shear_rate", f.shear_rate);
  // Integers, so that ParaView colours them by category and selects exactly.
  if (f.id.size() == n) {
    std::vector<std::int64_t> id(f.id.begin(), f.id.end());
    point += vtk_array_tag("Int64", "id", 1, app.add(id));
  }
  if (f.material.size() == n) {
    std::vector<std::int32_t> material(f.material.begin(), f.material.end());
    point += vtk_array_tag("Int32", "material", 1, app.add(material));
  }
  const std::string points =
      vtk_array_tag("Float64", "Points", 3, app.add(as_3d(f.position, f.dimension, n)));
  std::vector<std::int64_t> conn(n), offs(n);
  for (std::size_t p = 0; p < n; ++p) conn[p] = static_cast<std::int64_t>(p), offs[p] = p + 1;
  const std::string verts = vtk_array_tag("Int64", "connectivity", 1, app.add(conn)) +
                            vtk_array_tag("Int64", "offsets", 1, app.add(offs));
  return vtk_file_open("PolyData", compression) +
         fmt::format(
             "<PolyData>\n<FieldData>{}</FieldData>\n"
             "<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" "
             "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<PointData>{}</PointData>\n"
             "<Points>{}</Points>\n<Verts>{}</Verts>\n</Piece>\n</PolyData>\n",
             field, n, n, point, points, verts) +
         vtk_file_close(app);
}

std::string format_particle_csv(const ParticleFrame& f) {
  const int d = f.dimension;
  const int sc = f.stress_components();
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "{}\n",
                 d == 2 ? "x,y,vx,vy,volume,pressure,phi,sxx,syy,sxy"
                        : "x,y,z,vx,vy,vz,volume,pressure,phi,sxx,syy,szz,sxy,sxz,syz");
  for (std::size_t p = 0; p < f.count; ++p) {
    for (int a = 0; a < d; ++a) fmt::format_to(std::back_inserter(out), "{},", f.position[d * p + a]);
    for (int a = 0; a < d; ++a) fmt::format_to(std::back_inserter(out), "{},", f.velocity[d * p + a]);
    fmt::format_to(std::back_inserter(out), "{},{},{}", f.volume[p], f.pressure[p], f.phi[p]);
    for (int k = 0; k < sc; ++k) fmt::format_to(std::back_inserter(out), ",{}", f.stress[sc * p + k]);
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
  const auto values = [&](const char* name) -> std::vector<double>& {
    return arrays[name].values;
  };
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
