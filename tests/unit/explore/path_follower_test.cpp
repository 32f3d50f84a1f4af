// The follower driving a kinematic robot (the simulator's model: no acceleration limit) along
// planned paths through a doorway, and the door's axis (door_axis.hpp) it may steer along there.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "stereoscout/explore/door_axis.hpp"
#include "stereoscout/explore/path_follower.hpp"
#include "stereoscout/explore/path_planner.hpp"
#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

using testing::TestGrid;
using testing::test_params;

// A corridor's thin wall (the cell row y 4.0-4.1) with a 0.9 m door whose jambs stand at
// x 1.55 and 2.45, as the simulated office's do; the room lies south of it. The door's middle
// is a cell boundary, so the two passable cells in it are each 0.05 m off the middle.
constexpr double kMiddleX = 2.0;
constexpr double kWallY = 4.05;
constexpr double kJambHalfSpan = 0.45;

// With `jamb_cells_free`, the cells the jambs' edges lie in are free: the grid holds the door
// 1.1 m wide, and it has four passable cells, the outer two 0.15 m off its middle.
struct Doorway {
  explicit Doorway(const ExploreParams& p, bool jamb_cells_free = false) : params(p) {
    const int free_cells = jamb_cells_free ? 1 : 0;
    grid.walls();
    grid.fill(0, 40, 16 - free_cells, 41, CellState::occupied);
    grid.fill(24 + free_cells, 40, 60, 41, CellState::occupied);
  }
  ExploreParams params;
  NavigationMap map{params};
  PathPlanner planner{params};
  Plan plan{4096};
  TestGrid grid{60, 80, CellState::free};
};

// Least distance between the robot's disc and a jamb (a point at wall height across the wall
// cell's depth, as the simulator's thin wall has it); 0.10 m when passing in the middle.
double jamb_clearance_m(const core::Pose2& pose, double radius_m) {
  const double along = std::max(0.0, std::abs(pose.y - kWallY) - 0.05);
  const double across = kJambHalfSpan - std::abs(pose.x - kMiddleX);
  return std::hypot(across, along) - radius_m;
}

struct Passage {
  bool reached = false;
  double clearance_m = 1e9;
};

// Drives from `start` to `goal` at the drive task's 20 Hz, planning every 0.5 s from the
// robot's cell as the explorer does.
Passage drive_through(Doorway& door, const core::Pose2& start, const Eigen::Vector2d& goal) {
  const GridView grid = door.grid.view();
  const Eigen::Vector2d origin(start.x, start.y);
  EXPECT_TRUE(door.map.rebuild(grid, origin, origin));
  PathFollower follower(door.params);
  DoorAxis axis(door.params);
  core::Pose2 pose = start;
  Passage passage;
  const double dt = 0.05;
  const double replan_s = 0.5;
  double next_plan_s = 0.0;
  for (double t = 0.0; t < 200.0; t += dt) {
    if (t >= next_plan_s) {
      const Eigen::Vector2i cell = grid.cell_of({pose.x, pose.y});
      if (door.planner.plan(door.map, cell, grid.cell_of(goal), door.plan) != PlanResult::found) return passage;
      follower.reset();
      next_plan_s = t + replan_s;
    }
    if (door.params.explore.door_axis_before_m > 0.0) axis.update(door.plan, follower.progress(), door.map, {pose.x, pose.y});
    const FollowResult result = follower.follow(door.plan, pose, axis.passage());
    if (result.reached) {
      passage.reached = true;
      return passage;
    }
    const double v = result.command.linear_mps;
    const double w = result.command.angular_rad_s;
    pose.x += v * dt * std::cos(pose.theta + 0.5 * w * dt);
    pose.y += v * dt * std::sin(pose.theta + 0.5 * w * dt);
    pose.theta = core::wrap_angle(pose.theta + w * dt);
    passage.clearance_m = std::min(passage.clearance_m, jamb_clearance_m(pose, door.params.robot_radius_m));
  }
  return passage;
}

