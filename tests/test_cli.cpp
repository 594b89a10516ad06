// The command-line interface of the engine: `sablier run` writes the outputs
// the README lists, rejects bad scenes with one line and no output, refuses
// to mix runs in one folder, and gives bit-identical frames whatever the
// thread count.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "io/stats_writer.hpp"
#include "io/writers.hpp"
#include "test_support.hpp"

namespace sablier {
namespace {

namespace fs = std::filesystem;

using test::Result;
using test::sablier;
using test::scene_file;

const char* const kSmall = " --set time.frames=3 --set grid.resolution=[40,10] --quiet";

TEST(Cli, RunWritesTheOutputs) {
  const fs::path dir = test::fresh_dir("cli_run");
  const Result r = sablier("run " + scene_file("collapse2d.toml") + " --out " + dir.string() +
                           " --format vtp,csv" + kSmall);
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f : {"stats.csv", "series.pvd", "scene.toml", "frames/particles_00000.vtp",
                        "frames/particles_00003.vtp", "frames/particles_00003.csv"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "frames/particles_00004.vtp"));
  const auto rows = parse_stats_csv(read_file((dir / "stats.csv").string()));
  ASSERT_GE(rows.size(), 3u);
  EXPECT_NEAR(rows.back().time, 0.1, 1e-12);  // 3 frames at 30 fps
  for (const StepStats& s : rows) {
    EXPECT_GT(s.particles, 0);
    EXPECT_GT(s.iterations, 0);
    // Every step's residual is below the tolerance, or the step says it hit the cap.
    EXPECT_TRUE(s.residual <= 1e-5 || s.hit_cap) << "step " << s.step;
    EXPECT_GE(s.decompaction_work, 0.0) << "step " << s.step;  // a bound on an energy; NaN fails
    EXPECT_TRUE(s.overfill >= 0.0 && s.overfill < 1.0) << "step " << s.step;  // a fraction
  }
  const ParticleFrame f0 =
      parse_vtp(read_file((dir / "frames/particles_00000.vtp").string()), "f0");
  EXPECT_EQ(f0.time, 0.0);
  EXPECT_EQ(f0.dimension, 2);
  EXPECT_EQ(static_cast<long>(f0.count), rows.front().particles);
  // The resolved scene runs again and carries the overrides.
  const std::string resolved = read_file((dir / "scene.toml").string());
  EXPECT_NE(resolved.find("resolution = [40, 10]"), std::string::npos) << resolved;
}

// The run's last lines say how many steps stopped at the solver's cap, and
// nothing when none did.
TEST(Cli, RunEndsByCountingTheCappedSteps) {
  const fs::path capped = test::fresh_dir("cli_capped"),
                 converged = test::fresh_dir("cli_converged");
  const std::string frames = " --set time.frames=3";
  const Result r = sablier("run " + scene_file("collapse2d.toml") + " --out " + capped.string() +
                           frames + " --set solver.max_iterations=2");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto rows = parse_stats_csv(read_file((capped / "stats.csv").string()));
  long long hit = 0;
  for (const StepStats& s : rows) hit += s.hit_cap ? 1 : 0;
  ASSERT_GT(hit, 0);
  EXPECT_NE(
      r.output.find("note: " + std::to_string(hit) + " steps stopped at solver.max_iterations"),
      std::string::npos)
      << r.output;
  const Result ok =
      sablier("run " + scene_file("bed2d.toml") + " --out " + converged.string() + frames);
  ASSERT_EQ(ok.code, 0) << ok.output;
  EXPECT_EQ(ok.output.find("note:"), std::string::npos) << ok.output;
}

// The run ends with a note when grains stayed crowded beyond phi_max by more
// than 5% of their volume in some step, naming the largest overfill of
// stats.csv, and without one otherwise. METHOD.md's pure clamp with steps
// of up to 4 cells of travel crowds the 2D collapse to 16% (measured); the
// default moves keep it to 1.4% at the default step.
TEST(Cli, RunNotesOverFullSand) {
  const fs::path crowded = test::fresh_dir("cli_crowded"), spread = test::fresh_dir("cli_spread");
  const Result r =
      sablier("run " + scene_file("collapse2d.toml") + " --out " + crowded.string() +
              " --set time.frames=30 --set time.cfl=4" + " --set solver.decompaction=\"clamp\"");
  ASSERT_EQ(r.code, 0) << r.output;
  const StepStats* most = nullptr;
  const auto rows = parse_stats_csv(read_file((crowded / "stats.csv").string()));
  for (const StepStats& s : rows)
    if (!most || s.overfill > most->overfill) most = &s;
  ASSERT_GT(most->overfill, 0.05);
  EXPECT_NE(r.output.find(fmt::format("note: grains crowded beyond phi_max by up to {:.1f}% of "
                                      "their volume (step {},",
                                      100.0 * most->overfill, most->step)),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("solver.decompaction = \"project\" holds phi_max"), std::string::npos)
      << r.output;
  const Result ok = sablier("run " + scene_file("collapse2d.toml") + " --out " + spread.string() +
                            " --set time.frames=30");
  ASSERT_EQ(ok.code, 0) << ok.output;
  for (const StepStats& s : parse_stats_csv(read_file((spread / "stats.csv").string())))
    EXPECT_LE(s.overfill, 0.05) << "step " << s.step;
  EXPECT_EQ(ok.output.find("crowded beyond"), std::string::npos) << ok.output;
}

TEST(Cli, BadSceneWritesNothing) {
  const fs::path dir = test::fresh_dir("cli_bad");
  const fs::path bad = test::temp_path("cli_bad_scene", ".toml");
  std::ofstream(bad) << read_file(scene_file("collapse2d.toml"))
                     << "\n[solver]\ntolerence = 1e-3\n";
  Result r = sablier("run " + bad.string() + " --out " + dir.string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("solver.tolerence"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did you mean \"tolerance\""), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir));
  r = sablier("run " + scene_file("collapse2d.toml") + " --out " + dir.string() +
              " --set material.mu=nan");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("material.mu"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));
}

