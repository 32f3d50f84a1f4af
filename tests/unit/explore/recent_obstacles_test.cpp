// The recent obstacle layer: what the scans saw standing at the camera's height, kept in the
// odometry frame and stamped into the planning grid from the robot's current pose, forgotten
// when a later scan sees past it or when it is old.
#include <gtest/gtest.h>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/explore/recent_obstacles.hpp"
#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

using testing::TestGrid;

core::ExploreConfig recent_config() {
  core::ExploreConfig config;
  config.recent_obstacle_s = 30.0;
  return config;
}

core::DepthScanColumn column(double x, double y, core::DepthScanColumn::Kind kind, bool at_camera_height = true,
                             double measurable_from_m = 0.0) {
  core::DepthScanColumn c;
  c.x_robot_m = static_cast<float>(x);
  c.y_robot_m = static_cast<float>(y);
  c.kind = kind;
  c.obstacle_at_camera_height = kind == core::DepthScanColumn::Kind::obstacle && at_camera_height;
  c.measurable_from_m = static_cast<float>(measurable_from_m);
  return c;
}

// A surface straight ahead of the robot, `ahead_m` from its centre, `width_m` across, one
// column every centimetre (the camera at the robot's centre).
core::DepthScan wall_ahead(double ahead_m, double width_m, bool at_camera_height = true) {
  core::DepthScan scan;
  for (double y = -0.5 * width_m; y <= 0.5 * width_m + 1e-9; y += 0.01) {
    scan.columns.push_back(column(ahead_m, y, core::DepthScanColumn::Kind::obstacle, at_camera_height));
  }
  return scan;
}

// Floor seen straight ahead out to `free_to_m` across the same bearings, nothing measured
// nearer than `measurable_from_m`.
core::DepthScan floor_ahead(double free_to_m, double width_m, double measurable_from_m) {
  core::DepthScan scan;
  for (double y = -0.5 * width_m; y <= 0.5 * width_m + 1e-9; y += 0.01) {
    scan.columns.push_back(column(free_to_m, y * free_to_m, core::DepthScanColumn::Kind::free, false, measurable_from_m));
  }
  return scan;
}

SeenObstacles seen_at(const core::DepthScan& scan, const core::Pose2& odometry, double time_s,
                      const core::Pose2& pose = core::Pose2{}) {
  SeenObstacles seen;
  seen.time_s = time_s;
  seen.scan = &scan;
  seen.odometry = odometry;
  seen.pose = pose;
  return seen;
}

bool occupied_at(const GridView& grid, const Eigen::Vector2d& point) {
  const Eigen::Vector2i cell = grid.cell_of(point);
  return grid.at(cell.x(), cell.y()) == CellState::occupied;
}

// recent_obstacle_s 0 turns the layer off (on by default since 2026-11-29): nothing kept, the
// grid handed back as it came.
TEST(RecentObstacles, OffTheGridIsTheInputGrid) {
  core::ExploreConfig off;
  off.recent_obstacle_s = 0.0;
  ASSERT_GT(core::ExploreConfig{}.recent_obstacle_s, 0.0);
  RecentObstacles recent(off, 60, 60);
  const TestGrid grid(60, 60, CellState::free);
  const core::DepthScan scan = wall_ahead(1.0, 0.6);
  recent.observe(seen_at(scan, core::Pose2{}, 1.0));
  EXPECT_EQ(recent.stamp(grid.view(), core::Pose2{2.0, 3.0, 0.0}, core::Pose2{}, 1.0).cells, grid.view().cells);
  EXPECT_EQ(recent.held(), 0U);
}

