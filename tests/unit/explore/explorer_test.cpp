// The exploration behaviour on hand-made grids: replanning, blacklisting, safety stops,
// the emergency stop, the look around, termination, and no allocation in step().
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/explore/explorer.hpp"
#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

using testing::TestGrid;
using testing::test_params;

// A 10 x 6 m known room with an unknown region beyond x = 8 m: the goal lies towards it.
struct Corridor {
  TestGrid grid{100, 60, CellState::free};
  Corridor() {
    grid.walls();
    grid.fill(80, 1, 99, 59, CellState::unknown);
  }
};

ExploreInput input_at(const GridView& grid, double x, double y, double theta, double time_s, bool updated) {
  ExploreInput input;
  input.time_s = time_s;
  input.pose = core::Pose2{x, y, theta};
  input.odometry = input.pose;  // the wheels went where the estimate did: no correction
  input.grid = grid;
  input.grid_updated = updated;
  return input;
}

// How many events of `kind` the explorer's journal holds.
std::size_t journaled(const Explorer& explorer, ExploreEventKind kind) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < explorer.journal().size(); ++i) {
    if (explorer.journal()[i].kind == kind) ++count;
  }
  return count;
}

ExploreParams no_look_params(int width, int height) {
  ExploreParams params = test_params(width, height);
  params.explore.pan_at_goal = false;
  params.explore.return_to_start = false;
  return params;
}

TEST(Explorer, DrivesTowardsTheUnknownWithinTheLimits) {
  Corridor scene;
  const ExploreParams params = no_look_params(100, 60);
  Explorer explorer(params);
  const ExploreOutput output = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  ASSERT_EQ(output.state, ExploreState::drive);
  ASSERT_TRUE(explorer.goal().valid);
  EXPECT_GT(explorer.goal().position.x(), 4.0);
  EXPECT_GT(output.drive.linear_mps, 0.0);
  EXPECT_LE(output.drive.linear_mps, params.max_speed_mps);
  EXPECT_LE(std::abs(output.drive.angular_rad_s), params.max_turn_rate_rad_s);
  EXPECT_EQ(explorer.counters().goals_chosen, 1U);
}

TEST(Explorer, ReplansWhenAnObstacleAppearsOnThePath) {
  Corridor scene;
  Explorer explorer(no_look_params(100, 60));
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  ASSERT_EQ(explorer.state(), ExploreState::drive);
  // A wall across the middle of the room with a gap at the top, right over the plan.
  scene.grid.fill(40, 1, 42, 45, CellState::occupied);
  bool crossed = false;
  for (const Eigen::Vector2i& cell : explorer.plan().cells) crossed = crossed || (cell.x() >= 40 && cell.x() < 42);
  ASSERT_TRUE(crossed);
  const ExploreOutput output = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 1.0, true));
  EXPECT_EQ(explorer.counters().replans, 1U);
  EXPECT_EQ(output.state, ExploreState::drive);
  for (const Eigen::Vector2i& cell : explorer.plan().cells) {
    EXPECT_TRUE(explorer.navigation_map().passable(cell.x(), cell.y()));
    if (cell.x() >= 40 && cell.x() < 42) {
      EXPECT_GE(cell.y(), 45 + 4);  // through the gap
    }
  }
}

// The row at which the explorer's plan crosses the cells of column x (-1: it does not).
int crossing_row(const Explorer& explorer, int x) {
  for (const Eigen::Vector2i& cell : explorer.plan().cells) {
    if (cell.x() == x) return cell.y();
  }
  return -1;
}

// A plan made across an open room; then a wall with a door goes up around its crossing, whose
// far jamb leaves the kept crossing passable but within the safety margin, 0.15 m off the
// door's middle (as office seed 4's plan at 1520 s). The kept plan is only blocked where a
// cell turns impassable, so without plan_switch_saving_m it stays at the jamb; with it, a
// fresh plan through the door's middle cells is taken, once; but not while the door is
// farther ahead than plan_switch_within_m (1.5 m away here).
TEST(Explorer, AKeptPlanThatAJambMakesCostlyIsSwitchedForACheaperOne) {
  for (const auto& [saving, within] : {std::pair{0.0, 1.5}, std::pair{0.25, 1.0}, std::pair{0.25, 1.6}}) {
    Corridor scene;
    ExploreParams params = no_look_params(100, 60);
    params.explore.plan_switch_saving_m = saving;
    params.explore.plan_switch_within_m = within;
    Explorer explorer(params);
    explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
    ASSERT_EQ(explorer.state(), ExploreState::drive);
    const int row = crossing_row(explorer, 30);
    ASSERT_GT(row, 10);
    ASSERT_LT(row, 50);
    // Jamb cells' centres 1.1 m apart: passable rows row-3 .. row (0.4 m or more from both),
    // of which row-2 and row-1 are outside the safety margin (0.5 m or more).
    scene.grid.fill(30, 1, 31, row - 6, CellState::occupied);
    scene.grid.fill(30, row + 4, 31, 59, CellState::occupied);
    explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 1.0, true));
    ASSERT_TRUE(explorer.navigation_map().passable(30, row));
    ASSERT_NE(explorer.navigation_map().traversability(30, row), Traversability::safe);
    EXPECT_EQ(explorer.counters().replans, 0U) << saving;  // nothing on the plan impassable
    if (saving == 0.0 || within < 1.5) {
      EXPECT_EQ(crossing_row(explorer, 30), row);
      EXPECT_EQ(explorer.counters().plans_switched, 0U);
      continue;
    }
    const int switched = crossing_row(explorer, 30);
    EXPECT_TRUE(switched == row - 2 || switched == row - 1) << switched << " " << row;
    EXPECT_EQ(explorer.counters().plans_switched, 1U);
    EXPECT_EQ(journaled(explorer, ExploreEventKind::plan_switched), 1U);
    EXPECT_EQ(explorer.plan().cells[0], Eigen::Vector2i(15, 30));  // from the robot's cell
    // The same map again: the plan is the cheapest on it, and it stays.
    explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 2.0, true));
    EXPECT_EQ(explorer.counters().plans_switched, 1U);
    EXPECT_EQ(crossing_row(explorer, 30), switched);
  }
}

ExploreParams standing_robot_params(bool wait_for_walkers) {
  ExploreParams params = no_look_params(100, 60);
  params.explore.wait_for_walkers = wait_for_walkers;
  params.explore.trace_forget_after_s = 10.0;
  params.explore.stall_min_commanded_m = 1000.0;  // the robot stands still here: no stall
  return params;
}

// A person across the plan: the cells around its waypoint `ahead`.
void fill_across_plan(Corridor& scene, const Eigen::Vector2i& ahead, CellState state) {
  scene.grid.fill(ahead.x(), ahead.y() - 1, ahead.x() + 2, ahead.y() + 2, state);
}

// A person crosses the plan 3 m ahead: the cells they leave where the floor was free block it
// for a few updates. With wait_for_walkers the plan is kept (the person will have walked on);
// the same cells, once older than trace_forget_after_s, are an obstacle to plan around.
TEST(Explorer, APlanBlockedOnlyByAPasserByIsKeptWithWaitForWalkers) {
  for (const bool wait : {false, true}) {
    Corridor scene;
    Explorer explorer(standing_robot_params(wait));
    explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
    ASSERT_EQ(explorer.state(), ExploreState::drive);
    fill_across_plan(scene, explorer.plan().cells[30], CellState::occupied);
    explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 1.0, true));
    EXPECT_EQ(explorer.counters().replans, wait ? 0U : 1U) << wait;
    EXPECT_EQ(explorer.counters().plans_kept_for_walkers, wait ? 1U : 0U) << wait;
    EXPECT_EQ(explorer.state(), ExploreState::drive);
    if (!wait) continue;
    // Still there 10 s later: no passer-by.
    explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 11.0, true));
    EXPECT_EQ(explorer.counters().replans, 1U);
    for (const Eigen::Vector2i& cell : explorer.plan().cells) {
      EXPECT_TRUE(explorer.navigation_map().passable(cell.x(), cell.y()));
    }
  }
}

// A passer-by's cells across the kept plan 1 m ahead: with walker_hold_s the robot stands still
// (no drive, no turn) until the hold ends, then drives on along the same plan. Across it 3 m
// ahead, beyond walker_hold_within_m, the robot drives on at once.
TEST(Explorer, APasserByNearAKeptPlanHoldsTheRobotStillForWalkerHoldS) {
  for (const std::size_t ahead : {std::size_t{10}, std::size_t{30}}) {
    Corridor scene;
    ExploreParams params = standing_robot_params(true);
    params.explore.walker_hold_s = 3.0;
    params.explore.walker_hold_within_m = 1.5;
    Explorer explorer(params);
    explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
    ASSERT_EQ(explorer.state(), ExploreState::drive);
    fill_across_plan(scene, explorer.plan().cells[ahead], CellState::occupied);
    const ExploreOutput kept = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 1.0, true));
    ASSERT_EQ(explorer.counters().plans_kept_for_walkers, 1U);
    const bool near = ahead == 10;
    EXPECT_EQ(explorer.counters().walker_holds, near ? 1U : 0U) << ahead;
    const ExploreOutput held = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 3.9, false));
    for (const ExploreOutput& output : {kept, held}) {
      EXPECT_EQ(output.drive.linear_mps == 0.0 && output.drive.angular_rad_s == 0.0, near) << ahead;
    }
    const ExploreOutput after = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 4.1, false));
    EXPECT_GT(after.drive.linear_mps, 0.0) << ahead;
    EXPECT_EQ(explorer.counters().replans, 0U) << ahead;
    EXPECT_EQ(journaled(explorer, ExploreEventKind::walker_hold), near ? 1U : 0U) << ahead;
  }
}

// Cells that look like a passer-by's can be a blank wall's, erased by grazing rays and restored
// by the next view. So a goal's plans are kept for walker_wait_per_goal_s in all (the spans
// add up), then replanned as without wait_for_walkers.
TEST(Explorer, APlanKeptForWalkersIsReplannedOnceTheGoalsWaitIsUsedUp) {
  Corridor scene;
  ExploreParams params = standing_robot_params(true);
  params.explore.walker_wait_per_goal_s = 5.0;
  Explorer explorer(params);
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  ASSERT_EQ(explorer.state(), ExploreState::drive);
  const Eigen::Vector2i ahead = explorer.plan().cells[30];
  const auto block = [&](CellState state) { fill_across_plan(scene, ahead, state); };
  block(CellState::occupied);
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 1.0, true));  // waiting from 1 s
  block(CellState::free);
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 3.0, true));  // walked on: 2 s waited
  block(CellState::occupied);
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 4.0, true));  // waiting again from 4 s
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 6.5, true));  // 4.5 s in all
  EXPECT_EQ(explorer.counters().plans_kept_for_walkers, 3U);
  EXPECT_EQ(explorer.counters().replans, 0U);
  const auto spans_journaled = [&explorer] { return journaled(explorer, ExploreEventKind::plan_kept); };
  EXPECT_EQ(spans_journaled(), 2U);  // once at the start of each span
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 8.0, true));  // 6 s in all: used up
  EXPECT_EQ(explorer.counters().plans_kept_for_walkers, 3U);
  EXPECT_EQ(explorer.counters().walker_waits_ended, 1U);
  EXPECT_EQ(explorer.counters().replans, 1U);
  // A new passer-by across the new plan: refused at once, and not journaled as kept.
  fill_across_plan(scene, explorer.plan().cells[30], CellState::occupied);
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 9.0, true));
  EXPECT_EQ(explorer.counters().walker_waits_ended, 2U);
  EXPECT_EQ(explorer.counters().replans, 2U);
  EXPECT_EQ(spans_journaled(), 2U);
  EXPECT_EQ(explorer.state(), ExploreState::drive);
  for (const Eigen::Vector2i& cell : explorer.plan().cells) {
    EXPECT_TRUE(explorer.navigation_map().passable(cell.x(), cell.y()));
  }
}

