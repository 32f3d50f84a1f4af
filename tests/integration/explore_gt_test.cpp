// Exploration with ground-truth poses in the simulator (issue 7), short version: a small
// two-room world is explored to at least 95% of its reachable free space without a collision.
// The full runs of config/worlds/ are `stereoscout explore-gt --all-worlds` (docs/results.md).
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "explore_gt_run.hpp"
#include "stereoscout/core/system_config.hpp"
#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::cli {
namespace {

// 7 m x 5 m: two rooms joined by a 1.2 m door, a low box (below a planar laser) and a table.
constexpr const char* kSmallWorld = R"(
name: two_rooms
seed: 5
ceiling_height: 2.6
start: [1.2, 1.2, 20]
floor: {type: tile, texture: tile, brightness: 0.5, contrast: 0.5}
ceiling: {texture: low, brightness: 0.8, contrast: 0.2}
walls:
  - {points: [[0, 0], [7, 0], [7, 5], [0, 5], [0, 0]], texture: brick, brightness: 0.5, contrast: 0.7}
  - {points: [[4, 0], [4, 1.6]], texture: wood, brightness: 0.5, contrast: 0.7}
  - {points: [[4, 2.8], [4, 5]], texture: wood, brightness: 0.5, contrast: 0.7}
boxes:
  - {center: [2.2, 3.6], size: [0.8, 0.6], z: [0, 0.15], texture: wood, brightness: 0.5, contrast: 0.7}
  - {center: [5.8, 3.8], size: [1.2, 0.8], z: [0.7, 0.75], texture: wood, brightness: 0.5, contrast: 0.7}
)";

TEST(ExploreGroundTruth, SmallWorldCoverageGrowsWithoutCollisions) {
  host_sim::WorldLoad load = host_sim::load_world_text(kSmallWorld, "two_rooms");
  ASSERT_TRUE(load.ok()) << load.error_text();
  core::SystemConfig config;
  config.explore.time_limit_s = 150.0;  // short version (coverage is complete after about 90 s)
  ExploreGtOptions options;
  options.coverage_sample_period_s = 30.0;
  options.return_allowance_s = 200.0;
  if (const char* map = std::getenv("STEREOSCOUT_EXPLORE_MAP")) options.map_pgm = map;  // for a look at the grid
  const ExploreGtResult result = run_explore_gt(config, load.world, options);
  ASSERT_TRUE(result.error.empty()) << result.error;
  std::printf("%s\n", explore_gt_json("two_rooms", result).c_str());
  for (const CoverageSample& sample : result.coverage_curve) std::printf("t=%.0f coverage=%.3f\n", sample.time_s, sample.coverage);
  for (const std::string& line : result.collision_log) std::printf("collision: %s\n", line.c_str());
  EXPECT_EQ(result.collisions, 0U);
  EXPECT_EQ(result.final_state, explore::ExploreState::finished);
  EXPECT_GT(result.distance_m, 2.0);
  // Coverage grows as the robot explores, and most of the reachable space is seen in 2.5 minutes.
  ASSERT_GE(result.coverage_curve.size(), 3U);
  EXPECT_LT(result.coverage_curve.front().coverage, 0.6);
  for (std::size_t k = 1; k < result.coverage_curve.size(); ++k) {
    EXPECT_GE(result.coverage_curve[k].coverage, result.coverage_curve[k - 1].coverage - 0.02);
  }
  EXPECT_GE(result.coverage, 0.9);
}

}  // namespace
}  // namespace stereoscout::cli
