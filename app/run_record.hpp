// run.json: what ran, where, with what, and how it went, so that a folder of
// outputs documents itself (and a run can be reproduced or compared).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sablier {

struct RunRecord {
  std::string status = "running";  // running | finished | interrupted
  std::string scene_text;          // the resolved scene (scene.toml)
  std::uint64_t scene_hash = 0;    // fnv1a64(scene_text)
  std::vector<std::string> formats;
  bool compress = false, grid = false;  // --compress, --grid
  int threads = 0;
  // ISO 8601 UTC, of this invocation (a resumed run's is the resume's);
  // ended empty while running.
  std::string started, ended;
  long long resumed_from_step = -1;  // -1: not resumed
  long long steps = 0;
  int frames_written = 0;  // frame 0 included
  int frames = 0;          // the scene's time.frames
  double time = 0.0;       // simulated, s
  // Wall-clock totals over all steps (stats.csv columns summed), s.
  double transfer = 0.0, assembly = 0.0, solve = 0.0, advection = 0.0;
};

std::string format_run_json(const RunRecord& r);

// The current time as "2024-05-01T12:34:56Z".
std::string utc_now();

}  // namespace sablier
