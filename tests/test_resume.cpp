// Interrupt and resume: an interrupted run leaves a checkpoint, and
// `sablier run --resume DIR` continues it bit for bit as if it had never
// stopped; a damaged checkpoint is refused with one line and nothing written.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <utility>

#include "io/checkpoint.hpp"
#include "io/hash.hpp"
#include "io/stats_writer.hpp"
#include "io/writers.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;

using test::Result;
using test::sablier;
using test::scene_file;
using test::shell;

fs::path fresh(const std::string& name) { return test::fresh_dir("resume_" + name); }

// One thread: the comparison is between equal thread counts, and ctest runs
// tests side by side on few cores.
const std::string kSmall = " --set time.frames=4 --set grid.resolution=[40,10] --threads 1 --quiet";

std::string run_args(const fs::path& dir, const std::string& extra = "") {
  return "run " + scene_file("collapse2d.toml") + " --out " + dir.string() + kSmall + extra;
}

std::string file(const fs::path& p) { return read_file(p.string()); }

// Every stats.csv column but the wall-clock ones.
void expect_same_stats(const fs::path& a, const fs::path& b) {
  const auto ra = parse_stats_csv(file(a / "stats.csv"));
  const auto rb = parse_stats_csv(file(b / "stats.csv"));
  ASSERT_EQ(ra.size(), rb.size());
  for (std::size_t i = 0; i < ra.size(); ++i) {
    SCOPED_TRACE("row " + std::to_string(i));
    EXPECT_EQ(ra[i].step, rb[i].step);
    EXPECT_EQ(ra[i].time, rb[i].time);
    EXPECT_EQ(ra[i].dt, rb[i].dt);
    EXPECT_EQ(ra[i].particles, rb[i].particles);
    EXPECT_EQ(ra[i].active_nodes, rb[i].active_nodes);
    EXPECT_EQ(ra[i].iterations, rb[i].iterations);
    EXPECT_EQ(ra[i].residual, rb[i].residual);
    EXPECT_EQ(ra[i].kinetic_energy, rb[i].kinetic_energy);
    EXPECT_EQ(ra[i].potential_energy, rb[i].potential_energy);
    EXPECT_EQ(ra[i].max_speed, rb[i].max_speed);
    EXPECT_EQ(ra[i].hit_cap, rb[i].hit_cap);
  }
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST(Resume, ContinuesBitForBit) {
  const fs::path a = fresh("a"), b = fresh("b");
  ASSERT_EQ(sablier(run_args(a)).code, 0);

  const Result stopped = sablier(run_args(b, " --stop-after-frame 2"));
  ASSERT_EQ(stopped.code, 130) << stopped.output;
  EXPECT_TRUE(contains(stopped.output, "checkpoint written")) << stopped.output;
  EXPECT_TRUE(contains(stopped.output, "sablier run --resume " + b.string())) << stopped.output;
  EXPECT_TRUE(fs::exists(b / "frames/particles_00002.vtp"));
  EXPECT_FALSE(fs::exists(b / "frames/particles_00003.vtp"));
  EXPECT_TRUE(contains(file(b / "run.json"), "\"status\": \"interrupted\""));

  const Result resumed = sablier("run --resume " + b.string() + " --threads 1 --quiet");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  for (const char* f : {"frames/particles_00003.vtp", "frames/particles_00004.vtp", "series.pvd"})
    EXPECT_EQ(file(a / f), file(b / f)) << f;
  expect_same_stats(a, b);
  const std::string json = file(b / "run.json");
  EXPECT_TRUE(contains(json, "\"status\": \"finished\"")) << json;
  EXPECT_TRUE(contains(json, "\"resumed_from_step\": 2")) << json;

  // Nothing left to do: said so, and nothing changes.
  const Result again = sablier("run --resume " + b.string() + " --quiet");
  EXPECT_EQ(again.code, 0) << again.output;
  EXPECT_TRUE(contains(again.output, "finished")) << again.output;
  EXPECT_EQ(file(b / "run.json"), json);
  fs::remove_all(a);
  fs::remove_all(b);
}

// Grains that leave through an opening stay in the arrays until the next
// step drops them, and they set that step's length (Simulation::adaptive_dt):
// in silo2d's first frame the first grains fall out of the orifice faster
// than any left in the bin. A resumed run keeps them too
// (restore_simulation); before, it dropped them at once and its second
// frame took longer steps.
TEST(Resume, KeepsTheGrainsThatJustLeft) {
  const fs::path a = fresh("silo_a"), b = fresh("silo_b");
  const std::string silo =
      "run " + scene_file("silo2d.toml") + " --set time.frames=2" + " --threads 1 --quiet --out ";
  ASSERT_EQ(sablier(silo + a.string()).code, 0);
  ASSERT_EQ(sablier(silo + b.string() + " --stop-after-frame 1").code, 130);
  ASSERT_EQ(sablier("run --resume " + b.string() + " --threads 1 --quiet").code, 0);
  EXPECT_TRUE(file(a / "frames/particles_00002.vtp") == file(b / "frames/particles_00002.vtp"));
  expect_same_stats(a, b);
  fs::remove_all(a);
  fs::remove_all(b);
}

// With obstacles the checkpoint also holds the contact rows' warm start, and
// obstacles.csv is cut back to the checkpoint's steps: the resumed run's
// frames, stats and forces are those of the uninterrupted one.
TEST(Resume, WithObstaclesContinuesBitForBit) {
  const fs::path a = fresh("obs_a"), b = fresh("obs_b");
  const std::string args =
      "run " + scene_file("obstacle2d.toml") + " --set time.frames=6 --threads 1 --quiet --out ";
  ASSERT_EQ(sablier(args + a.string()).code, 0);
  const Result stopped = sablier(args + b.string() + " --stop-after-frame 3");
  ASSERT_EQ(stopped.code, 130) << stopped.output;
  const Result resumed = sablier("run --resume " + b.string() + " --threads 1 --quiet");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  for (const char* f :
       {"frames/particles_00004.vtp", "frames/particles_00006.vtp", "obstacles.csv"})
    EXPECT_EQ(file(a / f), file(b / f)) << f;
  expect_same_stats(a, b);
  const auto forces = parse_obstacle_forces_until(file(a / "obstacles.csv"), 2, 1L << 40);
  EXPECT_EQ(forces.size(), 2 * parse_stats_csv(file(a / "stats.csv")).size());
  fs::remove_all(a);
  fs::remove_all(b);
}

// A solid driven into the sand is where its velocity has taken it at the
// checkpoint's time, and the projection keeps nothing from step to step:
// the plough resumes bit for bit (frames, the blade's surfaces, forces).
TEST(Resume, WithAMovingSolidContinuesBitForBit) {
  const fs::path a = fresh("plough_a"), b = fresh("plough_b");
  const std::string args =
      "run " + scene_file("plough2d.toml") + " --set time.frames=6 --threads 1 --quiet --out ";
  ASSERT_EQ(sablier(args + a.string()).code, 0);
  const Result stopped = sablier(args + b.string() + " --stop-after-frame 3");
  ASSERT_EQ(stopped.code, 130) << stopped.output;
  const Result resumed = sablier("run --resume " + b.string() + " --threads 1 --quiet");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  for (const char* f : {"frames/particles_00004.vtp", "frames/particles_00006.vtp",
                        "frames/bodies_00006.vtp", "bodies_series.pvd", "obstacles.csv"})
    EXPECT_EQ(file(a / f), file(b / f)) << f;
  expect_same_stats(a, b);
  fs::remove_all(a);
  fs::remove_all(b);
}

// A rigid body's state is not in the checkpoint: a resumed run takes it
// from bodies.csv, cut back to the checkpoint's steps, and continues bit for
// bit (bodies.csv, frames and stats as the uninterrupted run's).
TEST(Resume, WithABodyContinuesBitForBit) {
  const fs::path a = fresh("body_a"), b = fresh("body_b");
  const std::string args =
      "run " + scene_file("drop2d.toml") + " --set time.frames=6 --threads 1 --quiet --out ";
  ASSERT_EQ(sablier(args + a.string()).code, 0);
  const Result stopped = sablier(args + b.string() + " --stop-after-frame 3");
  ASSERT_EQ(stopped.code, 130) << stopped.output;
  const Result resumed = sablier("run --resume " + b.string() + " --threads 1 --quiet");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  for (const char* f :
       {"frames/particles_00004.vtp", "frames/particles_00006.vtp", "obstacles.csv", "bodies.csv"})
    EXPECT_EQ(file(a / f), file(b / f)) << f;
  expect_same_stats(a, b);
  const auto rows = parse_bodies_until(file(a / "bodies.csv"), 2, 1L << 40);
  EXPECT_EQ(rows.size(), parse_stats_csv(file(a / "stats.csv")).size());
  // Without bodies.csv there is nothing to resume the body from.
  const Result stopped_again = sablier(args + b.string() + " --overwrite --stop-after-frame 3");
  ASSERT_EQ(stopped_again.code, 130) << stopped_again.output;
  fs::remove(b / "bodies.csv");
  const Result refused = sablier("run --resume " + b.string() + " --threads 1 --quiet");
  EXPECT_NE(refused.code, 0);
  EXPECT_TRUE(contains(refused.output, "bodies.csv: missing; cannot resume")) << refused.output;
  fs::remove_all(a);
  fs::remove_all(b);
}

// A turned 3D box body: its orientation (a quaternion) round-trips through
// bodies.csv to the last bit, so the resumed run goes on as the
// uninterrupted one.
TEST(Resume, WithATurnedBox3DContinuesBitForBit) {
  const fs::path a = fresh("box_a"), b = fresh("box_b"), dir = fresh("box_scene");
  const fs::path scene = dir / "crate.toml";
  fs::create_directories(dir);
  {
    std::ofstream out(scene);
    out << "dimension = 3\ngravity = [0.0, 0.0, -9.81]\n[grid]\nsize = [0.4, 0.3, 0.3]\n"
           "resolution = [12, 9, 9]\n[time]\nfps = 30\nframes = 6\n[boundary]\n"
           "zmax = \"free\"\n[[sand]]\nshape = \"box\"\nmin = [0.0, 0.0, 0.0]\n"
           "max = [0.4, 0.3, 0.1]\n[[obstacle]]\nshape = \"box\"\nmin = [0.12, 0.09, 0.13]\n"
           "max = [0.28, 0.21, 0.19]\ndensity = 1000\nangle = 25\naxis = [1, 1, 0]\n"
           "velocity = [0.0, 0.0, -1.0]\n";
  }
  const std::string args = "run " + scene.string() + " --threads 1 --quiet --out ";
  const Result first = sablier(args + a.string());
  ASSERT_EQ(first.code, 0) << first.output;
  const Result stopped = sablier(args + b.string() + " --stop-after-frame 3");
  ASSERT_EQ(stopped.code, 130) << stopped.output;
  const Result resumed = sablier("run --resume " + b.string() + " --threads 1 --quiet");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  for (const char* f : {"frames/particles_00006.vtp", "obstacles.csv", "bodies.csv"})
    EXPECT_EQ(file(a / f), file(b / f)) << f;
  expect_same_stats(a, b);
  const auto rows = parse_bodies_until(file(a / "bodies.csv"), 3, 1L << 40);
  ASSERT_FALSE(rows.empty());
  EXPECT_NE(rows.back().quaternion[0], 1.0);  // it is turned
  for (const fs::path& p : {a, b, dir}) fs::remove_all(p);
}

// A real signal lands anywhere, mostly within a frame: fixed substeps make
// the resumed run depend on how many steps of the frame were done. A run
// killed outright (-9) resumes from the checkpoint of its last frame.
TEST(Resume, AfterASignal) {
  const fs::path a = fresh("sig_a");
  const std::string extra = " --set time.frames=10 --set time.substeps=4";
  ASSERT_EQ(sablier(run_args(a, extra)).code, 0);
  for (const auto& [signal, code] : {std::pair<std::string, int>{"TERM", 130}, {"KILL", 137}}) {
    SCOPED_TRACE(signal);
    const fs::path b = fresh("sig_b");
    const Result stopped =
        shell(std::string(SABLIER_BINARY) + " " + run_args(b, extra) + " & pid=$!; while [ ! -f " +
              (b / "frames/particles_00002.vtp").string() + " ]; do sleep 0.01; done; kill -" +
              signal + " $pid; wait $pid");
    ASSERT_EQ(stopped.code, code) << stopped.output;
    if (code == 130) {
      EXPECT_TRUE(contains(stopped.output, "interrupted at step")) << stopped.output;
    }
    const Result resumed = sablier("run --resume " + b.string() + " --threads 1 --quiet");
    ASSERT_EQ(resumed.code, 0) << resumed.output;
    EXPECT_EQ(file(a / "frames/particles_00010.vtp"), file(b / "frames/particles_00010.vtp"));
    expect_same_stats(a, b);
    fs::remove_all(b);
  }
  fs::remove_all(a);
}

// The folder's files, with their contents.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = file(e.path());
  return files;
}