// The robot saw a jamb 1.05 m ahead, drove 0.8 m towards it by odometry (the jamb now beside or
// too near to see), and meanwhile the estimate moved to another lineage whose pose is 0.3 m
// off the first: the jamb is stamped 0.25 m ahead of the robot as it stands in the new pose,
// not where the first lineage's pose put it.
TEST(RecentObstacles, AnObstacleSeenAMomentAgoStaysWhereItIsRelativeToTheRobotWhenTheEstimateJumps) {
  RecentObstacles recent(recent_config(), 60, 60);
  const TestGrid grid(60, 60, CellState::free);
  const core::DepthScan scan = wall_ahead(1.05, 0.2);
  const core::Pose2 odometry_then{10.0, -4.0, 0.5};  // odometry's own frame: anywhere
  recent.observe(seen_at(scan, odometry_then, 1.0));
  EXPECT_GT(recent.held(), 3U);
  const core::Pose2 odometry_now = odometry_then.compose(core::Pose2{0.8, 0.0, 0.0});
  const core::Pose2 pose_now{2.0, 3.3, 0.0};  // the new lineage; the old one had (2.0, 3.0)
  const GridView stamped = recent.stamp(grid.view(), pose_now, odometry_now, 8.0);
  ASSERT_NE(stamped.cells, grid.view().cells);
  EXPECT_TRUE(occupied_at(stamped, {2.25, 3.3}));
  EXPECT_FALSE(occupied_at(stamped, {2.25, 3.0}));
  EXPECT_FALSE(occupied_at(stamped, {1.95, 3.3}));
  EXPECT_GT(recent.cells_stamped(), 0U);
  // The input grid is untouched.
  EXPECT_FALSE(occupied_at(grid.view(), {2.25, 3.3}));
}

// A look (two full turns in place) turns odometry's heading 0.25 rad against the estimate's,
// which the landmarks hold; then the robot drives 0.6 m towards a jamb it saw 1.05 m ahead
// before the look. Kept in the odometry frame the jamb is stamped 0.2 m to the side of where it
// stands; in the layer frame of recent_obstacle_estimate_heading, 0.45 m ahead, where it is.
TEST(RecentObstacles, WithTheEstimatesHeadingATurnInPlaceDoesNotSwingThePoints) {
  const TestGrid grid(60, 60, CellState::free);
  const core::DepthScan jamb = wall_ahead(1.05, 0.2);
  const core::DepthScan nothing;
  const double odometry_drift_rad = 0.25;
  const auto after_look = [&](RecentObstacles& recent) {
    recent.observe(seen_at(jamb, core::Pose2{}, 1.0, core::Pose2{2.0, 3.0, 0.0}));
    for (int step = 1; step <= 16; ++step) {
      const double turned = step * core::kPi / 4.0;
      const core::Pose2 odometry{0.0, 0.0, turned + odometry_drift_rad * step / 16.0};
      recent.observe(seen_at(nothing, odometry, 1.0 + step, core::Pose2{2.0, 3.0, turned}));
    }
    const core::Pose2 odometry_now = core::Pose2{0.0, 0.0, odometry_drift_rad}.compose(core::Pose2{0.6, 0.0, 0.0});
    return recent.stamp(grid.view(), core::Pose2{2.6, 3.0, 0.0}, odometry_now, 20.0);
  };
  core::ExploreConfig config = recent_config();
  RecentObstacles in_odometry(config, 60, 60);
  const GridView swung = after_look(in_odometry);
  EXPECT_FALSE(occupied_at(swung, {3.05, 3.05}));
  EXPECT_FALSE(occupied_at(swung, {3.05, 2.95}));
  EXPECT_TRUE(occupied_at(swung, {3.0, 2.8}));
  config.recent_obstacle_estimate_heading = true;
  RecentObstacles in_layer(config, 60, 60);
  const GridView held = after_look(in_layer);
  EXPECT_TRUE(occupied_at(held, {3.05, 3.05}));
  EXPECT_TRUE(occupied_at(held, {3.05, 2.95}));
  EXPECT_FALSE(occupied_at(held, {3.0, 2.8}));
}

