#include "stereoscout/occupancy/just_in_time_grid.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "ancestry_driver.hpp"
#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/occupancy/final_map.hpp"

namespace stereoscout::occupancy {
namespace {

using testing::AncestryDriver;
using testing::DriverSettings;

core::GridConfig small_config(int cache_capacity, int scan_history) {
  core::GridConfig config;
  config.width_cells = 80;
  config.height_cells = 80;
  config.resolution_m = 0.1;
  config.cache_capacity = cache_capacity;
  config.scan_history = scan_history;
  return config;
}

// The reference: every scan along the node's whole ancestry, root first, into an empty grid,
// from the test's own copies of the scans (not the ring the cache uses).
bool matches_grid_from_scratch(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                               const std::vector<core::DepthScan>& scans, const std::vector<bool>& recorded,
                               const OccupancyGrid& candidate, OccupancyGrid& reference) {
  std::vector<slam::TrajectoryNodeHandle> lineage;
  for (; node; node = tree.parent(node)) lineage.push_back(node);
  reference.clear();
  for (auto it = lineage.rbegin(); it != lineage.rend(); ++it) {
    const slam::TrajectoryNode& entry = tree.get(*it);
    if (recorded[entry.update_index]) reference.insert(scans[entry.update_index], entry.pose);
  }
  return reference.same_cells_as(candidate);
}

struct InvariantRun {
  std::uint64_t mismatches = 0;
  JustInTimeGridStats stats;
  std::size_t max_held = 0;
};

InvariantRun run_invariant(const DriverSettings& settings, int cache_capacity, std::uint32_t updates) {
  const core::GridConfig config = small_config(cache_capacity, 1000);
  slam::TrajectoryTree tree(20000);
  InvariantRun run;
  {
    AncestryDriver driver(tree, settings);
    const GridGeometry geometry = GridGeometry::centred_on(config, core::Pose2{});
    JustInTimeGrid cache(config, geometry, 32, tree);
    OccupancyGrid reference(geometry, LogOddsModel::from_config(config));
    std::vector<core::DepthScan> scans(updates + 1);
    std::vector<bool> recorded(updates + 1, false);
    driver.start(core::Pose2{});
    for (std::uint32_t u = 0; u <= updates; ++u) {
      if (u > 0) driver.step();
      // Every seventh update has no scan (a dropped frame): both sides skip it.
      if (u % 7 != 3) {
        driver.make_scan(scans[u], 32);
        cache.record_scan(u, scans[u]);
        recorded[u] = true;
      }
      cache.update(driver.ml_node(), driver.nodes(), driver.count());
      run.max_held = std::max(run.max_held, cache.grids_held());
      EXPECT_LE(cache.grids_held(), cache.cache_capacity());
      if (!matches_grid_from_scratch(tree, driver.ml_node(), scans, recorded, *cache.ml_grid(), reference)) {
        ++run.mismatches;
      }
    }
    run.stats = cache.stats();
    driver.release_all();
    EXPECT_GT(cache.grids_held(), 0u);
    cache.release_all();
    EXPECT_EQ(cache.grids_held(), 0u);
  }
  EXPECT_EQ(tree.in_use(), 0u) << "every node is freed once particles and cache let go";
  return run;
}

TEST(JustInTimeGrid, EqualsTheGridFromScratchAfterEveryUpdate) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    DriverSettings settings;
    settings.seed = seed;
    settings.particles = 24;
    const InvariantRun run = run_invariant(settings, 16, 120);
    EXPECT_EQ(run.mismatches, 0u) << "seed " << seed;
    EXPECT_EQ(run.stats.rollups, 121u);
    EXPECT_GT(run.stats.copies, 0u) << "seed " << seed;
    EXPECT_GT(run.stats.moves, 0u) << "seed " << seed;
    EXPECT_GT(run.stats.rollup_length_max, 1u) << "ML switches roll up more than one scan";
    EXPECT_EQ(run.stats.rollup_incomplete, 0u);
    EXPECT_EQ(run.stats.evictions, 0u);
  }
}

TEST(JustInTimeGrid, StaysExactWhenTheCacheIsTooSmallAndEvicts) {
  DriverSettings settings;
  settings.seed = 9;
  settings.particles = 40;
  settings.weight_noise = 2.0;
  const InvariantRun run = run_invariant(settings, 2, 150);
  EXPECT_EQ(run.mismatches, 0u);
  EXPECT_LE(run.max_held, 2u);
  EXPECT_GT(run.stats.evictions, 0u);
}