// An obstacle cell appears on the goal itself (a person's trace, a stereo outlier): the goal is
// not failed; the plan goes to the nearest passable cell within goal_shift_radius_m. With the
// shift off, the same update fails the goal.
TEST(Explorer, AGoalWhoseCellBecomesImpassableIsShiftedNotFailed) {
  for (const double shift_radius_m : {0.5, 0.0}) {
    Corridor scene;
    ExploreParams params = no_look_params(100, 60);
    params.explore.goal_shift_radius_m = shift_radius_m;
    Explorer explorer(params);
    explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
    ASSERT_EQ(explorer.state(), ExploreState::drive);
    const Goal goal = explorer.goal();
    scene.grid.set(goal.cell.x(), goal.cell.y(), CellState::occupied);
    explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 1.0, true));
    if (shift_radius_m == 0.0) {
      EXPECT_EQ(explorer.counters().goal_failures, 1U);
      EXPECT_EQ(explorer.counters().goal_shifts, 0U);
      continue;
    }
    EXPECT_EQ(explorer.state(), ExploreState::drive);
    EXPECT_EQ(explorer.counters().goal_failures, 0U);
    EXPECT_EQ(explorer.counters().goal_shifts, 1U);
    EXPECT_EQ(explorer.goal().cell, goal.cell);  // the goal (its value, the memory) is unchanged
    ASSERT_FALSE(explorer.plan().cells.empty());
    const Eigen::Vector2i end = explorer.plan().cells.back();
    EXPECT_TRUE(explorer.navigation_map().passable(end.x(), end.y()));
    EXPECT_LE((end - goal.cell).cast<double>().norm() * 0.1, shift_radius_m + 1e-9);
    EXPECT_GE((end - goal.cell).cast<double>().norm() * 0.1, params.robot_radius_m - 0.1);
  }
}

// Beside an obstacle, pure pursuit's heading can cut the plan's corner: the point just ahead
// would touch the obstacle where the plan keeps clear. The robot turns to face the plan and
// drives on, with no safety stop (before: stop, look, the same command, stop again, for ever).
TEST(Explorer, TurnsToFaceThePlanWhenOnlyTheCornerCutIsBlocked) {
  Corridor scene;
  const ExploreParams params = no_look_params(100, 60);
  Explorer explorer(params);
  const Eigen::Vector2d robot(2.0, 3.0);
  explorer.step(input_at(scene.grid.view(), robot.x(), robot.y(), 0.0, 0.0, true));
  ASSERT_EQ(explorer.state(), ExploreState::drive);
  // The plan's direction from the robot (its first waypoint at least 0.15 m away); the robot
  // heads 24 degrees right of it (the plan turns left), within the follower's turn-in-place angle.
  Eigen::Vector2d towards = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& waypoint : explorer.plan().waypoints) {
    if ((waypoint - robot).norm() >= 0.15) {
      towards = (waypoint - robot).normalized();
      break;
    }
  }
  const double plan_heading = std::atan2(towards.y(), towards.x());
  const double first_heading = plan_heading - core::degrees_to_radians(24.0);
  double heading = first_heading;
  const Eigen::Vector2d ahead = robot + 0.15 * Eigen::Vector2d(std::cos(heading), std::sin(heading));
  const Eigen::Vector2d facing = robot + 0.15 * towards;
  // An obstacle cell on the right that the disc just ahead would touch, and neither the robot
  // where it stands, nor the disc just ahead along the plan, nor the plan's next 0.6 m.
  const double radius = params.robot_radius_m;
  const auto centre = [](int x, int y) { return Eigen::Vector2d(0.1 * x + 0.05, 0.1 * y + 0.05); };
  Eigen::Vector2i obstacle(-1, -1);
  for (int y = 25; y < 40 && obstacle.x() < 0; ++y) {
    for (int x = 15; x < 30 && obstacle.x() < 0; ++x) {
      const Eigen::Vector2d cell = centre(x, y);
      bool clear_of_plan = (cell - robot).norm() > radius + 0.01 && (cell - facing).norm() > radius + 0.005;
      for (const Eigen::Vector2d& waypoint : explorer.plan().waypoints) {
        if ((waypoint - robot).norm() < 0.6) clear_of_plan = clear_of_plan && (cell - waypoint).norm() > radius + 0.005;
      }
      if (clear_of_plan && (cell - ahead).norm() < radius - 0.005) obstacle = {x, y};
    }
  }
  ASSERT_GE(obstacle.x(), 0);
  scene.grid.set(obstacle.x(), obstacle.y(), CellState::occupied);  // no rebuild: the plan stays
  double time = 0.1;
  ExploreOutput output = explorer.step(input_at(scene.grid.view(), robot.x(), robot.y(), heading, time, false));
  EXPECT_EQ(output.drive.linear_mps, 0.0);
  EXPECT_GT(output.drive.angular_rad_s, 0.0);  // towards the plan, away from the obstacle
  EXPECT_EQ(explorer.counters().turns_to_face_plan, 1U);
  const double dt = 0.02;
  for (int tick = 0; tick < 500 && output.drive.linear_mps == 0.0; ++tick) {
    heading += output.drive.angular_rad_s * dt;
    time += dt;
    output = explorer.step(input_at(scene.grid.view(), robot.x(), robot.y(), heading, time, false));
  }
  EXPECT_GT(output.drive.linear_mps, 0.0);
  EXPECT_EQ(explorer.counters().safety_stops, 0U);
  EXPECT_GT(heading, first_heading);  // it drives on once the point ahead is clear
}

// Something appears beside the path where the floor was free (a person stepping in): the
// robot keeps fresh_obstacle_margin_m more clearance from it: it does not drive on where it
// would have driven past a static obstacle at the same place (it stops, or turns away towards
// its plan); once the cell is no longer fresh it drives on.
TEST(Explorer, KeepsMoreClearanceFromAnObstacleThatJustAppeared) {
  for (const double margin_m : {0.3, 0.0}) {
    Corridor scene;
    ExploreParams params = no_look_params(100, 60);
    params.explore.fresh_obstacle_margin_m = margin_m;
    Explorer explorer(params);
    const ExploreOutput first = explorer.step(input_at(scene.grid.view(), 1.5, 3.05, 0.0, 0.0, true));
    ASSERT_GT(first.drive.linear_mps, 0.0);
    // 0.55 m to the side of the path, 0.2 m ahead: outside the disc, within disc + margin.
    scene.grid.set(17, 36, CellState::occupied);
    const ExploreOutput next = explorer.step(input_at(scene.grid.view(), 1.5, 3.05, 0.0, 0.5, true));
    if (margin_m == 0.0) {
      EXPECT_GT(next.drive.linear_mps, 0.0);
      EXPECT_EQ(explorer.counters().safety_stops, 0U);
      continue;
    }
    EXPECT_EQ(next.drive.linear_mps, 0.0);
    EXPECT_EQ(explorer.counters().safety_stops + explorer.counters().turns_to_face_plan, 1U);  // stopped, or turned away
    ExploreOutput later;
    for (double time = 0.55; time < 4.0; time += 0.05) {
      later = explorer.step(input_at(scene.grid.view(), 1.5, 3.05, 0.0, time, false));
    }
    EXPECT_GT(later.drive.linear_mps, 0.0);  // 3 s on, the cell is an ordinary obstacle
  }
}

// A scan saw a surface at the camera's height 1 m ahead (a jamb) that the grid does not hold
// (the estimate's lineage erased it). With recent_obstacle_s the plan keeps clear of it, and
// when the estimate jumps 0.3 m sideways with no odometry motion, the surface moves with the
// robot: it stays 1 m ahead of the pose the explorer now has.
bool plan_clear_of(const Explorer& explorer, const Eigen::Vector2d& point, double radius_m) {
  for (const Eigen::Vector2d& waypoint : explorer.plan().waypoints) {
    if ((waypoint - point).norm() < radius_m) return false;
  }
  return true;
}

TEST(Explorer, PlansKeepClearOfWhatARecentScanSawWhereTheGridHoldsNothing) {
  core::DepthScan scan;
  for (double y = -0.3; y <= 0.3 + 1e-9; y += 0.01) {
    core::DepthScanColumn column;
    column.x_robot_m = 1.0F;
    column.y_robot_m = static_cast<float>(y);
    column.kind = core::DepthScanColumn::Kind::obstacle;
    column.obstacle_at_camera_height = true;
    scan.columns.push_back(column);
  }
  for (const double keep_s : {0.0, 30.0}) {
    Corridor scene;
    ExploreParams params = no_look_params(100, 60);
    params.explore.recent_obstacle_s = keep_s;
    Explorer explorer(params);
    ExploreInput input = input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true);
    const core::Pose2 odometry = input.odometry;
    input.seen.scan = &scan;
    input.seen.time_s = 0.0;
    input.seen.pose = input.pose;
    input.seen.odometry = odometry;
    explorer.step(input);
    ASSERT_EQ(explorer.state(), ExploreState::drive);
    const double radius = params.robot_radius_m;
    const bool clear = plan_clear_of(explorer, {2.5, 3.0}, radius);
    if (keep_s == 0.0) {
      EXPECT_FALSE(clear);  // straight through: the grid is all there is
      continue;
    }
    EXPECT_TRUE(clear);
    EXPECT_GT(explorer.recent_obstacles().cells_stamped(), 0U);
    // The estimate jumps to (1.5, 3.3); odometry did not move.
    input = input_at(scene.grid.view(), 1.5, 3.3, 0.0, 1.0, true);
    input.odometry = odometry;
    input.seen.odometry = odometry;
    input.seen.scan = &scan;
    input.seen.time_s = 0.0;  // the same scan: not observed again
    explorer.step(input);
    const GridView& planned_on = explorer.navigation_map().grid();
    const auto occupied = [&planned_on](double x, double y) {
      const Eigen::Vector2i cell = planned_on.cell_of({x, y});
      return planned_on.at(cell.x(), cell.y()) == CellState::occupied;
    };
    EXPECT_TRUE(occupied(2.55, 3.55));   // the surface's left end, 1 m ahead of the new pose
    EXPECT_FALSE(occupied(2.55, 2.75));  // where its right end was from the old one
    EXPECT_TRUE(plan_clear_of(explorer, {2.5, 3.3}, radius));
    EXPECT_EQ(explorer.recent_obstacles().kept(), explorer.recent_obstacles().held());
  }
}

TEST(Explorer, StopsBeforeAnOccupiedCellAheadEvenBeforeTheMapIsRebuilt) {
  Corridor scene;
  Explorer explorer(no_look_params(100, 60));
  const ExploreOutput first = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  ASSERT_GT(first.drive.linear_mps, 0.0);
  // An obstacle 0.4 m ahead on the plan appears in the grid; no observation update flagged.
  scene.grid.set(19, 30, CellState::occupied);
  const ExploreOutput stopped = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.1, false));
  EXPECT_EQ(stopped.drive.linear_mps, 0.0);  // turning in place stays allowed
  EXPECT_EQ(explorer.counters().safety_stops, 1U);
  // Next tick: map rebuilt, plan goes around, motion resumes on a clear stretch.
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.2, false));
  EXPECT_EQ(explorer.counters().replans, 1U);
  for (const Eigen::Vector2i& cell : explorer.plan().cells) EXPECT_NE(cell, Eigen::Vector2i(19, 30));
}

// What the latest scan saw at the camera's height stops the robot before the grid holds it: a
// person walking towards it is in the scan at once, and in the grid only some updates later.
struct ScanGuardCase {
  int min_points = 8;
  int points = 20;
  double ahead_m = 0.55;     // the person's centre, straight ahead of the robot along its plan
  double scan_age_s = 0.05;  // since the scan's pair was captured
};

struct ScanGuardResult {
  ExploreOutput output;
  ExploreCounters counters;
  ExploreEventKind last_event = ExploreEventKind::goal_chosen;
  double drives_on_at_s = -1.0;  // when it moved again (forward or turning)
  ExploreCounters counters_then;
};