// In the layer frame a stretch driven between scans is the odometry's chord turned by the
// estimate's heading at the stretch's start, whatever the odometry's heading there.
TEST(RecentObstacles, WithTheEstimatesHeadingTheOdometrysTranslationIsKept) {
  core::ExploreConfig config = recent_config();
  config.recent_obstacle_estimate_heading = true;
  RecentObstacles recent(config, 80, 80);
  const TestGrid grid(80, 80, CellState::free);
  const core::DepthScan jamb = wall_ahead(1.05, 0.2);
  const core::DepthScan nothing;
  const core::Pose2 odometry_then{5.0, -1.0, 1.0};  // odometry's own frame, its heading 1 rad off
  recent.observe(seen_at(jamb, odometry_then, 1.0, core::Pose2{2.0, 3.0, 0.0}));
  // 0.5 m ahead, then a quarter turn left and 0.3 m on, by odometry.
  const core::Pose2 odometry_mid = odometry_then.compose(core::Pose2{0.5, 0.0, core::kPi / 2.0});
  recent.observe(seen_at(nothing, odometry_mid, 2.0, core::Pose2{2.4, 3.1, core::kPi / 2.0}));
  const core::Pose2 odometry_now = odometry_mid.compose(core::Pose2{0.3, 0.0, 0.0});
  // The estimate moved to another lineage meanwhile (0.3 m off); the jamb stays 0.3 m behind
  // the robot and 0.55 m to its right, as the odometry drove.
  const core::Pose2 pose_now{2.5, 3.6, core::kPi / 2.0};
  const GridView stamped = recent.stamp(grid.view(), pose_now, odometry_now, 3.0);
  EXPECT_TRUE(occupied_at(stamped, pose_now.transform_point({-0.3, -0.55})));
  EXPECT_FALSE(occupied_at(stamped, {3.05, 3.0}));  // where the first lineage's pose saw it
}

TEST(RecentObstacles, ACellTheGridHoldsOccupiedAlreadyNeedsNoCopy) {
  RecentObstacles recent(recent_config(), 60, 60);
  TestGrid grid(60, 60, CellState::free);
  grid.fill(29, 20, 31, 40, CellState::occupied);  // x 2.9-3.1 m: the wall as the grid holds it
  const core::DepthScan scan = wall_ahead(1.0, 0.4);
  recent.observe(seen_at(scan, core::Pose2{}, 1.0));
  EXPECT_EQ(recent.stamp(grid.view(), core::Pose2{2.0, 3.0, 0.0}, core::Pose2{}, 1.0).cells, grid.view().cells);
}

TEST(RecentObstacles, ALaterScanThatSawPastAPointForgetsIt) {
  RecentObstacles recent(recent_config(), 60, 60);
  const TestGrid grid(60, 60, CellState::free);
  const core::Pose2 pose{2.0, 3.0, 0.0};
  const core::DepthScan person = wall_ahead(1.0, 0.4);
  recent.observe(seen_at(person, core::Pose2{}, 1.0));
  ASSERT_NE(recent.stamp(grid.view(), pose, core::Pose2{}, 1.0).cells, grid.view().cells);
  // The person walked on: from the same place the floor is seen 3 m ahead on those bearings.
  const core::DepthScan floor = floor_ahead(3.0, 0.5, 0.6);
  recent.observe(seen_at(floor, core::Pose2{}, 2.0));
  EXPECT_EQ(recent.held(), 0U);
  EXPECT_GT(recent.seen_past(), 0U);
  EXPECT_EQ(recent.stamp(grid.view(), pose, core::Pose2{}, 2.0).cells, grid.view().cells);
}

// Nearer than the matcher measures (a jamb 0.5 m ahead of a matcher whose near limit is
// 0.63 m) a later scan says nothing about the point, nor does one that saw no farther than it.
TEST(RecentObstacles, APointNearerThanALaterScanMeasuresOrAsFarAsItSawIsKept) {
  RecentObstacles recent(recent_config(), 60, 60);
  const core::DepthScan jamb = wall_ahead(1.0, 0.2);
  recent.observe(seen_at(jamb, core::Pose2{}, 1.0));
  const std::size_t held = recent.held();
  const core::Pose2 half_a_metre_on{0.5, 0.0, 0.0};
  const core::DepthScan floor = floor_ahead(3.0, 1.0, 0.63);
  recent.observe(seen_at(floor, half_a_metre_on, 2.0));
  EXPECT_EQ(recent.held(), held);
  const core::DepthScan same_surface = wall_ahead(1.05, 0.4);  // the jamb again, 0.05 m deeper
  recent.observe(seen_at(same_surface, core::Pose2{}, 3.0));
  EXPECT_EQ(recent.seen_past(), 0U);
  EXPECT_GT(recent.held(), held);
}

