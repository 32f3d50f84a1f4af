// Goal value H(s) (paper VI) on hand-made grids, and goal selection.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "stereoscout/explore/goal_value.hpp"
#include "stereoscout/explore/navigation_map.hpp"
#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

using testing::TestGrid;
using testing::test_params;

// V along ray 0 (+x) from cell (5, 25) when the first non-free cell is `distance_cells` away.
double value_with_unknown_at(int distance_cells) {
  TestGrid grid(60, 50, CellState::free);
  grid.set(5 + distance_cells, 25, CellState::unknown);
  const GoalValue goal_value(test_params(60, 50));
  return goal_value.ray_value(grid.view(), 5, 25, 0);
}

TEST(GridView, FloorToIntIsStdFloorOnEitherSideOfZero) {
  for (double value = -3.0; value <= 3.0; value += 0.125) {
    EXPECT_EQ(floor_to_int(value), static_cast<int>(std::floor(value))) << value;
  }
  EXPECT_EQ(floor_to_int(-1e-12), -1);
  EXPECT_EQ(floor_to_int(1399.9999999), 1399);
  EXPECT_EQ(floor_to_int(-0.0), 0);
}

// A ray visits each cell it crosses once, in order, whatever its direction.
TEST(GridView, MarchCellsVisitsTheCrossedCellsInOrder) {
  std::vector<Eigen::Vector2i> visited;
  march_cells(5, 5, Eigen::Vector2d(-1.0, 0.0), 3.0, [&](int x, int y) {
    visited.emplace_back(x, y);
    return true;
  });
  ASSERT_EQ(visited.size(), 3U);
  EXPECT_EQ(visited[0], Eigen::Vector2i(4, 5));
  EXPECT_EQ(visited[2], Eigen::Vector2i(2, 5));
  visited.clear();
  const Eigen::Vector2d diagonal = Eigen::Vector2d(1.0, -1.0).normalized();
  march_cells(0, 0, diagonal, 2.9, [&](int x, int y) {
    visited.emplace_back(x, y);
    return true;
  });
  ASSERT_EQ(visited.size(), 2U);  // the corners grazed aside
  EXPECT_EQ(visited[0], Eigen::Vector2i(1, -1));
  EXPECT_EQ(visited[1], Eigen::Vector2i(2, -2));
}

TEST(GoalValue, UnknownCellExactlyPreferredDistanceAwayMaximisesV) {
  // r* = 2.0 m = 20 cells of 0.1 m.
  EXPECT_DOUBLE_EQ(value_with_unknown_at(20), 1.0);
  for (int distance = 1; distance <= 40; ++distance) {
    if (distance != 20) {
      EXPECT_LT(value_with_unknown_at(distance), 1.0) << distance;
    }
  }
  // One sigma (0.5 m) off r*: exp(-1/2).
  EXPECT_NEAR(value_with_unknown_at(25), std::exp(-0.5), 1e-12);
  EXPECT_NEAR(value_with_unknown_at(15), std::exp(-0.5), 1e-12);
}

TEST(GoalValue, RaysAreCutAtThePreferredDistancePlusThreeSigma) {
  // Cap r* + 3 sigma = 3.5 m: an unknown cell at 3.5 m counts, at 3.6 m the ray saw only free.
  EXPECT_NEAR(value_with_unknown_at(35), std::exp(-4.5), 1e-12);
  EXPECT_EQ(value_with_unknown_at(36), 0.0);
}

// office seed 5 on the 5 cm grid: goals beside the building's outer wall, which the grid had
// not held, took their value from its unknown cells and from the outside beyond them. With
// in_view_ends_goal_rays a ray ends with no value at an unknown cell the camera had in view
// (the stereo could not measure it: another look shows no more); unknown cells no view
// covered keep their value.
TEST(GoalValue, AnUnknownCellThatWasInViewEndsTheRayWithNoValue) {
  TestGrid grid(60, 50, CellState::free);
  grid.fill(25, 0, 60, 50, CellState::unknown);  // from 2 m east of (5, 25) on
  std::vector<std::uint8_t> in_view(grid.cells.size(), 0);
  for (int y = 25; y < 50; ++y) in_view[grid.view().index(25, y)] = 1;  // its first column, north half
  GridView seen = grid.view();
  seen.in_view = in_view.data();
  ExploreParams params = test_params(60, 50);
  const GoalValue plain(params);
  params.explore.in_view_ends_goal_rays = true;
  const GoalValue skipping(params);
  const std::size_t east = 0;
  const std::size_t north_east = 9;   // 45 degrees: meets the column at (25, 45)
  const std::size_t south_east = 63;  // -45 degrees: at (25, 5), never in view
  EXPECT_DOUBLE_EQ(plain.ray_value(seen, 5, 25, east), 1.0);
  EXPECT_DOUBLE_EQ(skipping.ray_value(seen, 5, 25, east), 0.0);
  EXPECT_GT(plain.ray_value(seen, 5, 25, north_east), 0.0);
  EXPECT_DOUBLE_EQ(skipping.ray_value(seen, 5, 25, north_east), 0.0);
  EXPECT_DOUBLE_EQ(skipping.ray_value(seen, 5, 25, south_east), plain.ray_value(seen, 5, 25, south_east));
  EXPECT_GT(skipping.ray_value(seen, 5, 25, south_east), 0.0);
  // Without the marks (grid.in_view_range_m 0) the rule changes nothing.
  EXPECT_DOUBLE_EQ(skipping.value(grid.view(), 5, 25), plain.value(grid.view(), 5, 25));
}

