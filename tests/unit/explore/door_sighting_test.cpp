// Door sighting (door_sighting.hpp) on synthetic scans: a blank wall the matcher does not
// measure, and through the door the floor beyond. The rendered views of the office's doors are
// in tests/integration/door_sighting_test.cpp.
#include "stereoscout/explore/door_sighting.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "stereoscout/core/config/camera.hpp"
#include "stereoscout/explore/explorer.hpp"
#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

constexpr int kColumns = 640;
constexpr double kFocal_px = 400.0;
constexpr double kCameraForward_m = 0.1;
constexpr double kBaseline_m = 0.1;

ExploreParams sighting_params() {
  ExploreParams params;
  params.explore.door_sighting_range_m = 2.0;
  params.explore.door_sighting_max_offset_m = 0.3;
  return params;
}

// A 0.9 m door in a wall at y = 6.2, passed northwards.
DoorPassage office_door(double grid_width_m = 0.9) {
  DoorPassage door;
  door.known = true;
  door.middle = {5.5, 6.2};
  door.along = {0.0, 1.0};
  door.width_m = grid_width_m;
  door.clear_after_m = 0.55;
  return door;
}

// What lies on the door's line beside the gap: a blank wall (no column measured), a wall the
// matcher measures, or a post 0.15 m wide at each jamb with the floor beyond past them.
enum class Beside { blank_wall, measured_wall, posts };

// The scan a camera at `truth` takes of a wall along the door's line with a gap
// `true_width_m` wide around `true_middle`, passed along `along`: columns of the right camera
// through the gap see the floor 1.5 m past the line where the left camera, kBaseline_m to its
// left, sees it too; the others nothing (the blank wall, and the background the left jamb hides
// from the left camera), or what `beside` says lies beside the gap.
core::DepthScan scan_of_door(const core::Pose2& truth, const Eigen::Vector2d& true_middle, double true_width_m,
                             const Eigen::Vector2d& along = Eigen::Vector2d(0.0, 1.0), double pan_rad = 0.0,
                             Beside beside = Beside::blank_wall) {
  core::DepthScan scan;
  scan.origin_robot = {kCameraForward_m, 0.0};
  scan.columns.resize(kColumns);
  const Eigen::Vector2d camera = truth.transform_point(scan.origin_robot);
  const Eigen::Vector2d camera_left(-std::sin(pan_rad), std::cos(pan_rad));
  const Eigen::Vector2d left_camera = truth.transform_point(scan.origin_robot + kBaseline_m * camera_left);
  const Eigen::Vector2d across(-along.y(), along.x());
  const auto through_gap = [&](const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
    const double t = (true_middle - from).dot(along) / (to - from).dot(along);
    return std::abs((from + t * (to - from) - true_middle).dot(across)) < 0.5 * true_width_m;
  };
  for (int u = 0; u < kColumns; ++u) {
    const double bearing = truth.theta + pan_rad + std::atan((0.5 * kColumns - u) / kFocal_px);
    const Eigen::Vector2d ray(std::cos(bearing), std::sin(bearing));
    core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(u)];
    const double towards = ray.dot(along);
    if (towards <= 0.0) continue;
    const double to_line = (true_middle - camera).dot(along);
    const Eigen::Vector2d on_line = camera + to_line / towards * ray;
    const Eigen::Vector2d beyond = camera + (to_line + 1.5) / towards * ray;
    const double aside = std::abs((on_line - true_middle).dot(across));
    if (aside >= 0.5 * true_width_m) {
      if (beside == Beside::blank_wall) continue;
      const bool on_wall = beside == Beside::measured_wall || aside < 0.5 * true_width_m + 0.15;
      const Eigen::Vector2d in_robot = truth.inverse().transform_point(on_wall ? on_line : beyond);
      column.kind = on_wall ? core::DepthScanColumn::Kind::obstacle : core::DepthScanColumn::Kind::free;
      column.obstacle_at_camera_height = on_wall;
      column.x_robot_m = static_cast<float>(in_robot.x());
      column.y_robot_m = static_cast<float>(in_robot.y());
      continue;
    }
    if (!through_gap(left_camera, beyond)) continue;  // hidden from the left camera
    const Eigen::Vector2d in_robot = truth.inverse().transform_point(beyond);
    column.kind = core::DepthScanColumn::Kind::free;
    column.x_robot_m = static_cast<float>(in_robot.x());
    column.y_robot_m = static_cast<float>(in_robot.y());
  }
  return scan;
}

