// `sablier plot`'s picture (io/plot.hpp) from stats.csv text: which panels
// it draws. The command itself is tested in test_render.cpp.
#include <gtest/gtest.h>

#include <algorithm>
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

// In 2D the energies are per metre of depth, and the energy panel's title
// says so: the 2D picture differs from the 3D one in that title's row only
// (above the first panel), which is longer.
TEST(Plot, TwoDEnergiesArePerMetre) {
  StatsSeries s = parse_stats_series(
      "step,time,kinetic_energy,potential_energy,iterations,residual,wall_seconds\n"
      "1,0.1,1,2,10,1e-6,0.01\n2,0.2,0.5,1.5,12,2e-6,0.02\n",
      "s.csv");
  s.dimension = 3;
  const Canvas three = plot_stats(s);
  s.dimension = 2;
  const Canvas two = plot_stats(s);
  int first = -1, last = -1, right = -1;
  for (int y = 0; y < two.height(); ++y)
    for (int x = 0; x < two.width(); ++x)
      if (!(two.at(x, y) == three.at(x, y))) {
        if (first < 0) first = y;
        last = y;
        right = std::max(right, x);
      }
  ASSERT_GE(first, 0) << "the same picture";
  EXPECT_LT(last, 30);                          // the title row, above the first panel's frame
  EXPECT_GT(right, text_width("energy J", 2));  // a longer title
}

}  // namespace
}  // namespace sablier