// A grid no machine holds (10^10 cells at 450 bytes each) is refused as a bad
// scene, by check and by run, before anything is allocated or written; so is
// a block asking for more grains than the machine holds (10^12 in 3D).
TEST(Cli, SceneTooBigForTheMachineIsRefused) {
  const fs::path dir = test::fresh_dir("cli_huge");
  const std::string huge = " --set grid.resolution=[100000,25000]";
  for (const char* cmd : {"check ", "run "}) {
    const Result r = sablier(cmd + scene_file("collapse2d.toml") +
                             (cmd[0] == 'r' ? " --out " + dir.string() : std::string()) + huge);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--set grid.resolution: 2500000000 cells need about"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("GB available; allowed: fewer cells or fewer particles per cell"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(dir));
  }
  // With a budget of 0.3 GB (SABLIER_MEMORY_LIMIT), 400 x 100 cells (18 MB)
  // fit, but the column's 100 x 80 cells at 8 x 8 grains each (512,000
  // grains at 1 kB) do not.
  const Result r =
      test::shell(std::string("SABLIER_MEMORY_LIMIT=3e8 ") + SABLIER_BINARY + " check " +
                  scene_file("collapse2d.toml") +
                  " --set grid.resolution=[400,100] --set sand.0.particles_per_cell=8");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(
      r.output.find(
          "sand: 40000 cells and about 5.12e+05 grains need about 0.5 GB, more than the 0.3 GB "
          "available"),
      std::string::npos)
      << r.output;
}

// Command-line mistakes get one line and exit code 2, as bad scenes do; one
// --set takes one KEY=VALUE, so a scene file after it is still the scene.
TEST(Cli, CommandLineMistakes) {
  Result r = sablier("frobnicate");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("unknown command \"frobnicate\"; allowed: run, check, render, plot, "
                          "info"),
            std::string::npos)
      << r.output;
  for (const char* n : {"-1", "1.5", "abc", "5000"}) {
    r = sablier(std::string("run ") + scene_file("bed2d.toml") + " --out x --threads " + n);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(std::string("--threads: \"") + n +
                            "\" is not a whole number from 0 (all cores) to 1024"),
              std::string::npos)
        << r.output;
  }
  r = sablier("run " + scene_file("bed2d.toml") + " --bogus");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--bogus"), std::string::npos) << r.output;
  // --set before the scene; --format csv writes the VTK frames too.
  const fs::path dir = test::fresh_dir("cli_set_first");
  r = sablier("run --set time.frames=1 " + scene_file("bed2d.toml") + " --out " + dir.string() +
              " --format csv --quiet");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f : {"frames/particles_00001.csv", "frames/particles_00001.vtp", "series.pvd"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "frames/particles_00002.vtp"));
}