// The grid's wall along y = 6.2 (the cell row 62), the door's cells free from x 5.1 to 5.9.
struct OfficeWall {
  testing::TestGrid grid{100, 100, CellState::free};
  OfficeWall() {
    grid.fill(0, 62, 51, 63, CellState::occupied);
    grid.fill(59, 62, 100, 63, CellState::occupied);
  }
};

SeenObstacles seen_at(const core::DepthScan& scan, const core::Pose2& believed, const core::Pose2& odometry,
                      double time_s) {
  SeenObstacles seen;
  seen.scan = &scan;
  seen.time_s = time_s;
  seen.pose = believed;
  seen.odometry = odometry;
  return seen;
}

// The robot 0.12 m west of the door's middle believes it is 0.03 m east: the sighting puts it
// where it stands, carries that along the odometry while it drives in (whatever the estimate
// does meanwhile), and lets go once the disc has cleared the jambs.
TEST(DoorSighting, PutsTheRobotWhereTheScanSawTheDoorUntilItHasPassed) {
  const OfficeWall wall;
  DoorSighting sighting(sighting_params());
  const DoorPassage door = office_door();
  const core::Pose2 truth{5.38, 5.0, core::kPi / 2.0};
  const core::Pose2 believed{5.53, 5.0, core::kPi / 2.0};
  const core::Pose2 odometry{-2.0, 1.0, 0.3};  // the odometry's own frame
  const core::DepthScan scan = scan_of_door(truth, door.middle, 0.9);
  sighting.observe(seen_at(scan, believed, odometry, 1.0), door, wall.grid.view());
  ASSERT_TRUE(sighting.holding());
  EXPECT_EQ(sighting.counters().sightings, 1U);
  EXPECT_EQ(sighting.counters().doors_sighted, 1U);
  EXPECT_NEAR(sighting.navigation_pose(believed, odometry).x, truth.x, 0.01);
  EXPECT_NEAR(sighting.navigation_pose(believed, odometry).y, truth.y, 1e-9);

  // 0.8 m on by the odometry; the estimate has jumped meanwhile.
  const core::Pose2 driven = odometry.compose(core::Pose2{0.8, 0.0, 0.0});
  const core::Pose2 jumped{5.7, 5.9, core::kPi / 2.0};
  const core::Pose2 inside = sighting.navigation_pose(jumped, driven);
  EXPECT_NEAR(inside.x, truth.x, 0.01);
  EXPECT_NEAR(inside.y, truth.y + 0.8, 1e-9);
  EXPECT_TRUE(sighting.holding());

  // Past the middle by more than the disc's clearance: the estimate again.
  const core::Pose2 through = odometry.compose(core::Pose2{1.8, 0.0, 0.0});
  const core::Pose2 after = sighting.navigation_pose(jumped, through);
  EXPECT_FALSE(sighting.holding());
  EXPECT_EQ(after.x, jumped.x);
  EXPECT_EQ(after.y, jumped.y);
}

// A scan taken with the pan unit turned: the left camera stands off to the camera's left, not
// the robot's, and the left jamb is on its ray from there.
TEST(DoorSighting, TakesTheLeftCameraWhereThePanUnitHadIt) {
  const OfficeWall wall;
  const double pan_rad = 0.6;
  const core::Pose2 truth{5.38, 4.9, core::kPi / 2.0 - pan_rad};  // the camera faces the door
  const core::Pose2 believed{5.53, 4.9, truth.theta};
  const core::DepthScan scan = scan_of_door(truth, {5.5, 6.2}, 0.9, {0.0, 1.0}, pan_rad);
  const auto corrected_error_m = [&](double pan_given_rad) {
    DoorSighting sighting(sighting_params());
    SeenObstacles seen = seen_at(scan, believed, core::Pose2(), 1.0);
    seen.pan_rad = pan_given_rad;
    sighting.observe(seen, office_door(), wall.grid.view());
    EXPECT_TRUE(sighting.holding());
    return std::abs(sighting.navigation_pose(believed, core::Pose2()).x - truth.x);
  };
  const double with_pan = corrected_error_m(pan_rad);
  const double without = corrected_error_m(0.0);
  std::printf("corrected pose off across the door: %.4f m with the pan, %.4f m taking it as 0\n", with_pan, without);
  EXPECT_LT(with_pan, 0.01);
  EXPECT_GT(without, 2.0 * with_pan);
}