// With `empty_scan_at_s` >= 0, a newer scan without the person arrives then (they came nearer
// than the matcher sees).
ScanGuardResult drive_past_seen_person(const ScanGuardCase& scene_case, double empty_scan_at_s = -1.0) {
  Corridor scene;
  ExploreParams params = no_look_params(100, 60);
  params.explore.scan_guard_min_points = scene_case.min_points;
  Explorer explorer(params);
  const ExploreOutput first = explorer.step(input_at(scene.grid.view(), 1.55, 3.05, 0.0, 0.0, true));
  EXPECT_GT(first.drive.linear_mps, 0.0);
  // Facing the plan, as the robot does when driving straight on: a robot off its plan turns to
  // face it first, and stops then.
  const Eigen::Vector2d robot(1.55, 3.05);
  Eigen::Vector2d along = Eigen::Vector2d::UnitX();
  for (const Eigen::Vector2d& waypoint : explorer.plan().waypoints) {
    if ((waypoint - robot).norm() < 0.15) continue;
    along = (waypoint - robot).normalized();
    break;
  }
  const double heading = std::atan2(along.y(), along.x());
  // The near half of a person of radius 0.25 m, as the scan's columns see them.
  std::vector<Eigen::Vector2d> person;
  for (int i = 0; i < scene_case.points; ++i) {
    const double angle = heading + M_PI * (0.5 + static_cast<double>(i) / std::max(1, scene_case.points - 1));
    person.push_back(robot + scene_case.ahead_m * along + 0.25 * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  ExploreInput input = input_at(scene.grid.view(), robot.x(), robot.y(), heading, 0.05, false);
  input.seen = SeenObstacles{person.data(), person.size(), 0.05 - scene_case.scan_age_s, nullptr, {}, {}};
  ScanGuardResult result;
  result.output = explorer.step(input);
  result.counters = explorer.counters();
  result.last_event = explorer.journal()[explorer.journal().size() - 1].kind;
  for (double time = 0.1; time < 4.0 && result.drives_on_at_s < 0.0; time += 0.05) {
    input.time_s = time;
    if (empty_scan_at_s >= 0.0 && time >= empty_scan_at_s - 1e-9) input.seen = SeenObstacles{person.data(), 0, empty_scan_at_s, nullptr, {}, {}};
    const core::DriveCommand drive = explorer.step(input).drive;
    if (drive.linear_mps != 0.0 || drive.angular_rad_s != 0.0) result.drives_on_at_s = time;
  }
  result.counters_then = explorer.counters();
  return result;
}

TEST(Explorer, StopsForAPersonTheLatestScanSawBeforeTheGridHoldsThem) {
  // 0.55 m ahead (within the grid's 0.5 m check), and 1.2 m ahead (beyond it, within the
  // scan guard's 0.8 m: the matcher does not see the person once nearer than 0.73 m).
  ScanGuardCase beyond_grid_check;
  beyond_grid_check.ahead_m = 1.2;
  for (const ScanGuardCase& scene_case : {ScanGuardCase{}, beyond_grid_check}) {
    const ScanGuardResult seen = drive_past_seen_person(scene_case);
    EXPECT_EQ(seen.output.drive.linear_mps, 0.0) << scene_case.ahead_m << " m ahead";
    EXPECT_EQ(seen.output.state, ExploreState::drive);  // no look: it stands and waits
    EXPECT_EQ(seen.counters.scan_guard_stops, 1U);
    EXPECT_EQ(seen.counters.safety_stops, 0U);
    EXPECT_EQ(seen.last_event, ExploreEventKind::scan_stop);
    // A standing robot makes no update: it holds until the scan is scan_guard_max_age_s old
    // (captured at 0 s), once, and drives on.
    EXPECT_NEAR(seen.drives_on_at_s, 2.05, 0.06);
    EXPECT_EQ(seen.counters_then.scan_guard_stops, 1U);
    EXPECT_EQ(seen.counters_then.looks, 0U);
  }
  // A newer scan 0.3 s into the hold no longer shows the person (nearer than the matcher
  // sees): the hold still lasts until the scan that found them is 2 s old.
  const ScanGuardResult too_near = drive_past_seen_person(ScanGuardCase{}, 0.3);
  EXPECT_NEAR(too_near.drives_on_at_s, 2.05, 0.06);
  EXPECT_EQ(too_near.counters_then.scan_guard_stops, 1U);
  // Fewer points than scan_guard_min_points (stray matches), an old scan, the guard off, or
  // a person beyond the checked stretch: it drives on.
  ScanGuardCase stray;
  stray.points = 7;
  ScanGuardCase old_scan;
  old_scan.scan_age_s = 2.5;
  ScanGuardCase off;
  off.min_points = 0;
  ScanGuardCase far;
  far.ahead_m = 1.5;
  for (const ScanGuardCase& scene_case : {stray, old_scan, off, far}) {
    const ScanGuardResult result = drive_past_seen_person(scene_case);
    EXPECT_GT(result.output.drive.linear_mps, 0.0) << scene_case.points << " points " << scene_case.ahead_m << " m ahead";
    EXPECT_EQ(result.counters.safety_stops, 0U);
  }
}

// A surface the grid does not hold (a blank wall: no disparity, its cells stay free or
// unknown) stops the robot: it commands forward motion and the pose stands still. The
// explorer notices within two stall windows, keeps the cell it pushes against as occupied for
// planning, and the next plan leads around it.
TEST(Explorer, AStallMarksTheContactAndThePlanLeadsAroundIt) {
  Corridor scene;
  ExploreParams params = no_look_params(100, 60);
  params.explore.stall_back_off_m = 0.0;  // replans where it stands (the back-off: below)
  Explorer explorer(params);
  ASSERT_GT(explorer.step(input_at(scene.grid.view(), 1.52, 3.0, 0.0, 0.0, true)).drive.linear_mps, 0.0);
  double time_s = 0.0;
  while (explorer.counters().stalls == 0 && time_s < 5.0) {
    time_s += 0.05;
    explorer.step(input_at(scene.grid.view(), 1.52, 3.0, 0.0, time_s, false));
  }
  ASSERT_EQ(explorer.counters().stalls, 1U);
  EXPECT_LE(time_s, 2.0 * params.explore.stall_window_s + 0.1);
  EXPECT_EQ(explorer.contacts().held(), 3U);
  const ExploreOutput next = explorer.step(input_at(scene.grid.view(), 1.52, 3.0, 0.0, time_s + 0.05, false));
  EXPECT_EQ(explorer.navigation_map().grid().at(19, 30), CellState::occupied);
  EXPECT_EQ(scene.grid.view().at(19, 30), CellState::free);  // the grid itself is not changed
  EXPECT_EQ(next.state, ExploreState::drive);
  ASSERT_FALSE(explorer.plan().empty());
  for (std::size_t k = 1; k < explorer.plan().cells.size(); ++k) {  // after the robot's own cell
    const Eigen::Vector2i& cell = explorer.plan().cells[k];
    EXPECT_TRUE(explorer.navigation_map().passable(cell.x(), cell.y())) << k;
    EXPECT_NE(cell, Eigen::Vector2i(19, 30));
  }
}

// The robot drives on at the commanded speed by odometry while the pose estimate, corrected at
// an update, steps 0.1 m back along the way 0.7 s in (office seed 1 at 222.7 s). Returns the
// stalls in the first second (one stall window).
std::uint64_t stalls_after_a_correction_back(bool stall_from_odometry) {
  Corridor scene;
  ExploreParams params = no_look_params(100, 60);
  params.explore.stall_from_odometry = stall_from_odometry;
  Explorer explorer(params);
  double x = 1.52;
  ExploreInput input = input_at(scene.grid.view(), x, 3.0, 0.0, 0.0, true);
  double linear_mps = explorer.step(input).drive.linear_mps;
  for (double time_s = 0.05; time_s < 1.025; time_s += 0.05) {
    x += 0.05 * linear_mps;
    const double correction_m = time_s >= 0.7 ? -0.1 : 0.0;
    input = input_at(scene.grid.view(), x + correction_m, 3.0, 0.0, time_s, false);
    input.odometry = core::Pose2{x, 3.0, 0.0};
    linear_mps = explorer.step(input).drive.linear_mps;
  }
  return explorer.counters().stalls;
}

// With stall_from_odometry a correction of the estimate is no stall; without, it is one.
TEST(Explorer, WithStallFromOdometryAnEstimateCorrectedBackIsNoStall) {
  EXPECT_EQ(stalls_after_a_correction_back(false), 1U);
  EXPECT_EQ(stalls_after_a_correction_back(true), 0U);
}

// With stall_from_odometry a robot whose wheels stand still stalls as before.
TEST(Explorer, WithStallFromOdometryARobotThatDoesNotMoveStalls) {
  Corridor scene;
  ExploreParams params = no_look_params(100, 60);
  params.explore.stall_from_odometry = true;
  params.explore.stall_back_off_m = 0.0;
  Explorer explorer(params);
  ExploreInput input = input_at(scene.grid.view(), 1.52, 3.0, 0.0, 0.0, true);
  input.odometry = core::Pose2{7.0, -2.0, 1.0};  // odometry's own frame
  ASSERT_GT(explorer.step(input).drive.linear_mps, 0.0);
  double time_s = 0.0;
  while (explorer.counters().stalls == 0 && time_s < 5.0) {
    time_s += 0.05;
    input.time_s = time_s;
    input.grid_updated = false;
    input.pose.x += 0.006;  // the estimate drifts on; the wheels stand still
    explorer.step(input);
  }
  EXPECT_EQ(explorer.counters().stalls, 1U);
  EXPECT_LE(time_s, 2.0 * params.explore.stall_window_s + 0.1);
}

// A 10 x 6 m room split by a thin wall at x = 3 m with a 0.9 m door (rows 26-34); the unknown
// beyond x = 8 m lies behind the door. The robot is narrower than the default (0.33 m) so that
// no clearance lies on the lethal distance and the scene's passable cells are clear-cut.
struct DoorScene {
  TestGrid grid{100, 60, CellState::free};
  DoorScene() {
    grid.walls();
    grid.fill(30, 1, 31, 26, CellState::occupied);
    grid.fill(30, 35, 31, 59, CellState::occupied);
    grid.fill(80, 1, 99, 59, CellState::unknown);
  }
};

// Holds the robot still at (x, y) facing theta, commanding forward motion, until it stalls;
// returns the output of the tick that found the stall (time_s: that tick's time).
ExploreOutput stall_at(Explorer& explorer, const GridView& grid, double x, double y, double theta, double& time_s) {
  const std::uint64_t stalls = explorer.counters().stalls;
  ExploreOutput output;
  for (const double end = time_s + 5.0; explorer.counters().stalls == stalls && time_s < end;) {
    time_s += 0.05;
    output = explorer.step(input_at(grid, x, y, theta, time_s, false));
  }
  return output;
}

// The robot touches the jamb in the door: the contact cells close the door to it, and nothing
// reachable is left on its side. It clears them rather than conclude "explored" at a closed door.
TEST(Explorer, ContactsThatCloseTheOnlyDoorAreClearedBeforeConcluding) {
  DoorScene scene;
  ExploreParams params = no_look_params(100, 60);
  params.robot_radius_m = 0.33;
  params.explore.stall_back_off_m = 0.0;
  Explorer explorer(params);
  ASSERT_EQ(explorer.step(input_at(scene.grid.view(), 3.05, 3.05, 0.0, 0.0, true)).state, ExploreState::drive);
  double time_s = 0.0;
  stall_at(explorer, scene.grid.view(), 3.05, 3.05, 0.0, time_s);
  ASSERT_EQ(explorer.counters().stalls, 1U);
  ASSERT_EQ(explorer.contacts().held(), 3U);
  // The next rebuild finds the plan blocked and no way through the door: the goal fails, no
  // other goal is reachable, so the contacts are cleared and the goal behind the door is chosen.
  const ExploreOutput next = explorer.step(input_at(scene.grid.view(), 3.05, 3.05, 0.0, time_s + 0.05, true));
  EXPECT_EQ(explorer.counters().goal_failures, 1U);
  EXPECT_EQ(explorer.counters().contact_clears, 1U);
  EXPECT_EQ(explorer.contacts().held(), 0U);
  EXPECT_EQ(explorer.contacts().cleared(), 3U);
  EXPECT_EQ(explorer.finish_reason(), FinishReason::none);
  EXPECT_EQ(next.state, ExploreState::drive);
  EXPECT_GT(explorer.goal().position.x(), 3.5);
}

// A 0.8 m door (rows 27-34) in a wall at x = 3.0-3.2 m; the top of the first room (y above
// 5.2 m) and the second room beyond x = 6 m unknown. The robot (0.3 m radius) drives from
// x = 2 m through the door along y = 3.05 m to x = 5 m, where it sees the second room whole. In the same update a cell
// smeared at the door's edge (29, 33) leaves no cell of the door the lethal 0.35 m from every
// occupied one: the door has closed behind it, though it just drove through it, 0.3 m and
// more from that cell.
struct DoorClosedBehind {
  TestGrid grid{100, 60, CellState::free};
  ExploreParams params;
  explicit DoorClosedBehind(ExploreParams base) : params(base) {
    params.robot_radius_m = 0.3;
    params.explore.trace_forget_after_s = 0.0;  // the smeared cell is no person's trace
    params.explore.max_pocket_area_m2 = 0.0;     // the top of the first room is a frontier
    grid.walls();
    grid.fill(30, 1, 32, 27, CellState::occupied);
    grid.fill(30, 35, 32, 59, CellState::occupied);
    grid.fill(1, 52, 30, 59, CellState::unknown);
    grid.fill(60, 1, 99, 59, CellState::unknown);
  }
  // The robot moves at 6 mm a tick, whatever the explorer commands; the output of the tick
  // at time_s that sees the second room and the smeared cell.
  ExploreOutput drive_through_and_smear(Explorer& explorer, double tick_s, double time_s) {
    const GridView view = grid.view();
    explorer.step(input_at(view, 2.0, 3.05, 0.0, 0.0, true));
    EXPECT_GT(explorer.goal().position.x(), 3.2);  // the first goal is in the second room
    double t = 0.0;
    for (double x = 2.0; x <= 5.0; x += 0.006) explorer.step(input_at(view, x, 3.05, 0.0, t += tick_s, false));
    grid.fill(60, 1, 99, 59, CellState::free);
    grid.walls();
    grid.set(29, 33, CellState::occupied);
    return explorer.step(input_at(view, 5.0, 3.05, 0.0, time_s, true));
  }
};

TEST(Explorer, ABoxedInRobotFollowsItsOwnPathBackRatherThanConcludeExplored) {
  DoorClosedBehind scene(no_look_params(100, 60));
  Explorer explorer(scene.params);
  const ExploreOutput output = scene.drive_through_and_smear(explorer, 0.05, 40.0);
  EXPECT_EQ(explorer.finish_reason(), FinishReason::none);
  EXPECT_EQ(output.state, ExploreState::drive);
  EXPECT_EQ(explorer.counters().trail_follows, 1U);
  EXPECT_LT(explorer.goal().position.x(), 3.0);  // the unknown top of the first room
  EXPECT_GT(explorer.goal().position.y(), 3.5);

  // Without the trail it concludes: nothing reachable is left.
  DoorClosedBehind without(no_look_params(100, 60));
  without.params.explore.trail_length_m = 0.0;
  Explorer concluding(without.params);
  without.drive_through_and_smear(concluding, 0.05, 40.0);
  EXPECT_EQ(concluding.finish_reason(), FinishReason::explored);
  EXPECT_EQ(concluding.counters().trail_follows, 0U);
}

// DoorClosedBehind's rooms seen from the first: a near view draws what hangs in the door
// (rows 27-31 of it, leaving 0.3 m) and the goal in the second room fails; then a view from
// afar opens the door again. With shut_gap_hold_s the door stays shut for planning, so the
// next goals are on this side; the door's cells are passable again once the hold is lifted.
struct AfterAViewFromAfar {
  std::unique_ptr<Explorer> explorer;
  bool door_open = false;  // the door's middle passable in the navigation map
};

AfterAViewFromAfar door_after_a_view_from_afar(double shut_gap_hold_s) {
  ExploreParams params = no_look_params(100, 60);
  params.explore.shut_gap_hold_s = shut_gap_hold_s;
  DoorClosedBehind scene(params);
  AfterAViewFromAfar result{std::make_unique<Explorer>(scene.params)};
  Explorer& explorer = *result.explorer;
  explorer.step(input_at(scene.grid.view(), 2.0, 3.05, 0.0, 0.0, true));
  EXPECT_GT(explorer.goal().position.x(), 3.2);  // the first goal is in the second room
  scene.grid.fill(30, 27, 32, 32, CellState::occupied);
  explorer.step(input_at(scene.grid.view(), 2.0, 3.05, 0.0, 0.5, true));
  EXPECT_EQ(explorer.counters().goal_failures, 1U);
  EXPECT_LT(explorer.goal().position.x(), 3.0);  // the unknown top of the first room
  scene.grid.fill(30, 27, 32, 32, CellState::free);
  explorer.step(input_at(scene.grid.view(), 2.0, 3.05, 0.0, 1.0, true));
  result.door_open = explorer.navigation_map().passable(31, 30);
  return result;
}

TEST(Explorer, AGoalFailedAtADoorANearViewShutKeepsTheDoorShutForPlanning) {
  const AfterAViewFromAfar shut = door_after_a_view_from_afar(600.0);
  EXPECT_FALSE(shut.door_open);
  EXPECT_EQ(shut.explorer->shut_gaps().gaps_shut(), 1U);
  EXPECT_EQ(journaled(*shut.explorer, ExploreEventKind::gap_shut), 1U);
  EXPECT_LT(shut.explorer->shut_gaps().last_shut_at().x(), 3.2);  // before the door or in it
  EXPECT_GT(shut.explorer->shut_gaps().last_shut_at().x(), 2.6);
  EXPECT_EQ(shut.explorer->shut_gaps().refused_driven(), 0U);
  // Off, the view from afar opens it.
  const AfterAViewFromAfar off = door_after_a_view_from_afar(0.0);
  EXPECT_TRUE(off.door_open);
  EXPECT_EQ(off.explorer->shut_gaps().gaps_shut(), 0U);
}

// The same door closed behind it on the way back: it follows its trail back to the start.
TEST(Explorer, NoWayBackButItsOwnPathIsNotGivenUp) {
  ExploreParams params = test_params(100, 60);
  params.explore.pan_at_goal = false;
  params.explore.time_limit_s = 10.0;
  DoorClosedBehind scene(params);
  Explorer explorer(scene.params);
  EXPECT_EQ(scene.drive_through_and_smear(explorer, 0.01, 10.0).state, ExploreState::returning);
  EXPECT_EQ(explorer.finish_reason(), FinishReason::time_limit);
  EXPECT_EQ(explorer.counters().return_failures, 0U);
  EXPECT_EQ(explorer.counters().trail_follows, 1U);
  EXPECT_FALSE(explorer.plan().empty());

  DoorClosedBehind without(params);
  without.params.explore.trail_length_m = 0.0;
  Explorer giving_up(without.params);
  EXPECT_EQ(without.drive_through_and_smear(giving_up, 0.01, 10.0).state, ExploreState::finished);
  EXPECT_EQ(giving_up.counters().return_failures, 1U);
}

// On the way back the same contacts would leave no way back at all: they are cleared and the
// return goes on through the door.
TEST(Explorer, ContactsThatCloseTheWayBackAreClearedBeforeGivingItUp) {
  DoorScene scene;
  ExploreParams params = test_params(100, 60);
  params.explore.pan_at_goal = false;
  params.explore.time_limit_s = 10.0;
  params.robot_radius_m = 0.33;
  params.explore.stall_back_off_m = 0.0;
  Explorer explorer(params);
  ASSERT_EQ(explorer.step(input_at(scene.grid.view(), 1.5, 3.05, 0.0, 0.0, true)).state, ExploreState::drive);
  ASSERT_EQ(explorer.step(input_at(scene.grid.view(), 3.05, 3.05, core::kPi, 10.0, true)).state,
            ExploreState::returning);
  double time_s = 10.0;
  stall_at(explorer, scene.grid.view(), 3.05, 3.05, core::kPi, time_s);
  ASSERT_EQ(explorer.counters().stalls, 1U);
  const ExploreOutput next = explorer.step(input_at(scene.grid.view(), 3.05, 3.05, core::kPi, time_s + 0.05, true));
  EXPECT_EQ(explorer.counters().contact_clears, 1U);
  EXPECT_EQ(explorer.counters().return_failures, 0U);
  EXPECT_EQ(next.state, ExploreState::returning);
  ASSERT_FALSE(explorer.plan().empty());
  EXPECT_EQ(explorer.plan().cells[explorer.plan().cells.size() - 1], Eigen::Vector2i(15, 30));
}

// Steps through a look with the pan unit reaching each target at once.
void complete_look(Explorer& explorer, const GridView& grid, double time_s) {
  for (const double pan_deg : {0.0, 90.0, 180.0, -90.0, 0.0}) {
    ExploreInput input = input_at(grid, 1.5, 3.0, 0.0, time_s, false);
    input.pan_rad = pan_deg * M_PI / 180.0;
    explorer.step(input);
  }
}

TEST(Explorer, ASafetyStopLooksAroundThenResumesTheSameGoal) {
  Corridor scene;
  ExploreParams params = test_params(100, 60);
  params.explore.return_to_start = false;
  Explorer explorer(params);
  complete_look(explorer, scene.grid.view(), 0.0);
  ASSERT_EQ(explorer.state(), ExploreState::drive);
  const Goal goal = explorer.goal();
  // Something appears 0.4 m ahead on the plan (a person stepping in): stop and look, since a
  // standing robot makes no observation update.
  scene.grid.set(19, 30, CellState::occupied);
  const ExploreOutput stopped = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.1, false));
  EXPECT_EQ(stopped.drive.linear_mps, 0.0);
  EXPECT_EQ(stopped.state, ExploreState::look_around);
  EXPECT_EQ(explorer.counters().safety_stops, 1U);
  EXPECT_EQ(explorer.counters().looks, 2U);
  complete_look(explorer, scene.grid.view(), 0.2);
  EXPECT_EQ(explorer.state(), ExploreState::drive);
  EXPECT_EQ(explorer.goal().cell, goal.cell);
  EXPECT_EQ(explorer.counters().goals_chosen, 1U);
  for (const Eigen::Vector2i& cell : explorer.plan().cells) EXPECT_NE(cell, Eigen::Vector2i(19, 30));
}