// Resuming `dir` fails with code 2, one line naming the checkpoint and
// containing `what`, and writes nothing.
void expect_refused(const fs::path& dir, const std::string& what) {
  const auto before = snapshot(dir);
  const Result r = sablier("run --resume " + dir.string() + " --quiet");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "checkpoint.bin")) << r.output;
  EXPECT_TRUE(contains(r.output, what)) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_TRUE(snapshot(dir) == before) << "files changed";
}

TEST(Resume, RefusesADamagedCheckpoint) {
  const fs::path dir = fresh("bad");
  ASSERT_EQ(sablier(run_args(dir, " --stop-after-frame 1")).code, 130);
  const fs::path ckpt = dir / "checkpoint.bin";
  const std::string good = file(ckpt);
  ASSERT_GT(good.size(), 1000u);

  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  write_file_atomic(ckpt.string(), flipped);
  expect_refused(dir, "corrupted");

  write_file_atomic(ckpt.string(), good.substr(0, good.size() / 3));
  expect_refused(dir, "truncated");

  std::string other_version = good;
  other_version[11] = 99;  // the format version follows the 11-byte signature
  write_file_atomic(ckpt.string(), other_version);
  expect_refused(dir, "format version 99");

  write_file_atomic(ckpt.string(), "not a checkpoint");
  expect_refused(dir, "not a sablier checkpoint");

  // The scene beside it is not the one it was written for.
  write_file_atomic(ckpt.string(), good);
  const std::string scene_text = file(dir / "scene.toml");
  write_file_atomic((dir / "scene.toml").string(), scene_text + "# edited\n");
  expect_refused(dir, "another scene");

  write_file_atomic((dir / "scene.toml").string(), scene_text);
  EXPECT_EQ(sablier("run --resume " + dir.string() + " --threads 1 --quiet").code, 0);
  fs::remove_all(dir);
}