TEST(GoalValue, OccupiedCellBlocksTheRay) {
  TestGrid grid(60, 50, CellState::free);
  grid.set(25, 25, CellState::unknown);
  const GoalValue goal_value(test_params(60, 50));
  EXPECT_DOUBLE_EQ(goal_value.ray_value(grid.view(), 5, 25, 0), 1.0);
  grid.set(15, 25, CellState::occupied);
  EXPECT_EQ(goal_value.ray_value(grid.view(), 5, 25, 0), 0.0);
}

TEST(GoalValue, HSumsSeventyTwoRays) {
  // A free disc of radius 2.0 m in unknown space: every ray meets unknown near r*.
  TestGrid grid(80, 80, CellState::unknown);
  for (int y = 0; y < 80; ++y) {
    for (int x = 0; x < 80; ++x) {
      if (std::hypot(x - 40, y - 40) < 20.0) grid.set(x, y, CellState::free);
    }
  }
  const GoalValue goal_value(test_params(80, 80));
  ASSERT_EQ(goal_value.ray_count(), 72U);
  const double h = goal_value.value(grid.view(), 40, 40);
  double sum = 0.0;
  for (std::size_t k = 0; k < 72; ++k) sum += goal_value.ray_value(grid.view(), 40, 40, k);
  EXPECT_EQ(h, sum);
  EXPECT_GT(h, 0.95 * 72.0);  // first unknown cell 2.0 to 2.1 m away on every ray
  // Walls all around: nothing left to see.
  TestGrid closed(80, 80, CellState::free);
  closed.walls();
  EXPECT_EQ(goal_value.value(closed.view(), 40, 40), 0.0);
}

TEST(GoalMemory, BlacklistsAfterTheConfiguredFailures) {
  GoalMemory memory(4, 0.5, 0.5, 3);
  const Eigen::Vector2d goal(2.0, 1.0);
  EXPECT_FALSE(memory.record_failure(goal, 0.0));
  EXPECT_FALSE(memory.record_failure(goal + Eigen::Vector2d(0.2, 0.0), 0.0));  // same goal, within radius
  EXPECT_FALSE(memory.excluded(goal, 0.0));
  EXPECT_TRUE(memory.record_failure(goal, 0.0));
  EXPECT_TRUE(memory.excluded(goal + Eigen::Vector2d(0.0, 0.4), 0.0));
  EXPECT_FALSE(memory.excluded(goal + Eigen::Vector2d(0.0, 0.6), 0.0));
  EXPECT_EQ(memory.blacklisted(), 1U);
  memory.record_visit(Eigen::Vector2d(5.0, 5.0));
  EXPECT_TRUE(memory.excluded(Eigen::Vector2d(5.0, 5.0), 0.0));
  memory.record_visit(Eigen::Vector2d(7.0, 5.0));
  memory.record_visit(Eigen::Vector2d(9.0, 5.0));
  memory.record_visit(Eigen::Vector2d(11.0, 5.0));  // full: counted, forgotten
  EXPECT_EQ(memory.forgotten(), 1U);
}

// A room seen through a door the robot cannot pass: once a goal in it is blacklisted, the
// goals beside it are skipped too, out to blacklist_radius_m; a visited goal keeps the small
// radius, so the space around a goal the robot did reach stays open.
TEST(GoalMemory, ABlacklistedGoalSkipsItsNeighbourhoodAVisitedOneOnlyItsSpot) {
  GoalMemory memory(8, 0.5, 2.0, 3);
  const Eigen::Vector2d goal(11.35, 8.45);
  memory.record_failure(goal, 0.0);
  memory.record_failure(goal + Eigen::Vector2d(0.0, 0.1), 0.0);
  EXPECT_FALSE(memory.excluded(goal + Eigen::Vector2d(-0.4, -0.2), 0.0));  // two failures: not yet
  EXPECT_TRUE(memory.record_failure(goal, 0.0));
  EXPECT_TRUE(memory.excluded(goal + Eigen::Vector2d(-0.4, -0.2), 0.0));
  EXPECT_TRUE(memory.excluded(goal + Eigen::Vector2d(-1.9, 0.0), 0.0));
  EXPECT_FALSE(memory.excluded(goal + Eigen::Vector2d(-2.1, 0.0), 0.0));
  const Eigen::Vector2d visited(3.0, 3.0);
  memory.record_visit(visited);
  EXPECT_TRUE(memory.excluded(visited + Eigen::Vector2d(0.4, 0.0), 0.0));
  EXPECT_FALSE(memory.excluded(visited + Eigen::Vector2d(0.6, 0.0), 0.0));
  // A failed goal that had been visited keeps the visited radius.
  memory.record_failure(visited, 0.0);
  EXPECT_FALSE(memory.excluded(visited + Eigen::Vector2d(0.6, 0.0), 0.0));
}