TEST(JustInTimeGrid, IsDeterministic) {
  DriverSettings settings;
  settings.seed = 5;
  const InvariantRun first = run_invariant(settings, 8, 60);
  const InvariantRun second = run_invariant(settings, 8, 60);
  EXPECT_EQ(first.stats.copies, second.stats.copies);
  EXPECT_EQ(first.stats.moves, second.stats.moves);
  EXPECT_EQ(first.stats.rollup_scans, second.stats.rollup_scans);
  EXPECT_EQ(first.stats.grids_held_sum, second.stats.grids_held_sum);
}

TEST(JustInTimeGrid, OneLineageMovesItsGridWithoutCopying) {
  const core::GridConfig config = small_config(4, 100);
  slam::TrajectoryTree tree(100);
  DriverSettings settings;
  settings.particles = 1;
  AncestryDriver driver(tree, settings);
  JustInTimeGrid cache(config, GridGeometry::centred_on(config, core::Pose2{}), 32, tree);
  core::DepthScan scan;
  driver.start(core::Pose2{});
  for (std::uint32_t u = 0; u < 30; ++u) {
    if (u > 0) driver.step();
    driver.make_scan(scan, 32);
    cache.record_scan(u, scan);
    cache.update(driver.ml_node(), driver.nodes(), driver.count());
    EXPECT_EQ(cache.grids_held(), 1u);
  }
  EXPECT_EQ(cache.stats().moves, 29u);
  EXPECT_EQ(cache.stats().copies, 0u);
  EXPECT_EQ(cache.stats().built_from_empty, 1u);
  EXPECT_EQ(cache.stats().rollup_length_max, 1u);
  // The particle and the cache hold the newest node; the cache holds nothing older.
  EXPECT_EQ(tree.use_count(driver.ml_node()), 2u);
  EXPECT_EQ(tree.use_count(tree.parent(driver.ml_node())), 1u);
}

TEST(JustInTimeGrid, ScanRingTooShortIsACountedDegradation) {
  // Two particles branch at update 0; the ML follows particle 0 for 20 updates, then switches
  // to particle 1, whose nearest grid (at the branch) is 20 updates back; the ring holds 5.
  const core::GridConfig config = small_config(4, 5);
  slam::TrajectoryTree tree(200);
  DriverSettings settings;
  settings.particles = 2;
  settings.resample_fraction = 0.0;  // never resample
  AncestryDriver driver(tree, settings);
  JustInTimeGrid cache(config, GridGeometry::centred_on(config, core::Pose2{}), 32, tree);
  core::DepthScan scan;
  driver.start(core::Pose2{});
  for (std::uint32_t u = 0; u <= 21; ++u) {
    if (u > 0) driver.step();
    driver.set_ml(u <= 20 ? 0 : 1);
    driver.make_scan(scan, 32);
    cache.record_scan(u, scan);
    cache.update(driver.ml_node(), driver.nodes(), driver.count());
    ASSERT_NE(cache.ml_grid(), nullptr);
  }
  EXPECT_EQ(cache.stats().rollup_incomplete, 1u);
  EXPECT_GT(cache.stats().dependents_unresolved, 0u);
  EXPECT_EQ(cache.stats().rollup_length_max, 5u);  // the walk stops where the ring ends
  EXPECT_EQ(cache.stats().built_from_empty, 2u);
}