TEST(Resume, DropsStatsRowsAfterTheCheckpoint) {
  const fs::path dir = fresh("tail");
  ASSERT_EQ(sablier(run_args(dir, " --stop-after-frame 2")).code, 130);
  const std::string stats = file(dir / "stats.csv");
  const auto rows_before = parse_stats_csv(stats);
  ASSERT_FALSE(rows_before.empty());
  // A row the checkpoint does not cover (as if written after it), then a torn one.
  const std::string last = stats.substr(stats.rfind('\n', stats.size() - 2) + 1);
  const std::string later =
      std::to_string(rows_before.back().step + 1) + last.substr(last.find(','));
  write_file_atomic((dir / "stats.csv").string(), stats + later + "9,0.1");
  ASSERT_EQ(sablier("run --resume " + dir.string() + " --threads 1 --quiet").code, 0);
  const auto rows = parse_stats_csv(file(dir / "stats.csv"));
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].step, static_cast<long>(i + 1));
  fs::remove_all(dir);
}

TEST(Resume, ResumeNeedsARunFolder) {
  const fs::path dir = fresh("none");
  fs::create_directories(dir);
  const Result r = sablier("run --resume " + dir.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.output, "not the folder of a sablier run")) << r.output;
  const Result mixed = sablier("run --resume " + dir.string() + " --set material.mu=0.3");
  EXPECT_NE(mixed.code, 0);
  fs::remove_all(dir);
}