// Least jamb clearance over approaches from the corridor (eight starts, three headings) to
// goals in the room straight ahead, beside the door and diagonally beyond it.
double least_clearance_m(const ExploreParams& params, bool jamb_cells_free = false) {
  const double starts_x[] = {0.6, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.5};
  const double headings[] = {0.0, core::kPi, -core::kPi / 2.0};
  const Eigen::Vector2d goals[] = {{2.0, 2.5}, {3.5, 2.8}, {0.8, 3.0}, {4.5, 1.5}};
  double least = 1e9;
  for (double x : starts_x) {
    for (double heading : headings) {
      for (const Eigen::Vector2d& goal : goals) {
        Doorway door(params, jamb_cells_free);
        const Passage passage = drive_through(door, core::Pose2{x, 5.1, heading}, goal);
        EXPECT_TRUE(passage.reached) << "from x " << x << " heading " << heading << " to " << goal.transpose();
        least = std::min(least, passage.clearance_m);
      }
    }
  }
  return least;
}

// Nearly the disc's 0.10 m in the grid that holds the door a cell wider and in the exact one.
void expect_clear_in_either_grid(const ExploreParams& params, const char* how) {
  const double wider = least_clearance_m(params, true);
  const double exact = least_clearance_m(params);
  std::printf("least jamb clearance, %s: %.3f m in the wider grid, %.3f m in the exact grid\n", how, wider, exact);
  EXPECT_GT(wider, 0.09);
  EXPECT_GT(exact, 0.09);
}

// Pure pursuit at 0.35 m cuts the turn into the door and the plan runs 0.05 m off its middle:
// with true poses the disc comes within 0.04 m of a jamb. Keeping to the path in narrow places
// and centring the waypoints on the jambs leave it nearly the whole 0.10 m.
TEST(PathFollower, PassesADoorNearItsMiddle) {
  ExploreParams params = test_params(60, 80);
  params.explore.narrow_lookahead_m = 0.0;
  params.explore.gap_centring_reach_m = 0.0;
  const double plain = least_clearance_m(params);
  EXPECT_GT(plain, 0.0);
  EXPECT_LT(plain, 0.05);

  params.explore.narrow_lookahead_m = 0.15;
  params.explore.gap_centring_reach_m = 0.55;
  EXPECT_GT(least_clearance_m(params), 0.085);
}

// Only where a waypoint up to the lookahead point is narrow does the lookahead shrink: in
// open space the follower's command is the same with and without it.
TEST(PathFollower, NarrowLookaheadActsOnlyNearObstacles) {
  ExploreParams params = test_params(60, 80);
  params.explore.narrow_lookahead_m = 0.0;
  Doorway wide(params);
  params.explore.narrow_lookahead_m = 0.15;
  Doorway narrow(params);
  const Eigen::Vector2d origin(3.0, 6.0);
  for (Doorway* door : {&wide, &narrow}) {
    ASSERT_TRUE(door->map.rebuild(door->grid.view(), origin, origin));
    ASSERT_EQ(door->planner.plan(door->map, {30, 60}, {50, 62}, door->plan), PlanResult::found);  // in the corridor
  }
  const core::Pose2 pose{3.0, 6.05, 0.1};
  PathFollower wide_follower(wide.params);
  PathFollower narrow_follower(narrow.params);
  const FollowResult open = wide_follower.follow(wide.plan, pose);
  const FollowResult same = narrow_follower.follow(narrow.plan, pose);
  EXPECT_EQ(open.command.linear_mps, same.command.linear_mps);
  EXPECT_EQ(open.command.angular_rad_s, same.command.angular_rad_s);
  for (std::size_t k = 0; k < narrow.plan.narrow.size(); ++k) EXPECT_FALSE(narrow.plan.narrow[k]);

  // Through the door: the waypoints in it are narrow, and the lookahead point is nearer.
  for (Doorway* door : {&wide, &narrow}) {
    ASSERT_EQ(door->planner.plan(door->map, {20, 44}, {20, 30}, door->plan), PlanResult::found);
  }
  const core::Pose2 before_door{2.0, 4.4, -core::kPi / 2.0 + 0.2};
  const FollowResult far = PathFollower(wide.params).follow(wide.plan, before_door);
  const FollowResult near = PathFollower(narrow.params).follow(narrow.plan, before_door);
  EXPECT_GT(std::abs(near.command.angular_rad_s), std::abs(far.command.angular_rad_s));
}