// A gap far narrower than the grid's door, an offset past the limit, a jamb at the image's
// edge, and a camera too near or too far: no sighting, each counted where it was measured.
TEST(DoorSighting, TrustsNoGapThatDisagreesWithTheGridsDoor) {
  const OfficeWall wall;
  const core::Pose2 truth{5.5, 5.0, core::kPi / 2.0};
  const core::Pose2 odometry;
  {
    DoorSighting sighting(sighting_params());
    const core::DepthScan scan = scan_of_door(truth, {5.5, 6.2}, 0.5);
    sighting.observe(seen_at(scan, truth, odometry, 1.0), office_door(0.9), wall.grid.view());
    EXPECT_FALSE(sighting.holding());
    EXPECT_EQ(sighting.counters().width_disagrees, 1U);
  }
  {
    DoorSighting sighting(sighting_params());
    const core::Pose2 back{5.5, 4.8, core::kPi / 2.0};  // both jambs well inside the image
    const core::DepthScan scan = scan_of_door(back, {5.15, 6.2}, 0.9);  // 0.35 m west of the grid's
    sighting.observe(seen_at(scan, back, odometry, 1.0), office_door(), wall.grid.view());
    EXPECT_FALSE(sighting.holding());
    EXPECT_EQ(sighting.counters().offset_too_large, 1U);
  }
  {
    DoorSighting sighting(sighting_params());
    const core::Pose2 turned{5.5, 5.0, core::kPi / 2.0 - 0.5};  // the west jamb at the image's edge
    const core::DepthScan scan = scan_of_door(turned, {5.5, 6.2}, 0.9);
    sighting.observe(seen_at(scan, turned, odometry, 1.0), office_door(), wall.grid.view());
    EXPECT_FALSE(sighting.holding());
    EXPECT_EQ(sighting.counters().jamb_at_image_edge, 1U);
  }
  {
    DoorSighting sighting(sighting_params());
    const core::Pose2 near{5.5, 5.8, core::kPi / 2.0};  // the camera 0.3 m before the line
    const core::Pose2 far{5.5, 3.5, core::kPi / 2.0};
    const core::DepthScan near_scan = scan_of_door(near, {5.5, 6.2}, 0.9);
    const core::DepthScan far_scan = scan_of_door(far, {5.5, 6.2}, 0.9);
    sighting.observe(seen_at(near_scan, near, odometry, 1.0), office_door(), wall.grid.view());
    sighting.observe(seen_at(far_scan, far, odometry, 2.0), office_door(), wall.grid.view());
    EXPECT_FALSE(sighting.holding());
    EXPECT_EQ(sighting.counters().scans_at_doors, 0U);
  }
}

// A gap the plan passes with no wall on its line beside it (a person's trace across a corridor
// from its wall, seen along the corridor) is no door to sight.
TEST(DoorSighting, LooksOnlyAtGapsInAWall) {
  const OfficeWall wall;
  testing::TestGrid open{100, 100, CellState::free};
  open.fill(50, 62, 51, 63, CellState::occupied);  // the jamb cells alone
  open.fill(59, 62, 60, 63, CellState::occupied);
  const core::Pose2 truth{5.38, 5.0, core::kPi / 2.0};
  const core::DepthScan scan = scan_of_door(truth, {5.5, 6.2}, 0.9);
  DoorSighting sighting(sighting_params());
  sighting.observe(seen_at(scan, truth, core::Pose2(), 1.0), office_door(), open.view());
  EXPECT_FALSE(sighting.holding());
  EXPECT_EQ(sighting.counters().not_in_a_wall, 1U);
  sighting.observe(seen_at(scan, truth, core::Pose2(), 2.0), office_door(), wall.grid.view());
  EXPECT_TRUE(sighting.holding());
}

// With door_wall_from_scan, a door the grid holds no wall beside (grazing views along a
// corridor erase its walls) is sighted when the scan measures the wall on its line beside both
// jambs; not when beside it lie a blank wall or two posts with the floor beyond.
TEST(DoorSighting, WithTheWallFromTheScanSightsADoorTheGridHoldsNoWallBeside) {
  testing::TestGrid open{100, 100, CellState::free};
  open.fill(50, 62, 51, 63, CellState::occupied);  // the jamb cells alone
  open.fill(59, 62, 60, 63, CellState::occupied);
  ExploreParams params = sighting_params();
  params.explore.door_wall_from_scan = true;
  const core::Pose2 truth{5.38, 5.0, core::kPi / 2.0};
  const core::Pose2 believed{5.53, 5.0, core::kPi / 2.0};
  const auto sighted = [&](Beside beside, std::uint64_t& not_in_a_wall) {
    DoorSighting sighting(params);
    const core::DepthScan scan = scan_of_door(truth, {5.5, 6.2}, 0.9, {0.0, 1.0}, 0.0, beside);
    sighting.observe(seen_at(scan, believed, core::Pose2(), 1.0), office_door(), open.view());
    not_in_a_wall = sighting.counters().not_in_a_wall;
    return sighting.holding() ? sighting.navigation_pose(believed, core::Pose2()).x : -1.0;
  };
  std::uint64_t refused = 0;
  EXPECT_NEAR(sighted(Beside::measured_wall, refused), truth.x, 0.01);
  EXPECT_EQ(refused, 0U);
  EXPECT_EQ(sighted(Beside::blank_wall, refused), -1.0);
  EXPECT_EQ(refused, 1U);
  EXPECT_EQ(sighted(Beside::posts, refused), -1.0);
  EXPECT_EQ(refused, 1U);

  // Without the key the measured wall is not asked: the grid's is.
  DoorSighting grid_only(sighting_params());
  const core::DepthScan scan = scan_of_door(truth, {5.5, 6.2}, 0.9, {0.0, 1.0}, 0.0, Beside::measured_wall);
  grid_only.observe(seen_at(scan, believed, core::Pose2(), 1.0), office_door(), open.view());
  EXPECT_FALSE(grid_only.holding());
  EXPECT_EQ(grid_only.counters().not_in_a_wall, 1U);
}

