// Writers: each file read back equals what was written; atomic writes leave
// no temporary file and fail cleanly.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "io/stats_writer.hpp"
#include "io/writers.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;

ParticleFrame sample(int d, std::size_t n) {
  ParticleFrame f;
  f.dimension = d;
  f.time = 0.125;
  f.count = n;
  const int sc = f.stress_components();
  for (std::size_t p = 0; p < n; ++p) {
    for (int a = 0; a < d; ++a) {
      f.position.push_back(0.1 * p + a + 1.0 / 3.0);
      f.velocity.push_back(-0.5 * p + a * 1e-7);
    }
    f.volume.push_back(1e-6 * (p + 1));
    f.pressure.push_back(1000.0 + p);
    f.phi.push_back(0.6 - 1e-3 * p);
    for (int k = 0; k < sc; ++k) f.stress.push_back(10.0 * k + p + 0.1);
    f.shear_rate.push_back(0.01 * p);
    f.id.push_back(static_cast<double>(p));
    f.material.push_back(static_cast<double>(p % 3));
  }
  return f;
}

using test::temp_dir;

void expect_same(const ParticleFrame& a, const ParticleFrame& b) {
  EXPECT_EQ(a.dimension, b.dimension);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.count, b.count);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.velocity, b.velocity);
  EXPECT_EQ(a.volume, b.volume);
  EXPECT_EQ(a.pressure, b.pressure);
  EXPECT_EQ(a.phi, b.phi);
  EXPECT_EQ(a.stress, b.stress);
  EXPECT_EQ(a.shear_rate, b.shear_rate);
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.material, b.material);
}

// Every array, both dimensions, raw and compressed, from an empty frame to
// one whose arrays span several zlib blocks.
TEST(Writers, VtpRoundTrip) {
  const fs::path dir = temp_dir("vtp");
  constexpr std::size_t kBig = 3000;
  static_assert(3 * 8 * kBig > kVtkZlibBlockBytes, "the big frame must span several blocks");
  for (VtkCompression c : {VtkCompression::None, VtkCompression::Zlib})
    for (int d : {2, 3})
      for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(57), kBig}) {
        SCOPED_TRACE(::testing::Message() << "zlib " << (c == VtkCompression::Zlib) << ", " << d
                                          << "D, " << n << " particles");
        const ParticleFrame f = sample(d, n);
        const std::string path = (dir / "f.vtp").string();
        const std::string vtp = format_vtp(f, c);
        EXPECT_EQ(vtp.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos,
                  c == VtkCompression::Zlib);
        write_file_atomic(path, vtp);
        const ParticleFrame g = parse_vtp(read_file(path), path);
        if (n == 0) {
          EXPECT_EQ(g.count, 0u);
          EXPECT_EQ(g.time, f.time);
          EXPECT_EQ(g.dimension, d);
        } else {
          expect_same(f, g);
        }
      }
}

// A frame without grains (a silo drained empty) keeps every point array, so
// that a ParaView pipeline over the series finds them in each frame.
TEST(Writers, EmptyVtpKeepsEveryArray) {
  for (int d : {2, 3}) {
    const std::string vtp = format_vtp(sample(d, 0));
    for (const char* name :
         {"velocity", "volume", "pressure", "phi", "stress", "shear_rate", "id", "material"})
      EXPECT_NE(vtp.find(std::string("Name=\"") + name + "\""), std::string::npos) << name;
    expect_same(parse_vtp(vtp, "empty"), sample(d, 0));
  }
}

TEST(Writers, VtpCompressionShrinksRegularData) {
  const ParticleFrame f = sample(3, 3000);
  EXPECT_LT(format_vtp(f, VtkCompression::Zlib).size(), format_vtp(f).size() / 2);
}

TEST(Writers, DamagedVtpIsRefused) {
  const ParticleFrame f = sample(2, 3000);
  for (VtkCompression c : {VtkCompression::None, VtkCompression::Zlib}) {
    const std::string vtp = format_vtp(f, c);
    const std::size_t data = vtp.find("<AppendedData");
    EXPECT_THROW(parse_vtp(vtp.substr(0, data + (vtp.size() - data) / 2), "cut.vtp"), IoError);
    if (c == VtkCompression::Zlib) {
      std::string bad = vtp;
      for (std::size_t k = data + 400; k < data + 440; ++k) bad[k] = static_cast<char>(~bad[k]);
      EXPECT_THROW(parse_vtp(bad, "flipped.vtp"), IoError);
    }
  }
}

GridFrame sample_grid(int d) {
  GridFrame g;
  g.dimension = d;
  g.time = 0.375;
  g.spacing = 1.0 / 48;
  g.nodes = {5, 4, d == 3 ? 3 : 1};
  const std::size_t n = g.node_count();
  for (std::size_t i = 0; i < n; ++i) {
    g.phi.push_back(0.6 * i / n);
    for (int a = 0; a < d; ++a) g.velocity.push_back(0.1 * i - a / 3.0);
    g.pressure.push_back(1234.5 / (i + 1));
    g.active.push_back(i % 2);
    g.regime.push_back(static_cast<std::uint8_t>(i % 4));
  }
  return g;
}

