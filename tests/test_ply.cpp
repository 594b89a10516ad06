// Binary PLY frames: the header a PLY reader expects, and each vertex's bytes
// in the order and types it announces.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>

#include "io/writers.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;

ParticleFrame sample(int d, std::size_t n) {
  ParticleFrame f;
  f.dimension = d;
  f.time = 0.25;
  f.count = n;
  for (std::size_t p = 0; p < n; ++p) {
    for (int a = 0; a < d; ++a) {
      f.position.push_back(0.1 * p + a + 1.0 / 3.0);
      f.velocity.push_back(-0.5 * p + a * 1e-7);
    }
    f.volume.push_back(1e-6 * (p + 1));
    f.pressure.push_back(1000.0 + p);
    f.phi.push_back(0.6 - 1e-3 * p);
    for (int k = 0; k < f.stress_components(); ++k) f.stress.push_back(k);
    f.shear_rate.push_back(0.01 * p);
    f.id.push_back(static_cast<double>(p + 7));
    f.material.push_back(static_cast<double>(p % 2 + 2));
  }
  return f;
}

// Little-endian values at `at`, whatever the host.
template <class T>
T read_le(const std::string& s, std::size_t at) {
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i)
    bits |= std::uint64_t(static_cast<unsigned char>(s[at + i])) << (8 * i);
  T v;
  if constexpr (sizeof(T) == 4) {
    const auto b32 = static_cast<std::uint32_t>(bits);
    std::memcpy(&v, &b32, 4);
  } else {
    std::memcpy(&v, &bits, 8);
  }
  return v;
}

const char* const kHeaderTail =
    "element vertex 3\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property double vx\nproperty double vy\nproperty double vz\n"
    "property double volume\nproperty double pressure\nproperty double phi\n"
    "property double shear_rate\nproperty double id\nproperty double material\n"
    "end_header\n";

TEST(Ply, HeaderAndVertexBytes) {
  for (int d : {2, 3}) {
    SCOPED_TRACE(d);
    const ParticleFrame f = sample(d, 3);
    const std::string ply = format_ply(f);
    ASSERT_EQ(ply.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u) << ply.substr(0, 80);
    const std::size_t end = ply.find("end_header\n");
    ASSERT_NE(end, std::string::npos);
    const std::size_t body = end + std::strlen("end_header\n");
    const std::string header = ply.substr(0, body);
    EXPECT_NE(header.find("comment "), std::string::npos);
    EXPECT_EQ(header.substr(header.find("element vertex")), kHeaderTail);
    ASSERT_EQ(ply.size(), body + 3 * kPlyVertexBytes);

    const std::size_t p = 1, v = body + p * kPlyVertexBytes;
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(read_le<float>(ply, v + 4 * a), a < d ? float(f.position[p * d + a]) : 0.0f);
    const std::size_t dbl = v + 12;
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(read_le<double>(ply, dbl + 8 * a), a < d ? f.velocity[p * d + a] : 0.0);
    EXPECT_EQ(read_le<double>(ply, dbl + 24), f.volume[p]);
    EXPECT_EQ(read_le<double>(ply, dbl + 32), f.pressure[p]);
    EXPECT_EQ(read_le<double>(ply, dbl + 40), f.phi[p]);
    EXPECT_EQ(read_le<double>(ply, dbl + 48), f.shear_rate[p]);
    EXPECT_EQ(read_le<double>(ply, dbl + 56), 8.0);  // id of particle 1
    EXPECT_EQ(read_le<double>(ply, dbl + 64), 3.0);  // its material
  }
}

TEST(Ply, MaterialDefaultsToZero) {
  ParticleFrame f = sample(2, 3);
  f.material.clear();  // a frame built without materials
  const std::string ply = format_ply(f);
  const std::size_t body = ply.find("end_header\n") + std::strlen("end_header\n");
  EXPECT_EQ(read_le<double>(ply, body + kPlyVertexBytes - 8), 0.0);
}

TEST(Ply, EmptyFrame) {
  const std::string ply = format_ply(sample(3, 0));
  EXPECT_NE(ply.find("element vertex 0\n"), std::string::npos);
  EXPECT_EQ(ply.substr(ply.size() - 11), "end_header\n");
}

TEST(Ply, RunWritesPlyFrames) {
  const fs::path dir = test::fresh_dir("ply");
  const std::string cmd = std::string(SABLIER_BINARY) + " run " + SABLIER_SOURCE_DIR +
                          "/scenes/collapse2d.toml --out " + dir.string() +
                          " --format ply --set time.frames=1 --set grid.resolution=[40,10] "
                          "--threads 1 --quiet";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string ply = read_file((dir / "frames/particles_00001.ply").string());
  EXPECT_NE(ply.find("element vertex 720\n"), std::string::npos);
  // The VTK frames come too: the outputs, and `render`'s input.
  EXPECT_TRUE(fs::exists(dir / "frames/particles_00001.vtp"));
  EXPECT_TRUE(fs::exists(dir / "series.pvd"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sablier
