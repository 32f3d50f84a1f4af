#include "commands.hpp"

#include <unistd.h>

#include <climits>
#include <fstream>

namespace stereoscout::cli {
namespace {

constexpr Command kCommands[] = {
    {"explore", "explore a simulated world with the whole stack; writes maps, trajectories, log, report.json", run_explore},
    {"replay", "re-run the whole stack on a recorded sensor log (byte-identical outputs)", run_replay},
    {"run", "run the whole stack on the robot computer (V4L2 cameras, serial base, GPIO)", run_run},
    {"check-budgets", "check a run's report.json against a target's budget profile (config/budgets/)", run_check_budgets},
    {"config", "check a config file, print the effective config or the key reference", run_config},
    {"sim-render", "render the simulated stereo pair and ground-truth depth seen from a pose", run_sim_render},
    {"world-map", "write the ground-truth occupancy map and reachable free space of a world", run_world_map},
    {"explore-gt", "explore simulated worlds with ground-truth poses: coverage, collisions, time, distance", run_explore_gt},
    {"landmark-slam", "run the landmark filter on one robot of a UTIAS MRCLAM dataset and score its map", run_landmark_slam},
    {"slam", "run the stereo front end and the filter on a KITTI odometry folder and score the trajectory", run_slam},
    {"eval-disparity", "dense disparity of a rectified pair scored against ground truth (JSON)", run_eval_disparity},
    {"eval-map", "score an occupancy map (map.yaml) against a ground-truth map (JSON)", run_eval_map},
    {"eval-scan", "score the 2.5D obstacle scan on rendered views of a world against its obstacles (JSON)", run_eval_scan},
    {nullptr, nullptr, nullptr},
};

bool file_exists(const std::string& path) { return std::ifstream(path).good(); }

std::string executable_directory() {
  char buffer[PATH_MAX];
  const ssize_t length = ::readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (length <= 0) {
    return ".";
  }
  std::string path(buffer, static_cast<std::size_t>(length));
  return path.substr(0, path.find_last_of('/'));
}

}  // namespace

const Command* command_table() { return kCommands; }

std::string resolve_data_path(const std::string& path) {
  if (path.empty() || path[0] == '/' || file_exists(path)) {
    return path;
  }
  // An installed binary finds its data beside it; a binary in a build tree, in the source.
  const std::string installed = executable_directory() + "/../share/stereoscout/" + path;
  if (file_exists(installed)) {
    return installed;
  }
  const std::string in_source = std::string(STEREOSCOUT_SOURCE_DIR) + "/" + path;
  if (file_exists(in_source)) {
    return in_source;
  }
  return path;
}

std::string default_config_path() { return resolve_data_path("config/stereoscout.yaml"); }

}  // namespace stereoscout::cli