// The robot 0.12 m west of the door's middle believes it is 0.03 m east and turned 8 degrees
// to its left. From the jambs alone the sighting takes the heading as it is, and 0.8 m on by
// the odometry the pose it carries is off across the door by the heading's 0.11 m. With
// door_sighting_heading the wall beside the door turns it back first; a nearer scan that sees
// no wall keeps the held sighting's heading, and so does one whose wall's heading jumps from it.
TEST(DoorSighting, TurnsTheHeadingByTheWallBesideTheDoorAndKeepsItNearer) {
  const OfficeWall wall;
  const DoorPassage door = office_door();
  const core::Pose2 truth{5.38, 4.6, core::kPi / 2.0};
  const core::Pose2 believed{5.53, 4.6, core::kPi / 2.0 + core::degrees_to_radians(8.0)};
  const core::Pose2 odometry{-2.0, 1.0, 0.3};
  const core::Pose2 ahead{0.8, 0.0, 0.0};
  const core::Pose2 truth_ahead = truth.compose(ahead);
  const core::DepthScan scan = scan_of_door(truth, door.middle, 0.9, {0.0, 1.0}, 0.0, Beside::measured_wall);
  const auto across_error_ahead = [&](DoorSighting& sighting) {
    return std::abs(sighting.navigation_pose(believed, odometry.compose(ahead)).x - truth_ahead.x);
  };

  DoorSighting jambs_only(sighting_params());
  jambs_only.observe(seen_at(scan, believed, odometry, 1.0), door, wall.grid.view());
  ASSERT_TRUE(jambs_only.holding());
  EXPECT_GT(across_error_ahead(jambs_only), 0.08);

  ExploreParams params = sighting_params();
  params.explore.door_sighting_heading = true;
  DoorSighting sighting(params);
  sighting.observe(seen_at(scan, believed, odometry, 1.0), door, wall.grid.view());
  ASSERT_TRUE(sighting.holding());
  EXPECT_EQ(sighting.counters().headings_corrected, 1U);
  const core::Pose2 corrected = sighting.navigation_pose(believed, odometry);
  EXPECT_NEAR(corrected.theta, truth.theta, core::degrees_to_radians(0.5));
  EXPECT_NEAR(corrected.x, truth.x, 0.01);
  EXPECT_NEAR(sighting.last_heading_correction(), core::degrees_to_radians(-8.0), core::degrees_to_radians(0.5));
  EXPECT_LT(across_error_ahead(sighting), 0.02);

  // 0.4 m on, the wall beside the door blank: the heading is the held sighting's.
  const core::Pose2 nearer{0.4, 0.0, 0.0};
  const core::DepthScan near_scan = scan_of_door(truth.compose(nearer), door.middle, 0.9);
  sighting.observe(seen_at(near_scan, believed.compose(nearer), odometry.compose(nearer), 2.0), door, wall.grid.view());
  EXPECT_EQ(sighting.counters().sightings, 2U);
  EXPECT_EQ(sighting.counters().headings_carried, 1U);
  EXPECT_EQ(sighting.counters().heading_unmeasured, 0U);
  const core::Pose2 kept = sighting.navigation_pose(believed, odometry.compose(nearer));
  EXPECT_NEAR(kept.theta, truth.theta, core::degrees_to_radians(0.5));
  EXPECT_NEAR(kept.x, truth.x, 0.01);

  // A scan whose wall lies 12 degrees from the held heading (the odometry saw no turn): the
  // held heading is kept.
  const core::Pose2 twisted = truth.compose(core::Pose2{0.2, 0.0, core::degrees_to_radians(12.0)});
  const core::DepthScan twisted_scan = scan_of_door(twisted, door.middle, 0.9, {0.0, 1.0}, 0.0, Beside::measured_wall);
  const core::Pose2 on{0.2, 0.0, 0.0};
  sighting.observe(seen_at(twisted_scan, believed.compose(on), odometry.compose(on), 3.0), door, wall.grid.view());
  EXPECT_EQ(sighting.counters().heading_jumps, 1U);
  EXPECT_EQ(sighting.counters().headings_corrected, 1U);
  EXPECT_NEAR(sighting.navigation_pose(believed, odometry.compose(on)).theta, truth.theta,
              core::degrees_to_radians(0.5));

  // A fresh sighting from there has no heading to keep: the estimate's is used, and counted.
  DoorSighting fresh(params);
  fresh.observe(seen_at(near_scan, believed.compose(nearer), odometry.compose(nearer), 2.0), door, wall.grid.view());
  EXPECT_EQ(fresh.counters().sightings, 1U);
  EXPECT_EQ(fresh.counters().heading_unmeasured, 1U);
}