// The way is shut while the robot looks after a safety stop: the rebuild at the end of the
// look finds the plan blocked and fails the goal once, not once more for the same map.
TEST(Explorer, AGoalCutOffDuringALookFailsOnce) {
  Corridor scene;
  ExploreParams params = test_params(100, 60);
  params.explore.return_to_start = false;
  Explorer explorer(params);
  complete_look(explorer, scene.grid.view(), 0.0);
  ASSERT_EQ(explorer.state(), ExploreState::drive);
  scene.grid.set(19, 30, CellState::occupied);
  ASSERT_EQ(explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.1, false)).state, ExploreState::look_around);
  scene.grid.fill(30, 1, 32, 59, CellState::occupied);
  complete_look(explorer, scene.grid.view(), 0.2);
  EXPECT_EQ(explorer.counters().replans, 1U);
  EXPECT_EQ(explorer.counters().plan_failures, 1U);
  EXPECT_EQ(explorer.counters().goal_failures, 1U);
  EXPECT_EQ(explorer.state(), ExploreState::finished);  // nothing left on this side of the wall
}

// After a stall the robot backs straight off the contact before it looks and replans: from
// the point of contact the plan leads into the same contact (a jamb grazed with the side).
TEST(Explorer, BacksOffAfterAStallThenLooks) {
  Corridor scene;
  ExploreParams params = test_params(100, 60);
  params.explore.return_to_start = false;
  Explorer explorer(params);
  complete_look(explorer, scene.grid.view(), 0.0);
  ASSERT_EQ(explorer.state(), ExploreState::drive);
  double time_s = 0.0;
  EXPECT_EQ(stall_at(explorer, scene.grid.view(), 1.5, 3.0, 0.0, time_s).drive.linear_mps, -params.max_speed_mps);
  ASSERT_EQ(explorer.counters().back_offs, 1U);
  double x = 1.5;
  for (int tick = 0; tick < 30; ++tick) {
    time_s += 0.05;
    const ExploreOutput output = explorer.step(input_at(scene.grid.view(), x, 3.0, 0.0, time_s, false));
    if (output.drive.linear_mps >= 0.0) break;
    EXPECT_EQ(output.drive.linear_mps, -params.max_speed_mps);
    x += output.drive.linear_mps * 0.05;
  }
  EXPECT_NEAR(x, 1.5 - params.explore.stall_back_off_m, 0.01);
  EXPECT_EQ(explorer.state(), ExploreState::look_around);
  EXPECT_EQ(explorer.counters().stalls, 1U);
}

