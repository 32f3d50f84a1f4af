#pragma once
// The subcommands of `stereoscout`. Adding one: write command_<name>.cpp with a
// `int run_<name>(int argc, char** argv)`, declare it here and add a row to the table in
// commands.cpp.

#include <string>

namespace stereoscout::cli {

struct Command {
  const char* name;
  const char* summary;
  int (*run)(int argc, char** argv);  // argv starts after the subcommand name
};

// The table of subcommands, ending with a row whose name is nullptr.
const Command* command_table();

// Where to find config/stereoscout.yaml: beside an installed binary
// (<prefix>/share/stereoscout/config), else in the source tree of this build.
std::string default_config_path();
// Resolves a relative path (a world file, ...) that is not found from the current directory
// against the install tree, then the source tree.
std::string resolve_data_path(const std::string& path);

int run_explore(int argc, char** argv);
int run_replay(int argc, char** argv);
int run_run(int argc, char** argv);
int run_check_budgets(int argc, char** argv);
int run_config(int argc, char** argv);
int run_eval_disparity(int argc, char** argv);
int run_eval_map(int argc, char** argv);
int run_sim_render(int argc, char** argv);
int run_eval_scan(int argc, char** argv);
int run_world_map(int argc, char** argv);
int run_explore_gt(int argc, char** argv);
int run_landmark_slam(int argc, char** argv);
int run_slam(int argc, char** argv);

}  // namespace stereoscout::cli