TEST(RecentObstacles, LowObstaclesAndFarSurfacesAreNotKept) {
  RecentObstacles recent(recent_config(), 60, 60);
  const core::DepthScan box = wall_ahead(1.0, 0.4, /*at_camera_height=*/false);
  recent.observe(seen_at(box, core::Pose2{}, 1.0));
  const core::DepthScan far_wall = wall_ahead(2.5, 0.4);  // beyond recent_obstacle_range_m (2 m)
  recent.observe(seen_at(far_wall, core::Pose2{}, 2.0));
  EXPECT_EQ(recent.held(), 0U);
}

core::DepthScan blank_wall_ahead(double ahead_m, double width_m) {
  core::DepthScan scan = wall_ahead(ahead_m, width_m, /*at_camera_height=*/false);
  for (core::DepthScanColumn& c : scan.columns) c.blank_wall = core::DepthScanColumn::BlankWall::base;
  return scan;
}

// A door's jamb in a blank wall: the scan puts it at the wall's base, not measured at the
// camera's height. Kept with recent_obstacle_blank_walls only, once the scan before saw it
// too; a low box never.
TEST(RecentObstacles, BlankWallColumnsSeenTwiceAreKeptWithTheirKeyOnly) {
  const core::DepthScan blank_jamb = blank_wall_ahead(1.0, 0.4);
  const core::DepthScan box = wall_ahead(1.5, 0.4, /*at_camera_height=*/false);
  core::ExploreConfig config = recent_config();
  RecentObstacles without(config, 60, 60);
  without.observe(seen_at(blank_jamb, core::Pose2{}, 1.0));
  without.observe(seen_at(blank_jamb, core::Pose2{}, 1.5));
  EXPECT_EQ(without.held(), 0U);
  config.recent_obstacle_blank_walls = true;
  RecentObstacles with(config, 60, 60);
  with.observe(seen_at(box, core::Pose2{}, 1.0));
  with.observe(seen_at(box, core::Pose2{}, 1.5));
  EXPECT_EQ(with.held(), 0U);
  with.observe(seen_at(blank_jamb, core::Pose2{}, 2.0));
  EXPECT_EQ(with.held(), 0U);  // once: not yet
  EXPECT_GT(with.blank_unconfirmed(), 0U);
  // Seen again 0.04 m nearer, the robot having driven 0.04 m: the same place in the layer.
  const core::DepthScan again = blank_wall_ahead(0.96, 0.4);
  with.observe(seen_at(again, core::Pose2{0.04, 0.0, 0.0}, 2.5));
  EXPECT_GT(with.held(), 0U);
  // Placed by the odometry: the estimate 0.3 m off across the way does not move it.
  const TestGrid grid(60, 60, CellState::free);
  const core::Pose2 estimate{2.0, 3.3, 0.0};
  const GridView stamped = with.stamp(grid.view(), estimate, core::Pose2{0.04, 0.0, 0.0}, 3.0);
  EXPECT_TRUE(occupied_at(stamped, Eigen::Vector2d(2.96, 3.3)));
  EXPECT_FALSE(occupied_at(stamped, Eigen::Vector2d(2.96, 2.6)));
}

// A brightness step on the floor that a scan takes for a wall's base once (seen through a door)
// and the next scan does not: never kept.
TEST(RecentObstacles, ABlankWallPointOfOneScanAloneIsNotKept) {
  core::ExploreConfig config = recent_config();
  config.recent_obstacle_blank_walls = true;
  RecentObstacles recent(config, 60, 60);
  recent.observe(seen_at(blank_wall_ahead(1.2, 0.3), core::Pose2{}, 1.0));
  recent.observe(seen_at(blank_wall_ahead(1.6, 0.3), core::Pose2{}, 1.5));  // elsewhere
  recent.observe(seen_at(floor_ahead(2.0, 0.3, 0.5), core::Pose2{}, 2.0));
  EXPECT_EQ(recent.held(), 0U);
  EXPECT_GT(recent.blank_unconfirmed(), 0U);
}