// The grid often holds a 0.9 m door a cell wider on either side (the cells its jambs' edges
// lie in seen free): no waypoint in it is within the safety margin, so the follower keeps its
// long lookahead and cuts the turn into the door, and the plan may pass 0.15 m off its
// middle. Calling waypoints within 0.6 m of an obstacle narrow and steering along the door's
// axis leave the disc nearly its 0.10 m in either grid.
TEST(PathFollower, PassesADoorTheGridHoldsWiderAlongItsAxis) {
  ExploreParams params = test_params(60, 80);
  const double wider = least_clearance_m(params, true);
  EXPECT_LT(wider, 0.05);
  params.explore.narrow_clearance_m = 0.6;
  params.explore.door_axis_before_m = 0.6;
  const double wider_on_axis = least_clearance_m(params, true);
  const double on_axis = least_clearance_m(params);
  std::printf("least jamb clearance: %.3f m in the wider grid, %.3f m along the axis (%.3f m in the exact grid)\n",
              wider, wider_on_axis, on_axis);
  EXPECT_GT(wider_on_axis, 0.09);
  EXPECT_GT(on_axis, 0.09);
}

// The same door axis found among all the plan's waypoints with obstacle cells on both sides
// (door_axis_all_gaps), so that the lookahead stays long wherever no waypoint lies within the
// safety margin: the disc keeps nearly its 0.10 m in either grid too.
TEST(PathFollower, PassesADoorTheGridHoldsWiderAlongTheAxisOfAnyGap) {
  ExploreParams params = test_params(60, 80);
  params.explore.narrow_clearance_m = 0.0;
  params.explore.door_axis_before_m = 0.6;
  params.explore.door_axis_all_gaps = true;
  expect_clear_in_either_grid(params, "along the axis of any gap");
}

// The same wider grid without the door's axis: a centring reach that finds the grid's jamb
// cells (0.6 m from the door's middle there) on both sides of the waypoints in the door, and
// the short lookahead within 0.6 m of an obstacle, keep the disc nearly its 0.10 m too, while
// the follower keeps to the latest plan.
TEST(PathFollower, PassesADoorTheGridHoldsWiderCentredBetweenItsJambCells) {
  ExploreParams params = test_params(60, 80);
  params.explore.gap_centring_reach_m = 0.55;
  params.explore.narrow_clearance_m = 0.0;
  EXPECT_LT(least_clearance_m(params, true), 0.05);
  params.explore.gap_centring_reach_m = 0.7;
  EXPECT_LT(least_clearance_m(params, true), 0.075);  // centred, but the long lookahead cuts the turn
  params.explore.narrow_clearance_m = 0.6;
  expect_clear_in_either_grid(params, "centring reach 0.7 m, narrow within 0.6 m");
}

