#include "io/stats_writer.hpp"

#include <fmt/format.h>

#include <limits>
#include <sstream>
#include <stdexcept>

#include "io/writers.hpp"

namespace sablier {

#define SABLIER_STATS_COLUMNS                                                                \
  "step,time,dt,particles,active_nodes,iterations,residual,kinetic_energy,potential_energy," \
  "max_speed,wall_seconds,hit_cap,transfer_seconds,assembly_seconds,solve_seconds,"          \
  "advection_seconds"
const char* const kStatsHeader = SABLIER_STATS_COLUMNS ",decompaction_work,overfill";

namespace {
// The headers before decompaction_work (2026-12-02) and before overfill
// (2026-12-06): a run written by an older build resumes, its earlier rows
// reading NaN in the new columns.
const char* const kStatsHeader16 = SABLIER_STATS_COLUMNS;
const char* const kStatsHeader17 = SABLIER_STATS_COLUMNS ",decompaction_work";
}  // namespace
#undef SABLIER_STATS_COLUMNS

std::string StatsTable::csv() const {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "{}\n", kStatsHeader);
  for (const StepStats& s : rows_) {
    fmt::format_to(
        std::back_inserter(out), "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", s.step,
        s.time, s.dt, s.particles, s.active_nodes, s.iterations, s.residual, s.kinetic_energy,
        s.potential_energy, s.max_speed, s.wall_seconds, s.hit_cap ? 1 : 0, s.transfer_seconds,
        s.assembly_seconds, s.solve_seconds, s.advection_seconds, s.decompaction_work, s.overfill);
  }
  return fmt::to_string(out);
}

namespace {

// The numbers of one CSV row; false on a malformed cell (then in `bad`).
bool parse_numbers(const std::string& line, std::vector<double>& v, std::string* bad = nullptr) {
  v.clear();
  std::istringstream ls(line);
  std::string cell;
  while (std::getline(ls, cell, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(cell, &used));
      if (used != cell.size()) throw std::invalid_argument(cell);
    } catch (const std::exception&) {
      if (bad) *bad = cell;
      return false;
    }
  }
  return true;
}

// One data row; false (with `error` set) if it is not `columns` numbers
// (18, or 16 or 17 for a file of an older build).
bool parse_stats_row(const std::string& line, StepStats& s, std::string& error,
                     std::size_t columns) {
  std::vector<double> v;
  std::string bad;
  if (!parse_numbers(line, v, &bad)) {
    error = "stats.csv: bad number \"" + bad + "\"";
    return false;
  }
  if (v.size() != columns) {
    error = fmt::format("stats.csv: expected {} columns in \"{}\"", columns, line);
    return false;
  }
  s.step = static_cast<long>(v[0]);
  s.time = v[1];
  s.dt = v[2];
  s.particles = static_cast<long>(v[3]);
  s.active_nodes = static_cast<long>(v[4]);
  s.iterations = static_cast<int>(v[5]);
  s.residual = v[6];
  s.kinetic_energy = v[7];
  s.potential_energy = v[8];
  s.max_speed = v[9];
  s.wall_seconds = v[10];
  s.hit_cap = v[11] != 0.0;
  s.transfer_seconds = v[12];
  s.assembly_seconds = v[13];
  s.solve_seconds = v[14];
  s.advection_seconds = v[15];
  const double nan = std::numeric_limits<double>::quiet_NaN();
  s.decompaction_work = columns > 16 ? v[16] : nan;
  s.overfill = columns > 17 ? v[17] : nan;
  return true;
}

// The number of columns the header names; throws IoError on an unknown header.
std::size_t stats_columns(std::istream& in) {
  std::string line;
  if (std::getline(in, line)) {
    if (line == kStatsHeader) return 18;
    if (line == kStatsHeader17) return 17;
    if (line == kStatsHeader16) return 16;
  }
  throw IoError("stats.csv: bad header");
}

}  // namespace

std::vector<StepStats> parse_stats_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line, error;
  const std::size_t columns = stats_columns(in);
  std::vector<StepStats> rows;
  StepStats s;
  while (std::getline(in, line)) {
    if (!parse_stats_row(line, s, error, columns)) throw IoError(error);
    rows.push_back(s);
  }
  return rows;
}

