// `sablier plot`'s picture (io/plot.hpp) from stats.csv text: which panels
// it draws. The command itself is tested in test_render.cpp.
#include <gtest/gtest.h>

#include <string>

#include "io/image.hpp"
#include "io/plot.hpp"

namespace sablier {
namespace {

// `sablier plot` adds a panel for the grains' volume beyond phi_max when
// stats.csv has the column (five panels), and keeps four for a file of an
// older build. Counted on the picture: the panels' frames are the only dark
// vertical runs taller than a line of text (30 pixels) down the left margin.
TEST(Plot, ShowsTheOverfillWhenTheColumnIsThere) {
  const std::string head = "step,time,kinetic_energy,potential_energy,iterations,residual,";
  const std::string with = head + "wall_seconds,overfill\n1,0.1,1,2,10,1e-6,0.01,0.02\n" +
                           "2,0.2,0.5,1.5,12,2e-6,0.02,0.03\n";
  const std::string without =
      head + "wall_seconds\n1,0.1,1,2,10,1e-6,0.01\n2,0.2,0.5,1.5,12,2e-6,0.02\n";
  const StatsSeries a = parse_stats_series(with, "a.csv"), b = parse_stats_series(without, "b.csv");
  ASSERT_EQ(a.overfill.size(), 2u);
  EXPECT_EQ(a.overfill[1], 0.03);
  EXPECT_TRUE(b.overfill.empty());
  const auto frames = [](const Canvas& c) {
    const int x = (8 * kGlyphAdvance + 6) * 2;  // the left margin at 2 pixels per font pixel
    int frames = 0, run = 0;
    for (int y = 0; y <= c.height(); ++y) {
      if (y < c.height() && c.at(x, y) == Rgb{40, 40, 40}) {
        ++run;
        continue;
      }
      frames += run >= 30;
      run = 0;
    }
    return frames;
  };
  EXPECT_EQ(frames(plot_stats(a)), 5);
  EXPECT_EQ(frames(plot_stats(b)), 4);
}

}  // namespace
}  // namespace sablier
