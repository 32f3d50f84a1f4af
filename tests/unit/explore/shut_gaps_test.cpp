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

// A 6 m square room split by a wall along y = 3.0-3.1 m with a 1.0 m door (x 2.5-3.5 m), and
// the explorer's planning parts. A near view draws what hangs in the door's west half
// (x 2.5-2.9 m) and shuts it; the view from afar opens it again.
struct DoorScene {
  explicit DoorScene(const ExploreParams& scene_params)
      : params(scene_params), grid(kSize, kSize, CellState::free), map(params), planner(params), gaps(params, kSize, kSize) {
    grid.walls();
    grid.fill(0, 30, 25, 31, CellState::occupied);
    grid.fill(35, 30, kSize, 31, CellState::occupied);
  }
  void hang_in_door(CellState state) { grid.fill(25, 30, 29, 31, state); }
  // Plans through the open door, then shuts it: where the plan was blocked (its size if not).
  std::size_t plan_then_shut_door() {
    EXPECT_TRUE(map.rebuild(grid.view(), robot, robot));
    EXPECT_EQ(planner.plan(map, robot_cell, goal_cell, plan), PlanResult::found);
    hang_in_door(CellState::occupied);
    EXPECT_TRUE(map.rebuild(grid.view(), robot, robot));
    std::size_t k = 0;
    while (k < plan.cells.size() && map.passable(plan.cells[k].x(), plan.cells[k].y())) ++k;
    return k;
  }
  PlanResult plan_on(const GridView& view) {
    EXPECT_TRUE(map.rebuild(view, robot, robot));
    return planner.plan(map, robot_cell, goal_cell, plan);
  }

  ExploreParams params;
  TestGrid grid;
  NavigationMap map;
  PathPlanner planner;
  Plan plan{kPlanCapacity};
  ShutGaps gaps;
  const Eigen::Vector2d robot{2.95, 2.05};
  const Eigen::Vector2i robot_cell{29, 20};
  const Eigen::Vector2i goal_cell{29, 45};
};

TEST(ShutGaps, AGoalFailedAtANearGapTheRobotNeverDroveThroughKeepsItShutUntilLifted) {
  DoorScene scene(shut_gap_params());
  scene.gaps.drove(scene.grid.view(), scene.robot);  // where it stands: south of the wall
  const std::size_t blocked = scene.plan_then_shut_door();
  ASSERT_LT(blocked, scene.plan.cells.size());
  scene.gaps.blocked(scene.map, scene.plan, blocked, scene.robot);
  // No other way: the goal fails, and the gap is shut.
  EXPECT_EQ(scene.planner.plan(scene.map, scene.robot_cell, scene.goal_cell, scene.plan), PlanResult::no_path);
  EXPECT_TRUE(scene.gaps.shut(10.0));
  EXPECT_EQ(scene.gaps.gaps_shut(), 1U);
  EXPECT_GT(scene.gaps.held(), 0U);

  // The view from afar opens the door in the grid: the shut cells keep it shut for planning.
  scene.hang_in_door(CellState::free);
  EXPECT_NE(scene.plan_on(scene.gaps.stamp(scene.grid.view(), 20.0)), PlanResult::found);
  // Lifted (before concluding "explored"), the door is open again.
  EXPECT_EQ(scene.gaps.lift(), scene.gaps.cells_shut());
  EXPECT_EQ(scene.plan_on(scene.gaps.stamp(scene.grid.view(), 30.0)), PlanResult::found);
}

TEST(ShutGaps, AShutGapOpensAgainAfterItsHold) {
  DoorScene scene(shut_gap_params());
  scene.gaps.blocked(scene.map, scene.plan, scene.plan_then_shut_door(), scene.robot);
  ASSERT_TRUE(scene.gaps.shut(10.0));
  scene.hang_in_door(CellState::free);
  EXPECT_NE(scene.gaps.stamp(scene.grid.view(), 10.0 + kHold_s - 1.0).cells, scene.grid.view().cells);
  EXPECT_EQ(scene.gaps.stamp(scene.grid.view(), 10.0 + kHold_s).cells, scene.grid.view().cells);
  EXPECT_EQ(scene.gaps.held(), 0U);
}

TEST(ShutGaps, ADoorTheRobotDroveThroughIsNeverShut) {
  DoorScene scene(shut_gap_params());
  // It came in through the door's middle, from the north.
  for (double y = 5.0; y >= scene.robot.y(); y -= 0.05) scene.gaps.drove(scene.grid.view(), {3.0, y});
  scene.gaps.blocked(scene.map, scene.plan, scene.plan_then_shut_door(), scene.robot);
  EXPECT_FALSE(scene.gaps.shut(10.0));
  EXPECT_EQ(scene.gaps.refused_driven(), 1U);
  EXPECT_EQ(scene.gaps.held(), 0U);
}

TEST(ShutGaps, AGapBlockedFartherThanTheRangeIsNotShut) {
  ExploreParams params = shut_gap_params();
  params.explore.shut_gap_range_m = 0.5;  // the door is 0.75 m from the robot's centre
  DoorScene scene(params);
  scene.gaps.blocked(scene.map, scene.plan, scene.plan_then_shut_door(), scene.robot);
  EXPECT_FALSE(scene.gaps.shut(10.0));
  EXPECT_EQ(scene.gaps.refused_far(), 1U);
  // 0: at any distance.
  params.explore.shut_gap_range_m = 0.0;
  DoorScene any_distance(params);
  any_distance.gaps.blocked(any_distance.map, any_distance.plan, any_distance.plan_then_shut_door(), any_distance.robot);
  EXPECT_TRUE(any_distance.gaps.shut(10.0));
}

TEST(ShutGaps, OffByDefaultAndNothingAllocates) {
  DoorScene off(test_params(kSize, kSize));
  off.gaps.blocked(off.map, off.plan, off.plan_then_shut_door(), off.robot);
  EXPECT_FALSE(off.gaps.shut(10.0));

  DoorScene scene(shut_gap_params());
  const std::size_t blocked = scene.plan_then_shut_door();
  const core::AllocationScope counter;
  scene.gaps.drove(scene.grid.view(), scene.robot);
  scene.gaps.blocked(scene.map, scene.plan, blocked, scene.robot);
  EXPECT_TRUE(scene.gaps.shut(10.0));
  const GridView stamped = scene.gaps.stamp(scene.grid.view(), 20.0);
  EXPECT_EQ(counter.allocations(), 0U);
  EXPECT_NE(stamped.cells, scene.grid.view().cells);
}

}  // namespace
}  // namespace stereoscout::explore
