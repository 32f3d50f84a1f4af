#pragma once
// Config section `run`: what a run does and how it is seeded.
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

inline constexpr const char* kLocalizationChoices[] = {"rbpf", "groundtruth", "odometry", nullptr};

struct RunConfig {
  std::int64_t seed = 1;
  double max_time_s = 3600.0;
  std::string localization = "rbpf";
  std::string world = "config/worlds/lab.yaml";
};

inline void describe(ConfigVisitor& v, RunConfig& c) {
  v.begin_section("run", "The run as a whole: seed, time limit, pose source, simulated world.");
  v.integer_field("seed", c.seed, {0, 2147483647, "", "Seed of every random stream; same inputs and seed give byte-identical outputs."});
  v.number("max_time_s", c.max_time_s, {1.0, 1e7, "s", "Exploration stops at this (simulated or robot) time."});
  v.choice("localization", c.localization, kLocalizationChoices, "Pose source: the particle filter, the simulator's ground truth, or raw odometry (ablations).");
  v.text("world", c.world, "Simulated world file, relative to the source tree or absolute.");
  v.end_section();
}

}  // namespace stereoscout::core