std::vector<StepStats> parse_stats_csv_until(const std::string& text, long last_step) {
  std::istringstream in(text);
  std::string line, error;
  const std::size_t columns = stats_columns(in);
  std::vector<StepStats> rows;
  StepStats s;
  // A row without its newline is a torn write: dropped like a bad one.
  while (std::getline(in, line) && !in.eof() && parse_stats_row(line, s, error, columns) &&
         s.step <= last_step)
    rows.push_back(s);
  return rows;
}

namespace {
std::string obstacle_header(int dimension) {
  return dimension == 2 ? "step,time,obstacle,fx,fy" : "step,time,obstacle,fx,fy,fz";
}

std::string bodies_header(int dimension) {
  return dimension == 2 ? "step,time,obstacle,x,y,vx,vy,omega,angle"
                        : "step,time,obstacle,x,y,z,vx,vy,vz,wx,wy,wz,qw,qx,qy,qz";
}
}  // namespace

std::string obstacle_forces_csv(const std::vector<ObstacleForceRow>& rows, int dimension) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "{}\n", obstacle_header(dimension));
  for (const ObstacleForceRow& r : rows) {
    fmt::format_to(std::back_inserter(out), "{},{},{}", r.step, r.time, r.obstacle);
    for (int a = 0; a < dimension; ++a) fmt::format_to(std::back_inserter(out), ",{}", r.force[a]);
    fmt::format_to(std::back_inserter(out), "\n");
  }
  return fmt::to_string(out);
}

std::vector<ObstacleForceRow> parse_obstacle_forces_until(const std::string& text, int dimension,
                                                          long last_step) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != obstacle_header(dimension))
    throw IoError("obstacles.csv: bad header");
  std::vector<ObstacleForceRow> rows;
  std::vector<double> v;
  while (std::getline(in, line) && !in.eof()) {
    if (!parse_numbers(line, v) || static_cast<int>(v.size()) != 3 + dimension) break;
    ObstacleForceRow r;
    r.step = static_cast<long>(v[0]);
    if (r.step > last_step) break;
    r.time = v[1];
    r.obstacle = static_cast<int>(v[2]);
    for (int a = 0; a < dimension; ++a) r.force[a] = v[3 + a];
    rows.push_back(r);
  }
  return rows;
}

std::string bodies_csv(const std::vector<BodyRow>& rows, int dimension) {
  fmt::memory_buffer out;
  auto put = [&](double x) { fmt::format_to(std::back_inserter(out), ",{}", x); };
  fmt::format_to(std::back_inserter(out), "{}\n", bodies_header(dimension));
  for (const BodyRow& r : rows) {
    fmt::format_to(std::back_inserter(out), "{},{},{}", r.step, r.time, r.obstacle);
    for (int a = 0; a < dimension; ++a) put(r.centre[a]);
    for (int a = 0; a < dimension; ++a) put(r.velocity[a]);
    if (dimension == 2) {
      put(r.spin[0]);
      put(r.angle);
    } else {
      for (int a = 0; a < 3; ++a) put(r.spin[a]);
      for (int a = 0; a < 4; ++a) put(r.quaternion[a]);
    }
    fmt::format_to(std::back_inserter(out), "\n");
  }
  return fmt::to_string(out);
}

std::vector<BodyRow> parse_bodies_until(const std::string& text, int dimension, long last_step) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != bodies_header(dimension))
    throw IoError("bodies.csv: its header is not " + bodies_header(dimension) +
                  " (written by another build?)");
  const int columns = dimension == 2 ? 9 : 16;
  std::vector<BodyRow> rows;
  std::vector<double> v;
  while (std::getline(in, line) && !in.eof()) {
    if (!parse_numbers(line, v) || static_cast<int>(v.size()) != columns) break;
    BodyRow r;
    r.step = static_cast<long>(v[0]);
    if (r.step > last_step) break;
    r.time = v[1];
    r.obstacle = static_cast<int>(v[2]);
    for (int a = 0; a < dimension; ++a) {
      r.centre[a] = v[3 + a];
      r.velocity[a] = v[3 + dimension + a];
    }
    if (dimension == 2) {
      r.spin[0] = v[7];
      r.angle = v[8];
    } else {
      for (int a = 0; a < 3; ++a) r.spin[a] = v[9 + a];
      for (int a = 0; a < 4; ++a) r.quaternion[a] = v[12 + a];
    }
    rows.push_back(r);
  }
  return rows;
}

}  // namespace sablier