// Backing off is blind but for the grid: it stops short where the disc behind would touch an
// occupied cell, and after twice its time when the robot does not move.
TEST(Explorer, BacksOffOnlyIntoClearSpaceAndForALimitedTime) {
  ExploreParams params = no_look_params(100, 60);
  params.explore.stall_back_off_turn_deg = 60.0;  // no turn helps against a wall behind
  Corridor walled;
  walled.grid.fill(10, 1, 12, 59, CellState::occupied);  // a wall whose cells lie 0.45 m behind
  Explorer explorer(params);
  explorer.step(input_at(walled.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  double time_s = 0.0;
  const ExploreOutput refused = stall_at(explorer, walled.grid.view(), 1.5, 3.0, 0.0, time_s);
  EXPECT_EQ(refused.drive.linear_mps, 0.0);
  EXPECT_EQ(refused.drive.angular_rad_s, 0.0);  // every way back within 60 deg is shut too
  EXPECT_EQ(explorer.counters().back_offs, 1U);
  EXPECT_EQ(explorer.counters().back_off_turns, 0U);
  // In open space, held still: backing off ends after 2 * 0.15 / 0.12 = 2.5 s.
  Corridor open;
  Explorer held(params);
  held.step(input_at(open.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  time_s = 0.0;
  ASSERT_LT(stall_at(held, open.grid.view(), 1.5, 3.0, 0.0, time_s).drive.linear_mps, 0.0);
  const double started_s = time_s;
  while (held.step(input_at(open.grid.view(), 1.5, 3.0, 0.0, time_s, false)).drive.linear_mps < 0.0) time_s += 0.05;
  EXPECT_NEAR(time_s - started_s, 2.0 * params.explore.stall_back_off_m / params.max_speed_mps, 0.06);
}

// A cell behind-right that the disc would reach 0.15 m straight back (0.43 m from the centre
// now, 0.32 m there): the robot turns in place to the right until the way back leads past it,
// then backs off along its new heading. Turning left would bring the cell nearer.
TEST(Explorer, TurnsInPlaceWhenTheWayStraightBackIsShut) {
  ExploreParams params = no_look_params(100, 60);
  params.explore.stall_back_off_turn_deg = 60.0;
  Corridor scene;
  scene.grid.set(11, 27, CellState::occupied);  // centre (1.15, 2.75)
  const Eigen::Vector2d cell(1.15, 2.75);
  Explorer explorer(params);
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  double time_s = 0.0;
  const ExploreOutput first = stall_at(explorer, scene.grid.view(), 1.5, 3.0, 0.0, time_s);
  EXPECT_EQ(first.drive.linear_mps, 0.0);
  EXPECT_EQ(first.drive.angular_rad_s, -params.max_turn_rate_rad_s);
  EXPECT_EQ(explorer.counters().back_offs, 1U);
  EXPECT_EQ(explorer.counters().back_off_turns, 1U);
  Eigen::Vector2d robot(1.5, 3.0);
  double theta = first.drive.angular_rad_s * 0.05;
  double backed_m = 0.0;
  for (int tick = 0; tick < 400; ++tick) {
    time_s += 0.05;
    const ExploreOutput output = explorer.step(input_at(scene.grid.view(), robot.x(), robot.y(), theta, time_s, false));
    if (output.drive.linear_mps == 0.0 && output.drive.angular_rad_s == 0.0) break;
    if (output.drive.linear_mps < 0.0) {
      EXPECT_EQ(output.drive.angular_rad_s, 0.0);  // straight back, no turning
    }
    theta += output.drive.angular_rad_s * 0.05;
    const Eigen::Vector2d move = output.drive.linear_mps * 0.05 * Eigen::Vector2d(std::cos(theta), std::sin(theta));
    robot += move;
    backed_m += move.norm();
    EXPECT_GE((robot - cell).norm(), params.robot_radius_m);
  }
  // Towards 30 deg right (at 15 deg the disc would reach the cell 0.05 m into the back-off),
  // and no further than the first heading from which half the back-off clears it: about 18 deg.
  EXPECT_LT(theta, -0.29);
  EXPECT_GT(theta, -0.35);
  EXPECT_GE(backed_m, 0.5 * params.explore.stall_back_off_m);
  EXPECT_LE(backed_m, params.explore.stall_back_off_m + 0.01);
  EXPECT_LT(robot.x(), 1.5 - 0.05);  // away from the stall, not only sideways
  EXPECT_EQ(explorer.counters().stalls, 1U);
  // Without the turn the back-off ends where it began.
  ExploreParams straight = params;
  straight.explore.stall_back_off_turn_deg = 0.0;
  Explorer unturned(straight);
  unturned.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  time_s = 0.0;
  const ExploreOutput refused = stall_at(unturned, scene.grid.view(), 1.5, 3.0, 0.0, time_s);
  EXPECT_EQ(refused.drive.linear_mps, 0.0);
  EXPECT_EQ(refused.drive.angular_rad_s, 0.0);
  EXPECT_EQ(unturned.counters().back_off_turns, 0U);
}

// The speed the explorer commands at (1.5, 3.0) heading east in the corridor, right after
// cell (x, y) turned occupied: it was driving east on the step before.
double speed_after_a_cell_appears(int x, int y, bool grid_updated, Explorer& explorer) {
  Corridor scene;
  EXPECT_GT(explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true)).drive.linear_mps, 0.0);
  scene.grid.set(x, y, CellState::occupied);
  return explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.1, grid_updated)).drive.linear_mps;
}

TEST(Explorer, DoesNotPushDeeperIntoAnObstacleItGrazes) {
  // A cell whose centre is 0.29 m ahead-left: inside the 0.35 m disc already, not deep under it.
  Explorer explorer(no_look_params(100, 60));
  EXPECT_EQ(speed_after_a_cell_appears(17, 31, false, explorer), 0.0);
  EXPECT_EQ(explorer.counters().safety_stops, 1U);
  // Deep under the robot (0.11 m from its centre: a person's trace), it does not stop it.
  Explorer unblocked(no_look_params(100, 60));
  EXPECT_GT(speed_after_a_cell_appears(15, 30, false, unblocked), 0.0);
  EXPECT_EQ(unblocked.counters().safety_stops, 0U);
}

// The plan's first waypoint is the centre of the robot's own cell, 7 cm ahead-left of it: a
// cell 0.29 m behind-left (inside the disc, not deep) is 0.28 m from that centre. Moving on
// east takes the robot away from it, so it drives; the lab's robot stood in a walker's lane
// for 1400 s, stopped by such a waypoint at every try.
TEST(Explorer, TheWaypointAtTheRobotsOwnCellIsNoMoveDeeper) {
  Explorer explorer(no_look_params(100, 60));
  EXPECT_GT(speed_after_a_cell_appears(13, 32, true, explorer), 0.0);
  EXPECT_EQ(explorer.counters().safety_stops, 0U);
  EXPECT_EQ(explorer.counters().plan_failures, 0U);
}

TEST(Explorer, EmergencyStopHaltsInTheSameTickAndResumes) {
  Corridor scene;
  Explorer explorer(no_look_params(100, 60));
  ASSERT_GT(explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true)).drive.linear_mps, 0.0);
  ExploreInput stop = input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.1, false);
  stop.emergency_stop = true;
  stop.pan_rad = 0.3;
  const ExploreOutput halted = explorer.step(stop);
  EXPECT_EQ(halted.drive.linear_mps, 0.0);
  EXPECT_EQ(halted.drive.angular_rad_s, 0.0);
  EXPECT_EQ(halted.pan_target_rad, 0.3);  // the pan unit holds still too
  EXPECT_EQ(explorer.counters().emergency_stop_ticks, 1U);
  EXPECT_GT(explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.2, false)).drive.linear_mps, 0.0);
}

// The 10 x 6 m room, unknown only in its top right corner, and a wall at x = 3 m from the
// top down to y = 1.5 m: from the top left the way to the unknown goes down round the wall's
// end, 3.5 m away from the goal before it comes nearer.
struct WallToGoRound {
  TestGrid grid{100, 60, CellState::free};
  WallToGoRound() {
    grid.walls();
    grid.fill(80, 30, 99, 59, CellState::unknown);
    grid.fill(30, 15, 32, 59, CellState::occupied);
  }
};

// Where the robot is after `travelled_m` along `waypoints`, facing along them.
core::Pose2 along(const std::vector<Eigen::Vector2d>& waypoints, double travelled_m) {
  for (std::size_t k = 0; k + 1 < waypoints.size(); ++k) {
    const Eigen::Vector2d step = waypoints[k + 1] - waypoints[k];
    if (travelled_m <= step.norm()) {
      const Eigen::Vector2d at = waypoints[k] + step * (travelled_m / step.norm());
      return {at.x(), at.y(), std::atan2(step.y(), step.x())};
    }
    travelled_m -= step.norm();
  }
  return {waypoints.back().x(), waypoints.back().y(), 0.0};
}

std::vector<Eigen::Vector2d> plan_of(const Explorer& explorer) {
  return {explorer.plan().waypoints.begin(), explorer.plan().waypoints.end()};
}

double length_of(const std::vector<Eigen::Vector2d>& waypoints) {
  double length = 0.0;
  for (std::size_t k = 0; k + 1 < waypoints.size(); ++k) length += (waypoints[k + 1] - waypoints[k]).norm();
  return length;
}

// Progress is measured along the plan: a robot going round the wall, for longer than
// stuck_timeout_s away from the goal, is not stuck; one standing still is, after that time.
TEST(Explorer, ARobotGoingRoundAWallAwayFromItsGoalIsNotStuck) {
  WallToGoRound scene;
  ExploreParams params = no_look_params(100, 60);
  params.explore.stuck_timeout_s = 10.0;
  Explorer explorer(params);
  explorer.step(input_at(scene.grid.view(), 2.0, 5.0, -1.57, 0.0, true));
  ASSERT_EQ(explorer.state(), ExploreState::drive);
  const std::vector<Eigen::Vector2d> plan = plan_of(explorer);
  const Eigen::Vector2d goal = explorer.goal().position;
  ASSERT_GT(goal.x(), 4.0);
  double farthest_from_goal_s = 0.0;  // when the straight-line distance was largest
  double largest_distance_m = 0.0;
  const double dt = 0.1;
  double t = dt;
  for (; explorer.state() == ExploreState::drive && t < 200.0; t += dt) {
    const core::Pose2 pose = along(plan, params.max_speed_mps * t);
    const double distance = (Eigen::Vector2d(pose.x, pose.y) - goal).norm();
    if (distance > largest_distance_m) {
      largest_distance_m = distance;
      farthest_from_goal_s = t;
    }
    explorer.step(input_at(scene.grid.view(), pose.x, pose.y, pose.theta, t, false));
  }
  EXPECT_GT(farthest_from_goal_s, params.explore.stuck_timeout_s);  // the old rule would have failed it
  EXPECT_EQ(explorer.counters().stuck, 0U);
  EXPECT_EQ(explorer.counters().goal_failures, 0U);
  EXPECT_EQ(explorer.counters().goals_reached, 1U);

  Explorer still(params);
  still.step(input_at(scene.grid.view(), 2.0, 5.0, -1.57, 0.0, true));
  for (t = dt; still.counters().stuck == 0 && t < 30.0; t += dt) {
    still.step(input_at(scene.grid.view(), 2.0, 5.0, -1.57, t, false));
  }
  EXPECT_EQ(still.counters().stuck, 1U);
  EXPECT_NEAR(t, params.explore.stuck_timeout_s, 0.25);
}

// Progress on every plan resets the stuck timer, so a goal has a time limit of its own:
// stuck_timeout_s plus goal_time_factor times its longest plan's driving time. A robot
// creeping along at 0.05 m/s (progress every 2 s) runs out of it; with the factor at 0, not.
TEST(Explorer, AGoalTakingFarLongerThanItsPlanFailsOnItsTimeLimit) {
  for (const double factor : {1.0, 0.0}) {
    WallToGoRound scene;
    ExploreParams params = no_look_params(100, 60);
    params.explore.stuck_timeout_s = 10.0;
    params.explore.goal_time_factor = factor;
    Explorer explorer(params);
    explorer.step(input_at(scene.grid.view(), 2.0, 5.0, -1.57, 0.0, true));
    ASSERT_EQ(explorer.state(), ExploreState::drive);
    const std::vector<Eigen::Vector2d> plan = plan_of(explorer);
    const double plan_m = (plan.front() - Eigen::Vector2d(2.0, 5.0)).norm() + length_of(plan);
    const double limit_s = params.explore.stuck_timeout_s + factor * plan_m / params.max_speed_mps;
    double t = 0.1;
    for (; explorer.counters().goal_failures == 0 && explorer.counters().goals_reached == 0 && t < 400.0; t += 0.1) {
      const core::Pose2 pose = along(plan, 0.05 * t);
      explorer.step(input_at(scene.grid.view(), pose.x, pose.y, pose.theta, t, false));
    }
    EXPECT_EQ(explorer.counters().stuck, 0U) << factor;
    if (factor == 0.0) {
      EXPECT_EQ(explorer.counters().goal_timeouts, 0U);
      EXPECT_EQ(explorer.counters().goals_reached, 1U);
      continue;
    }
    EXPECT_EQ(explorer.counters().goal_timeouts, 1U);
    EXPECT_EQ(explorer.counters().goal_failures, 1U);
    EXPECT_NEAR(t - 0.1, limit_s, 0.15);  // t: one step past the failing one
    EXPECT_GT(journaled(explorer, ExploreEventKind::goal_timeout), 0U);
  }
}

// A wall at x = 5 m with two ways through: a gap level with the robot and an opening at the
// bottom. Each view closes one and opens the other, as views of a blank wall did in the
// office: the robot heads for the gap, which closes as it comes near, turns for the long way
// round, which closes in its turn while the gap opens again, and so on.
struct GapThatComesAndGoes {
  TestGrid grid{100, 60, CellState::free};
  GapThatComesAndGoes() {
    grid.walls();
    grid.fill(80, 30, 99, 59, CellState::unknown);
    grid.fill(50, 1, 52, 59, CellState::occupied);
    open_gap(true);
  }
  void open_gap(bool gap) {
    grid.fill(50, 38, 52, 50, gap ? CellState::free : CellState::occupied);
    grid.fill(50, 1, 52, 13, gap ? CellState::occupied : CellState::free);
  }
};

