// Exploration with ground-truth poses in the simulator (issue 7), short version: a small
// two-room world is explored to at least 95% of its reachable free space without a collision.
// The full runs of config/worlds/ are `stereoscout explore-gt --all-worlds` (docs/results.md).
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "explore_gt_run.hpp"
#include "stereoscout/test/small_world.hpp"
#include "stereoscout/core/system_config.hpp"
#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::cli {
namespace {

constexpr const char* kSmallWorld = test::kTwoRoomsWorld;

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
