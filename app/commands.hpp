// The sablier command-line tool's commands.
#pragma once

#include <string>
#include <vector>

namespace sablier {

struct RunOptions {
  std::string scene_path;
  std::string out_dir;
  std::vector<std::string> overrides;  // --set KEY=VALUE
  std::vector<std::string> formats{"vtp"};
  int threads = 0;  // 0 = OpenMP default
  bool quiet = false;
  bool overwrite = false;
};

// Runs a scene; returns the process exit code.
int run_command(const RunOptions& options);
// Validates a scene and prints a summary; returns the exit code.
int check_command(const std::string& scene_path, const std::vector<std::string>& overrides);
// Prints version, build and OpenMP information.
int info_command();

}  // namespace sablier