TEST(Writers, VtiRoundTrip) {
  for (VtkCompression c : {VtkCompression::None, VtkCompression::Zlib})
    for (int d : {2, 3}) {
      const GridFrame g = sample_grid(d);
      const std::string vti = format_vti(g, c);
      EXPECT_NE(vti.find(d == 2 ? "WholeExtent=\"0 4 0 3 0 0\"" : "WholeExtent=\"0 4 0 3 0 2\""),
                std::string::npos);
      EXPECT_NE(vti.find("Origin=\"0 0 0\""), std::string::npos);
      const GridFrame h = parse_vti(vti, "g.vti");
      EXPECT_EQ(h.dimension, d);
      EXPECT_EQ(h.time, g.time);
      EXPECT_EQ(h.spacing, g.spacing);
      EXPECT_EQ(h.nodes, g.nodes);
      EXPECT_EQ(h.phi, g.phi);
      EXPECT_EQ(h.velocity, g.velocity);
      EXPECT_EQ(h.pressure, g.pressure);
      EXPECT_EQ(h.active, g.active);
      EXPECT_EQ(h.regime, g.regime);
    }
}

TEST(Writers, CsvHeaderAndValues) {
  for (int d : {2, 3}) {
    const ParticleFrame f = sample(d, 5);
    std::istringstream in(format_particle_csv(f));
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, d == 2 ? "x,y,vx,vy,volume,pressure,phi,sxx,syy,sxy"
                           : "x,y,z,vx,vy,vz,volume,pressure,phi,sxx,syy,szz,sxy,sxz,syz");
    for (std::size_t p = 0; p < f.count; ++p) {
      ASSERT_TRUE(std::getline(in, line));
      std::vector<double> v;
      std::istringstream ls(line);
      for (std::string c; std::getline(ls, c, ',');) v.push_back(std::stod(c));
      ASSERT_EQ(v.size(), static_cast<std::size_t>(2 * d + 3 + f.stress_components()));
      EXPECT_EQ(v[0], f.position[d * p]);
      EXPECT_EQ(v[d], f.velocity[d * p]);
      EXPECT_EQ(v[2 * d], f.volume[p]);
      EXPECT_EQ(v[2 * d + 1], f.pressure[p]);
      EXPECT_EQ(v.back(), f.stress[f.stress_components() * (p + 1) - 1]);
    }
  }
}

TEST(Writers, PvdListsFrames) {
  const std::string pvd =
      format_pvd({{0.0, "frames/particles_00000.vtp"}, {0.5, "frames/particles_00001.vtp"}});
  EXPECT_NE(pvd.find("timestep=\"0.5\" group=\"\" part=\"0\" file=\"frames/particles_00001.vtp\""),
            std::string::npos);
  EXPECT_NE(pvd.find("type=\"Collection\""), std::string::npos);
}

TEST(Writers, StatsRoundTrip) {
  StatsTable t;
  StepStats s;
  s.step = 3;
  s.time = 0.1;
  s.dt = 1.0 / 30;
  s.iterations = 17;
  s.residual = 3.3e-4;
  s.kinetic_energy = 1.0 / 7;
  s.hit_cap = true;
  s.decompaction_work = 2.0 / 3;
  s.overfill = 1.0 / 9;
  t.add(s);
  const std::string csv = t.csv();
  const auto rows = parse_stats_csv(csv);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].dt, s.dt);
  EXPECT_EQ(rows[0].kinetic_energy, s.kinetic_energy);
  EXPECT_EQ(rows[0].iterations, 17);
  EXPECT_TRUE(rows[0].hit_cap);
  EXPECT_EQ(rows[0].decompaction_work, s.decompaction_work);
  EXPECT_EQ(rows[0].overfill, s.overfill);
  // Files of builds before overfill (17 columns) and before
  // decompaction_work (16) still read, the missing columns as NaN, so that
  // such a run can be resumed.
  std::string old_header = kStatsHeader, line = csv.substr(csv.find('\n') + 1);
  line.pop_back();  // its newline
  std::string old;
  for (int dropped = 1; dropped <= 2; ++dropped) {
    old_header = old_header.substr(0, old_header.rfind(','));
    line = line.substr(0, line.rfind(','));
    old = old_header + "\n" + line + "\n";
    const auto old_rows = parse_stats_csv(old);
    ASSERT_EQ(old_rows.size(), 1u) << dropped;
    EXPECT_EQ(old_rows[0].iterations, 17);
    EXPECT_TRUE(std::isnan(old_rows[0].overfill));
    EXPECT_EQ(std::isnan(old_rows[0].decompaction_work), dropped == 2);
    EXPECT_EQ(parse_stats_csv_until(old, 3).size(), 1u);
  }
  EXPECT_THROW(parse_stats_csv(old_header + ",extra\n"), IoError);
}

TEST(Writers, AtomicWriteReplacesAndLeavesNoTemporary) {
  const fs::path dir = temp_dir("atomic");
  const std::string path = (dir / "a.txt").string();
  write_file_atomic(path, "first");
  write_file_atomic(path, "second");
  EXPECT_EQ(read_file(path), "second");
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) ++entries, (void)e;
  EXPECT_EQ(entries, 1);
}

TEST(Writers, AtomicWriteFailsCleanly) {
  const fs::path dir = temp_dir("atomic_fail");
  write_file_atomic((dir / "file").string(), "x");
  // A path "under" a regular file cannot be written, even as root.
  EXPECT_THROW(write_file_atomic((dir / "file" / "a.txt").string(), "y"), IoError);
  EXPECT_THROW(ensure_directory((dir / "file" / "sub").string()), IoError);
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) ++entries, (void)e;
  EXPECT_EQ(entries, 1);
  ensure_directory((dir / "x" / "y" / "z").string());
  EXPECT_TRUE(fs::is_directory(dir / "x" / "y" / "z"));
}

}  // namespace
}  // namespace sablier