Checkpoint tiny() {
  Checkpoint c;
  c.dimension = 2;
  c.scene_hash = 0x0123456789abcdefull;
  c.steps = 7;
  c.time = 0.1;
  c.frame = 1;
  c.substep = 2;
  c.formats = "vtp,ply";
  c.frame_times = {0.0, 1.0 / 30.0};
  c.particles = 2;
  c.position = {0.1, 0.2, 0.3, 0.4};
  c.velocity = {-1.0, 1.0, 2.0, 1e-300};
  c.affine = {1, 2, 3, 4, 5, 6, 7, 8};
  c.volume = {1e-6, 2e-6};
  c.cohesion = {0.0, 5.0};
  c.inertial = {0.0, std::numeric_limits<double>::infinity()};
  c.id = {42, -1};
  c.material = {0, 3};
  c.stress = {1, 2, 3, 4, 5, 6};
  c.phi = {0.6, 0.5};
  c.shear_rate = {0.0, 3.0};
  c.nodes = 3;
  c.warm_stress = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  c.warm_case = {0, 2, 1};
  return c;
}

TEST(Resume, CheckpointRoundTrip) {
  const Checkpoint c = tiny();
  const std::string bytes = encode_checkpoint(c, "t.bin");
  EXPECT_EQ(bytes.substr(0, 11), "SABLIERCKPT");
  const Checkpoint d = decode_checkpoint(bytes, "t.bin");
  EXPECT_EQ(d.scene_hash, c.scene_hash);
  EXPECT_EQ(d.steps, c.steps);
  EXPECT_EQ(d.time, c.time);
  EXPECT_EQ(d.frame, c.frame);
  EXPECT_EQ(d.substep, c.substep);
  EXPECT_EQ(d.formats, c.formats);
  EXPECT_EQ(d.frame_times, c.frame_times);
  EXPECT_EQ(d.velocity, c.velocity);
  EXPECT_EQ(d.affine, c.affine);
  EXPECT_EQ(d.inertial, c.inertial);
  EXPECT_EQ(d.id, c.id);
  EXPECT_EQ(d.material, c.material);
  EXPECT_EQ(d.warm_stress, c.warm_stress);
  EXPECT_EQ(d.warm_case, c.warm_case);
  // Every truncation is refused, whatever its length.
  for (std::size_t n = 0; n < bytes.size(); ++n)
    EXPECT_THROW(decode_checkpoint(bytes.substr(0, n), "t.bin"), CheckpointError) << n;
  // Arrays that disagree with the counts are not written.
  Checkpoint bad = c;
  bad.phi.pop_back();
  EXPECT_THROW(encode_checkpoint(bad, "t.bin"), CheckpointError);
}