// A sighting is of one door: when the plan passes another one next, it is dropped; a scan seen
// before is not looked at again.
TEST(DoorSighting, DropsTheSightingForAnotherDoorAndLooksAtEachScanOnce) {
  const OfficeWall wall;
  DoorSighting sighting(sighting_params());
  const core::Pose2 truth{5.38, 5.0, core::kPi / 2.0};
  const core::Pose2 believed{5.53, 5.0, core::kPi / 2.0};
  const core::Pose2 odometry;
  const core::DepthScan scan = scan_of_door(truth, {5.5, 6.2}, 0.9);
  const SeenObstacles seen = seen_at(scan, believed, odometry, 1.0);
  sighting.observe(seen, office_door(), wall.grid.view());
  ASSERT_TRUE(sighting.holding());
  EXPECT_FALSE(sighting.wants(seen));
  sighting.observe(seen, office_door(), wall.grid.view());
  EXPECT_EQ(sighting.counters().scans_at_doors, 1U);

  DoorPassage other = office_door();
  other.middle = {13.0, 6.2};
  sighting.observe(seen_at(scan, believed, odometry, 2.0), other, wall.grid.view());
  EXPECT_FALSE(sighting.holding());
  EXPECT_EQ(sighting.navigation_pose(believed, odometry).x, believed.x);
}

// A thin wall at x 3.0-3.1 (the cell column x = 30) with a 0.9 m door from y 2.6 to 3.5, the
// unknown beyond x = 8 m: the explorer's goal lies through the door. The estimate is 0.12 m
// north of the robot all along, the odometry exact.
struct OffsetDoorScene {
  testing::TestGrid grid{100, 60, CellState::free};
  OffsetDoorScene() {
    grid.walls();
    grid.fill(30, 1, 31, 26, CellState::occupied);
    grid.fill(30, 35, 31, 59, CellState::occupied);
    grid.fill(80, 1, 99, 59, CellState::unknown);
  }
};

// A 0.9 m door in a thin wall (0.1 m deep) of a test scene, passed along `along`, and the robot
// that drives through it with its estimate `error` off all along, the odometry exact.
struct DoorDrive {
  const testing::TestGrid& grid;
  Eigen::Vector2d middle;
  Eigen::Vector2d along;
  Eigen::Vector2d error;
  // Through once the robot's centre is this far past the door's line.
  double past_m = 0.0;
  // What the scans see beside the door.
  Beside beside = Beside::blank_wall;
  // The estimate's heading is off by this too: its frame turned about the start.
  double heading_error_rad = 0.0;
};

// Least distance between the disc at `robot` and a jamb of `drive`'s door (a point at wall
// height across the wall's depth).
double jamb_clearance_m(const DoorDrive& drive, const Eigen::Vector2d& robot, double radius_m) {
  const Eigen::Vector2d across(-drive.along.y(), drive.along.x());
  const double along = std::max(0.0, std::abs((robot - drive.middle).dot(drive.along)) - 0.05);
  double least = 1e9;
  for (double side : {-0.45, 0.45}) {
    least = std::min(least, std::hypot((robot - drive.middle).dot(across) - side, along) - radius_m);
  }
  return least;
}

struct Passage {
  double clearance_m = 1e9;
  bool through = false;
  double widest_pan_target_rad = 0.0;  // the largest turn of the camera off the heading asked for
};