TEST(Cli, RefusesToMixRuns) {
  const fs::path dir = test::fresh_dir("cli_mix");
  const std::string kSmall = " --set time.frames=2 --quiet";
  ASSERT_EQ(sablier("run " + scene_file("bed2d.toml") + " --out " + dir.string() + kSmall).code, 0);
  const Result again =
      sablier("run " + scene_file("bed2d.toml") + " --out " + dir.string() + kSmall);
  EXPECT_NE(again.code, 0);
  EXPECT_NE(again.output.find("--overwrite"), std::string::npos) << again.output;
  // --overwrite replaces the run's files and keeps the user's own, in the
  // folder and in frames/.
  std::ofstream(dir / "notes.txt") << "mine";
  std::ofstream(dir / "frames/mine.txt") << "mine";
  std::ofstream(dir / "frames/particles_00009.vtp") << "an earlier run's frame";
  EXPECT_EQ(sablier("run " + scene_file("bed2d.toml") + " --out " + dir.string() + kSmall +
                    " --overwrite")
                .code,
            0);
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir / "frames/mine.txt"));
  EXPECT_FALSE(fs::exists(dir / "frames/particles_00009.vtp"));
  EXPECT_TRUE(fs::exists(dir / "frames/particles_00002.vtp"));
}

// (solver.zone_rows = 100: the sand is swept in several zones, so the solve
// too runs on both threads, which a scene this small would not otherwise use.)
TEST(Cli, SameResultWhateverTheThreadCount) {
  const fs::path a = test::fresh_dir("cli_t1"), b = test::fresh_dir("cli_t2");
  const std::string every = " --set solver.zone_rows=100";
  ASSERT_EQ(sablier("run " + scene_file("collapse2d.toml") + " --out " + a.string() +
                    " --threads 1" + kSmall + every)
                .code,
            0);
  ASSERT_EQ(sablier("run " + scene_file("collapse2d.toml") + " --out " + b.string() +
                    " --threads 2" + kSmall + every)
                .code,
            0);
  for (const char* f : {"frames/particles_00001.vtp", "frames/particles_00003.vtp"})
    EXPECT_EQ(read_file((a / f).string()), read_file((b / f).string())) << f;
}

TEST(Cli, CheckAndInfo) {
  Result r = sablier("check " + scene_file("collapse3d.toml"));
  EXPECT_EQ(r.code, 0) << r.output;
  // 20 x 8 x 16 cells of sand, 3 x 3 x 3 grains each.
  EXPECT_NE(r.output.find("particles  69120"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("solver     tolerance 1e-05, at most 2000 sweeps, Anderson depth 5; "
                          "grains of over-full nodes moved apart 4 times, then projected in at "
                          "most 4 rounds per step"),
            std::string::npos)
      << r.output;
  // The cohesive tower of castle3d: 3000 Pa over rho g (1 / sqrt(3) - mu / 3),
  // 2500 x 9.81 x 0.41068 Pa/m, holds a free face 0.298 m high.
  r = sablier("check " + scene_file("castle3d.toml"));
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("cohesion   sand[0]: 3000 Pa holds a free vertical face up to 0.298 m "
                          "high (limit analysis's lower bound); it decays where the sand yields"),
            std::string::npos)
      << r.output;
  r = sablier("info");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.output.find("openmp"), std::string::npos);
  EXPECT_NE(r.output.find("pictures   png (libpng 1."), std::string::npos) << r.output;
  // Without a PATH neither animation tool can be found, and info says how
  // to get them.
  r = test::shell(std::string("PATH=/nonexistent ") + SABLIER_BINARY + " info");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("gif unavailable (apt-get install imagemagick), mp4 unavailable "
                          "(apt-get install ffmpeg)"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace sablier
