// Line plots of stats.csv: axes, ticks, legends and polylines on a Canvas.
#include "io/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "io/writers.hpp"

namespace sablier {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr Rgb kPaper{255, 255, 255}, kAxis{40, 40, 40}, kGrid{225, 225, 225};
// matplotlib's first two category colours: distinct for most colour vision.
constexpr Rgb kBlue{31, 119, 180}, kOrange{255, 127, 14};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  return cells;
}

struct Series {
  const std::vector<double>* y;
  Rgb color;
  std::string name;  // legend; empty for none
};

struct Panel {
  std::string title;
  std::vector<Series> series;
  bool log_scale = false;
};

struct Rect {
  int x0, y0, x1, y1;
};

// An axis maps data values (log10 of them on a log axis) to pixels.
struct Axis {
  double lo, hi;
  int p0, p1;  // pixels of lo and hi
  double map(double v) const { return p0 + (v - lo) / (hi - lo) * (p1 - p0); }
};

// Data range of the panel's series, finite (and positive on a log axis).
void data_range(const Panel& panel, double* lo, double* hi) {
  *lo = kInf, *hi = -kInf;
  for (const Series& s : panel.series)
    for (double v : *s.y) {
      if (!std::isfinite(v) || (panel.log_scale && v <= 0.0)) continue;
      const double x = panel.log_scale ? std::log10(v) : v;
      *lo = std::min(*lo, x), *hi = std::max(*hi, x);
    }
  if (*lo > *hi) *lo = 0.0, *hi = 1.0;  // nothing to show: an empty, labelled axis
}

std::string tick_label(double v, bool log_scale) {
  if (!log_scale) return format_number(v);
  const long e = std::lround(v);
  return e == 0 ? "1" : "1e" + std::to_string(e);
}

std::vector<double> log_ticks(double lo, double hi) {
  // A little headroom: data just under a power of ten (a residual at its
  // tolerance) should not run along the frame.
  double a = std::floor(lo - 0.05), b = std::ceil(hi + 0.05);
  if (b <= a) b = a + 1;
  const double step = std::max(1.0, std::ceil((b - a) / 6));  // at most ~6 decades labelled
  std::vector<double> ticks;
  for (double e = a; e < b + step; e += step) ticks.push_back(e);
  return ticks;
}

void draw_y_axis(Canvas& c, const Rect& r, const std::vector<double>& ticks, const Axis& ay,
                 bool log_scale, int s) {
  for (double t : ticks) {
    const int y = static_cast<int>(std::lround(ay.map(t)));
    c.fill_rect(r.x0 + 1, y, r.x1, y + 1, kGrid);
    c.fill_rect(r.x0 - 3 * s, y, r.x0, y + 1, kAxis);
    const std::string label = tick_label(t, log_scale);
    c.text(r.x0 - 5 * s - text_width(label, s), y - kGlyphHeight * s / 2, label, kAxis, s);
  }
}

void draw_x_axis(Canvas& c, const Rect& r, const std::vector<double>& ticks, const Axis& ax,
                 int s) {
  for (double t : ticks) {
    const int x = static_cast<int>(std::lround(ax.map(t)));
    c.fill_rect(x, r.y0 + 1, x + 1, r.y1, kGrid);
    c.fill_rect(x, r.y1, x + 1, r.y1 + 3 * s, kAxis);
    const std::string label = tick_label(t, false);
    c.text(x - text_width(label, s) / 2, r.y1 + 5 * s, label, kAxis, s);
  }
}

// Polyline through the finite points; a gap where a value is missing (or
// not positive on a log axis).
void draw_series(Canvas& c, const std::vector<double>& x, const Series& series, const Axis& ax,
                 const Axis& ay, bool log_scale, int s) {
  const std::vector<double>& y = *series.y;
  bool have_last = false;
  double lx = 0, ly = 0;
  for (std::size_t k = 0; k < x.size() && k < y.size(); ++k) {
    const bool ok = std::isfinite(y[k]) && (!log_scale || y[k] > 0.0);
    if (!ok) {
      have_last = false;
      continue;
    }
    const double px = ax.map(x[k]), py = ay.map(log_scale ? std::log10(y[k]) : y[k]);
    if (have_last) c.line(lx, ly, px, py, series.color, s);
    lx = px, ly = py, have_last = true;
  }
  if (x.size() == 1 && have_last) c.disc(lx, ly, 2.0 * s, series.color);
}

void draw_legend(Canvas& c, const Rect& r, const Panel& panel, int s) {
  int x = r.x1;
  for (auto it = panel.series.rbegin(); it != panel.series.rend(); ++it) {
    if (it->name.empty()) continue;
    x -= text_width(it->name, s);
    const int y = r.y0 - kGlyphHeight * s - 3 * s;
    c.text(x, y, it->name, kAxis, s);
    c.fill_rect(x - 14 * s, y + 3 * s, x - 3 * s, y + 4 * s + s, it->color);
    x -= 24 * s;
  }
}