// Drives the kinematic robot from `truth` by the explorer's commands at 20 Hz until it is
// through the door (or 200 s pass), with an update, and a scan of the door, each 0.07 m or
// degree the camera turned (the robot or the pan unit), as the stack makes them; the pan unit
// turns the camera where the explorer wants it at the default camera.pan_rate_deg_s.
Passage drive_through_door(Explorer& explorer, const DoorDrive& drive, core::Pose2 truth, double radius_m) {
  core::DepthScan scan;
  SeenObstacles seen;
  Passage passage;
  double pan_rad = 0.0;
  const double pan_step_rad = core::degrees_to_radians(core::CameraConfig{}.pan_rate_deg_s) * 0.05;
  core::Pose2 last_scan_pose = truth;
  double last_scan_pan_rad = 0.0;
  const auto past_m = [&] { return (truth.translation() - drive.middle).dot(drive.along); };
  // The estimate's frame: at the start `error` off, turned by the heading's error about it.
  const Eigen::Vector2d start = truth.translation();
  const Eigen::Vector2d shift =
      start + drive.error - Eigen::Rotation2Dd(drive.heading_error_rad) * start;
  const core::Pose2 estimate_frame{shift.x(), shift.y(), drive.heading_error_rad};
  for (double time_s = 0.0; time_s < 200.0 && past_m() < drive.past_m; time_s += 0.05) {
    ExploreInput input;
    input.time_s = time_s;
    input.pose = estimate_frame.compose(truth);
    input.odometry = truth;
    input.pan_rad = pan_rad;
    input.grid = drive.grid.view();
    const bool moved = (truth.translation() - last_scan_pose.translation()).norm() >= 0.07 ||
                       std::abs(core::wrap_angle(truth.theta + pan_rad - last_scan_pose.theta - last_scan_pan_rad)) >=
                           core::degrees_to_radians(1.0);
    input.grid_updated = time_s == 0.0 || moved;
    if (input.grid_updated) {
      last_scan_pose = truth;
      last_scan_pan_rad = pan_rad;
      scan = scan_of_door(truth, drive.middle, 0.9, drive.along, pan_rad, drive.beside);
      seen = seen_at(scan, input.pose, truth, time_s);
      seen.pan_rad = pan_rad;
    }
    input.seen = seen;
    const ExploreOutput output = explorer.step(input);
    const core::DriveCommand command = output.drive;
    pan_rad += std::clamp(output.pan_target_rad - pan_rad, -pan_step_rad, pan_step_rad);
    if (std::abs(output.pan_target_rad) > std::abs(passage.widest_pan_target_rad)) {
      passage.widest_pan_target_rad = output.pan_target_rad;
    }
    truth.x += command.linear_mps * 0.05 * std::cos(truth.theta);
    truth.y += command.linear_mps * 0.05 * std::sin(truth.theta);
    truth.theta = core::wrap_angle(truth.theta + command.angular_rad_s * 0.05);
    passage.clearance_m = std::min(passage.clearance_m, jamb_clearance_m(drive, truth.translation(), radius_m));
  }
  passage.through = past_m() >= drive.past_m;
  return passage;
}

ExploreParams closed_loop_params(int width, int height) {
  ExploreParams params = testing::test_params(width, height);
  params.explore.pan_at_goal = false;
  params.explore.return_to_start = false;
  return params;
}

// Drives the kinematic robot by the explorer's commands until it is through the door; the least
// clearance between its true disc and a jamb.
double least_clearance_through_offset_door(double sighting_range_m) {
  OffsetDoorScene scene;
  ExploreParams params = closed_loop_params(100, 60);
  params.explore.door_sighting_range_m = sighting_range_m;
  Explorer explorer(params);
  const DoorDrive drive{scene.grid, {3.05, 3.05}, {1.0, 0.0}, {0.0, 0.12}, 0.95};
  const Passage passage = drive_through_door(explorer, drive, core::Pose2{1.2, 3.05, 0.0}, params.robot_radius_m);
  EXPECT_TRUE(passage.through) << "not through the door";
  if (sighting_range_m > 0.0) {
    EXPECT_GT(explorer.door_sighting().counters().sightings, 0U);
  }
  return passage.clearance_m;
}

