// Particle files: VTK XML PolyData (binary appended), CSV, and the ParaView
// collection that lists the frames.
#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <map>

#include "io/writers.hpp"

namespace sablier {
namespace {

// Appended-data blocks of a VTK XML file: each is a UInt64 byte count then
// raw little-endian values; arrays refer to their block by byte offset.
class Appended {
 public:
  template <class T>
  std::size_t add(const std::vector<T>& values) {
    const std::size_t offset = data_.size();
    const std::uint64_t bytes = values.size() * sizeof(T);
    append(&bytes, sizeof bytes);
    if (bytes) append(values.data(), bytes);
    return offset;
  }
  const std::string& data() const { return data_; }

 private:
  void append(const void* p, std::size_t n) { data_.append(static_cast<const char*>(p), n); }
  std::string data_;
};

std::string array_tag(const char* type, const std::string& name, int components,
                      std::size_t offset) {
  return fmt::format(
      R"(<DataArray type="{}" Name="{}" NumberOfComponents="{}" format="appended" offset="{}"/>)",
      type, name, components, offset);
}

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

std::string format_vtp(const ParticleFrame& f) {
  const std::size_t n = f.count;
  Appended app;
  std::string field, point;
  field += array_tag("Float64", "TIME", 1, app.add(std::vector<double>{f.time}));
  field += array_tag("Int32", "DIMENSION", 1, app.add(std::vector<std::int32_t>{f.dimension}));
  const auto scalar = [&](const char* name, const std::vector<double>& v) {
    if (v.size() == n && n > 0) point += array_tag("Float64", name, 1, app.add(v));
  };
  point += array_tag("Float64", "velocity", 3, app.add(as_3d(f.velocity, f.dimension, n)));
  scalar("volume", f.volume);
  scalar("pressure", f.pressure);
  scalar("phi", f.phi);
  point += array_tag("Float64", "stress", 9, app.add(as_tensor9(f)));
  scalar("shear_rate", f.shear_rate);
  if (f.id.size() == n) {
    std::vector<std::int64_t> id(f.id.begin(), f.id.end());
    point += array_tag("Int64", "id", 1, app.add(id));
  }
  const std::string points =
      array_tag("Float64", "Points", 3, app.add(as_3d(f.position, f.dimension, n)));
  std::vector<std::int64_t> conn(n), offs(n);
  for (std::size_t p = 0; p < n; ++p) conn[p] = static_cast<std::int64_t>(p), offs[p] = p + 1;
  const std::string verts = array_tag("Int64", "connectivity", 1, app.add(conn)) +
                            array_tag("Int64", "offsets", 1, app.add(offs));
  std::string out = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n<PolyData>\n<FieldData>{}</FieldData>\n"
      "<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" "
      "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<PointData>{}</PointData>\n"
      "<Points>{}</Points>\n<Verts>{}</Verts>\n</Piece>\n</PolyData>\n"
      "<AppendedData encoding=\"raw\">\n_",
      field, n, n, point, points, verts);
  out += app.data();
  out += "\n</AppendedData>\n</VTKFile>\n";
  return out;
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

namespace {

std::string attribute(const std::string& tag, const std::string& key) {
  const std::size_t k = tag.find(" " + key + "=\"");
  if (k == std::string::npos) return "";
  const std::size_t start = k + key.size() + 3;
  return tag.substr(start, tag.find('"', start) - start);
}

}  // namespace

ParticleFrame parse_vtp(const std::string& s, const std::string& source) {
  const auto fail = [&](const std::string& why) { return IoError(source + ": " + why); };
  const std::size_t app = s.find("<AppendedData encoding=\"raw\">");
  if (app == std::string::npos) throw fail("no raw appended data");
  const std::size_t base = s.find('_', app) + 1;
  // Arrays by name: (type, components, values as doubles).
  std::map<std::string, std::vector<double>> arrays;
  for (std::size_t pos = s.find("<DataArray"); pos < app; pos = s.find("<DataArray", pos + 1)) {
    const std::string tag = s.substr(pos, s.find('>', pos) - pos);
    const std::string type = attribute(tag, "type");
    const std::size_t offset = std::stoull(attribute(tag, "offset"));
    std::uint64_t bytes = 0;
    if (base + offset + 8 > s.size()) throw fail("truncated appended data");
    std::memcpy(&bytes, s.data() + base + offset, 8);
    const char* data = s.data() + base + offset + 8;
    if (base + offset + 8 + bytes > s.size()) throw fail("truncated appended data");
    std::vector<double>& v = arrays[attribute(tag, "Name")];
    const std::size_t size = type == "Int32" ? 4 : 8;
    v.resize(bytes / size);
    for (std::size_t k = 0; k < v.size(); ++k) {
      if (type == "Float64") {
        std::memcpy(&v[k], data + 8 * k, 8);
      } else if (type == "Int64") {
        std::int64_t x;
        std::memcpy(&x, data + 8 * k, 8);
        v[k] = static_cast<double>(x);
      } else if (type == "Int32") {
        std::int32_t x;
        std::memcpy(&x, data + 4 * k, 4);
        v[k] = x;
      } else {
        throw fail("unsupported type " + type);
      }
    }
  }
  for (const char* name : {"TIME", "DIMENSION", "Points", "velocity", "stress"})
    if (!arrays.count(name)) throw fail(std::string("missing array ") + name);
  ParticleFrame f;
  f.time = arrays["TIME"].at(0);
  f.dimension = static_cast<int>(arrays["DIMENSION"].at(0));
  const int d = f.dimension;
  f.count = arrays["Points"].size() / 3;
  for (std::size_t p = 0; p < f.count; ++p)
    for (int a = 0; a < d; ++a) {
      f.position.push_back(arrays["Points"][3 * p + a]);
      f.velocity.push_back(arrays["velocity"][3 * p + a]);
    }
  f.volume = arrays["volume"];
  f.pressure = arrays["pressure"];
  f.phi = arrays["phi"];
  f.shear_rate = arrays["shear_rate"];
  f.id = arrays["id"];
  const int idx2[] = {0, 4, 1}, idx3[] = {0, 4, 8, 1, 2, 5};
  for (std::size_t p = 0; p < f.count; ++p)
    for (int k = 0; k < f.stress_components(); ++k)
      f.stress.push_back(arrays["stress"][9 * p + (d == 2 ? idx2[k] : idx3[k])]);
  return f;
}

}  // namespace sablier
