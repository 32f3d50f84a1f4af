// The robot's own path: a point every 5 cm of travel, not joined across a jump of the estimate,
// the last trail_length_m kept; and the cells along it that the navigation map opens for the
// explorer's last resort.
#include <gtest/gtest.h>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/explore/navigation_map.hpp"
#include "stereoscout/explore/trail_memory.hpp"
#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

using testing::TestGrid;

TEST(TrailMemory, KeepsAPointEveryFiveCentimetresAndTheLastTrailLength) {
  core::ExploreConfig config;
  config.trail_length_m = 1.0;
  TrailMemory trail(config);
  ASSERT_TRUE(trail.enabled());
  core::AllocationScope counter;
  for (int tick = 0; tick <= 1000; ++tick) trail.record({0.006 * tick, 1.0});  // 6 m at 6 mm a tick
  EXPECT_EQ(counter.allocations(), 0U);
  ASSERT_EQ(trail.size(), 21U);  // 1 m of 5 cm steps, and the point it starts from
  // Each kept point is the first at least 5 cm from the previous one (9 ticks of 6 mm).
  EXPECT_NEAR(trail[trail.size() - 1].position.x() - trail[trail.size() - 2].position.x(), 0.054, 1e-9);
  EXPECT_GT(trail[0].position.x(), 4.8);
  for (std::size_t i = 1; i < trail.size(); ++i) EXPECT_TRUE(trail[i].joined);
}

TEST(TrailMemory, AJumpOfTheEstimateIsNotJoinedAndOffKeepsNothing) {
  core::ExploreConfig config;
  TrailMemory trail(config);
  trail.record({1.0, 1.0});
  trail.record({1.1, 1.0});
  trail.record({1.1, 1.5});  // 0.5 m in one tick: another particle became the most likely
  trail.record({1.1, 1.52});  // under 5 cm: not kept
  ASSERT_EQ(trail.size(), 3U);
  EXPECT_FALSE(trail[0].joined);
  EXPECT_TRUE(trail[1].joined);
  EXPECT_FALSE(trail[2].joined);

  config.trail_length_m = 0.0;
  TrailMemory off(config);
  EXPECT_FALSE(off.enabled());
  off.record({1.0, 1.0});
  EXPECT_EQ(off.size(), 0U);
}

// A 0.8 m door (rows 27-34) in a wall at x = 3.0-3.2 m, a smeared cell at its edge (29, 33):
// for a robot of 0.3 m radius no cell of the door is the lethal 0.35 m from every occupied
// one. The robot drove through along y = 3.05 m (row 30).
struct SmearedDoor {
  TestGrid grid{60, 60, CellState::free};
  ExploreParams params = testing::test_params(60, 60);
  SmearedDoor() {
    params.robot_radius_m = 0.3;
    grid.walls();
    grid.fill(30, 1, 32, 27, CellState::occupied);
    grid.fill(30, 35, 32, 59, CellState::occupied);
    grid.set(29, 33, CellState::occupied);
  }
};

TEST(NavigationMap, TheTrailOpensTheCellsTheSafetyCheckWouldLetTheRobotCross) {
  SmearedDoor door;
  NavigationMap map(door.params);
  ASSERT_TRUE(map.rebuild(door.grid.view(), {1.5, 3.05}, {1.5, 3.05}));
  map.compute_reachable({15, 30});
  EXPECT_FALSE(map.reachable(45, 30));  // the door is closed

  TrailMemory trail(door.params.explore);
  for (double x = 1.5; x <= 4.5; x += 0.006) trail.record({x, 3.05});
  core::AllocationScope counter;
  EXPECT_EQ(map.open_trail(trail), 3U);  // x = 2.8 to 3.0 m: 0.3 to 0.32 m from the smeared cell
  EXPECT_EQ(counter.allocations(), 0U);
  EXPECT_TRUE(map.passable(29, 30));
  EXPECT_EQ(map.traversability(29, 30), Traversability::inflated);
  map.compute_reachable({15, 30});
  EXPECT_TRUE(map.reachable(45, 30));

  // A trail a row nearer the smeared cell would put the disc within its 0.3 m: it stays closed.
  NavigationMap closer(door.params);
  closer.rebuild(door.grid.view(), {1.5, 3.15}, {1.5, 3.15});
  TrailMemory near_trail(door.params.explore);
  for (double x = 1.5; x <= 4.5; x += 0.006) near_trail.record({x, 3.15});
  closer.open_trail(near_trail);
  EXPECT_FALSE(closer.passable(29, 31));
  closer.compute_reachable({15, 31});
  EXPECT_FALSE(closer.reachable(45, 31));
}

}  // namespace
}  // namespace stereoscout::explore