// As least_clearance_through_offset_door, with the estimate's heading 8 degrees off from 1.85 m
// before the door (its position right there), the wall beside the door measured in the scans.
// The recent obstacle layer is off: the wall's points, placed from the turned estimate before
// any plan (a sighting needs one), would shut the door in the planning grid from the start.
double least_clearance_through_turned_door(double sighting_range_m, bool correct_heading) {
  OffsetDoorScene scene;
  ExploreParams params = closed_loop_params(100, 60);
  params.explore.recent_obstacle_s = 0.0;
  params.explore.door_sighting_range_m = sighting_range_m;
  params.explore.door_sighting_heading = correct_heading;
  Explorer explorer(params);
  DoorDrive drive{scene.grid, {3.05, 3.05}, {1.0, 0.0}, {0.0, 0.0}, 0.95};
  drive.beside = Beside::measured_wall;
  drive.heading_error_rad = core::degrees_to_radians(8.0);
  const Passage passage = drive_through_door(explorer, drive, core::Pose2{1.2, 3.05, 0.0}, params.robot_radius_m);
  EXPECT_TRUE(passage.through) << "not through the door";
  if (correct_heading) {
    EXPECT_GT(explorer.door_sighting().counters().headings_corrected, 0U);
  }
  return passage.clearance_m;
}

// With the estimate 0.12 m off across a 0.9 m door, the robot centred on the door in its belief
// touches the jamb; sighting the door puts it back in the middle.
TEST(Explorer, ThroughADoorWithThePoseOffAcrossItTheSightingKeepsTheRobotClear) {
  const double blind = least_clearance_through_offset_door(0.0);
  const double sighted = least_clearance_through_offset_door(2.0);
  std::printf("least jamb clearance with the pose 0.12 m off: %.3f m, with door sighting %.3f m\n", blind, sighted);
  EXPECT_LT(blind, 0.0);
  EXPECT_GT(sighted, 0.07);
}

// The same door with a post 0.15 m wide at each jamb, which the scans measure (the floor beyond
// them): the layer keeps the posts where the camera saw them relative to the robot.
double least_clearance_through_offset_door_by_layer(double layer_gap_reach_m, double error_m) {
  OffsetDoorScene scene;
  ExploreParams params = closed_loop_params(100, 60);
  params.explore.layer_gap_reach_m = layer_gap_reach_m;
  Explorer explorer(params);
  DoorDrive drive{scene.grid, {3.05, 3.05}, {1.0, 0.0}, {0.0, error_m}, 0.95};
  drive.beside = Beside::posts;
  const Passage passage = drive_through_door(explorer, drive, core::Pose2{1.2, 3.05, 0.0}, params.robot_radius_m);
  EXPECT_TRUE(passage.through) << "not through the door";
  if (layer_gap_reach_m > 0.0) {
    EXPECT_GT(explorer.counters().layer_gap_steers, 0U);
  } else {
    EXPECT_EQ(explorer.counters().layer_gap_steers, 0U);
  }
  return passage.clearance_m;
}

// With the estimate 0.08-0.16 m off across the door, the plan on the grid and the layer's cells
// leaves the robot as little as 0.03 m from a jamb; steering at the middle of the gap between
// the posts the layer kept, judged by the odometry alone, it keeps near the 0.1 m there is.
// With the estimate's heading 8 degrees off, the jambs' bearings alone put the robot right only
// where the scan was taken; the odometry carries the heading's error on across the door.
// Turning the heading by the wall beside the door keeps the robot on the door's middle.
TEST(Explorer, ThroughADoorWithTheHeadingOffTheWallBesideItKeepsTheRobotClear) {
  const double blind = least_clearance_through_turned_door(0.0, false);
  const double jambs_only = least_clearance_through_turned_door(2.0, false);
  const double turned = least_clearance_through_turned_door(2.0, true);
  std::printf("least jamb clearance with the heading 8 degrees off: %.3f m, door sighting %.3f m, with the heading %.3f m\n",
              blind, jambs_only, turned);
  EXPECT_LT(blind, 0.0);
  EXPECT_GT(turned, 0.07);
  EXPECT_GT(turned, jambs_only);
}

TEST(Explorer, ThroughADoorWithThePoseOffAcrossItTheLayersGapKeepsTheRobotClear) {
  double least_blind = 1e9;
  for (const double error_m : {0.08, 0.10, 0.12, 0.14, 0.16}) {
    const double blind = least_clearance_through_offset_door_by_layer(0.0, error_m);
    const double steered = least_clearance_through_offset_door_by_layer(0.25, error_m);
    std::printf("least jamb clearance with the pose %.2f m off: %.3f m, steering by the layer's gap %.3f m\n", error_m,
                blind, steered);
    EXPECT_GT(steered, 0.08) << "pose " << error_m << " m off";
    EXPECT_GT(steered, blind) << "pose " << error_m << " m off";
    least_blind = std::min(least_blind, blind);
  }
  EXPECT_LT(least_blind, 0.04);
}

