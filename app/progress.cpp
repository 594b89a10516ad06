#include "progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace sablier {

std::string format_duration(double s) {
  if (!(s >= 0.0) || s > 1e8) return "?";
  const long long t = static_cast<long long>(s + 0.5);
  if (t < 60) return fmt::format("{}s", t);
  if (t < 3600) return fmt::format("{}m{:02d}s", t / 60, t % 60);
  return fmt::format("{}h{:02d}m", t / 3600, t / 60 % 60);
}

Progress::Progress(bool quiet, int frames, double end_time, int frame, double time, long long steps)
    : quiet_(quiet),
      tty_(::isatty(::fileno(stderr)) != 0),
      frames_(frames),
      frame_(frame),
      end_time_(end_time),
      start_time_(time),
      start_steps_(steps),
      start_(Clock::now()),
      last_draw_(start_) {}

double Progress::wall() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

// From the simulated time covered so far: steps get shorter as the sand
// speeds up, so counting steps or frames would be less steady.
std::string Progress::eta(double time) const {
  const double done = time - start_time_;
  if (done <= 0.0) return "?";
  return format_duration(wall() / done * (end_time_ - time));
}

void Progress::step(double time, long long steps, int iterations, bool hit_cap) {
  last_iterations_ = iterations;
  iterations_ += iterations;
  ++frame_steps_;
  capped_ += hit_cap ? 1 : 0;
  capped_total_ += hit_cap ? 1 : 0;
  // At most ten redraws a second: a terminal is slow, steps can be fast.
  if (!quiet_ && tty_ && Clock::now() - last_draw_ > std::chrono::milliseconds(100))
    draw(time, steps);
}

void Progress::draw(double time, long long steps) {
  const double w = wall();
  const double rate = w > 0.0 ? (steps - start_steps_) / w : 0.0;
  // "\033[K" clears what a longer previous line left on the right.
  // frame_ is the last frame written: the line reads N/N when the run is done.
  std::fprintf(stderr, "\r\033[Kframe %d/%d  t=%.4f s  %.1f steps/s  iterations %d  ETA %s", frame_,
               frames_, time, rate, last_iterations_, eta(time).c_str());
  std::fflush(stderr);
  drawn_ = true;
  last_draw_ = Clock::now();
}

void Progress::frame(int f, double time, long long steps) {
  frame_ = f;
  if (!quiet_ && tty_) {
    draw(time, steps);
  } else if (!quiet_) {
    const double w = wall();
    std::fprintf(stderr,
                 "frame %d/%d  t=%.6g s  steps=%lld  mean_iterations=%.1f%s  wall=%.2f s (+%.2f)\n",
                 f, frames_, time, steps, frame_steps_ ? double(iterations_) / frame_steps_ : 0.0,
                 capped_ ? fmt::format("  ({} at max_iterations)", capped_).c_str() : "", w,
                 w - last_frame_wall_);
    last_frame_wall_ = w;
  }
  iterations_ = frame_steps_ = 0;
  capped_ = 0;
}

void Progress::finish() {
  if (drawn_) std::fputc('\n', stderr);
  drawn_ = false;
}

}  // namespace sablier
