// A run's output folder: whether it holds a run's outputs, and removing
// them (`run --overwrite`) without touching the user's own files.
#pragma once

#include <filesystem>
#include <string>

namespace sablier {

// Whether `dir` holds a run's files (stats.csv, scene.toml, frames/, ...).
bool holds_run_outputs(const std::filesystem::path& dir);
// Whether `name` is a file a run writes in frames/ (or an interrupted
// write's temporary of one).
bool run_frame_file(const std::string& name);
// Removes the run's files from `dir`, and frames/ when that leaves it empty.
void remove_run_outputs(const std::filesystem::path& dir);

}  // namespace sablier