// A goal that just failed (no way through a blank wall yet, a passer-by in the door) is not
// taken up again at once: for the cooldown it excludes its neighbourhood as a blacklisted one
// does, then it may be chosen again, until its last allowed failure blacklists it for good.
TEST(GoalMemory, AGoalThatJustFailedIsSkippedForTheCooldownOnly) {
  GoalMemory memory(8, 0.5, 2.0, 3, 300.0);
  const Eigen::Vector2d goal(1.35, 8.55);
  const Eigen::Vector2d beside = goal + Eigen::Vector2d(1.5, 0.0);
  EXPECT_FALSE(memory.excluded(beside, 100.0));
  EXPECT_FALSE(memory.record_failure(goal, 100.0));
  EXPECT_TRUE(memory.excluded(goal, 100.0));
  EXPECT_TRUE(memory.excluded(beside, 399.0));
  EXPECT_FALSE(memory.excluded(goal + Eigen::Vector2d(2.1, 0.0), 101.0));
  EXPECT_FALSE(memory.excluded(beside, 400.0));
  EXPECT_FALSE(memory.record_failure(goal, 500.0));  // a second failure restarts the cooldown
  EXPECT_TRUE(memory.excluded(beside, 700.0));
  EXPECT_FALSE(memory.excluded(beside, 801.0));
  EXPECT_TRUE(memory.record_failure(goal, 900.0));
  EXPECT_TRUE(memory.excluded(beside, 1e6));

  GoalMemory without(8, 0.5, 2.0, 3);  // no cooldown: the default
  without.record_failure(goal, 100.0);
  EXPECT_FALSE(without.excluded(goal, 100.0));
}

// With a failure radius, failures add up by place: goals 1-2 m apart in a room the robot
// cannot enter count as one, against the nearest failed goal; a visited goal within it takes
// none of them, and a goal farther away starts a place of its own.
TEST(GoalMemory, WithAFailureRadiusFailuresAddUpByPlace) {
  GoalMemory memory(8, 0.5, 2.0, 3, 0.0, 0.0, 2.0);
  const Eigen::Vector2d goal(6.25, 9.15);
  memory.record_visit(goal + Eigen::Vector2d(0.0, -1.0));
  EXPECT_FALSE(memory.record_failure(goal, 100.0));
  EXPECT_FALSE(memory.record_failure(goal + Eigen::Vector2d(1.5, 0.0), 200.0));
  const Eigen::Vector2d far = goal + Eigen::Vector2d(4.0, 0.0);
  EXPECT_FALSE(memory.record_failure(far, 250.0));
  EXPECT_FALSE(memory.excluded(goal + Eigen::Vector2d(-1.0, 0.5), 250.0));
  EXPECT_TRUE(memory.record_failure(goal + Eigen::Vector2d(-1.2, 0.8), 300.0));
  EXPECT_EQ(memory.blacklisted(), 1U);
  EXPECT_TRUE(memory.excluded(goal + Eigen::Vector2d(-1.0, 0.5), 300.0));
  EXPECT_FALSE(memory.excluded(far + Eigen::Vector2d(0.5, 0.0), 300.0));  // one failure there

  GoalMemory by_goal(8, 0.5, 2.0, 3);  // the default: by goal
  EXPECT_FALSE(by_goal.record_failure(goal, 100.0));
  EXPECT_FALSE(by_goal.record_failure(goal + Eigen::Vector2d(1.5, 0.0), 200.0));
  EXPECT_FALSE(by_goal.record_failure(goal + Eigen::Vector2d(-1.2, 0.8), 300.0));
  EXPECT_EQ(by_goal.blacklisted(), 0U);
}

