// Grid fields as VTK XML ImageData (.vti): one point per real grid node, so
// ParaView shows the fields the solver works on (volume fraction, velocity
// after the solve, pressure of the stress rows) rather than their particle
// interpolations.
#include <fmt/format.h>

#include <sstream>

#include "io/vtk_xml.hpp"
#include "io/writers.hpp"

namespace sablier {

std::string format_vti(const GridFrame& g, VtkCompression compression) {
  const std::size_t n = g.node_count();
  const int d = g.dimension;
  VtkAppended app(compression);
  std::string field, point;
  field += vtk_field_tag("Float64", "TIME", 1, app.add(std::vector<double>{g.time}));
  field += vtk_field_tag("Int32", "DIMENSION", 1, app.add(std::vector<std::int32_t>{d}));
  point += vtk_array_tag("Float64", "phi", 1, app.add(g.phi));
  std::vector<double> velocity(3 * n, 0.0);  // z = 0 in 2D
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < d; ++a) velocity[3 * i + a] = g.velocity[d * i + a];
  point += vtk_array_tag("Float64", "velocity", 3, app.add(velocity));
  point += vtk_array_tag("Float64", "pressure", 1, app.add(g.pressure));
  point += vtk_array_tag("UInt8", "active", 1, app.add(g.active));
  point += vtk_array_tag("UInt8", "regime", 1, app.add(g.regime));
  const std::string extent =
      fmt::format("0 {} 0 {} 0 {}", g.nodes[0] - 1, g.nodes[1] - 1, g.nodes[2] - 1);
  return vtk_file(
      "ImageData",
      fmt::format("<ImageData WholeExtent=\"{0}\" Origin=\"0 0 0\" Spacing=\"{1} {1} {1}\">\n"
                  "<FieldData>{2}</FieldData>\n<Piece Extent=\"{0}\">\n"
                  "<PointData Scalars=\"phi\" Vectors=\"velocity\">{3}</PointData>\n"
                  "<CellData></CellData>\n</Piece>\n</ImageData>\n",
                  extent, g.spacing, field, point),
      app);
}

GridFrame parse_vti(const std::string& s, const std::string& source) {
  const auto fail = [&](const std::string& why) { return IoError(source + ": " + why); };
  std::map<std::string, VtkArray> arrays = read_vtk_arrays(s, source);
  for (const char* name : {"TIME", "DIMENSION", "phi", "velocity", "pressure", "active"})
    if (!arrays.count(name)) throw fail(std::string("missing array ") + name);
  const std::size_t tag = s.find("<ImageData");
  if (tag == std::string::npos) throw fail("no ImageData");
  const std::string image = s.substr(tag, s.find('>', tag) - tag);

  GridFrame g;
  g.time = arrays["TIME"].values.at(0);
  g.dimension = static_cast<int>(arrays["DIMENSION"].values.at(0));
  if (g.dimension != 2 && g.dimension != 3) throw fail("dimension is not 2 or 3");
  std::istringstream extent(xml_attribute(image, "WholeExtent"));
  for (int a = 0; a < 3; ++a) {
    int lo = -1, hi = -1;
    if (!(extent >> lo >> hi) || lo != 0 || hi < 0) throw fail("bad WholeExtent");
    g.nodes[a] = hi + 1;
  }
  if (!(std::istringstream(xml_attribute(image, "Spacing")) >> g.spacing))
    throw fail("bad Spacing");
  const std::size_t n = g.node_count();
  g.phi = arrays["phi"].values;
  g.pressure = arrays["pressure"].values;
  g.active.assign(arrays["active"].values.begin(), arrays["active"].values.end());
  // Files written before the array existed (2026-12-07) read as no rows.
  if (arrays.count("regime"))
    g.regime.assign(arrays["regime"].values.begin(), arrays["regime"].values.end());
  else
    g.regime.assign(n, kNoRow);
  const std::vector<double>& v = arrays["velocity"].values;
  if (g.phi.size() != n || g.pressure.size() != n || g.active.size() != n || g.regime.size() != n ||
      v.size() != 3 * n)
    throw fail("arrays do not match the extent");
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < g.dimension; ++a) g.velocity.push_back(v[3 * i + a]);
  return g;
}

}  // namespace sablier