// Drives the robot along whatever plan the explorer has at 0.12 m/s. The gap closes when
// the robot comes within 0.6 m of the wall, and opens again (the bottom closing) after
// `detour_s` on the way round. Returns the time the goal failed, or -1.
double chase_the_gap(Explorer& explorer, GapThatComesAndGoes& scene, double until_s) {
  constexpr double dt = 0.1;
  constexpr double detour_s = 8.0;
  core::Pose2 pose{1.0, 4.3, 0.0};
  explorer.step(input_at(scene.grid.view(), pose.x, pose.y, pose.theta, 0.0, true));
  std::vector<Eigen::Vector2d> planned = plan_of(explorer);
  std::vector<Eigen::Vector2d> plan = planned;
  double plan_since_s = 0.0;
  bool gap_open = true;
  for (double t = dt; t < until_s; t += dt) {
    bool updated = false;
    if (gap_open && pose.x > 4.4) {
      gap_open = false;
      updated = true;
    } else if (!gap_open && t - plan_since_s > detour_s) {
      gap_open = true;
      updated = true;
    }
    scene.open_gap(gap_open);
    explorer.step(input_at(scene.grid.view(), pose.x, pose.y, pose.theta, t, updated));
    if (explorer.counters().goal_failures > 0) return t;
    if (explorer.counters().goals_reached > 0) return -1.0;
    if (plan_of(explorer) != planned) {
      planned = plan_of(explorer);
      plan = planned;
      plan_since_s = t;
      plan.insert(plan.begin(), Eigen::Vector2d(pose.x, pose.y));
    }
    pose = along(plan, 0.12 * (t - plan_since_s));
  }
  return -1.0;
}

// The explorer's settings for the gap that comes and goes: a short stuck timeout, and no time
// limit but the one a test sets.
ExploreParams gap_chase_params() {
  ExploreParams params = no_look_params(100, 60);
  params.explore.stuck_timeout_s = 10.0;
  params.explore.goal_time_factor = 0.0;
  return params;
}

// One chase of the gap that comes and goes, for 240 s, with the given settings.
struct GapChase {
  explicit GapChase(const ExploreParams& params) : explorer(params), failed_s(chase_the_gap(explorer, scene, 240.0)) {}
  GapThatComesAndGoes scene;
  Explorer explorer;
  double failed_s;  // when the goal failed, or -1
};

// Progress along each new plan resets the stuck timer, and a goal's time limit grows with its
// longest plan: a robot going back and forth between two routes comes no nearer to its goal
// and would go on to its time limit. With net_progress_timeout_s it fails after that long
// without getting nearer than before; without it, it is still going when the test ends.
TEST(Explorer, ARobotGoingBackAndForthBetweenTwoRoutesFailsWithoutNetProgress) {
  for (const double timeout_s : {30.0, 0.0}) {
    ExploreParams params = gap_chase_params();
    params.explore.net_progress_timeout_s = timeout_s;
    GapChase chase(params);
    const Explorer& explorer = chase.explorer;
    const double failed_s = chase.failed_s;
    EXPECT_GT(explorer.counters().replans, 4U) << timeout_s;  // it went back and forth
    EXPECT_EQ(explorer.counters().stuck, 0U) << timeout_s;
    EXPECT_EQ(explorer.counters().goals_reached, 0U) << timeout_s;
    if (timeout_s == 0.0) {
      EXPECT_LT(failed_s, 0.0);
      continue;
    }
    EXPECT_EQ(explorer.counters().net_progress_timeouts, 1U);
    EXPECT_EQ(explorer.counters().goal_failures, 1U);
    EXPECT_GT(failed_s, timeout_s);
    EXPECT_LT(failed_s, 120.0);
    EXPECT_GT(journaled(explorer, ExploreEventKind::no_net_progress), 0U);
  }
}

// The same two routes: each block sends the robot back the way it came. With
// max_plan_reversals the goal fails at that many plans that lead back; without, the robot is
// still turning about when the test ends.
TEST(Explorer, AGoalWhoseBlockedPlansKeepLeadingBackFailsAtTheLimit) {
  for (const int limit : {2, 0}) {
    ExploreParams params = gap_chase_params();
    params.explore.max_plan_reversals = limit;
    GapChase chase(params);
    const Explorer& explorer = chase.explorer;
    const double failed_s = chase.failed_s;
    EXPECT_EQ(explorer.counters().goals_reached, 0U) << limit;
    EXPECT_EQ(explorer.counters().stuck, 0U) << limit;
    if (limit == 0) {
      EXPECT_LT(failed_s, 0.0);
      EXPECT_GT(explorer.counters().replans, 4U);  // it went back and forth all the while
      EXPECT_EQ(journaled(explorer, ExploreEventKind::plan_reversed), 0U);
      continue;
    }
    EXPECT_GT(failed_s, 0.0);
    EXPECT_LT(failed_s, 60.0);
    EXPECT_EQ(explorer.counters().plan_reversals, 2U);
    EXPECT_EQ(explorer.counters().reversal_limits, 1U);
    EXPECT_EQ(explorer.counters().goal_failures, 1U);
    std::size_t limit_at = explorer.journal().size();
    for (std::size_t i = 0; i < explorer.journal().size(); ++i) {
      if (explorer.journal()[i].kind == ExploreEventKind::reversed_too_often) limit_at = i;
    }
    ASSERT_LT(limit_at + 1, explorer.journal().size());
    EXPECT_EQ(explorer.journal()[limit_at - 1].kind, ExploreEventKind::plan_reversed);
    EXPECT_EQ(explorer.journal()[limit_at + 1].kind, ExploreEventKind::goal_failed);
  }
}

// A block straight ahead in open floor: the new plan turns aside round it, which is no
// reversal, and the goal is reached even with a limit of one.
TEST(Explorer, APlanThatTurnsAsideRoundABlockIsNoReversal) {
  TestGrid grid(100, 60, CellState::free);
  grid.walls();
  grid.fill(80, 1, 99, 59, CellState::unknown);
  ExploreParams params = gap_chase_params();
  params.explore.max_plan_reversals = 1;
  Explorer explorer(params);
  core::Pose2 pose{1.0, 3.0, 0.0};
  explorer.step(input_at(grid.view(), pose.x, pose.y, pose.theta, 0.0, true));
  std::vector<Eigen::Vector2d> planned = plan_of(explorer);
  std::vector<Eigen::Vector2d> plan = planned;
  double plan_since_s = 0.0;
  bool blocked = false;
  for (double t = 0.1; t < 120.0 && explorer.counters().goals_reached == 0; t += 0.1) {
    const bool block_now = !blocked && pose.x > 2.5;
    if (block_now) grid.fill(38, 22, 41, 39, CellState::occupied);  // across the way, 1.2-1.5 m ahead
    blocked = blocked || block_now;
    explorer.step(input_at(grid.view(), pose.x, pose.y, pose.theta, t, block_now));
    if (plan_of(explorer) != planned) {
      planned = plan_of(explorer);
      plan = planned;
      plan.insert(plan.begin(), Eigen::Vector2d(pose.x, pose.y));
      plan_since_s = t;
    }
    pose = along(plan, 0.12 * (t - plan_since_s));
  }
  EXPECT_TRUE(blocked);
  EXPECT_GE(explorer.counters().replans, 1U);
  EXPECT_EQ(explorer.counters().plan_reversals, 0U);
  EXPECT_EQ(explorer.counters().goal_failures, 0U);
  EXPECT_EQ(explorer.counters().goals_reached, 1U);
}

// The same two routes: each view blocks the plan through the gap or the one round it. With
// max_blocked_plans the goal fails at that many blocked plans, long before its time limit.
TEST(Explorer, AGoalWhosePlansKeepBeingBlockedFailsAtTheLimit) {
  GapThatComesAndGoes scene;
  ExploreParams params = gap_chase_params();
  params.explore.max_blocked_plans = 3;
  Explorer explorer(params);
  const double failed_s = chase_the_gap(explorer, scene, 240.0);
  EXPECT_GT(failed_s, 0.0);
  EXPECT_EQ(explorer.counters().blocked_plan_limits, 1U);
  EXPECT_EQ(explorer.counters().goal_failures, 1U);
  EXPECT_EQ(explorer.counters().replans, 3U);
  EXPECT_EQ(explorer.counters().stuck, 0U);
  std::size_t blocked = 0;
  std::size_t limit_at = explorer.journal().size();
  for (std::size_t i = 0; i < explorer.journal().size() && limit_at == explorer.journal().size(); ++i) {
    if (explorer.journal()[i].kind == ExploreEventKind::plan_blocked) ++blocked;
    if (explorer.journal()[i].kind == ExploreEventKind::blocked_too_often) limit_at = i;
  }
  ASSERT_LT(limit_at + 1, explorer.journal().size());
  EXPECT_EQ(blocked, 3U);  // journaled at the third
  EXPECT_EQ(explorer.journal()[limit_at + 1].kind, ExploreEventKind::goal_failed);
}

// The same two routes, the way round longer than the way through the gap. With
// goal_time_first_plan the time limit is the first plan's (through the gap), so the goal
// fails at stuck_timeout_s plus that plan's driving time; by the longest plan, later.
TEST(Explorer, WithTheFirstPlansTimeLimitAGoalWhosePlansGrowFailsSooner) {
  double failed_s[2] = {-1.0, -1.0};
  for (const bool first : {true, false}) {
    GapThatComesAndGoes scene;
    ExploreParams params = gap_chase_params();
    params.explore.goal_time_factor = 1.0;
    params.explore.goal_time_first_plan = first;
    Explorer twin(params);  // the first plan, as the chase's explorer makes it at its start
    twin.step(input_at(scene.grid.view(), 1.0, 4.3, 0.0, 0.0, true));
    const std::vector<Eigen::Vector2d> plan = plan_of(twin);
    const double first_plan_m = (plan.front() - Eigen::Vector2d(1.0, 4.3)).norm() + length_of(plan);
    Explorer fresh(params);
    failed_s[first ? 0 : 1] = chase_the_gap(fresh, scene, 400.0);
    EXPECT_EQ(fresh.counters().goal_timeouts, 1U) << first;
    if (first) {
      EXPECT_NEAR(failed_s[0], params.explore.stuck_timeout_s + first_plan_m / params.max_speed_mps, 0.2);
    }
  }
  EXPECT_GT(failed_s[1], failed_s[0] + 5.0);
}

// The robot starts in a disc whose floor the camera cannot see. A strip of it that no later
// view covered can be the only way on (the office's corridor, beside the first office's
// door): its cells stay passable all the run, not only near the robot or on the way back.
TEST(Explorer, TheStartsBlindDiscStaysPassableAfterTheRobotLeavesIt) {
  TestGrid grid{100, 60, CellState::free};
  grid.walls();
  grid.fill(80, 1, 99, 59, CellState::unknown);
  grid.fill(30, 1, 32, 59, CellState::occupied);  // a wall at x = 3 m ...
  grid.fill(30, 24, 32, 36, CellState::unknown);  // ... open only where the start's disc was
  Explorer explorer(no_look_params(100, 60));
  explorer.step(input_at(grid.view(), 2.8, 3.0, 0.0, 0.0, true));
  ASSERT_EQ(explorer.state(), ExploreState::drive);
  explorer.step(input_at(grid.view(), 1.0, 1.0, 0.0, 1.0, true));  // 2.4 m from the gap
  EXPECT_TRUE(explorer.navigation_map().passable(30, 30));
  EXPECT_TRUE(explorer.navigation_map().passable(31, 30));
  EXPECT_FALSE(explorer.navigation_map().passable(30, 45));  // the wall itself
  EXPECT_EQ(explorer.counters().goal_failures, 0U);
}

TEST(Explorer, BlacklistsGoalsThatKeepFailingThenFinishes) {
  Corridor scene;
  ExploreParams params = no_look_params(100, 60);
  params.explore.max_plan_waypoints = 3;  // every plan fails: too long for the plan
  Explorer explorer(params);
  for (int tick = 0; tick < 200 && explorer.state() != ExploreState::finished; ++tick) {
    const ExploreOutput output = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.1 * tick, tick == 0));
    EXPECT_EQ(output.drive.linear_mps, 0.0);
  }
  const ExploreCounters& counters = explorer.counters();
  EXPECT_EQ(explorer.state(), ExploreState::finished);
  EXPECT_EQ(explorer.finish_reason(), FinishReason::explored);
  EXPECT_GT(counters.goals_blacklisted, 0U);
  EXPECT_EQ(counters.goal_failures, counters.goals_blacklisted * 3U);
  EXPECT_EQ(counters.plan_failures, counters.goal_failures);
}