TEST(RecentObstacles, PointsExpireAndAStrayPointMarksNoCell) {
  core::ExploreConfig config = recent_config();
  config.recent_obstacle_min_points = 2;
  RecentObstacles recent(config, 60, 60);
  const TestGrid grid(60, 60, CellState::free);
  const core::Pose2 pose{2.0, 3.0, 0.0};
  core::DepthScan stray;
  stray.columns.push_back(column(1.0, 0.0, core::DepthScanColumn::Kind::obstacle));
  recent.observe(seen_at(stray, core::Pose2{}, 1.0));
  EXPECT_EQ(recent.held(), 1U);
  EXPECT_EQ(recent.stamp(grid.view(), pose, core::Pose2{}, 1.0).cells, grid.view().cells);
  const core::DepthScan wall = wall_ahead(1.0, 0.4);
  recent.observe(seen_at(wall, core::Pose2{}, 2.0));
  EXPECT_NE(recent.stamp(grid.view(), pose, core::Pose2{}, 31.5).cells, grid.view().cells);
  EXPECT_EQ(recent.expired(), 1U);  // the stray point, 30.5 s old
  EXPECT_EQ(recent.stamp(grid.view(), pose, core::Pose2{}, 32.5).cells, grid.view().cells);
  EXPECT_EQ(recent.held(), 0U);
}

// With recent_obstacle_travel_m, a point lasts while the robot turns or waits (odometry does
// not drift standing still), and goes once the odometry has driven that far.
TEST(RecentObstacles, PointsLastWhileTheRobotTurnsAndExpireByTheDistanceDriven) {
  core::ExploreConfig config = recent_config();
  config.recent_obstacle_s = 600.0;
  config.recent_obstacle_travel_m = 3.0;
  RecentObstacles recent(config, 80, 80);
  const TestGrid grid(80, 80, CellState::free);
  const core::Pose2 pose{2.0, 3.0, 0.0};
  const core::DepthScan wall = wall_ahead(1.0, 0.4);
  const core::DepthScan nothing;
  recent.observe(seen_at(wall, core::Pose2{}, 1.0));
  recent.observe(seen_at(nothing, core::Pose2{2.0, 0.0, 0.0}, 20.0));
  for (int turn = 1; turn <= 8; ++turn) {
    recent.observe(seen_at(nothing, core::Pose2{2.0, 0.0, 0.7 * turn}, 20.0 + 30.0 * turn));
  }
  const double time_s = 300.0;  // ten times recent_config()'s 30 s
  const core::Pose2 odometry{2.0, 0.0, 0.0};
  const GridView turned = recent.stamp(grid.view(), pose, odometry, time_s);
  EXPECT_NEAR(recent.driven_m(), 2.0, 1e-9);
  EXPECT_TRUE(occupied_at(turned, pose.compose(odometry.inverse()).transform_point({1.0, 0.0})));
  EXPECT_EQ(recent.expired(), 0U);
  recent.observe(seen_at(nothing, core::Pose2{2.0, 1.1, 0.0}, time_s + 10.0));
  EXPECT_EQ(recent.stamp(grid.view(), pose, core::Pose2{2.0, 1.1, 0.0}, time_s + 10.0).cells, grid.view().cells);
  EXPECT_EQ(recent.held(), 0U);
  EXPECT_EQ(recent.expired(), recent.kept());
}

TEST(RecentObstacles, AScanIsObservedOnceAndAFullMemoryDropsItsOldest) {
  core::ExploreConfig config = recent_config();
  config.recent_obstacle_capacity = 50;
  RecentObstacles recent(config, 60, 60);
  const core::DepthScan wall = wall_ahead(1.0, 1.2);  // 31-41 points, 0.03-0.04 m apart
  recent.observe(seen_at(wall, core::Pose2{}, 1.0));
  const std::size_t one_scan = recent.held();
  recent.observe(seen_at(wall, core::Pose2{}, 1.0));
  EXPECT_EQ(recent.held(), one_scan);
  recent.observe(seen_at(wall, core::Pose2{}, 2.0));
  EXPECT_LT(one_scan, 50U);
  EXPECT_LE(recent.held(), 50U);
  EXPECT_GT(recent.dropped_full(), 0U);
  EXPECT_EQ(recent.kept(), 2 * one_scan);
}

