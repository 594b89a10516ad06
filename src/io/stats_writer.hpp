// Per-step statistics of a run (stats.csv).
#pragma once

#include <string>
#include <vector>

namespace sablier {

struct StepStats {
  long step = 0;
  double time = 0.0, dt = 0.0;
  long particles = 0, active_nodes = 0;
  int iterations = 0;
  double residual = 0.0, kinetic_energy = 0.0, potential_energy = 0.0, max_speed = 0.0;
  double wall_seconds = 0.0;
  bool hit_cap = false;
  double transfer_seconds = 0.0, assembly_seconds = 0.0, solve_seconds = 0.0,
         advection_seconds = 0.0;
  // J (J/m in 2D): bound on the energy the decompaction of over-full nodes
  // may have added in the step (StepInfo::restoring_work); NaN in the rows
  // of a file written before the column existed.
  double decompaction_work = 0.0;
  // The grain volume beyond phi_max after the step, as a fraction of all of
  // it (StepInfo::overfill); NaN in the rows of a file written before the
  // column existed.
  double overfill = 0.0;
};

class StatsTable {
 public:
  void add(const StepStats& s) { rows_.push_back(s); }
  std::size_t size() const { return rows_.size(); }
  const std::vector<StepStats>& rows() const { return rows_; }
  std::string csv() const;  // header + one row per step, round-trip precision

 private:
  std::vector<StepStats> rows_;
};

// The header of stats.csv.
extern const char* const kStatsHeader;

// Parses stats.csv text (tests, tools). Throws IoError.
std::vector<StepStats> parse_stats_csv(const std::string& text);
// The rows of steps up to `last_step` (a resumed run continues after them),
// stopping at the first malformed or unterminated row (a torn tail). Throws
// IoError on a bad header.
std::vector<StepStats> parse_stats_csv_until(const std::string& text, long last_step);

// Forces the sand exerts on the scene's [[obstacle]] blocks (obstacles.csv):
// one row per step and obstacle, `step,time,obstacle,fx,fy[,fz]`, in N (N/m
// in 2D), averaged over the step.
struct ObstacleForceRow {
  long step = 0;
  double time = 0.0;
  int obstacle = 0;
  double force[3] = {0, 0, 0};
};

std::string obstacle_forces_csv(const std::vector<ObstacleForceRow>& rows, int dimension);
// The rows of steps up to `last_step`, stopping at the first malformed or
// unterminated row (a torn tail). Throws IoError on a bad header.
std::vector<ObstacleForceRow> parse_obstacle_forces_until(const std::string& text, int dimension,
                                                          long last_step);

// The state of the scene's rigid bodies (bodies.csv: [[obstacle]] blocks
// with a density) at the end of each step: one row per step and body,
// 2D `step,time,obstacle,x,y,vx,vy,omega,angle`, 3D
// `step,time,obstacle,x,y,z,vx,vy,vz,wx,wy,wz`: centre (m), velocity (m/s),
// angular velocity (rad/s) and, in 2D, the angle turned through since the
// start (rad, counter-clockwise). Numbers are written to round trip, so a
// resumed run restarts from the exact state.
struct BodyRow {
  long step = 0;
  double time = 0.0;
  int obstacle = 0;
  double centre[3] = {0, 0, 0};
  double velocity[3] = {0, 0, 0};
  double spin[3] = {0, 0, 0};           // 2D: spin[0] = omega
  double angle = 0.0;                   // 2D only: rad, counter-clockwise
  double quaternion[4] = {1, 0, 0, 0};  // 3D only: orientation (w, x, y, z)
};

std::string bodies_csv(const std::vector<BodyRow>& rows, int dimension);
// As parse_obstacle_forces_until.
std::vector<BodyRow> parse_bodies_until(const std::string& text, int dimension, long last_step);

}  // namespace sablier