// "Explored" is not concluded on goals only put aside: when every goal left is blacklisted
// and held, the holds are lifted once and the goals tried again; blacklisted a second time,
// they keep their holds and the run ends. With blacklist_releases 0 it ends at once.
TEST(Explorer, HeldBlacklistingsAreLiftedOnceBeforeConcludingExplored) {
  Corridor scene;
  for (const int releases : {1, 0}) {
    ExploreParams params = no_look_params(100, 60);
    params.explore.max_plan_waypoints = 3;  // every plan fails: too long for the plan
    params.explore.blacklist_releases = releases;
    Explorer explorer(params);
    for (int tick = 0; tick < 400 && explorer.state() != ExploreState::finished; ++tick) {
      explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.1 * tick, tick == 0));
    }
    ASSERT_EQ(explorer.state(), ExploreState::finished) << releases;
    EXPECT_EQ(explorer.finish_reason(), FinishReason::explored);
    const ExploreCounters& counters = explorer.counters();
    EXPECT_EQ(counters.blacklist_releases, static_cast<std::uint64_t>(releases));
    EXPECT_EQ(journaled(explorer, ExploreEventKind::blacklist_released), static_cast<std::size_t>(releases));
    EXPECT_EQ(counters.goal_failures, counters.goals_blacklisted * 3U);
    if (releases == 0) continue;
    // Every goal blacklisted before the release is blacklisted again after it.
    std::size_t before = 0, after = 0;
    bool released = false;
    for (std::size_t i = 0; i < explorer.journal().size(); ++i) {
      const ExploreEventKind kind = explorer.journal()[i].kind;
      if (kind == ExploreEventKind::blacklist_released) released = true;
      if (kind == ExploreEventKind::goal_blacklisted) ++(released ? after : before);
    }
    EXPECT_GT(before, 0U);
    EXPECT_EQ(after, before);
  }
}

// The journal tells the same story as the counters, goal by goal: each chosen goal fails for
// want of a plan, the third failure of a goal blacklists it, and the run ends "explored".
TEST(Explorer, TheJournalRecordsWhyEachGoalFailed) {
  Corridor scene;
  ExploreParams params = no_look_params(100, 60);
  params.explore.max_plan_waypoints = 3;
  Explorer explorer(params);
  for (int tick = 0; tick < 200 && explorer.state() != ExploreState::finished; ++tick) {
    explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.1 * tick, tick == 0));
  }
  const ExploreJournal& journal = explorer.journal();
  const ExploreCounters& counters = explorer.counters();
  ASSERT_GT(journal.size(), 4U);
  EXPECT_EQ(journal.dropped(), 0U);
  std::uint64_t chosen = 0, no_plan = 0, failed = 0, blacklisted = 0;
  for (std::size_t i = 0; i < journal.size(); ++i) {
    const ExploreEvent& event = journal[i];
    EXPECT_DOUBLE_EQ(event.pose.x, 1.5);
    if (i > 0) {
      EXPECT_GE(event.time_s, journal[i - 1].time_s);
    }
    switch (event.kind) {
      case ExploreEventKind::goal_chosen:
        ++chosen;
        EXPECT_GT(event.goal_value, params.explore.min_goal_value);
        ASSERT_LT(i + 2, journal.size());
        EXPECT_EQ(journal[i + 1].kind, ExploreEventKind::no_plan);
        EXPECT_EQ(journal[i + 2].kind, ExploreEventKind::goal_failed);
        EXPECT_EQ(journal[i + 2].goal, event.goal);
        break;
      case ExploreEventKind::no_plan: ++no_plan; break;
      case ExploreEventKind::goal_failed: ++failed; break;
      case ExploreEventKind::goal_blacklisted: ++blacklisted; break;
      default: break;
    }
  }
  EXPECT_EQ(chosen, counters.goals_chosen);
  EXPECT_EQ(no_plan, counters.plan_failures);
  EXPECT_EQ(failed, counters.goal_failures);
  EXPECT_EQ(blacklisted, counters.goals_blacklisted);
  EXPECT_EQ(journal[journal.size() - 1].kind, ExploreEventKind::explored);
}

TEST(ExploreJournal, KeepsTheLatestEventsAndCountsTheDropped) {
  ExploreJournal journal(3);
  for (int i = 0; i < 5; ++i) {
    ExploreEvent event;
    event.time_s = static_cast<double>(i);
    event.kind = i % 2 == 0 ? ExploreEventKind::look : ExploreEventKind::stall;
    journal.record(event);
  }
  ASSERT_EQ(journal.size(), 3U);
  EXPECT_EQ(journal.recorded(), 5U);
  EXPECT_EQ(journal.dropped(), 2U);
  EXPECT_DOUBLE_EQ(journal[0].time_s, 2.0);
  EXPECT_DOUBLE_EQ(journal[2].time_s, 4.0);
  EXPECT_STREQ(to_string(journal[1].kind), "stall");
}

TEST(Explorer, LooksAroundWithThePanUnitInQuarterTurns) {
  Corridor scene;
  ExploreParams params = test_params(100, 60);
  Explorer explorer(params);
  const double targets[] = {core::kPi / 2, core::kPi, -core::kPi / 2, 0.0};
  double pan = 0.0;
  for (double target : targets) {
    ExploreInput input = input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, pan == 0.0);
    input.pan_rad = pan + 0.5;  // still on its way
    const ExploreOutput output = explorer.step(input);
    EXPECT_EQ(output.state, ExploreState::look_around);
    EXPECT_NEAR(output.pan_target_rad, target, 1e-12);
    EXPECT_EQ(output.drive.linear_mps, 0.0);
    EXPECT_EQ(output.drive.angular_rad_s, 0.0);
    pan = target;
    ExploreInput reached = input_at(scene.grid.view(), 1.5, 3.0, 0.0, 1.0, false);
    reached.pan_rad = pan;
    const ExploreOutput next = explorer.step(reached);
    // The last quarter turn ends the look: a goal is chosen and driving starts at once.
    EXPECT_EQ(next.state, target == 0.0 ? ExploreState::drive : ExploreState::look_around);
  }
  EXPECT_EQ(explorer.counters().looks, 1U);
}

TEST(Explorer, TurnsInPlaceAFullCircleWithoutAPanUnit) {
  Corridor scene;
  Explorer explorer(test_params(100, 60, /*has_pan_unit=*/false));
  double heading = 0.0;
  int ticks = 0;
  ExploreOutput output = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, heading, 0.0, true));
  while (output.state == ExploreState::look_around && ticks < 1000) {
    EXPECT_EQ(output.drive.linear_mps, 0.0);
    EXPECT_DOUBLE_EQ(output.drive.angular_rad_s, core::degrees_to_radians(8.0));
    heading = core::wrap_angle(heading + output.drive.angular_rad_s * 0.5);
    ++ticks;
    output = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, heading, 0.5 * ticks, false));
  }
  EXPECT_EQ(ticks, 90);  // 360 deg at 8 deg/s in 0.5 s ticks
  EXPECT_EQ(output.state, ExploreState::drive);
}

TEST(Explorer, FinishesWhenNothingIsLeft) {
  TestGrid room(60, 60, CellState::free);
  room.walls();
  ExploreParams params = test_params(60, 60);
  params.explore.pan_at_goal = false;
  Explorer explorer(params);
  // Nothing unknown: explored at once; the robot is at its start, so the return ends at once.
  const ExploreOutput output = explorer.step(input_at(room.view(), 3.0, 3.0, 0.0, 0.0, true));
  EXPECT_EQ(explorer.finish_reason(), FinishReason::explored);
  EXPECT_EQ(output.state, ExploreState::finished);
  EXPECT_EQ(explorer.counters().return_failures, 0U);
}

TEST(Explorer, FinishesByItselfWhenOnlyAnUnobservablePocketIsLeft) {
  // A seen room with a box whose inside (and a two-cell gap of its side) was never seen.
  TestGrid room(60, 60, CellState::free);
  room.walls();
  room.fill(20, 20, 30, 30, CellState::occupied);
  room.fill(21, 21, 29, 29, CellState::unknown);
  room.fill(20, 22, 21, 28, CellState::unknown);
  ExploreParams params = no_look_params(60, 60);
  Explorer explorer(params);
  explorer.step(input_at(room.view(), 0.5, 2.5, 0.0, 0.0, true));
  EXPECT_EQ(explorer.finish_reason(), FinishReason::explored);
  EXPECT_EQ(explorer.state(), ExploreState::finished);
  // Counting the pocket as a frontier, its gap is worth a trip and exploration goes on.
  params.explore.max_pocket_area_m2 = 0.0;
  Explorer counting_pockets(params);
  counting_pockets.step(input_at(room.view(), 0.5, 2.5, 0.0, 0.0, true));
  EXPECT_EQ(counting_pockets.finish_reason(), FinishReason::none);
  EXPECT_EQ(counting_pockets.state(), ExploreState::drive);
}

TEST(Explorer, ReturnsToTheStartAfterTheTimeLimit) {
  Corridor scene;
  ExploreParams params = test_params(100, 60);
  params.explore.pan_at_goal = false;
  params.explore.time_limit_s = 10.0;
  Explorer explorer(params);
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  ASSERT_EQ(explorer.state(), ExploreState::drive);
  const ExploreOutput output = explorer.step(input_at(scene.grid.view(), 5.0, 3.0, 0.0, 10.0, false));
  EXPECT_EQ(explorer.finish_reason(), FinishReason::time_limit);
  EXPECT_EQ(output.state, ExploreState::returning);
  ASSERT_FALSE(explorer.plan().empty());
  EXPECT_EQ(explorer.plan().cells[explorer.plan().cells.size() - 1], Eigen::Vector2i(15, 30));
  EXPECT_EQ(output.drive.linear_mps, 0.0);  // the start is behind: turn in place first
  EXPECT_GT(std::abs(output.drive.angular_rad_s), 0.0);
  EXPECT_EQ(explorer.step(input_at(scene.grid.view(), 1.52, 3.0, core::kPi, 200.0, false)).state,
            ExploreState::finished);
}

// Looking along the plan turns the camera off the heading while driving; once the return ends
// nothing asks for another pan target, so the camera must come back to the heading then.
TEST(Explorer, TheCameraLooksAlongTheHeadingAgainWhenTheReturnEnds) {
  Corridor scene;
  ExploreParams params = test_params(100, 60);
  params.explore.pan_at_goal = false;
  params.explore.time_limit_s = 10.0;
  params.explore.gaze_ahead_m = 1.5;
  Explorer explorer(params);
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  const ExploreOutput returning = explorer.step(input_at(scene.grid.view(), 5.0, 3.0, 0.0, 10.0, false));
  ASSERT_EQ(returning.state, ExploreState::returning);
  // The start lies behind: the camera turns as far as it may towards the way back.
  EXPECT_NEAR(std::abs(returning.pan_target_rad), core::degrees_to_radians(params.explore.gaze_max_pan_deg), 1e-9);
  const ExploreOutput finished = explorer.step(input_at(scene.grid.view(), 1.52, 3.0, core::kPi, 200.0, false));
  ASSERT_EQ(finished.state, ExploreState::finished);
  EXPECT_EQ(finished.pan_target_rad, 0.0);
}

// Steps through a whole look with the pan unit, each quarter turn reached at once.
ExploreOutput finish_a_look(Explorer& explorer, const GridView& grid, double x, double y, double time_s) {
  ExploreOutput output;
  for (const double target : {core::kPi / 2, core::kPi, -core::kPi / 2, 0.0}) {
    ExploreInput reached = input_at(grid, x, y, 0.0, time_s, false);
    reached.pan_rad = target;
    output = explorer.step(reached);
  }
  return output;
}