// With a hold, a blacklisting passes: the goal (and the candidates beside it) may be chosen
// again hold_s after its last failure, its failures counted afresh, and a second blacklisting
// lasts twice as long. A failure while held neither counts nor lengthens the hold. Visited
// goals, and blacklistings without a hold, last for good.
TEST(GoalMemory, ABlacklistingLastsItsHoldThenTwiceAsLongTheNextTime) {
  GoalMemory memory(8, 0.5, 2.0, 3, 0.0, 600.0);
  const Eigen::Vector2d goal(14.05, 5.15);
  const Eigen::Vector2d beside = goal + Eigen::Vector2d(1.5, 0.0);
  EXPECT_FALSE(memory.record_failure(goal, 100.0));
  EXPECT_FALSE(memory.record_failure(goal, 200.0));
  EXPECT_TRUE(memory.record_failure(goal, 300.0));
  EXPECT_TRUE(memory.excluded(beside, 899.0));
  EXPECT_TRUE(memory.record_failure(goal, 500.0));  // held: not counted
  EXPECT_FALSE(memory.excluded(beside, 901.0));
  EXPECT_FALSE(memory.excluded(goal, 901.0));
  EXPECT_FALSE(memory.record_failure(goal, 1000.0));
  EXPECT_FALSE(memory.excluded(beside, 1001.0));  // one failure again: not blacklisted
  EXPECT_FALSE(memory.record_failure(goal, 1100.0));
  EXPECT_TRUE(memory.record_failure(goal, 1200.0));
  EXPECT_EQ(memory.blacklisted(), 2U);
  EXPECT_TRUE(memory.excluded(beside, 2399.0));
  EXPECT_FALSE(memory.excluded(beside, 2401.0));

  const Eigen::Vector2d visited(3.0, 3.0);
  memory.record_visit(visited);
  EXPECT_TRUE(memory.excluded(visited, 1e6));
  EXPECT_TRUE(memory.record_failure(visited, 1e6));

  GoalMemory for_good(8, 0.5, 2.0, 3);  // no hold (0): for good
  for (double t : {100.0, 200.0, 300.0}) for_good.record_failure(goal, t);
  EXPECT_TRUE(for_good.excluded(beside, 1e6));
}

// Before concluding "explored" the explorer lifts the holds of goals put aside: those
// blacklisted at most max_blacklistings times, not visited ones, not ones blacklisted for good
// (no hold). A released goal counts its failures afresh, and its next blacklisting holds twice
// as long and is not released again at 1.
TEST(GoalMemory, ReleasingLiftsTheHoldsOfGoalsBlacklistedAtMostSoOften) {
  GoalMemory memory(8, 0.5, 2.0, 3, 0.0, 600.0);
  const Eigen::Vector2d goal(6.05, 4.95);
  const Eigen::Vector2d beside = goal + Eigen::Vector2d(1.5, 0.0);
  EXPECT_EQ(memory.release_held(0.0, 1), 0U);  // nothing held
  for (double t : {100.0, 110.0, 120.0}) memory.record_failure(goal, t);
  const Eigen::Vector2d visited(3.0, 3.0);
  memory.record_visit(visited);
  ASSERT_TRUE(memory.excluded(beside, 200.0));
  EXPECT_EQ(memory.release_held(200.0, 0), 0U);  // 0: never
  EXPECT_EQ(memory.release_held(200.0, 1), 1U);
  EXPECT_FALSE(memory.excluded(beside, 200.0));
  EXPECT_FALSE(memory.excluded(goal, 200.0));
  EXPECT_TRUE(memory.excluded(visited, 200.0));
  EXPECT_EQ(memory.release_held(201.0, 1), 0U);  // nothing held any more
  EXPECT_FALSE(memory.record_failure(goal, 300.0));
  EXPECT_FALSE(memory.record_failure(goal, 310.0));
  EXPECT_TRUE(memory.record_failure(goal, 320.0));
  EXPECT_EQ(memory.blacklisted(), 2U);
  EXPECT_EQ(memory.release_held(400.0, 1), 0U);  // blacklisted twice now
  EXPECT_TRUE(memory.excluded(beside, 1519.0));  // 1200 s from its last failure
  EXPECT_EQ(memory.release_held(400.0, 2), 1U);

  GoalMemory for_good(8, 0.5, 2.0, 3);  // no hold: blacklisted for good, never released
  for (double t : {100.0, 200.0, 300.0}) for_good.record_failure(goal, t);
  EXPECT_EQ(for_good.release_held(400.0, 100), 0U);
  EXPECT_TRUE(for_good.excluded(beside, 400.0));
}

// A known free room (walls around) with an unknown region beyond its right wall seen through
// a doorway, and a second free room that is not connected to the robot's.
struct SelectionScene {
  TestGrid grid{120, 60, CellState::unknown};
  SelectionScene() {
    grid.fill(0, 0, 60, 60, CellState::free);
    grid.fill(0, 0, 60, 1, CellState::occupied);
    grid.fill(0, 59, 60, 60, CellState::occupied);
    grid.fill(0, 0, 1, 60, CellState::occupied);
    grid.fill(59, 0, 60, 60, CellState::occupied);
    grid.fill(59, 25, 60, 35, CellState::free);  // 1 m doorway to the unknown right half
    // An isolated free pocket inside the unknown half, walled off.
    grid.fill(90, 5, 110, 20, CellState::occupied);
    grid.fill(91, 6, 109, 19, CellState::free);
  }
};