// A corridor (y 3.1-5.3) along the south wall of which (the cell row y = 30) a 0.9 m door opens
// from x 4.55 to 5.45 into a room whose far part is unknown: the explorer's goal lies through
// the door, which the robot, driving east along the corridor, sees only obliquely until it
// turns into it. The estimate is 0.12 m east of the robot all along, the odometry exact.
struct SideDoorScene {
  testing::TestGrid grid{100, 60, CellState::free};
  SideDoorScene() {
    grid.walls();
    grid.fill(1, 30, 46, 31, CellState::occupied);
    grid.fill(54, 30, 99, 31, CellState::occupied);
    grid.fill(1, 53, 99, 59, CellState::occupied);
    grid.fill(70, 31, 99, 53, CellState::occupied);
    grid.fill(1, 1, 99, 15, CellState::unknown);
  }
};

struct SideDoorPassage {
  Passage passage;
  DoorStandoffCounters standoff;
  std::uint64_t sightings = 0;
};

SideDoorPassage through_side_door(double standoff_m, double gaze_ahead_m = 0.0) {
  SideDoorScene scene;
  ExploreParams params = closed_loop_params(100, 60);
  params.explore.gaze_ahead_m = gaze_ahead_m;
  params.explore.door_sighting_range_m = 1.4;
  params.explore.door_axis_before_m = 1.4;
  params.explore.door_axis_all_gaps = true;
  params.explore.door_standoff_m = standoff_m;
  Explorer explorer(params);
  // Through once the disc has cleared the jambs (the safe distance past the door's line).
  const DoorDrive drive{scene.grid, {5.0, 3.05}, {0.0, -1.0}, {0.12, 0.0}, 0.55};
  SideDoorPassage result;
  result.passage = drive_through_door(explorer, drive, core::Pose2{2.0, 4.2, 0.0}, params.robot_radius_m);
  result.standoff = explorer.door_standoff().counters();
  result.sightings = explorer.door_sighting().counters().sightings;
  return result;
}

// From the corridor the door is seen only obliquely: the robot turns into it with the pose
// 0.12 m off unmeasured and touches a jamb. Standing off in front of the door first, it sees
// the door square on, and the sighting puts it back in the middle.
TEST(Explorer, StandingOffBeforeASideDoorLetsTheSightingKeepTheRobotClear) {
  const SideDoorPassage oblique = through_side_door(0.0);
  const SideDoorPassage square = through_side_door(1.0);
  std::printf("side door, pose 0.12 m off: least jamb clearance %.3f m with %llu sightings; standing off %.3f m "
              "with %llu\n",
              oblique.passage.clearance_m, static_cast<unsigned long long>(oblique.sightings), square.passage.clearance_m,
              static_cast<unsigned long long>(square.sightings));
  EXPECT_TRUE(square.passage.through);
  EXPECT_EQ(square.standoff.doors, 1U);
  EXPECT_EQ(square.standoff.stood_off, 1U);
  EXPECT_GT(square.sightings, 0U);
  EXPECT_GT(square.passage.clearance_m, 0.07);
  EXPECT_LT(oblique.passage.clearance_m, 0.0);
}

// Looking where the plan goes (explore.gaze_ahead_m), the camera sees the side door from the
// corridor before the robot turns into it, near enough for a sighting and far enough for the
// dense matcher, without standing off.
TEST(Explorer, LookingAlongThePlanLetsTheSightingKeepTheRobotClearOfASideDoor) {
  const SideDoorPassage ahead = through_side_door(0.0);
  const SideDoorPassage gazing = through_side_door(0.0, 1.5);
  std::printf("side door, pose 0.12 m off: least jamb clearance %.3f m with %llu sightings; looking along the plan "
              "%.3f m with %llu\n",
              ahead.passage.clearance_m, static_cast<unsigned long long>(ahead.sightings),
              gazing.passage.clearance_m, static_cast<unsigned long long>(gazing.sightings));
  EXPECT_TRUE(gazing.passage.through);
  // The door lies to the right (south) of the robot driving east: the camera turned clockwise,
  // as far as gaze_max_pan_deg lets it; looking ahead, never.
  EXPECT_NEAR(gazing.passage.widest_pan_target_rad, -core::degrees_to_radians(30.0), 1e-9);
  EXPECT_EQ(ahead.passage.widest_pan_target_rad, 0.0);
  EXPECT_EQ(gazing.standoff.doors, 0U);
  EXPECT_GT(gazing.sightings, 0U);
  EXPECT_GT(gazing.passage.clearance_m, 0.07);
  EXPECT_LT(ahead.passage.clearance_m, 0.0);
}

}  // namespace
}  // namespace stereoscout::explore