// The door is found where the plan's narrow stretch is narrowest, its middle between the grid's
// jamb cells in either grid, its axis the way the plan passes. A door ahead that a new plan
// no longer passes is dropped; one the robot is passing is kept until the disc has cleared it.
// The same with the door looked for among all waypoints with obstacle cells on both sides;
// with neither that nor narrow_clearance_m, the grid that holds the door a cell wider has no
// narrow waypoint in it, and no door.
TEST(DoorAxis, FindsTheDoorOnThePlanAndKeepsItWhilePassing) {
  ExploreParams neither = test_params(60, 80);
  neither.explore.door_axis_before_m = 0.6;
  ExploreParams narrow = neither;
  narrow.explore.narrow_clearance_m = 0.6;
  ExploreParams all_gaps = neither;
  all_gaps.explore.door_axis_all_gaps = true;
  for (const ExploreParams& params : {neither, narrow, all_gaps}) {
    for (bool jamb_cells_free : {false, true}) {
      Doorway door(params, jamb_cells_free);
      const Eigen::Vector2d robot(1.5, 4.9);
      ASSERT_TRUE(door.map.rebuild(door.grid.view(), robot, robot));
      ASSERT_EQ(door.planner.plan(door.map, {15, 49}, {25, 25}, door.plan), PlanResult::found);
      DoorAxis axis(params);
      axis.update(door.plan, 0, door.map, robot);
      const bool neither_key = params.explore.narrow_clearance_m == 0.0 && !params.explore.door_axis_all_gaps;
      if (neither_key && jamb_cells_free) {
        EXPECT_FALSE(axis.passage().known);
        continue;
      }
      ASSERT_TRUE(axis.passage().known) << jamb_cells_free;
      EXPECT_NEAR(axis.passage().middle.x(), kMiddleX, 1e-9);
      EXPECT_NEAR(axis.passage().middle.y(), kWallY, 1e-9);
      EXPECT_NEAR(axis.passage().along.y(), -1.0, 1e-9);
      Eigen::Vector2d target(0.0, 0.0);
      ASSERT_TRUE(axis.passage().axis_target({1.9, 4.5}, 0.15, 0.6, target));
      EXPECT_NEAR(target.x(), kMiddleX, 1e-9);
      EXPECT_NEAR(target.y(), 4.5 - 0.15, 1e-9);
      EXPECT_FALSE(axis.passage().axis_target({1.9, 5.0}, 0.15, 0.6, target));  // 0.95 m before it

      // Passed the other way, the same door turns its axis round.
      ASSERT_EQ(door.planner.plan(door.map, {20, 30}, {15, 49}, door.plan), PlanResult::found);
      axis.update(door.plan, 0, door.map, {2.05, 3.05});
      ASSERT_TRUE(axis.passage().known);
      EXPECT_NEAR(axis.passage().along.y(), 1.0, 1e-9);

      // A plan along the corridor instead: the door ahead is dropped.
      ASSERT_EQ(door.planner.plan(door.map, {15, 49}, {45, 49}, door.plan), PlanResult::found);
      axis.update(door.plan, 0, door.map, robot);
      EXPECT_FALSE(axis.passage().known);

      // In the door, with a plan whose narrow stretch lies behind: kept until 0.5 m past it.
      ASSERT_EQ(door.planner.plan(door.map, {15, 49}, {25, 25}, door.plan), PlanResult::found);
      axis.update(door.plan, 0, door.map, robot);
      ASSERT_TRUE(axis.passage().known);
      ASSERT_EQ(door.planner.plan(door.map, {20, 30}, {40, 20}, door.plan), PlanResult::found);
      axis.update(door.plan, 0, door.map, {2.0, 3.7});
      EXPECT_TRUE(axis.passage().known);
      axis.update(door.plan, 0, door.map, {2.0, 3.5});
      EXPECT_FALSE(axis.passage().known);
    }
  }
}

