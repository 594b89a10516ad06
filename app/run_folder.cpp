// A run's output folder (run_folder.hpp).
#include "run_folder.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

namespace sablier {
namespace {

namespace fs = std::filesystem;

// Files a run writes at the top of its folder: their presence means the
// folder holds a run's outputs.
const char* const kRunFiles[] = {"stats.csv",       "obstacles.csv",     "bodies.csv", "series.pvd",
                                 "grid_series.pvd", "bodies_series.pvd", "scene.toml", "run.json",
                                 "checkpoint.bin",  "obstacles.obj"};

}  // namespace

bool holds_run_outputs(const fs::path& dir) {
  for (const char* f : kRunFiles)
    if (fs::exists(dir / f)) return true;
  return fs::exists(dir / "frames");
}

// A file of frames/ that a run writes: particles_, grid_ or bodies_ with a
// five-digit frame number and the run's extensions, or a temporary that an
// interrupted write left (".NAME.tmp.PID", io/atomic_file.cpp).
bool run_frame_file(const std::string& name) {
  std::string n = name;
  if (n.size() > 1 && n[0] == '.') {
    const std::size_t tmp = n.find(".tmp.");
    if (tmp == std::string::npos) return false;
    n = n.substr(1, tmp - 1);
  }
  for (const char* prefix : {"particles_", "grid_", "bodies_"}) {
    const std::size_t k = std::strlen(prefix);
    if (n.compare(0, k, prefix) != 0 || n.size() < k + 6 || n[k + 5] != '.') continue;
    if (!std::all_of(n.begin() + k, n.begin() + k + 5, [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    const std::string ext = n.substr(k + 6);
    return ext == "vtp" || ext == "csv" || ext == "ply" || ext == "vti";
  }
  return false;
}

// --overwrite: the earlier run's files go; anything else the user put in the
// folder or in frames/ stays (frames/ goes only when it is left empty).
void remove_run_outputs(const fs::path& dir) {
  for (const char* f : kRunFiles) fs::remove(dir / f);
  const fs::path frames = dir / "frames";
  if (!fs::is_directory(frames)) return;
  std::vector<fs::path> doomed;
  for (const fs::directory_entry& e : fs::directory_iterator(frames))
    if (e.is_regular_file() && run_frame_file(e.path().filename().string()))
      doomed.push_back(e.path());
  for (const fs::path& f : doomed) fs::remove(f);
  if (fs::is_empty(frames)) fs::remove(frames);
}

}  // namespace sablier