// Format 3 (no per-node cases) is still read: the same bytes without the
// cases, which come back empty (Simulation::restore_clock then knows none).
TEST(Resume, ReadsFormat3WithoutCases) {
  const Checkpoint c = tiny();
  std::string bytes = encode_checkpoint(c, "t.bin");
  bytes.resize(bytes.size() - 8 - c.warm_case.size());  // drop the checksum and the cases
  const std::uint32_t three = 3;
  std::memcpy(&bytes[11], &three, sizeof three);  // little-endian hosts, as the format
  const std::uint64_t sum = fnv1a64(bytes);
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  const Checkpoint d = decode_checkpoint(bytes, "t.bin");
  EXPECT_EQ(d.version, 3u);
  EXPECT_EQ(d.warm_stress, c.warm_stress);
  EXPECT_TRUE(d.warm_case.empty());
  // Versions outside 3-5 are refused, naming both.
  std::string six = encode_checkpoint(c, "t.bin");
  const std::uint32_t v6 = 6;
  std::memcpy(&six[11], &v6, sizeof v6);
  try {
    decode_checkpoint(six, "t.bin");
    ADD_FAILURE() << "format 6 read";
  } catch (const CheckpointError& e) {
    EXPECT_TRUE(contains(e.what(), "format version 6")) << e.what();
    EXPECT_TRUE(contains(e.what(), "reads versions 3 to 5")) << e.what();
  }
}