TEST(GoalValue, SelectsAReachableSafeCellFacingTheUnknown) {
  SelectionScene scene;
  const ExploreParams params = test_params(120, 60);
  NavigationMap map(params);
  const Eigen::Vector2d robot(1.5, 3.0);
  ASSERT_TRUE(map.rebuild(scene.grid.view(), robot, robot));
  map.compute_reachable(scene.grid.view().cell_of(robot));
  GoalMemory memory(16, params.explore.visited_goal_radius_m, params.explore.blacklist_radius_m,
                    params.explore.goal_failures_before_blacklist);
  const GoalValue goal_value(params);
  const Goal goal = goal_value.select(map, memory, 0.0);
  ASSERT_TRUE(goal.valid);
  EXPECT_TRUE(map.reachable(goal.cell.x(), goal.cell.y()));
  EXPECT_EQ(map.traversability(goal.cell.x(), goal.cell.y()), Traversability::safe);
  EXPECT_LT(goal.cell.x(), 59);  // in the robot's room, not the isolated pocket
  EXPECT_GT(goal.value, params.explore.min_goal_value);
  EXPECT_DOUBLE_EQ(goal.value, goal_value.value(scene.grid.view(), goal.cell.x(), goal.cell.y()));
  // No candidate is worth more (full-resolution search over the candidates).
  double best = 0.0;
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 120; ++x) {
      if (goal_value.is_candidate(map, memory, 0.0, x, y)) best = std::max(best, goal_value.value(scene.grid.view(), x, y));
    }
  }
  EXPECT_GT(goal.value, 0.9 * best);  // lattice then local refinement finds (nearly) the optimum
  // Blacklisting the chosen goal moves the choice elsewhere.
  for (int k = 0; k < params.explore.goal_failures_before_blacklist; ++k) memory.record_failure(goal.position, 0.0);
  const Goal next = goal_value.select(map, memory, 0.0);
  ASSERT_TRUE(next.valid);
  EXPECT_GT((next.position - goal.position).norm(), params.explore.blacklist_radius_m);
}

// A long hall, 16 x 4 m, the robot at its west end: a small unknown patch in the wall near it,
// the whole east end unknown. The paper's argmax H drives to the east end; a cost per metre
// of path keeps the robot at the patch beside it. reach_distance_m is the fill's path length.
TEST(GoalValue, ADistanceCostPrefersTheNearGoalToAFarBetterOne) {
  TestGrid grid(160, 40, CellState::free);
  grid.walls();
  grid.fill(140, 1, 159, 39, CellState::unknown);  // the east end
  grid.fill(38, 39, 44, 40, CellState::unknown);   // a patch in the north wall near the robot
  ExploreParams params = test_params(160, 40);
  NavigationMap map(params);
  const Eigen::Vector2d robot(1.0, 2.0);
  ASSERT_TRUE(map.rebuild(grid.view(), robot, robot));
  const Eigen::Vector2i start = grid.view().cell_of(robot);
  map.compute_reachable(start);
  EXPECT_DOUBLE_EQ(map.reach_distance_m(start.x(), start.y()), 0.0);
  EXPECT_NEAR(map.reach_distance_m(start.x() + 50, start.y()), 5.0, 1e-9);
  EXPECT_NEAR(map.reach_distance_m(start.x() + 50, start.y() + 10), 5.0, 1e-9) << "8-connected: a diagonal step is one";
  GoalMemory memory(16, params.explore.visited_goal_radius_m, params.explore.blacklist_radius_m,
                    params.explore.goal_failures_before_blacklist);
  const Goal paper = GoalValue(params).select(map, memory, 0.0);
  ASSERT_TRUE(paper.valid);
  EXPECT_GT(paper.position.x(), 10.0) << "argmax H: the east end";
  EXPECT_DOUBLE_EQ(paper.utility, paper.value);
  params.explore.goal_distance_cost = 2.0;
  const Goal near = GoalValue(params).select(map, memory, 0.0);
  ASSERT_TRUE(near.valid);
  EXPECT_LT(near.position.x(), 7.0) << "with the cost: the patch beside the robot";
  EXPECT_LT(near.value, paper.value);
  EXPECT_NEAR(near.utility, near.value - 2.0 * map.reach_distance_m(near.cell.x(), near.cell.y()), 1e-9);
}