// A passer-by blocks the only way back: the robot looks and tries again after each failure,
// goes on once the way is clear, and gives the return up at the
// goal_failures_before_blacklist-th failure (so a return that keeps failing ends).
TEST(Explorer, AReturnBlockedByAPasserByLooksAndTriesAgain) {
  Corridor scene;
  ExploreParams params = test_params(100, 60);
  params.explore.time_limit_s = 10.0;
  Explorer explorer(params);
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  ASSERT_EQ(finish_a_look(explorer, scene.grid.view(), 1.5, 3.0, 1.0).state, ExploreState::drive);
  ASSERT_EQ(explorer.step(input_at(scene.grid.view(), 5.0, 3.0, 0.0, 10.0, false)).state, ExploreState::returning);
  const auto block = [&](CellState state) { scene.grid.fill(30, 1, 32, 58, state); };
  block(CellState::occupied);
  EXPECT_EQ(explorer.step(input_at(scene.grid.view(), 5.0, 3.0, 0.0, 11.0, true)).state, ExploreState::look_around);
  EXPECT_EQ(explorer.counters().return_failures, 1U);
  EXPECT_EQ(finish_a_look(explorer, scene.grid.view(), 5.0, 3.0, 12.0).state, ExploreState::look_around);
  EXPECT_EQ(explorer.counters().return_failures, 2U);  // no way even after a look: look again
  block(CellState::free);
  EXPECT_EQ(finish_a_look(explorer, scene.grid.view(), 5.0, 3.0, 13.0).state, ExploreState::returning);
  ASSERT_FALSE(explorer.plan().empty());
  // Blocked again: the third failure ends the return.
  block(CellState::occupied);
  EXPECT_EQ(explorer.step(input_at(scene.grid.view(), 5.0, 3.0, 0.0, 14.0, true)).state, ExploreState::finished);
  EXPECT_EQ(explorer.counters().return_failures, 3U);
}

// A person walked past the only door while the robot looked out of its room, and left
// occupied cells across the door's far side that no view from the room can clear. Once they
// are trace_forget_after_s old, the robot does not conclude that nothing is left: plans cross
// them, but the safety check does not. The robot stops before them and looks, and goes on if
// the look saw the person gone.
struct TraceInTheDoor {
  DoorScene scene;
  ExploreParams params = test_params(100, 60);
  TraceInTheDoor() {
    params.explore.return_to_start = false;
    params.explore.trace_forget_after_s = 10.0;
    params.explore.trace_confirm_radius_m = 1.5;
    params.explore.trace_confirm_seen_floor = true;
    params.robot_radius_m = 0.33;
  }
  void walk_past(CellState state) { scene.grid.fill(32, 26, 33, 35, state); }
  // The robot looks, drives off towards the unknown beyond the door, and then, at t = 1 s,
  // the person walks past the door: the output of that tick.
  ExploreOutput person_walks_past(Explorer& explorer) {
    const GridView grid = scene.grid.view();
    explorer.step(input_at(grid, 1.5, 3.05, 0.0, 0.0, true));
    EXPECT_EQ(finish_a_look(explorer, grid, 1.5, 3.05, 0.5).state, ExploreState::drive);
    walk_past(CellState::occupied);
    return explorer.step(input_at(grid, 1.5, 3.05, 0.0, 1.0, true));
  }
};

// Moves the robot along y = 3.05 m (the plan's row) in 5 cm steps, one tick each, while the
// explorer drives it forward; returns the x where it stopped (time_s: that tick's time).
double drive_until_stopped(Explorer& explorer, const GridView& grid, double x, double& time_s) {
  for (; x < 4.0; x += 0.05) {
    time_s += 0.5;
    const ExploreOutput output = explorer.step(input_at(grid, x, 3.05, 0.0, time_s, false));
    if (output.state != ExploreState::drive || output.drive.linear_mps <= 0.0) break;
  }
  return x;
}

// The person walks past the door; the look ends 10 s later and the robot drives at the trace
// until the safety check stops it. Returns the x where it stopped (time_s: that tick's time).
double drive_to_the_trace(TraceInTheDoor& door, Explorer& explorer, double& time_s) {
  const GridView grid = door.scene.grid.view();
  door.person_walks_past(explorer);
  EXPECT_EQ(finish_a_look(explorer, grid, 1.5, 3.05, 11.0).state, ExploreState::drive);
  time_s = 11.0;
  return drive_until_stopped(explorer, grid, 1.5, time_s);
}

// Moves the robot back along y = 3.05 m in 5 cm steps while the explorer backs it off; returns
// the x where the look began (time_s: that tick's time).
double back_off_until_look(Explorer& explorer, const GridView& grid, double x, double& time_s) {
  for (; x > 0.5; x -= 0.05) {
    time_s += 0.5;
    const ExploreOutput output = explorer.step(input_at(grid, x, 3.05, 0.0, time_s, false));
    if (output.state != ExploreState::drive || output.drive.linear_mps >= 0.0) break;
  }
  return x;
}

// True when a plan cell lies beyond the trace (x = 3.25 m).
bool plan_leads_past_the_door(const Explorer& explorer) {
  for (const Eigen::Vector2i& cell : explorer.plan().cells) {
    if (cell.x() > 32) return true;
  }
  return false;
}

TEST(Explorer, APersonsOldTraceInTheOnlyDoorIsCrossedByPlansNotByTheSafetyCheck) {
  TraceInTheDoor door;
  Explorer explorer(door.params);
  const GridView grid = door.scene.grid.view();
  // Fresh: the person is there now. The goal beyond fails, nothing else is left: look again.
  EXPECT_EQ(door.person_walks_past(explorer).state, ExploreState::look_around);
  EXPECT_EQ(explorer.counters().goal_failures, 1U);
  EXPECT_EQ(explorer.counters().trace_crossings, 0U);
  // The look ends 10 s later, far from the door: the trace is crossed, the robot drives.
  const ExploreOutput driving = finish_a_look(explorer, grid, 1.5, 3.05, 11.0);
  ASSERT_EQ(driving.state, ExploreState::drive);
  EXPECT_GT(driving.drive.linear_mps, 0.0);
  EXPECT_TRUE(plan_leads_past_the_door(explorer));
  EXPECT_EQ(explorer.counters().traces_confirmed, 0U);
  EXPECT_EQ(explorer.counters().trace_crossings, 1U);
  // At the door the cells are still occupied in the grid: the safety check stops the robot
  // before its disc (0.33 m) reaches them (x from 3.2 m).
  double time_s = 11.0;
  const double stopped_x = drive_until_stopped(explorer, grid, 1.5, time_s);
  EXPECT_LT(stopped_x, 3.2 - 0.33);
  EXPECT_GT(stopped_x, 2.0);
  EXPECT_EQ(explorer.counters().safety_stops, 1U);
  // The nearest cell's centre (3.25 m) lies where the camera sees no floor: the robot backs
  // off until it lies a cell beyond that, and looks.
  EXPECT_EQ(explorer.counters().back_offs_to_see, 1U);
  EXPECT_EQ(explorer.state(), ExploreState::drive);
  const double look_x = back_off_until_look(explorer, grid, stopped_x, time_s);
  EXPECT_EQ(explorer.state(), ExploreState::look_around);
  EXPECT_LE(look_x, 3.25 - door.params.unseen_floor_radius_m() + 1e-9);
  EXPECT_GT(look_x, 3.25 - door.params.unseen_floor_radius_m() - 0.2);
  // The look sees the floor there: the person has gone. The robot goes on through the door.
  door.walk_past(CellState::free);
  explorer.step(input_at(grid, look_x, 3.05, 0.0, time_s + 1.0, true));
  const ExploreOutput through = finish_a_look(explorer, grid, look_x, 3.05, time_s + 2.0);
  EXPECT_EQ(through.state, ExploreState::drive);
  EXPECT_GT(through.drive.linear_mps, 0.0);
  EXPECT_TRUE(plan_leads_past_the_door(explorer));
  EXPECT_EQ(explorer.counters().traces_confirmed, 0U);
  EXPECT_EQ(explorer.counters().goal_failures, 1U);
}

// The same, but the look from the door still sees the cells occupied: they are an obstacle,
// which closes the door; the goal beyond fails.
TEST(Explorer, ATraceStillThereAfterALookNearItIsAnObstacleAgain) {
  TraceInTheDoor door;
  Explorer explorer(door.params);
  const GridView grid = door.scene.grid.view();
  double time_s = 0.0;
  const double stopped_x = drive_to_the_trace(door, explorer, time_s);
  const double look_x = back_off_until_look(explorer, grid, stopped_x, time_s);
  ASSERT_EQ(explorer.state(), ExploreState::look_around);
  finish_a_look(explorer, grid, look_x, 3.05, time_s + 2.0);
  EXPECT_EQ(explorer.counters().traces_confirmed, 9U);
  EXPECT_EQ(explorer.counters().goal_failures, 2U);
  EXPECT_FALSE(plan_leads_past_the_door(explorer));
}

// Without trace_confirm_seen_floor the look comes at the stop itself, and it confirms the
// cells in the camera's blind zone too: they close the door.
TEST(Explorer, WithoutSeenFloorOnlyTheLookAtTheStopConfirmsTheTraceInTheBlindZone) {
  TraceInTheDoor door;
  door.params.explore.trace_confirm_seen_floor = false;
  Explorer explorer(door.params);
  const GridView grid = door.scene.grid.view();
  double time_s = 0.0;
  const double stopped_x = drive_to_the_trace(door, explorer, time_s);
  EXPECT_EQ(explorer.state(), ExploreState::look_around);
  EXPECT_EQ(explorer.counters().back_offs_to_see, 0U);
  finish_a_look(explorer, grid, stopped_x, 3.05, time_s + 2.0);
  EXPECT_EQ(explorer.counters().traces_confirmed, 9U);
  EXPECT_FALSE(plan_leads_past_the_door(explorer));
}

// The person walks past the door while the robot looks, 1.25 m from the cells (within the
// confirm radius, where the camera sees the floor). With trace_confirm_before_look the look
// watched them appear and does not confirm them: they stay traces, and the plan to the goal
// beyond the door crosses them. Without it the look confirms them and shuts the door.
TEST(Explorer, ALookConfirmsNoTraceThatAppearedWhileItLooked) {
  for (const bool before_look : {false, true}) {
    TraceInTheDoor door;
    door.params.explore.trace_confirm_before_look = before_look;
    Explorer explorer(door.params);
    const GridView grid = door.scene.grid.view();
    ASSERT_EQ(explorer.step(input_at(grid, 2.0, 3.05, 0.0, 0.0, true)).state, ExploreState::look_around);
    door.walk_past(CellState::occupied);
    explorer.step(input_at(grid, 2.0, 3.05, 0.0, 0.5, true));
    finish_a_look(explorer, grid, 2.0, 3.05, 11.0);
    EXPECT_EQ(explorer.counters().traces_confirmed, before_look ? 0U : 9U) << before_look;
    EXPECT_EQ(plan_leads_past_the_door(explorer), before_look) << before_look;
    EXPECT_EQ(explorer.counters().trace_crossings, before_look ? 1U : 0U) << before_look;
  }
}

// Crossing traces ends with the goal it was for, also when the goal is abandoned (seen on the
// way): the next goals are chosen on the map with the traces, and crossing them again is a
// new last resort, counted again.
TEST(Explorer, CrossingTracesEndsWithAnAbandonedGoal) {
  TraceInTheDoor door;
  Explorer explorer(door.params);
  const GridView grid = door.scene.grid.view();
  door.person_walks_past(explorer);
  ASSERT_EQ(finish_a_look(explorer, grid, 1.5, 3.05, 11.0).state, ExploreState::drive);
  ASSERT_EQ(explorer.counters().trace_crossings, 1U);
  door.scene.grid.fill(80, 1, 99, 59, CellState::free);  // all of it seen: nothing left
  explorer.step(input_at(grid, 1.5, 3.05, 0.0, 12.0, true));
  EXPECT_EQ(explorer.counters().goals_abandoned, 1U);
  finish_a_look(explorer, grid, 1.5, 3.05, 13.0);
  EXPECT_EQ(explorer.counters().trace_crossings, 2U);
  EXPECT_EQ(explorer.finish_reason(), FinishReason::explored);
}

TEST(Explorer, StopsExploringAtTheTimeLimit) {
  Corridor scene;
  ExploreParams params = no_look_params(100, 60);
  params.explore.time_limit_s = 10.0;
  Explorer explorer(params);
  explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 0.0, true));
  EXPECT_EQ(explorer.state(), ExploreState::drive);
  const ExploreOutput output = explorer.step(input_at(scene.grid.view(), 1.5, 3.0, 0.0, 10.0, false));
  EXPECT_EQ(output.state, ExploreState::finished);
  EXPECT_EQ(explorer.finish_reason(), FinishReason::time_limit);
  EXPECT_EQ(output.drive.linear_mps, 0.0);
}

TEST(Explorer, StepDoesNotAllocate) {
  Corridor scene;
  Explorer explorer(test_params(100, 60));
  const core::AllocationScope scope;
  double pan = 0.0;
  for (int tick = 0; tick < 50; ++tick) {
    ExploreInput input = input_at(scene.grid.view(), 1.5 + 0.01 * tick, 3.0, 0.0, 0.1 * tick, tick % 5 == 0);
    input.pan_rad = pan;
    pan = explorer.step(input).pan_target_rad;
  }
  EXPECT_EQ(explorer.state(), ExploreState::drive);
  EXPECT_EQ(scope.allocations(), 0U);
}

}  // namespace
}  // namespace stereoscout::explore
