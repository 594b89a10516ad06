// A run's progress on stderr. On a terminal: one line rewritten in place
// (carriage return) with the frame, simulated time, steps per second, the
// last solve's iterations and an ETA. Otherwise (a log file, a pipe): one
// plain line per frame, which stays readable in a log. Nothing when quiet.
#pragma once

#include <chrono>
#include <string>

namespace sablier {

// "42s", "3m07s", "2h05m".
std::string format_duration(double seconds);

class Progress {
 public:
  // A run of `frames` frames ending at simulated time `end_time`, starting
  // (or resuming) after frame `frame` at `time` with `steps` steps done.
  Progress(bool quiet, int frames, double end_time, int frame, double time, long long steps);

  void step(double time, long long steps, int iterations, bool hit_cap);
  void frame(int f, double time, long long steps);
  // Ends the terminal line, so that a message can follow on its own line.
  void finish();
  // Steps of this run (since it started or resumed) whose solve stopped at
  // max_iterations above the tolerance.
  long long capped_steps() const { return capped_total_; }

 private:
  using Clock = std::chrono::steady_clock;
  double wall() const;
  std::string eta(double time) const;
  void draw(double time, long long steps);

  bool quiet_, tty_;
  int frames_, frame_;
  double end_time_, start_time_;
  long long start_steps_;
  Clock::time_point start_, last_draw_;
  bool drawn_ = false;
  int last_iterations_ = 0;
  long long iterations_ = 0, frame_steps_ = 0;  // since the last frame
  int capped_ = 0;                              // since the last frame
  long long capped_total_ = 0;                  // since the run started or resumed
  double last_frame_wall_ = 0.0;
};

}  // namespace sablier