TEST(RecentObstacles, ObservingAndStampingAllocateNothing) {
  RecentObstacles recent(recent_config(), 60, 60);
  const TestGrid grid(60, 60, CellState::free);
  const core::DepthScan wall = wall_ahead(1.0, 0.6);
  const core::DepthScan floor = floor_ahead(3.0, 0.5, 0.6);
  const core::AllocationScope scope;
  for (int i = 0; i < 20; ++i) {
    recent.observe(seen_at(i % 3 == 0 ? floor : wall, core::Pose2{}, 1.0 + i));
    recent.stamp(grid.view(), core::Pose2{2.0, 3.0, 0.0}, core::Pose2{}, 1.0 + i);
  }
  EXPECT_EQ(scope.allocations(), 0U);
}

// The gap ahead is found in the robot's frame by the odometry since the scan, whatever the map
// pose: the innermost points either side, the second nearest the line on each so that a lone
// stray match inside the door makes no side.
TEST(RecentObstacles, FindsTheGapBetweenKeptPointsAheadInTheRobotsFrame) {
  RecentObstacles recent(recent_config(), 60, 60);
  core::DepthScan scan;
  // Two posts 1.0 m ahead, their inner edges at y = +0.42 and -0.48, one column a centimetre.
  for (double y = 0.42; y <= 0.6; y += 0.01) scan.columns.push_back(column(1.0, y, core::DepthScanColumn::Kind::obstacle));
  for (double y = -0.48; y >= -0.6; y -= 0.01) scan.columns.push_back(column(1.0, y, core::DepthScanColumn::Kind::obstacle));
  // A stray match inside the gap, 0.1 m left of the line.
  scan.columns.push_back(column(1.2, 0.1, core::DepthScanColumn::Kind::obstacle));
  const core::Pose2 odometry_at_scan{-2.0, 1.0, 0.3};
  recent.observe(seen_at(scan, odometry_at_scan, 1.0));

  // 0.5 m on by the odometry; the map pose is anywhere.
  const core::Pose2 odometry_now = odometry_at_scan.compose(core::Pose2{0.5, 0.0, 0.0});
  const core::Pose2 map_pose{7.0, -3.0, 2.0};
  RecentObstacles::Gap gap;
  ASSERT_TRUE(recent.gap_ahead(map_pose, odometry_now, 0.35, 0.8, 0.6, 2, gap));
  EXPECT_NEAR(gap.left.x(), 0.5, 1e-6);
  EXPECT_NEAR(gap.right.x(), 0.5, 1e-6);
  // The second point from the line: the stray one is first on the left, then the post's edge.
  EXPECT_NEAR(gap.left.y(), 0.42, 1e-3);
  EXPECT_NEAR(gap.right.y(), -0.51, 1e-3);  // a scan's points are kept 0.03 m apart: -0.48, -0.51, ...

  // With support 1 the stray point is the left side.
  ASSERT_TRUE(recent.gap_ahead(map_pose, odometry_now, 0.35, 0.8, 0.6, 1, gap));
  EXPECT_NEAR(gap.left.y(), 0.1, 1e-3);
  // Too far ahead, or behind the robot: no gap.
  EXPECT_FALSE(recent.gap_ahead(map_pose, odometry_at_scan, 0.35, 0.8, 0.6, 2, gap));
  EXPECT_FALSE(recent.gap_ahead(map_pose, odometry_at_scan.compose(core::Pose2{1.5, 0.0, 0.0}), 0.35, 0.8, 0.6, 2, gap));
  // Neither side within reach of the line: none.
  EXPECT_FALSE(recent.gap_ahead(map_pose, odometry_now, 0.35, 0.8, 0.4, 2, gap));
}

}  // namespace
}  // namespace stereoscout::explore