// A goal's cell made impassable moves to the nearest passable cell in sight of it, never to
// the other side of a wall (the view from there is not the goal's).
TEST(NavigationMap, NearestPassableCellStaysOnTheGoalsSideOfAWall) {
  TestGrid grid(60, 60, CellState::free);
  grid.fill(14, 0, 15, 60, CellState::occupied);  // two walls 0.6 m apart: nothing passable between
  grid.fill(20, 0, 21, 60, CellState::occupied);
  NavigationMap map(test_params(60, 60));
  const Eigen::Vector2d robot(4.0, 1.0);
  ASSERT_TRUE(map.rebuild(grid.view(), robot, robot));
  Eigen::Vector2i found(-1, -1);
  ASSERT_FALSE(map.passable(19, 30));
  EXPECT_FALSE(map.nearest_passable({19, 30}, 0.6, found));  // the passable cells are across x = 20
  ASSERT_FALSE(map.passable(21, 30));
  ASSERT_TRUE(map.nearest_passable({21, 30}, 0.6, found));
  EXPECT_EQ(found, Eigen::Vector2i(24, 30));
  grid.set(21, 30, CellState::occupied);  // a trace on the goal's own cell does not hide the rest
  ASSERT_TRUE(map.rebuild(grid.view(), robot, robot));
  ASSERT_TRUE(map.nearest_passable({21, 30}, 0.6, found));
  EXPECT_EQ(found, Eigen::Vector2i(25, 30));  // 0.4 m from the trace
}

TEST(NavigationMap, InflatesObstaclesByTheRobotRadiusAndMargin) {
  TestGrid grid(60, 60, CellState::free);
  grid.set(30, 30, CellState::occupied);
  const ExploreParams params = test_params(60, 60);
  NavigationMap map(params);
  const Eigen::Vector2d robot(1.0, 1.0);
  ASSERT_TRUE(map.rebuild(grid.view(), robot, robot));
  EXPECT_DOUBLE_EQ(map.occupied_distance_m(34, 30), 0.4);
  EXPECT_NEAR(map.occupied_distance_m(33, 34), 0.5, 1e-12);
  EXPECT_EQ(map.traversability(30, 30), Traversability::lethal);
  EXPECT_EQ(map.traversability(33, 30), Traversability::lethal);    // 0.3 m < 0.35 + 0.05
  EXPECT_EQ(map.traversability(34, 30), Traversability::inflated);  // 0.4 m, inside the 0.1 m margin
  EXPECT_EQ(map.traversability(35, 30), Traversability::safe);      // 0.5 m
  // Unknown cells are passable only near the robot.
  TestGrid unknown(60, 60, CellState::unknown);
  ASSERT_TRUE(map.rebuild(unknown.view(), robot, robot));
  EXPECT_TRUE(map.passable(14, 10));   // 0.4 m from the robot
  EXPECT_FALSE(map.passable(25, 10));  // 1.5 m from the robot
  // Near the start pose (the explorer's extra centre when returning) too; near the robot only
  // with unknown_travel_near_robot, and never a cell that was in view (a blank wall).
  const Eigen::Vector2d start(4.0, 4.0);
  ExploreParams start_only_params = params;
  start_only_params.explore.unknown_travel_near_robot = false;
  NavigationMap start_only(start_only_params);
  ASSERT_TRUE(start_only.rebuild(unknown.view(), robot, start));
  EXPECT_FALSE(start_only.passable(14, 10));
  EXPECT_TRUE(start_only.passable(43, 40));
  std::vector<std::uint8_t> in_view(unknown.cells.size(), 0);
  in_view[unknown.view().index(14, 10)] = 1;
  GridView seen = unknown.view();
  seen.in_view = in_view.data();
  ASSERT_TRUE(map.rebuild(seen, robot, start));
  EXPECT_FALSE(map.passable(14, 10));  // in view: a surface the stereo could not measure
  EXPECT_TRUE(map.passable(10, 14));   // as near, never in view: the blind zone
  EXPECT_TRUE(map.passable(43, 40));
  // Unless the marks are for the goal value only.
  ExploreParams value_only_params = params;
  value_only_params.explore.in_view_blocks_travel = false;
  NavigationMap value_only(value_only_params);
  ASSERT_TRUE(value_only.rebuild(seen, robot, start));
  EXPECT_TRUE(value_only.passable(14, 10));
}