// Format 4 had the layout of format 5 with an FNV-1a checksum: still read,
// and the checksum checked as FNV-1a (a CRC-32 there is refused).
TEST(Resume, ReadsFormat4WithItsChecksum) {
  const Checkpoint c = tiny();
  std::string bytes = encode_checkpoint(c, "t.bin");
  bytes.resize(bytes.size() - 8);
  const std::uint32_t four = 4;
  std::memcpy(&bytes[11], &four, sizeof four);  // little-endian hosts, as the format
  std::string crc = bytes;
  const std::uint64_t sum = fnv1a64(bytes);
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  const Checkpoint d = decode_checkpoint(bytes, "t.bin");
  EXPECT_EQ(d.version, 4u);
  EXPECT_EQ(d.position, c.position);
  EXPECT_EQ(d.warm_case, c.warm_case);
  const std::uint64_t crc_sum = crc32_z(
      crc32_z(0, nullptr, 0), reinterpret_cast<const unsigned char*>(crc.data()), crc.size());
  crc.append(reinterpret_cast<const char*>(&crc_sum), sizeof crc_sum);
  EXPECT_THROW(decode_checkpoint(crc, "t.bin"), CheckpointError);
}

// With the sand cut into zones (solver.zone_rows small), the next step's
// cuts depend on the cases the last solve ended in (transfer.cpp,
// kZoneCost): the checkpoint carries them, and the resumed run is still the
// uninterrupted one, bit for bit.
TEST(Resume, InZonesContinuesBitForBit) {
  const fs::path a = fresh("zones_a"), b = fresh("zones_b");
  const auto args = [](const fs::path& dir) {
    return "run " + scene_file("collapse2d.toml") + " --out " + dir.string() +
           " --set time.frames=4 --set grid.resolution=[80,20] --set solver.zone_rows=40"
           " --threads 1 --quiet";
  };
  ASSERT_EQ(sablier(args(a)).code, 0);
  ASSERT_EQ(sablier(args(b) + " --stop-after-frame 2").code, 130);
  const Result resumed = sablier("run --resume " + b.string() + " --threads 1 --quiet");
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  for (const char* f : {"frames/particles_00003.vtp", "frames/particles_00004.vtp"})
    EXPECT_EQ(file(a / f), file(b / f)) << f;
  expect_same_stats(a, b);
  fs::remove_all(a);
  fs::remove_all(b);
}

// An interrupt in a frame's last step, which a real signal hits only by
// chance (--interrupt-after-step hits it every time). The frame's files hold
// the particles in the order that step left them and the grid of its
// solve; a run resumed from before the frame would write them after
// sorting the particles and without a solve. Every file the resumed run
// writes is the uninterrupted run's, byte for byte (stats.csv but for its
// wall-clock columns; run.json says when and how it ran). Step 7, one
// before the frame's last, stops within the frame as before.
TEST(Resume, InAFramesLastStepContinuesBitForBit) {
  const fs::path a = fresh("last_a");
  const std::string extra = " --set time.substeps=4 --grid --format vtp,csv";
  ASSERT_EQ(sablier(run_args(a, extra)).code, 0);
  const auto uninterrupted = snapshot(a);
  for (const int step : {8, 7}) {
    SCOPED_TRACE("interrupted after step " + std::to_string(step));
    const fs::path b = fresh("last_b");
    const Result stopped =
        sablier(run_args(b, extra + " --interrupt-after-step " + std::to_string(step)));
    ASSERT_EQ(stopped.code, 130) << stopped.output;
    EXPECT_TRUE(contains(stopped.output, step == 8 ? "frames 0..2 are" : "frames 0..1 are"))
        << stopped.output;
    EXPECT_EQ(fs::exists(b / "frames/particles_00002.vtp"), step == 8);
    const Result resumed = sablier("run --resume " + b.string() + " --threads 1 --quiet");
    ASSERT_EQ(resumed.code, 0) << resumed.output;
    auto files = snapshot(b);
    ASSERT_EQ(files.size(), uninterrupted.size());
    for (const auto& [name, bytes] : uninterrupted) {
      if (name == "run.json" || name == "stats.csv") continue;
      EXPECT_TRUE(files[name] == bytes) << name << " differs";
    }
    expect_same_stats(a, b);
    fs::remove_all(b);
  }
  fs::remove_all(a);
}

}  // namespace
}  // namespace sablier
