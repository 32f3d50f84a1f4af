// Shut gaps: a goal that failed at a gap a near view shut, where the robot has never been,
// keeps the gap shut for planning, so the next view from afar that opens it again does not
// send the robot back to every goal behind it.
#include <gtest/gtest.h>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/explore/shut_gaps.hpp"
#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

using testing::TestGrid;
using testing::test_params;

constexpr int kSize = 60;
constexpr double kHold_s = 100.0;
constexpr std::size_t kPlanCapacity = 4096;

ExploreParams shut_gap_params() {
  ExploreParams params = test_params(kSize, kSize);
  params.explore.shut_gap_hold_s = kHold_s;
  params.explore.shut_gap_range_m = 3.0;
  return params;
}

// A 6 m square room split by a wall along y = 3.0-3.1 m with a 1.0 m door (x 2.5-3.5 m). A
// near view draws what hangs in the door's west half (x 2.5-2.9 m) and shuts it; the view from
// afar opens it again.
struct DoorScene {
  DoorScene() : grid(kSize, kSize, CellState::free) {
    grid.walls();
    grid.fill(0, 30, 25, 31, CellState::occupied);
    grid.fill(35, 30, kSize, 31, CellState::occupied);
  }
  void hang_in_door(CellState state) { grid.fill(25, 30, 29, 31, state); }

  TestGrid grid;
  const Eigen::Vector2d robot{2.95, 2.05};
  const Eigen::Vector2i robot_cell{29, 20};
  const Eigen::Vector2i goal_cell{29, 45};
};

// The first cell of `plan` the map holds impassable (the plan's size if none).
std::size_t first_blocked(const NavigationMap& map, const Plan& plan) {
  std::size_t k = 0;
  while (k < plan.cells.size() && map.passable(plan.cells[k].x(), plan.cells[k].y())) ++k;
  return k;
}

// The scene's plan through the open door, blocked once the door is shut: where it was blocked.
std::size_t plan_then_shut_door(DoorScene& scene, NavigationMap& map, PathPlanner& planner, Plan& plan) {
  EXPECT_TRUE(map.rebuild(scene.grid.view(), scene.robot, scene.robot));
  EXPECT_EQ(planner.plan(map, scene.robot_cell, scene.goal_cell, plan), PlanResult::found);
  scene.hang_in_door(CellState::occupied);
  EXPECT_TRUE(map.rebuild(scene.grid.view(), scene.robot, scene.robot));
  return first_blocked(map, plan);
}

TEST(ShutGaps, AGoalFailedAtANearGapTheRobotNeverDroveThroughKeepsItShutUntilLifted) {
  const ExploreParams params = shut_gap_params();
  DoorScene scene;
  NavigationMap map(params);
  PathPlanner planner(params);
  Plan plan(kPlanCapacity);
  ShutGaps gaps(params, kSize, kSize);
  gaps.drove(scene.grid.view(), scene.robot);  // where it stands: south of the wall
  const std::size_t blocked = plan_then_shut_door(scene, map, planner, plan);
  ASSERT_LT(blocked, plan.cells.size());
  gaps.blocked(map, plan, blocked, scene.robot);
  // No other way: the goal fails, and the gap is shut.
  EXPECT_EQ(planner.plan(map, scene.robot_cell, scene.goal_cell, plan), PlanResult::no_path);
  EXPECT_TRUE(gaps.shut(10.0));
  EXPECT_EQ(gaps.gaps_shut(), 1U);
  EXPECT_GT(gaps.held(), 0U);

  // The view from afar opens the door in the grid: the shut cells keep it shut for planning.
  scene.hang_in_door(CellState::free);
  ASSERT_TRUE(map.rebuild(gaps.stamp(scene.grid.view(), 20.0), scene.robot, scene.robot));
  EXPECT_NE(planner.plan(map, scene.robot_cell, scene.goal_cell, plan), PlanResult::found);
  // Lifted (before concluding "explored"), the door is open again.
  EXPECT_EQ(gaps.lift(), gaps.cells_shut());
  ASSERT_TRUE(map.rebuild(gaps.stamp(scene.grid.view(), 30.0), scene.robot, scene.robot));
  EXPECT_EQ(planner.plan(map, scene.robot_cell, scene.goal_cell, plan), PlanResult::found);
}

TEST(ShutGaps, AShutGapOpensAgainAfterItsHold) {
  const ExploreParams params = shut_gap_params();
  DoorScene scene;
  NavigationMap map(params);
  PathPlanner planner(params);
  Plan plan(kPlanCapacity);
  ShutGaps gaps(params, kSize, kSize);
  gaps.blocked(map, plan, plan_then_shut_door(scene, map, planner, plan), scene.robot);
  ASSERT_TRUE(gaps.shut(10.0));
  scene.hang_in_door(CellState::free);
  EXPECT_NE(gaps.stamp(scene.grid.view(), 10.0 + kHold_s - 1.0).cells, scene.grid.view().cells);
  EXPECT_EQ(gaps.stamp(scene.grid.view(), 10.0 + kHold_s).cells, scene.grid.view().cells);
  EXPECT_EQ(gaps.held(), 0U);
}

TEST(ShutGaps, ADoorTheRobotDroveThroughIsNeverShut) {
  const ExploreParams params = shut_gap_params();
  DoorScene scene;
  NavigationMap map(params);
  PathPlanner planner(params);
  Plan plan(kPlanCapacity);
  ShutGaps gaps(params, kSize, kSize);
  // It came in through the door's middle, from the north.
  for (double y = 5.0; y >= scene.robot.y(); y -= 0.05) gaps.drove(scene.grid.view(), {3.0, y});
  gaps.blocked(map, plan, plan_then_shut_door(scene, map, planner, plan), scene.robot);
  EXPECT_FALSE(gaps.shut(10.0));
  EXPECT_EQ(gaps.refused_driven(), 1U);
  EXPECT_EQ(gaps.held(), 0U);
}

TEST(ShutGaps, AGapBlockedFarFromTheRobotIsNotShut) {
  ExploreParams params = shut_gap_params();
  params.explore.shut_gap_range_m = 0.5;  // the door is 0.75 m from the robot's centre
  DoorScene scene;
  NavigationMap map(params);
  PathPlanner planner(params);
  Plan plan(kPlanCapacity);
  ShutGaps gaps(params, kSize, kSize);
  gaps.blocked(map, plan, plan_then_shut_door(scene, map, planner, plan), scene.robot);
  EXPECT_FALSE(gaps.shut(10.0));
  EXPECT_EQ(gaps.refused_far(), 1U);
}

TEST(ShutGaps, OffByDefaultAndNothingAllocates) {
  DoorScene scene;
  ExploreParams params = test_params(kSize, kSize);
  NavigationMap map(params);
  PathPlanner planner(params);
  Plan plan(kPlanCapacity);
  const std::size_t blocked = plan_then_shut_door(scene, map, planner, plan);
  ShutGaps off(params, kSize, kSize);
  off.blocked(map, plan, blocked, scene.robot);
  EXPECT_FALSE(off.shut(10.0));

  params = shut_gap_params();
  ShutGaps gaps(params, kSize, kSize);
  const core::AllocationScope counter;
  gaps.drove(scene.grid.view(), scene.robot);
  gaps.blocked(map, plan, blocked, scene.robot);
  EXPECT_TRUE(gaps.shut(10.0));
  const GridView stamped = gaps.stamp(scene.grid.view(), 20.0);
  EXPECT_EQ(counter.allocations(), 0U);
  EXPECT_NE(stamped.cells, scene.grid.view().cells);
}

}  // namespace
}  // namespace stereoscout::explore