// A corridor whose walls were never seen (blank: their cells stay unknown), far from the
// start: the robot keeps its radius and margin from them as from occupied cells, except
// where it stands (it cannot be in a wall).
// The distance transforms against the nearest site found by brute force, on a scatter of
// occupied and unknown cells: within a small fraction of a cell everywhere (two-pass
// propagation is not exact in every configuration), and "none" where there is no site.
TEST(NavigationMap, DistancesMatchTheNearestCellFoundByBruteForce) {
  const int width = 90;
  const int height = 70;
  TestGrid grid(width, height, CellState::free);
  std::mt19937 random(7);
  std::uniform_int_distribution<int> pick_x(0, width - 1);
  std::uniform_int_distribution<int> pick_y(0, height - 1);
  for (int k = 0; k < 60; ++k) grid.set(pick_x(random), pick_y(random), CellState::occupied);
  for (int k = 0; k < 12; ++k) grid.set(pick_x(random), pick_y(random), CellState::unknown);
  grid.fill(0, 0, 12, 12, CellState::free);  // nothing under or near the robot
  ExploreParams params = test_params(width, height);
  params.explore.unknown_clearance = false;  // the occupied transform's sites: occupied cells only
  params.explore.shadow_depth_m = 0.0;
  NavigationMap map(params);
  const Eigen::Vector2d robot(0.55, 0.55);
  ASSERT_TRUE(map.rebuild(grid.view(), robot, robot));
  auto nearest_m = [&](int x, int y, CellState state) {
    double best = 1e9;
    for (int sy = 0; sy < height; ++sy) {
      for (int sx = 0; sx < width; ++sx) {
        if (grid.cells[static_cast<std::size_t>(sy * width + sx)] == static_cast<std::uint8_t>(state)) {
          best = std::min(best, 0.1 * std::hypot(sx - x, sy - y));
        }
      }
    }
    return best;
  };
  int exact = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double occupied = nearest_m(x, y, CellState::occupied);
      const double unknown = nearest_m(x, y, CellState::unknown);
      EXPECT_NEAR(map.occupied_distance_m(x, y), occupied, 0.02) << x << ", " << y;
      EXPECT_NEAR(map.unknown_distance_m(x, y), unknown, 0.02) << x << ", " << y;
      if (std::abs(map.occupied_distance_m(x, y) - occupied) < 1e-12 &&
          std::abs(map.unknown_distance_m(x, y) - unknown) < 1e-12) {
        ++exact;
      }
    }
  }
  EXPECT_GE(exact, width * height * 99 / 100);
  // No unknown cell at all: every distance is "none".
  TestGrid known(width, height, CellState::free);
  known.set(50, 40, CellState::occupied);
  ASSERT_TRUE(map.rebuild(known.view(), robot, robot));
  EXPECT_GT(map.unknown_distance_m(50, 30), 1e6);
  EXPECT_NEAR(map.occupied_distance_m(50, 30), 1.0, 1e-12);
}

TEST(NavigationMap, UnknownCellsPathsMayNotCrossAreKeptClearOf) {
  TestGrid grid(80, 40, CellState::unknown);
  grid.fill(0, 10, 80, 32, CellState::free);  // 2.2 m of floor between y = 1 and 3.2
  ExploreParams params = test_params(80, 40);
  params.explore.unknown_clearance = true;
  NavigationMap map(params);
  const Eigen::Vector2d start(0.5, 2.1);
  const Eigen::Vector2d robot(5.0, 2.1);
  ASSERT_TRUE(map.rebuild(grid.view(), robot, start));
  EXPECT_NEAR(map.occupied_distance_m(60, 13), 0.4, 1e-12);  // 0.4 m from the unknown row 9
  EXPECT_EQ(map.traversability(60, 12), Traversability::lethal);    // 0.3 m: the disc in the wall
  EXPECT_EQ(map.traversability(60, 13), Traversability::inflated);  // 0.4 m
  EXPECT_EQ(map.traversability(60, 21), Traversability::safe);      // the middle
  // The robot standing 0.2 m from the wall (a pose error) may still leave.
  const Eigen::Vector2d grazing(5.05, 1.25);
  ASSERT_TRUE(map.rebuild(grid.view(), grazing, start));
  EXPECT_NE(map.traversability(50, 14), Traversability::lethal);  // 0.5 m out
  // Without the rule only the unknown cells themselves are barred.
  ExploreParams plain_params = params;
  plain_params.explore.unknown_clearance = false;
  NavigationMap plain(plain_params);
  ASSERT_TRUE(plain.rebuild(grid.view(), robot, start));
  EXPECT_NE(plain.traversability(60, 10), Traversability::lethal);
  EXPECT_EQ(plain.traversability(60, 9), Traversability::lethal);
}

