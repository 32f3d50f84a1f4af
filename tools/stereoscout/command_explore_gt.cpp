// stereoscout explore-gt: exploration in the simulator with ground-truth poses (issue 7's
// end-to-end check; no SLAM). Prints one JSON line per world.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "commands.hpp"
#include "explore_gt_run.hpp"
#include "stereoscout/core/system_config.hpp"
#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::cli {
namespace {

std::vector<std::string> world_files(const Arguments& arguments, const core::SystemConfig& config) {
  std::vector<std::string> files;
  if (arguments.has("all-worlds")) {
    const std::filesystem::path folder = resolve_data_path("config/worlds");
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
      if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());
  } else {
    files.push_back(resolve_data_path(arguments.has("world") ? arguments.get("world") : config.run.world));
  }
  return files;
}

}  // namespace

int run_explore_gt(int argc, char** argv) {
  Arguments arguments("explore-gt",
                      "Explores simulated worlds with ground-truth poses (no SLAM): rendered depth ->\n"
                      "vision 2.5D scan -> occupancy grid -> explorer -> simulated drive. Reports the\n"
                      "coverage of the reachable free space, collisions, time and distance (JSON lines).");
  arguments.option("config", "FILE", "config file", default_config_path());
  arguments.option("world", "FILE", "world file (default: run.world of the config)");
  arguments.flag("all-worlds", "explore every world in config/worlds/ in turn");
  arguments.flag("no-people", "remove the walking people from the worlds");
  arguments.option("time-limit", "S", "exploration time limit in simulated seconds (default: explore.time_limit_s)");
  arguments.option("out", "DIR", "write <world>.pgm/.yaml (final grid) and results.jsonl here");
  if (!arguments.parse(argc, argv)) return arguments.exit_code();
  const core::SystemConfigLoad load = core::load_system_config(arguments.get("config"));
  if (!load.ok()) {
    std::fprintf(stderr, "stereoscout explore-gt: config problem(s):\n%s", load.error_text().c_str());
    return 1;
  }
  core::SystemConfig config = load.config;
  if (arguments.has("time-limit")) {
    double limit = 0.0;
    if (!arguments.get_double("time-limit", limit)) return 2;
    config.explore.time_limit_s = limit;
    config.run.max_time_s = limit;
  }
  const std::string out = arguments.get("out");
  std::ofstream results;
  if (!out.empty()) {
    std::filesystem::create_directories(out);
    results.open(out + "/results.jsonl");
  }
  int failures = 0;
  for (const std::string& file : world_files(arguments, config)) {
    host_sim::WorldLoad world_load = host_sim::load_world(file);
    if (!world_load.ok()) {
      std::fprintf(stderr, "stereoscout explore-gt: world problem(s):\n%s", world_load.error_text().c_str());
      return 1;
    }
    host_sim::World& world = world_load.world;
    if (arguments.has("no-people")) world.people.clear();
    ExploreGtOptions options;
    options.coverage_sample_period_s = 30.0;
    if (!out.empty()) options.map_pgm = out + "/" + world.name + ".pgm";
    const ExploreGtResult result = run_explore_gt(config, world, options);
    if (!result.error.empty()) {
      std::fprintf(stderr, "stereoscout explore-gt: %s: %s\n", world.name.c_str(), result.error.c_str());
      ++failures;
      continue;
    }
    const std::string line = explore_gt_json(world.name, result);
    for (const std::string& collision : result.collision_log) {
      std::fprintf(stderr, "stereoscout explore-gt: %s: collision at %s\n", world.name.c_str(), collision.c_str());
    }
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    if (results.is_open()) results << line << "\n";
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace stereoscout::cli
