#pragma once
// The whole configuration of the stack (config/stereoscout.yaml), one section per part.
// A module takes its own section (or the few it needs), never the whole struct.

#include <string>
#include <vector>

#include "stereoscout/core/config.hpp"
#include "stereoscout/core/config/budgets.hpp"
#include "stereoscout/core/config/camera.hpp"
#include "stereoscout/core/config/dataset.hpp"
#include "stereoscout/core/config/explore.hpp"
#include "stereoscout/core/config/filter.hpp"
#include "stereoscout/core/config/grid.hpp"
#include "stereoscout/core/config/robot.hpp"
#include "stereoscout/core/config/robot_pc.hpp"
#include "stereoscout/core/config/run.hpp"
#include "stereoscout/core/config/sim.hpp"
#include "stereoscout/core/config/vision.hpp"

namespace stereoscout::core {

struct SystemConfig {
  RunConfig run;
  RobotConfig robot;
  CameraConfig camera;
  VisionConfig vision;
  FilterConfig filter;
  GridConfig grid;
  ExploreConfig explore;
  BudgetsConfig budgets;
  SimConfig sim;
  RobotPcConfig robot_pc;
  DatasetConfig dataset;
};

void describe(ConfigVisitor& visitor, SystemConfig& config);

struct SystemConfigLoad {
  SystemConfig config;
  std::vector<ConfigError> errors;
  bool ok() const { return errors.empty(); }
  std::string error_text() const;
};

// Loads a config file over the paper's defaults. Keys left out keep their defaults.
SystemConfigLoad load_system_config(const std::string& path);
SystemConfigLoad load_system_config_text(const std::string& yaml, const std::string& name);

// The effective configuration as YAML (loads back to the same values).
std::string to_yaml(const SystemConfig& config);
// The markdown reference of every key with its default (docs/config.md is made from it).
std::string config_reference_markdown();

}  // namespace stereoscout::core