// The clutter hall's brick box (seed 3, 304 s): the robot drove along its low south face with
// the face out of the camera's view, then turned towards the gap beside it. With the grid's
// looked-over marks, the unknown cells near the robot that no ray passed over are barred and
// kept clear of; the unknown cells the camera looked over (its blind ring) stay passable.
TEST(NavigationMap, UnknownCellsNearTheRobotNoViewSweptAreKeptClearOf) {
  TestGrid grid(60, 60, CellState::free);
  grid.fill(33, 33, 39, 39, CellState::unknown);  // never looked over: the box's unseen side
  grid.fill(22, 30, 27, 31, CellState::unknown);  // looked over, not measured: the blind ring
  grid.fill(48, 48, 52, 52, CellState::unknown);  // never looked over, far from the robot
  std::vector<std::uint8_t> looked_over(grid.cells.size(), 1);
  for (int y = 33; y < 39; ++y) {
    for (int x = 33; x < 39; ++x) looked_over[grid.view().index(x, y)] = 0;
  }
  for (int y = 48; y < 52; ++y) {
    for (int x = 48; x < 52; ++x) looked_over[grid.view().index(x, y)] = 0;
  }
  GridView marked = grid.view();
  marked.looked_over = looked_over.data();
  const ExploreParams params = test_params(60, 60);
  const Eigen::Vector2d robot(3.05, 3.05);  // cell (30, 30)
  const Eigen::Vector2d start(0.55, 0.55);
  NavigationMap map(params);
  ASSERT_TRUE(map.rebuild(marked, robot, start));
  EXPECT_FALSE(map.passable(34, 34));                             // 0.57 m from the robot
  EXPECT_EQ(map.traversability(36, 31), Traversability::lethal);  // 0.2 m from the unswept cells
  EXPECT_NEAR(map.occupied_distance_m(36, 28), 0.5, 1e-12);
  EXPECT_TRUE(map.passable(24, 30));                              // 0.6 m away, looked over
  EXPECT_GT(map.occupied_distance_m(50, 46), 1.0);                // far: barred, not kept clear of
  // Without the marks every unknown cell near the robot is passable, and none is kept clear of.
  NavigationMap plain(params);
  ASSERT_TRUE(plain.rebuild(grid.view(), robot, start));
  EXPECT_TRUE(plain.passable(34, 34));
  EXPECT_NE(plain.traversability(36, 31), Traversability::lethal);
}

// A walled room, all seen, with a 0.8 m box whose inside is unknown and whose ring has a
// two-cell gap the camera never saw (unknown too), and a 3.2 x 3.2 m unknown block walled off.
struct PocketScene {
  TestGrid grid{80, 60, CellState::free};
  PocketScene() {
    grid.walls();
    grid.fill(20, 20, 30, 30, CellState::occupied);
    grid.fill(21, 21, 29, 29, CellState::unknown);
    grid.fill(20, 24, 21, 26, CellState::unknown);  // the gap, facing west
    grid.fill(44, 10, 78, 44, CellState::occupied);
    grid.fill(45, 11, 77, 43, CellState::unknown);  // 10.2 m^2: larger than a pocket
  }
};

TEST(NavigationMap, SmallEnclosedUnknownRegionsArePocketsOpenOrLargeOnesAreNot) {
  PocketScene scene;
  const ExploreParams params = test_params(80, 60);
  NavigationMap map(params);
  const Eigen::Vector2d robot(0.5, 2.5);
  ASSERT_TRUE(map.rebuild(scene.grid.view(), robot, robot));
  EXPECT_TRUE(map.in_pocket(25, 25));
  EXPECT_TRUE(map.in_pocket(20, 24));  // the gap is part of it
  EXPECT_FALSE(map.in_pocket(22, 40));  // free
  EXPECT_FALSE(map.in_pocket(60, 30));  // too large
  EXPECT_EQ(map.pocket_cells(), 64U + 2U);
  // A grid whose unknown reaches the window's edge: the world outside, never a pocket.
  TestGrid open_room(80, 60, CellState::unknown);
  open_room.fill(10, 10, 20, 20, CellState::free);
  open_room.set(12, 12, CellState::unknown);
  ASSERT_TRUE(map.rebuild(open_room.view(), robot, robot));
  EXPECT_TRUE(map.in_pocket(12, 12));  // one unseen cell inside seen floor
  EXPECT_FALSE(map.in_pocket(40, 40));
  EXPECT_EQ(map.pocket_cells(), 1U);
}

TEST(GoalValue, RaysIntoAPocketAreWorthNothing) {
  PocketScene scene;
  const ExploreParams params = test_params(80, 60);
  NavigationMap map(params);
  const Eigen::Vector2d robot(0.5, 2.5);
  ASSERT_TRUE(map.rebuild(scene.grid.view(), robot, robot));
  const GoalValue goal_value(params);
  // 1.9 m west of the gap, nothing else unknown within the ray cap: the plain H sees the
  // gap near r*; the map's H does not.
  EXPECT_GT(goal_value.value(scene.grid.view(), 1, 25), 0.5);
  EXPECT_DOUBLE_EQ(goal_value.value(map, 1, 25), 0.0);
}

}  // namespace
}  // namespace stereoscout::explore
