// Cells that turn from free to occupied (a person walking into view) are fresh for
// fresh_obstacle_hold_s; a first sighting (unknown to occupied) is not.
#include <gtest/gtest.h>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/explore/fresh_obstacles.hpp"
#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

using testing::TestGrid;

TEST(FreshObstacles, FreeToOccupiedIsFreshForTheHoldTimeAndFirstSightingsAreNot) {
  core::ExploreConfig config;
  config.fresh_obstacle_margin_m = 0.3;
  config.fresh_obstacle_hold_s = 3.0;
  FreshObstacles fresh(config, 20, 20);
  TestGrid grid(20, 20, CellState::free);
  grid.fill(15, 0, 20, 20, CellState::unknown);
  fresh.observe(grid.view(), 0.0);
  grid.set(5, 5, CellState::occupied);    // where the floor was free
  grid.set(16, 5, CellState::occupied);   // never seen before
  fresh.observe(grid.view(), 10.0);
  EXPECT_TRUE(fresh.fresh(grid.view(), 5, 5, 10.0));
  EXPECT_TRUE(fresh.fresh(grid.view(), 5, 5, 13.0));
  EXPECT_FALSE(fresh.fresh(grid.view(), 5, 5, 13.1));
  EXPECT_FALSE(fresh.fresh(grid.view(), 16, 5, 10.0));
  EXPECT_FALSE(fresh.fresh(grid.view(), 6, 5, 10.0));
  // Free again, then occupied again: fresh from the new time.
  grid.set(5, 5, CellState::free);
  fresh.observe(grid.view(), 20.0);
  grid.set(5, 5, CellState::occupied);
  fresh.observe(grid.view(), 21.0);
  EXPECT_TRUE(fresh.fresh(grid.view(), 5, 5, 23.5));
}

TEST(FreshObstacles, ObserveDoesNotAllocateAndAZeroMarginIsOff) {
  core::ExploreConfig config;
  config.fresh_obstacle_margin_m = 0.3;
  FreshObstacles fresh(config, 50, 50);
  TestGrid grid(50, 50, CellState::free);
  fresh.observe(grid.view(), 0.0);
  grid.set(10, 10, CellState::occupied);
  const core::AllocationScope scope;
  fresh.observe(grid.view(), 1.0);
  EXPECT_EQ(scope.allocations(), 0U);
  EXPECT_TRUE(fresh.fresh(grid.view(), 10, 10, 1.0));

  config.fresh_obstacle_margin_m = 0.0;
  FreshObstacles off(config, 50, 50);
  off.observe(grid.view(), 0.0);
  grid.set(20, 20, CellState::occupied);
  off.observe(grid.view(), 1.0);
  EXPECT_FALSE(off.fresh(grid.view(), 20, 20, 1.0));
}

}  // namespace
}  // namespace stereoscout::explore
