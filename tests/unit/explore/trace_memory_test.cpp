// Cells that turn from free to occupied (a person walking into view) are fresh for
// fresh_obstacle_hold_s, and traces that planning crosses after trace_forget_after_s; a first
// sighting (unknown to occupied) is neither.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/explore/trace_memory.hpp"
#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

using testing::TestGrid;

TEST(TraceMemory, FreeToOccupiedIsFreshForTheHoldTimeAndFirstSightingsAreNot) {
  core::ExploreConfig config;
  config.fresh_obstacle_margin_m = 0.3;
  config.fresh_obstacle_hold_s = 3.0;
  TraceMemory fresh(config, 20, 20);
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

TEST(TraceMemory, ObserveDoesNotAllocateAndIsOffWithNoMarginNoForgettingAndNoViewCounting) {
  core::ExploreConfig config;
  config.fresh_obstacle_margin_m = 0.3;
  TraceMemory fresh(config, 50, 50);
  TestGrid grid(50, 50, CellState::free);
  fresh.observe(grid.view(), 0.0);
  grid.set(10, 10, CellState::occupied);
  const core::AllocationScope scope;
  fresh.observe(grid.view(), 1.0);
  EXPECT_EQ(scope.allocations(), 0U);
  EXPECT_TRUE(fresh.fresh(grid.view(), 10, 10, 1.0));

  config.fresh_obstacle_margin_m = 0.0;
  config.trace_forget_after_s = 0.0;
  config.trace_view_updates = 0;
  TraceMemory off(config, 50, 50);
  off.observe(grid.view(), 0.0);
  grid.set(20, 20, CellState::occupied);
  off.observe(grid.view(), 1.0);
  EXPECT_FALSE(off.fresh(grid.view(), 20, 20, 1.0));
  EXPECT_EQ(off.forget_traces(grid.view(), 100.0).cells, grid.view().cells);
}

// Cells turned occupied are traces after 10 s; a look confirms those within confirm_radius_m.
core::ExploreConfig forgetting_config(double confirm_radius_m) {
  core::ExploreConfig config;
  config.trace_forget_after_s = 10.0;
  config.trace_confirm_radius_m = confirm_radius_m;
  return config;
}

// A look confirms no trace nearer than seen_from_m, where the camera sees no floor: a person
// who walked past right in front of the robot left cells the look could not have cleared.
TEST(TraceMemory, ALookConfirmsNoTraceWhereTheCameraSeesNoFloor) {
  TraceMemory traces(forgetting_config(2.0), 40, 20);
  TestGrid grid(40, 20, CellState::free);
  traces.observe(grid.view(), 0.0);
  grid.set(15, 10, CellState::occupied);  // 0.5 m from (1.05, 1.05)
  grid.set(20, 10, CellState::occupied);  // 1.0 m
  traces.observe(grid.view(), 1.0);
  const Eigen::Vector2d robot(1.05, 1.05);
  const Eigen::Vector2d east(1.0, 0.0);
  EXPECT_NEAR(traces.nearest_trace_ahead_m(grid.view(), robot, east, 1.5, 11.0), 0.5, 1e-9);
  EXPECT_TRUE(std::isinf(traces.nearest_trace_ahead_m(grid.view(), robot, east, 0.4, 11.0)));
  EXPECT_TRUE(std::isinf(traces.nearest_trace_ahead_m(grid.view(), robot, east, 1.5, 10.9)));  // not yet traces
  EXPECT_TRUE(std::isinf(traces.nearest_trace_ahead_m(grid.view(), robot, -east, 1.5, 11.0)));  // behind
  EXPECT_EQ(traces.confirm_near(grid.view(), robot, 0.7, 11.0, 11.0), 1U);
  const GridView forgotten = traces.forget_traces(grid.view(), 11.0);
  EXPECT_EQ(forgotten.at(15, 10), CellState::free);
  EXPECT_EQ(forgotten.at(20, 10), CellState::occupied);
  EXPECT_NEAR(traces.nearest_trace_ahead_m(grid.view(), robot, east, 1.5, 11.0), 0.5, 1e-9);
  // From farther back the same look confirms it.
  EXPECT_EQ(traces.confirm_near(grid.view(), Eigen::Vector2d(0.65, 1.05), 0.7, 12.0, 12.0), 1U);
  EXPECT_TRUE(std::isinf(traces.nearest_trace_ahead_m(grid.view(), robot, east, 1.5, 12.0)));
}

// A look that began at 12 s confirms the cell that was a trace by then (turned occupied at
// 1 s), not the one that turned occupied at 6 s, which it watched appear, though both are
// traces when it ends.
TEST(TraceMemory, ALookConfirmsOnlyWhatWasATraceWhenItBegan) {
  TraceMemory traces(forgetting_config(2.0), 40, 20);
  TestGrid grid(40, 20, CellState::free);
  traces.observe(grid.view(), 0.0);
  grid.set(15, 10, CellState::occupied);
  traces.observe(grid.view(), 1.0);
  grid.set(20, 10, CellState::occupied);
  traces.observe(grid.view(), 6.0);
  EXPECT_EQ(traces.confirm_near(grid.view(), Eigen::Vector2d(1.05, 1.05), 0.0, 17.0, 12.0), 1U);
  const GridView forgotten = traces.forget_traces(grid.view(), 17.0);
  EXPECT_EQ(forgotten.at(15, 10), CellState::occupied);
  EXPECT_EQ(forgotten.at(20, 10), CellState::free);
  // A later look that began after both were traces confirms the second.
  EXPECT_EQ(traces.confirm_near(grid.view(), Eigen::Vector2d(1.05, 1.05), 0.0, 30.0, 17.0), 1U);
  EXPECT_EQ(traces.forget_traces(grid.view(), 30.0).cells, grid.view().cells);
}

TEST(TraceMemory, AnOldTraceAwayFromStandingObstaclesIsForgottenUntilALookConfirmsIt) {
  TraceMemory traces(forgetting_config(1.0), 40, 20);
  TestGrid grid(40, 20, CellState::free);
  grid.fill(30, 0, 40, 20, CellState::unknown);
  grid.fill(10, 10, 21, 11, CellState::occupied);  // a wall
  traces.observe(grid.view(), 0.0);
  grid.set(5, 5, CellState::occupied);    // a person walked here
  grid.set(25, 5, CellState::occupied);   // and here
  grid.set(31, 5, CellState::occupied);   // a first sighting: an obstacle
  traces.observe(grid.view(), 1.0);
  // Not yet old: the grid itself.
  EXPECT_EQ(traces.forget_traces(grid.view(), 10.9).cells, grid.view().cells);
  EXPECT_EQ(traces.forgotten_last(), 0U);
  const GridView forgotten = traces.forget_traces(grid.view(), 11.0);
  ASSERT_NE(forgotten.cells, grid.view().cells);
  EXPECT_EQ(traces.forgotten_last(), 2U);
  EXPECT_EQ(forgotten.at(5, 5), CellState::free);
  EXPECT_EQ(forgotten.at(25, 5), CellState::free);
  EXPECT_EQ(forgotten.at(31, 5), CellState::occupied);
  EXPECT_EQ(forgotten.at(30, 5), CellState::unknown);
  // A look from (0.55, 1.05): the trace within a metre is still there, so it is an obstacle;
  // the one 2 m away was out of reach of the look and stays a trace.
  const core::AllocationScope scope;
  EXPECT_EQ(traces.confirm_near(grid.view(), Eigen::Vector2d(0.55, 1.05), 0.0, 12.0, 12.0), 1U);
  EXPECT_EQ(traces.confirmed(), 1U);
  const GridView after = traces.forget_traces(grid.view(), 12.0);
  EXPECT_EQ(scope.allocations(), 0U);
  EXPECT_EQ(traces.forgotten_last(), 1U);
  EXPECT_EQ(after.at(5, 5), CellState::occupied);
  EXPECT_EQ(after.at(25, 5), CellState::free);
  // A trace next to a standing obstacle is part of it: a blank wall's cell, erased by grazing
  // rays and seen again.
  grid.set(20, 10, CellState::free);
  traces.observe(grid.view(), 21.0);
  grid.set(20, 10, CellState::occupied);  // its end erased, then seen again
  traces.observe(grid.view(), 22.0);
  const GridView with_wall = traces.forget_traces(grid.view(), 40.0);
  EXPECT_EQ(traces.forgotten_last(), 1U);
  EXPECT_EQ(with_wall.at(20, 10), CellState::occupied);
  EXPECT_EQ(with_wall.at(25, 5), CellState::free);
  // A trace seen free again is no trace any more.
  grid.set(25, 5, CellState::free);
  traces.observe(grid.view(), 23.0);
  EXPECT_EQ(traces.forget_traces(grid.view(), 40.0).cells, grid.view().cells);
}

TEST(TraceMemory, ACellSeenStandingInViewForEnoughUpdatesIsNoTrace) {
  core::ExploreConfig config;
  config.trace_forget_after_s = 10.0;
  config.trace_view_updates = 3;
  TraceMemory traces(config, 60, 30);
  TestGrid grid(60, 30, CellState::free);
  traces.observe(grid.view(), 0.0);
  grid.set(20, 5, CellState::occupied);  // 1.5 m straight ahead of the camera
  grid.set(22, 5, CellState::occupied);  // behind it
  grid.set(10, 20, CellState::occupied);  // outside the field of view
  grid.set(12, 3, CellState::occupied);  // nearer than the floor the camera sees
  grid.set(30, 5, CellState::occupied);  // farther than the wedge reaches
  CameraWedge view;
  view.position = Eigen::Vector2d(0.55, 0.55);
  view.half_fov_rad = 0.6;
  view.near_m = 1.0;
  view.far_m = 2.0;
  traces.observe(grid.view(), 1.0, &view);
  traces.observe(grid.view(), 2.0, &view);
  EXPECT_EQ(traces.seen_standing(), 0U);
  const core::AllocationScope scope;
  traces.observe(grid.view(), 3.0, &view);
  EXPECT_EQ(scope.allocations(), 0U);
  EXPECT_EQ(traces.seen_standing(), 1U);
  const GridView forgotten = traces.forget_traces(grid.view(), 20.0);
  EXPECT_EQ(traces.forgotten_last(), 4U);
  EXPECT_EQ(forgotten.at(20, 5), CellState::occupied);
  EXPECT_EQ(forgotten.at(22, 5), CellState::free);
  EXPECT_EQ(forgotten.at(10, 20), CellState::free);
  EXPECT_EQ(forgotten.at(12, 3), CellState::free);
  EXPECT_EQ(forgotten.at(30, 5), CellState::free);
  // Remembered as standing, for plans (GridView::seen_standing): that cell only.
  ASSERT_NE(traces.standing_cells(), nullptr);
  EXPECT_EQ(traces.standing_cells()[grid.view().index(20, 5)], 1);
  EXPECT_EQ(std::count(traces.standing_cells(), traces.standing_cells() + 60 * 30, 1), 1);
  // Cleared and hit again (a blank wall's cell erased by a grazing ray): counted anew.
  grid.set(20, 5, CellState::free);
  traces.observe(grid.view(), 21.0, &view);
  grid.set(20, 5, CellState::occupied);
  traces.observe(grid.view(), 22.0, &view);
  EXPECT_EQ(traces.forget_traces(grid.view(), 40.0).at(20, 5), CellState::free);
  // A first sighting (unknown to occupied) in view is seen standing too: a wall seen for the
  // first time, which grazing rays may erase later.
  grid.set(18, 8, CellState::unknown);
  traces.observe(grid.view(), 41.0, &view);
  grid.set(18, 8, CellState::occupied);
  for (double t = 42.0; t < 44.5; t += 1.0) traces.observe(grid.view(), t, &view);
  EXPECT_EQ(traces.standing_cells()[grid.view().index(18, 8)], 1);
}

}  // namespace
}  // namespace stereoscout::explore