void draw_panel(Canvas& c, const Rect& r, const std::vector<double>& time, const Axis& ax,
                const std::vector<double>& xticks, const Panel& panel, int s) {
  double lo, hi;
  data_range(panel, &lo, &hi);
  const std::vector<double> ticks = panel.log_scale ? log_ticks(lo, hi) : nice_ticks(lo, hi, 4);
  const Axis ay{ticks.front(), ticks.back(), r.y1, r.y0};
  draw_y_axis(c, r, ticks, ay, panel.log_scale, s);
  draw_x_axis(c, r, xticks, ax, s);
  for (const Series& series : panel.series)
    draw_series(c, time, series, ax, ay, panel.log_scale, s);
  c.rect(r.x0, r.y0, r.x1, r.y1, kAxis);
  c.text(r.x0, r.y0 - kGlyphHeight * s - 3 * s, panel.title, kAxis, s);
  draw_legend(c, r, panel, s);
}

double column_value(const std::string& cell, const std::string& source, int line) {
  char* end = nullptr;
  const double v = std::strtod(cell.c_str(), &end);
  if (cell.empty() || *end != '\0')
    throw IoError(source + ":" + std::to_string(line) + ": bad number \"" + cell + "\"");
  return v;
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) {  // one value: a unit-wide axis around it
    const double w = lo == 0.0 ? 1.0 : 0.5 * std::abs(lo);
    lo -= w, hi += w;
  }
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * mag;
  for (double m : {1.0, 2.0, 5.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  // Integer multiples of the step, so that zero is exactly zero.
  std::vector<double> ticks;
  long i = std::lround(std::floor(lo / step + 1e-9));
  do {
    ticks.push_back(static_cast<double>(i++) * step);
  } while (ticks.back() < hi - 1e-9 * step);
  return ticks;
}

StatsSeries parse_stats_series(const std::string& csv, const std::string& source) {
  std::istringstream in(csv);
  std::string line;
  if (!std::getline(in, line)) throw IoError(source + ": empty file");
  const std::vector<std::string> header = split(line);
  StatsSeries out;
  const std::pair<const char*, std::vector<double>*> wanted[] = {
      {"time", &out.time},
      {"kinetic_energy", &out.kinetic_energy},
      {"potential_energy", &out.potential_energy},
      {"iterations", &out.iterations},
      {"residual", &out.residual},
      {"wall_seconds", &out.wall_seconds}};
  std::vector<std::size_t> index;
  for (const auto& [name, column] : wanted) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw IoError(source + ": no column \"" + name + "\" in the header");
    index.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  // Optional: files of older builds lack it.
  const auto over = std::find(header.begin(), header.end(), "overfill");
  const std::size_t over_index = static_cast<std::size_t>(over - header.begin());
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = split(line);
    const auto value = [&](std::size_t i) {
      if (i >= cells.size())
        throw IoError(source + ":" + std::to_string(number) + ": too few columns");
      return column_value(cells[i], source, number);
    };
    for (std::size_t k = 0; k < index.size(); ++k) wanted[k].second->push_back(value(index[k]));
    if (over != header.end()) out.overfill.push_back(value(over_index));
  }
  return out;
}

Canvas plot_stats(const StatsSeries& st, int width, int height) {
  Canvas c(width, height, kPaper);
  const int s = width >= 600 ? 2 : 1;
  std::vector<double> total(st.kinetic_energy.size());
  for (std::size_t k = 0; k < total.size() && k < st.potential_energy.size(); ++k)
    total[k] = st.kinetic_energy[k] + st.potential_energy[k];
  std::vector<double> percent(st.overfill.size());
  for (std::size_t k = 0; k < percent.size(); ++k) percent[k] = 100.0 * st.overfill[k];
  std::vector<Panel> panels = {
      {st.dimension == 2 ? "energy J/m" : "energy J",
       {{&total, kBlue, "kinetic+potential"}, {&st.kinetic_energy, kOrange, "kinetic"}}},
      {"solver iterations per step", {{&st.iterations, kBlue, ""}}},
      {"residual", {{&st.residual, kBlue, ""}}, true},
  };
  if (!st.overfill.empty())
    panels.push_back({"grain volume beyond phi_max %", {{&percent, kBlue, ""}}});
  panels.push_back({"wall seconds per step", {{&st.wall_seconds, kBlue, ""}}});
  const int count = static_cast<int>(panels.size());
  // Room for 8-character tick labels on the left, a title row above and
  // tick labels below each panel, and the time axis caption at the bottom.
  // The right margin leaves room for half of the last time label.
  const int left = (8 * kGlyphAdvance + 6) * s, right = 16 * s;
  const int title = kGlyphHeight * s + 8 * s, below = kGlyphHeight * s + 8 * s;
  const int caption = kGlyphHeight * s + 6 * s;
  const int panel_h = (height - caption) / count;
  double tlo = 0.0, thi = 0.0;
  for (double t : st.time) tlo = std::min(tlo, t), thi = std::max(thi, t);
  const std::vector<double> xticks = nice_ticks(tlo, thi, 6);
  const Axis ax{xticks.front(), xticks.back(), left, width - right};
  for (int k = 0; k < count; ++k) {
    const Rect r{left, k * panel_h + title, width - right, (k + 1) * panel_h - below};
    if (r.y1 - r.y0 < 10)
      throw IoError("plot: the picture is too small for " + std::to_string(count) + " panels");
    draw_panel(c, r, st.time, ax, xticks, panels[k], s);
  }
  const std::string xlabel = "time s";
  c.text((left + width - right - text_width(xlabel, s)) / 2, height - caption + s, xlabel, kAxis,
         s);
  return c;
}

}  // namespace sablier
