#pragma once
// Exploration in the simulator with ground-truth poses (no SLAM): the closed loop of issue 7's
// end-to-end check, shared by `stereoscout explore-gt` and the integration test.
//
// Per control tick (explore-gt control period): when the robot moved more than
// robot.update_min_translation_m or the camera turned more than robot.update_min_rotation_deg
// (body or pan unit), an observation update runs: the simulator renders the stereo pair with
// its ground-truth depth; the depth becomes a left-referenced disparity map (d = f B / Z,
// forward-mapped from the right image) that goes through the vision module's 2.5D
// ObstacleScanner; the DepthScan is inserted into the occupancy module's log-odds grid at the
// TRUE pose; the grid is classified with the ROS thresholds into the explorer's GridView. The
// explorer's command drives the simulator. The stereo matcher is bypassed (ground-truth
// disparity) so that this measures exploration, not stereo or SLAM.

#include <cstdint>
#include <string>
#include <vector>

#include "stereoscout/core/system_config.hpp"
#include "stereoscout/explore/explorer.hpp"
#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::cli {

struct ExploreGtOptions {
  double control_period_s = 0.1;
  double return_allowance_s = 1200.0;  // simulated time allowed after the exploration time limit
  double coverage_sample_period_s = 60.0;
  std::string map_pgm;  // when not empty: the final grid as a ROS map (pgm + yaml beside it)
};

struct CoverageSample {
  double time_s = 0.0;
  double coverage = 0.0;
};

struct ExploreGtResult {
  std::string error;  // empty on success
  double coverage = 0.0;  // fraction of the reachable free space the grid holds as free
  std::size_t reachable_cells = 0;
  std::size_t covered_cells = 0;
  std::uint64_t collisions = 0;       // the robot drove into an obstacle or a person
  std::uint64_t person_contacts = 0;  // a person walked into the stopped (or turning) robot
  double exploration_time_s = 0.0;  // until exploration ended (before the return)
  double total_time_s = 0.0;
  double distance_m = 0.0;
  double distance_from_start_m = 0.0;  // at the end
  std::uint64_t updates = 0;
  explore::ExploreCounters counters;
  explore::FinishReason finish_reason = explore::FinishReason::none;
  explore::ExploreState final_state = explore::ExploreState::look_around;
  std::vector<CoverageSample> coverage_curve;
  std::vector<std::string> collision_log;  // the first few collisions: time, pose, explorer state
};

ExploreGtResult run_explore_gt(const core::SystemConfig& config, const host_sim::World& world,
                               const ExploreGtOptions& options);

// One line of JSON with every figure of the result.
std::string explore_gt_json(const std::string& world_name, const ExploreGtResult& result);

}  // namespace stereoscout::cli