TEST(JustInTimeGrid, UpdateDoesNotTouchTheHeap) {
  const core::GridConfig config = small_config(16, 200);
  slam::TrajectoryTree tree(20000);
  DriverSettings settings;
  settings.particles = 50;
  AncestryDriver driver(tree, settings);
  JustInTimeGrid cache(config, GridGeometry::centred_on(config, core::Pose2{}), 32, tree);
  core::DepthScan scan;
  driver.make_scan(scan, 32);
  driver.start(core::Pose2{});
  std::uint64_t allocations = 0;
  for (std::uint32_t u = 0; u < 100; ++u) {
    if (u > 0) driver.step();
    driver.make_scan(scan, 32);
    core::AllocationScope scope;
    cache.record_scan(u, scan);
    cache.update(driver.ml_node(), driver.nodes(), driver.count());
    allocations += scope.allocations();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_GT(cache.stats().copies, 0u);
  cache.update({}, driver.nodes(), driver.count());
  EXPECT_EQ(cache.stats().updates_skipped_no_ml_node, 1u);
  EXPECT_NE(cache.ml_grid(), nullptr);
}

// 1000 particles whose log-likelihoods score their distance to the true path (sigma 1 cm),
// 200 updates: the cache stays inside its 64 slots without evicting, the update never
// touches the heap, and the final ML grid still equals the one built from scratch.
TEST(JustInTimeGrid, ThousandParticlesStayInsideTheCache) {
  core::GridConfig config = small_config(64, 1000);
  config.width_cells = 40;
  config.height_cells = 40;
  slam::TrajectoryTree tree(1000 * 210);
  DriverSettings settings;
  settings.particles = 1000;
  settings.weight_noise = 0.1;
  settings.likelihood_sigma_m = 0.01;
  AncestryDriver driver(tree, settings);
  const GridGeometry geometry = GridGeometry::centred_on(config, core::Pose2{});
  JustInTimeGrid cache(config, geometry, 8, tree);
  core::DepthScan scan;
  driver.make_scan(scan, 8);
  driver.start(core::Pose2{});
  std::uint64_t allocations = 0;
  for (std::uint32_t u = 0; u <= 200; ++u) {
    if (u > 0) driver.step();
    driver.make_scan(scan, 8);
    core::AllocationScope scope;
    cache.record_scan(u, scan);
    cache.update(driver.ml_node(), driver.nodes(), driver.count());
    allocations += scope.allocations();
  }
  const JustInTimeGridStats& stats = cache.stats();
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(stats.evictions, 0u);
  EXPECT_LE(stats.grids_held_max, 64u);
  EXPECT_GT(stats.copies, 0u);
  EXPECT_EQ(stats.rollup_incomplete, 0u);
  OccupancyGrid reference(geometry, LogOddsModel::from_config(config));
  insert_trajectory_scans(tree, driver.ml_node(), cache.scans(), reference);
  EXPECT_TRUE(reference.same_cells_as(*cache.ml_grid()));
  std::printf("1000 particles, 201 updates: grids held mean %.2f max %llu; roll-up length mean %.2f max %llu; "
              "copies %llu moves %llu; walk steps per update %.0f\n",
              stats.mean_grids_held(), static_cast<unsigned long long>(stats.grids_held_max),
              stats.mean_rollup_length(), static_cast<unsigned long long>(stats.rollup_length_max),
              static_cast<unsigned long long>(stats.copies), static_cast<unsigned long long>(stats.moves),
              static_cast<double>(stats.dependents_walk_steps) / static_cast<double>(stats.updates));
}

TEST(JustInTimeGrid, FinalMapHoldsTheWholeTrajectory) {
  const core::GridConfig config = small_config(8, 100);
  slam::TrajectoryTree tree(5000);
  DriverSettings settings;
  settings.particles = 10;
  AncestryDriver driver(tree, settings);
  const GridGeometry geometry = GridGeometry::centred_on(config, core::Pose2{});
  JustInTimeGrid cache(config, geometry, 32, tree);
  core::DepthScan scan;
  driver.start(core::Pose2{});
  for (std::uint32_t u = 0; u < 40; ++u) {
    if (u > 0) driver.step();
    driver.make_scan(scan, 32);
    cache.record_scan(u, scan);
    cache.update(driver.ml_node(), driver.nodes(), driver.count());
  }
  // Same geometry: the from-scratch builder reproduces the just-in-time grid.
  OccupancyGrid rebuilt(geometry, LogOddsModel::from_config(config));
  const TrajectoryScanCounts counts = insert_trajectory_scans(tree, driver.ml_node(), cache.scans(), rebuilt);
  EXPECT_EQ(counts.nodes, 40u);
  EXPECT_EQ(counts.scans_inserted, 40u);
  EXPECT_TRUE(rebuilt.same_cells_as(*cache.ml_grid()));
  // Final map at 1 cm: fitted around the trajectory and its scans.
  TrajectoryScanCounts final_counts;
  const auto final_map = build_final_map(tree, driver.ml_node(), cache.scans(), 0.01, 0.5,
                                         LogOddsModel::from_config(config), &final_counts);
  EXPECT_EQ(final_counts.scans_inserted, 40u);
  int cell_x = 0;
  int cell_y = 0;
  for (slam::TrajectoryNodeHandle node = driver.ml_node(); node; node = tree.parent(node)) {
    EXPECT_TRUE(final_map->cell_of(tree.get(node).pose.x, tree.get(node).pose.y, cell_x, cell_y));
  }
  EXPECT_DOUBLE_EQ(final_map->geometry().resolution_m, 0.01);
  EXPECT_GT(final_map->insert_counts().rays, 1000u);
}

}  // namespace
}  // namespace stereoscout::occupancy