// A person standing in the corridor just past the door, aside of its middle, makes a gap with
// the far jamb whose middle lies within 0.3 m of the door's, its axis 20-30 degrees off the
// door's (office seed 4 at S2). Once the person has gone, the door found on the next plan is
// another door: the axis turns square to the wall, and a sighting of the skewed gap is not
// followed.
TEST(DoorAxis, TakesTheDoorForAnotherOnceThePersonBesideItHasGone) {
  ExploreParams params = test_params(60, 80);
  params.explore.door_axis_before_m = 1.4;
  params.explore.door_axis_all_gaps = true;
  const Eigen::Vector2d robot(2.0, 3.0);
  const Eigen::Vector2i robot_cell(20, 30);
  const Eigen::Vector2i goal_cell(45, 55);
  Doorway with_person(params);
  with_person.grid.fill(9, 43, 17, 46, CellState::occupied);
  ASSERT_TRUE(with_person.map.rebuild(with_person.grid.view(), robot, robot));
  ASSERT_EQ(with_person.planner.plan(with_person.map, robot_cell, goal_cell, with_person.plan), PlanResult::found);
  DoorAxis axis(params);
  axis.update(with_person.plan, 0, with_person.map, robot);
  ASSERT_TRUE(axis.passage().known);
  const DoorPassage skewed = axis.passage();
  std::printf("the gap beside the person: middle (%.2f, %.2f), axis %.1f degrees off the door's\n", skewed.middle.x(),
              skewed.middle.y(), core::radians_to_degrees(std::acos(skewed.along.y())));
  ASSERT_LT(skewed.along.y(), std::cos(core::degrees_to_radians(kSameDoorAngle_deg)));

  Doorway gone(params);
  ASSERT_TRUE(gone.map.rebuild(gone.grid.view(), robot, robot));
  ASSERT_EQ(gone.planner.plan(gone.map, robot_cell, goal_cell, gone.plan), PlanResult::found);
  axis.update(gone.plan, 0, gone.map, robot);
  ASSERT_TRUE(axis.passage().known);
  EXPECT_NEAR(axis.passage().along.y(), 1.0, 1e-9);
  EXPECT_NEAR(axis.passage().middle.x(), kMiddleX, 1e-9);
  EXPECT_FALSE(same_door(skewed, axis.passage()));
  axis.follow_sighting(skewed);
  EXPECT_NEAR(axis.passage().along.y(), 1.0, 1e-9);
}

// A held door sighting measured the pose against its own find of the door, whose middle can lie
// a cell aside of the axis's (the grid's jamb cells move between plans): the axis runs through
// the sighted door from then on, and later finds of the same door keep it there. Another door
// leaves the axis as it is, and an axis with no door (the plan no longer passes it) gets none.
TEST(DoorAxis, RunsThroughTheDoorTheSightingMeasuredThePoseAgainst) {
  ExploreParams params = test_params(60, 80);
  params.explore.door_axis_before_m = 0.6;
  params.explore.door_axis_all_gaps = true;
  Doorway door(params);
  const Eigen::Vector2d robot(1.5, 4.9);
  ASSERT_TRUE(door.map.rebuild(door.grid.view(), robot, robot));
  ASSERT_EQ(door.planner.plan(door.map, {15, 49}, {25, 25}, door.plan), PlanResult::found);
  DoorAxis axis(params);
  axis.update(door.plan, 0, door.map, robot);
  ASSERT_TRUE(axis.passage().known);
  ASSERT_NEAR(axis.passage().middle.x(), kMiddleX, 1e-9);

  DoorPassage sighted = axis.passage();
  sighted.middle.x() += 0.1;
  axis.follow_sighting(sighted);
  EXPECT_NEAR(axis.passage().middle.x(), kMiddleX + 0.1, 1e-9);
  axis.update(door.plan, 0, door.map, robot);
  EXPECT_NEAR(axis.passage().middle.x(), kMiddleX + 0.1, 1e-9);

  DoorPassage other = sighted;
  other.middle.x() += 1.0;
  axis.follow_sighting(other);
  EXPECT_NEAR(axis.passage().middle.x(), kMiddleX + 0.1, 1e-9);

  DoorAxis fresh(params);
  fresh.follow_sighting(sighted);
  EXPECT_FALSE(fresh.passage().known);
}

}  // namespace
}  // namespace stereoscout::explore
