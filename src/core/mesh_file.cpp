// Reading triangle meshes: Wavefront OBJ (positions and faces) and STL
// (binary or ASCII). Vertices with identical coordinates are merged, since
// STL repeats them per facet and open_edge_count() needs shared indices.
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/mesh.hpp"

namespace sablier {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string read_bytes(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw MeshError("is a directory, not a mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshError(std::string("cannot open the file (") + std::strerror(errno) + ")");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw MeshError("cannot read the file");
  return ss.str();
}

// Collects triangles given by coordinates, merging equal vertices.
class Welder {
 public:
  std::int32_t vertex(const Point3& p) {
    const auto [it, added] = index_.emplace(p, static_cast<std::int32_t>(mesh_.vertices.size()));
    if (added) mesh_.vertices.push_back(p);
    return it->second;
  }
  void triangle(const Point3& a, const Point3& b, const Point3& c) {
    mesh_.triangles.push_back({vertex(a), vertex(b), vertex(c)});
  }
  TriangleMesh take() {
    if (mesh_.triangles.empty()) throw MeshError("no triangles");
    return std::move(mesh_);
  }

 private:
  std::map<Point3, std::int32_t> index_;
  TriangleMesh mesh_;
};

[[noreturn]] void fail_line(std::size_t line, const std::string& what) {
  throw MeshError("line " + std::to_string(line) + ": " + what);
}

// The next whitespace-separated number of `text` from `pos`; false if none.
bool next_number(const std::string& text, std::size_t& pos, double& value) {
  const char* start = text.c_str() + pos;
  char* end = nullptr;
  value = std::strtod(start, &end);
  if (end == start) return false;
  pos += static_cast<std::size_t>(end - start);
  return std::isfinite(value);
}

// An OBJ face corner "v", "v/vt", "v//vn" or "v/vt/vn": the vertex index,
// 1-based, negative counting back from the last vertex read so far.
std::int64_t face_corner(const std::string& token, std::size_t vertices, std::size_t line) {
  char* end = nullptr;
  const long long k = std::strtoll(token.c_str(), &end, 10);
  if (end == token.c_str() || (*end != '\0' && *end != '/'))
    fail_line(line, "\"" + token + "\" is not a face vertex index");
  const long long index = k < 0 ? static_cast<long long>(vertices) + k : k - 1;
  if (k == 0 || index < 0 || index >= static_cast<long long>(vertices))
    fail_line(line, "face vertex " + token + " does not exist (" + std::to_string(vertices) +
                        " vertices so far)");
  return index;
}

TriangleMesh read_obj(const std::string& text) {
  std::vector<Point3> positions;
  Welder weld;
  std::istringstream in(text);
  std::size_t line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      Point3 p;
      std::string rest;
      std::getline(words, rest);
      std::size_t pos = 0;
      for (double& x : p)
        if (!next_number(rest, pos, x)) fail_line(line_no, "a vertex needs 3 finite coordinates");
      positions.push_back(p);
    } else if (tag == "f") {
      std::vector<std::int64_t> corners;
      for (std::string token; words >> token;)
        corners.push_back(face_corner(token, positions.size(), line_no));
      if (corners.size() < 3) fail_line(line_no, "a face needs at least 3 vertices");
      for (std::size_t k = 1; k + 1 < corners.size(); ++k)  // fan triangulation
        weld.triangle(positions[corners[0]], positions[corners[k]], positions[corners[k + 1]]);
    }
  }
  return weld.take();
}

// Binary STL: 80-byte header, u32 facet count, 50 bytes per facet (normal,
// three vertices as little-endian float32, u16 attribute).
bool is_binary_stl(const std::string& bytes) {
  if (bytes.size() < 84) return false;
  std::uint32_t n = 0;
  for (int k = 3; k >= 0; --k) n = n << 8 | static_cast<unsigned char>(bytes[80 + k]);
  return bytes.size() == 84 + 50 * static_cast<std::uint64_t>(n);
}

double float_at(const std::string& bytes, std::size_t pos) {
  std::uint32_t bits = 0;
  for (int k = 3; k >= 0; --k) bits = bits << 8 | static_cast<unsigned char>(bytes[pos + k]);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

TriangleMesh read_binary_stl(const std::string& bytes) {
  Welder weld;
  const std::size_t facets = (bytes.size() - 84) / 50;
  for (std::size_t t = 0; t < facets; ++t) {
    Point3 v[3];
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) {
        v[k][a] = float_at(bytes, 84 + 50 * t + 12 * (k + 1) + 4 * a);
        if (!std::isfinite(v[k][a]))
          throw MeshError("facet " + std::to_string(t) + ": a coordinate is not finite");
      }
    weld.triangle(v[0], v[1], v[2]);
  }
  return weld.take();
}

// ASCII STL: the `vertex x y z` lines, three per facet; the rest (facet
// normals, loop keywords) carries nothing the inside test needs.
TriangleMesh read_ascii_stl(const std::string& text) {
  Welder weld;
  std::istringstream in(text);
  std::vector<Point3> corners;
  std::size_t line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "endloop" && corners.size() != 3)
      fail_line(line_no,
                "a facet needs exactly 3 vertices, found " + std::to_string(corners.size()));
    if (tag == "endloop") {
      weld.triangle(corners[0], corners[1], corners[2]);
      corners.clear();
    }
    if (tag != "vertex") continue;
    std::string rest;
    std::getline(words, rest);
    std::size_t pos = 0;
    Point3 p;
    for (double& x : p)
      if (!next_number(rest, pos, x)) fail_line(line_no, "a vertex needs 3 finite coordinates");
    corners.push_back(p);
  }
  if (!corners.empty()) throw MeshError("the last facet has no endloop");
  return weld.take();
}

TriangleMesh read_stl(const std::string& bytes) {
  if (is_binary_stl(bytes)) return read_binary_stl(bytes);
  const std::size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start != std::string::npos && bytes.compare(start, 5, "solid") == 0)
    return read_ascii_stl(bytes);
  throw MeshError(
      "neither binary STL (84 + 50 n bytes for n facets) nor ASCII STL (starting with \"solid\")");
}

}  // namespace

TriangleMesh read_mesh_file(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::string ext = dot == std::string::npos ? "" : lower(path.substr(dot));
  if (ext != ".obj" && ext != ".stl")
    throw MeshError("unknown mesh format \"" + ext + "\" (.obj or .stl expected)");
  const std::string bytes = read_bytes(path);
  return ext == ".obj" ? read_obj(bytes) : read_stl(bytes);
}

}  // namespace sablier
