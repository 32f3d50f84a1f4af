#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/core.hpp>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/vision/dense_disparity.hpp"
#include "stereoscout/vision/obstacle_scan.hpp"
#include "synthetic_stereo.hpp"

namespace stereoscout::vision {
namespace {

using Kind = core::DepthScanColumn::Kind;

core::CameraMount paper_mount() { return {0.10, 0.0, 0.6, 0.0}; }

// The exact left-referenced disparity of a rendering: d = f B / Z (0 depth: invalid).
cv::Mat disparity_from_depth(const cv::Mat& left_depth, const StereoCalibration& camera) {
  cv::Mat disparity(left_depth.size(), CV_32FC1);
  for (int y = 0; y < left_depth.rows; ++y) {
    for (int x = 0; x < left_depth.cols; ++x) {
      const double z = left_depth.at<double>(y, x);
      disparity.at<float>(y, x) = z > 0.0 ? static_cast<float>(camera.focal_px * camera.baseline_m / z) : kInvalidDisparity;
    }
  }
  return disparity;
}

struct ScanSetup {
  StereoCalibration camera;
  ObstacleScanner scanner{ObstacleScanParams{}, StereoCalibration{}, paper_mount()};
  core::DepthScan scan;
  ScanSetup() { scanner.allocate(scan); }
  const core::DepthScan& run(const test::Scene& scene) {
    const test::Rendering view = test::render(scene, camera, paper_mount(), core::Pose2{});
    scanner.compute(disparity_from_depth(view.left_depth, camera), 0.0, 5, scan);
    return scan;
  }
};

double range_of(const core::DepthScan& scan, const core::DepthScanColumn& column) {
  return std::hypot(column.x_robot_m - scan.origin_robot.x(), column.y_robot_m - scan.origin_robot.y());
}

TEST(ObstacleScan, EmptyFloorIsFreeUpToMaxRange) {
  ScanSetup setup;
  const core::DepthScan& scan = setup.run(test::Scene{});
  EXPECT_EQ(scan.timestamp_ns, 5);
  EXPECT_NEAR(scan.origin_robot.x(), 0.10, 1e-12);
  int free_columns = 0;
  for (const core::DepthScanColumn& column : scan.columns) {
    if (!(column.measurable_from_m < 6.0F)) {
      EXPECT_EQ(column.kind, Kind::invalid);  // at the right edge: nothing within range measurable
      continue;
    }
    ASSERT_EQ(column.kind, Kind::free);
    EXPECT_NEAR(range_of(scan, column), 6.0, 1e-3);
    ++free_columns;
  }
  EXPECT_GT(free_columns, 600);
}

// A right-image column c holds left pixels c + d: the largest disparity there is
// min(63, 633 - c) (64 disparities, the matcher's 6-pixel border), and its depth f B / d is the
// nearest the column can measure (on the floor, longer towards the edges like the floor).
TEST(ObstacleScan, ColumnsSayHowNearTheyCanMeasure) {
  ScanSetup setup;
  const core::DepthScan& scan = setup.run(test::Scene{});
  const auto on_floor = [](int column, double depth) {
    return depth * std::sqrt(1.0 + std::pow((column - 319.5) / 400.0, 2));
  };
  EXPECT_NEAR(scan.columns[0].measurable_from_m, on_floor(0, 40.0 / 63.0), 1e-5);
  EXPECT_NEAR(scan.columns[320].measurable_from_m, on_floor(320, 40.0 / 63.0), 1e-5);
  EXPECT_NEAR(scan.columns[600].measurable_from_m, on_floor(600, 40.0 / 33.0), 1e-5);
  EXPECT_FALSE(std::isfinite(scan.columns[633].measurable_from_m));
  EXPECT_EQ(scan.columns[633].kind, Kind::invalid);
}

TEST(ObstacleScan, ColumnsSayWhereTheirFloorBecomesVisible) {
  ScanSetup setup;
  const core::DepthScan& scan = setup.run(test::Scene{});
  // Bottom row 239.5 px below the centre, f = 400 px, head at 0.6 m: 0.6 x 400 / 239.5 m
  // straight ahead, longer towards the image edges by sqrt(1 + ((u - c_x) / f)^2).
  const double ahead = 0.6 * 400.0 / 239.5;
  EXPECT_NEAR(scan.columns[320].floor_visible_from_m, ahead * std::sqrt(1.0 + std::pow(0.5 / 400.0, 2)), 1e-5);
  EXPECT_NEAR(scan.columns[0].floor_visible_from_m, ahead * std::sqrt(1.0 + std::pow(319.5 / 400.0, 2)), 1e-5);
  // The same after a pan: floor distances do not depend on it.
  core::DepthScan panned;
  setup.scanner.allocate(panned);
  const test::Rendering view = test::render(test::Scene{}, setup.camera, paper_mount(), core::Pose2{});
  setup.scanner.compute(disparity_from_depth(view.left_depth, setup.camera), 0.7, 5, panned);
  EXPECT_FLOAT_EQ(panned.columns[100].floor_visible_from_m, scan.columns[100].floor_visible_from_m);
  // Tilted 10 deg down, the floor comes into view nearer: h / tan(10 deg + atan(239.5 / 400)).
  ObstacleScanner tilted(ObstacleScanParams{}, StereoCalibration{}, {0.10, 0.0, 0.6, 10.0 * M_PI / 180.0});
  tilted.compute(disparity_from_depth(view.left_depth, setup.camera), 0.0, 5, panned);
  const double expected = 0.6 / std::tan(10.0 * M_PI / 180.0 + std::atan(239.5 / 400.0));
  EXPECT_NEAR(panned.columns[320].floor_visible_from_m, expected, 1e-3);
}

TEST(ObstacleScan, TenCentimetreBoxShowsUp) {
  test::Scene scene;
  scene.boxes.push_back({{1.5, -0.2, 0.0}, {1.7, 0.2, 0.10}});
  ScanSetup setup;
  const core::DepthScan& scan = setup.run(scene);
  // Columns looking straight ahead hit the box's front face at x = 1.5 m.
  for (int x = 300; x < 340; ++x) {
    const core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(x)];
    ASSERT_EQ(column.kind, Kind::obstacle) << "column " << x;
    EXPECT_NEAR(column.x_robot_m, 1.5, 0.01);
    EXPECT_FALSE(column.obstacle_at_camera_height) << "column " << x;  // out of view when near
    EXPECT_EQ(column.blank_wall, core::DepthScanColumn::BlankWall::no) << "column " << x;  // measured
  }
  // Columns far to the side see only floor.
  EXPECT_EQ(scan.columns[20].kind, Kind::free);
  EXPECT_EQ(scan.columns[620].kind, Kind::free);
}

// Stereo gives a blank surface no disparity: keeps the floor's pixels nearer than
// `floor_until_m` (of the paper's head: height 0.6 - (v - c_y) Z / f) and, with
// `keep_off_floor`, every pixel off the floor; the others get `unmatched`, the matcher's mark
// for a pixel without texture unless told otherwise.
cv::Mat without_blank_pixels(const cv::Mat& left_depth, const StereoCalibration& camera, double floor_until_m,
                             bool keep_off_floor, float unmatched = kUntexturedDisparity) {
  cv::Mat disparity = disparity_from_depth(left_depth, camera);
  for (int y = 0; y < left_depth.rows; ++y) {
    for (int x = 0; x < left_depth.cols; ++x) {
      const double z = left_depth.at<double>(y, x);
      const double height = 0.6 - (y - camera.principal_y_px) * z / camera.focal_px;
      const bool floor = std::fabs(height) < 0.01;
      if (floor ? z > floor_until_m : !keep_off_floor) disparity.at<float>(y, x) = unmatched;
    }
  }
  return disparity;
}

// The scan of a wall across the view, `wall_x_m` ahead of the robot, from `bottom_m` to 2.5 m
// high, through without_blank_pixels.
core::DepthScan scan_of_wall(double wall_x_m, double bottom_m, double floor_until_m, bool keep_off_floor,
                             const ObstacleScanParams& params = ObstacleScanParams{},
                             float unmatched = kUntexturedDisparity) {
  test::Scene scene;
  scene.boxes.push_back({{wall_x_m, -8.0, bottom_m}, {wall_x_m + 0.1, 8.0, 2.5}});
  StereoCalibration camera;
  const test::Rendering view = test::render(scene, camera, paper_mount(), core::Pose2{});
  ObstacleScanner scanner(params, camera, paper_mount());
  core::DepthScan scan;
  scanner.allocate(scan);
  scanner.compute(without_blank_pixels(view.left_depth, camera, floor_until_m, keep_off_floor, unmatched), 0.0, 0,
                  scan);
  return scan;
}

TEST(ObstacleScan, ABlankWallIsAnObstacleWhereTheFloorEnds) {
  // A wall 1.2 m ahead of the camera, nothing of it measured.
  const core::DepthScan scan = scan_of_wall(1.3, 0.0, 100.0, false);
  for (int x = 100; x < 540; x += 20) {
    const core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(x)];
    ASSERT_EQ(column.kind, Kind::obstacle) << "column " << x;
    EXPECT_NEAR(column.x_robot_m, 1.3, 0.05) << "column " << x;
    EXPECT_EQ(column.blank_wall, core::DepthScanColumn::BlankWall::floor_end) << "column " << x;
    EXPECT_FALSE(column.obstacle_at_camera_height) << "column " << x;
  }
  ObstacleScanParams off;
  off.blank_wall_within_m = 0.0;
  const core::DepthScan unaware = scan_of_wall(1.3, 0.0, 100.0, false, off);
  EXPECT_EQ(unaware.columns[320].kind, Kind::free);  // the wall's cell would stay unknown
}

// The left image of a scene of blank surfaces on a tiled floor: floor grey 120 or 140 by
// 0.3 m tiles of depth, everything else 190 (the office's corridor wall against its tiles).
cv::Mat blank_wall_image(const cv::Mat& left_depth, const StereoCalibration& camera) {
  cv::Mat left(left_depth.size(), CV_8UC1, cv::Scalar(190));
  for (int y = 0; y < left_depth.rows; ++y) {
    for (int x = 0; x < left_depth.cols; ++x) {
      const double z = left_depth.at<double>(y, x);
      const double height = 0.6 - (y - camera.principal_y_px) * z / camera.focal_px;
      // Floor pixels lie on the plane to rounding; the wall's lowest rows are a few mm up.
      if (z > 0.0 && std::fabs(height) < 1e-6) left.at<std::uint8_t>(y, x) = (static_cast<int>(z / 0.3) % 2) ? 140 : 120;
    }
  }
  return left;
}

// A blank wall across the view at wall_x_m, its floor matched only up to floor_until_m from
// the camera (none by default: tile interiors, the head-on office wall), scanned with the
// left image (or without, when `with_image` is false).
core::DepthScan scan_of_wall_faced_head_on(double wall_x_m, bool with_image, const ObstacleScanParams& params = {},
                                           double floor_until_m = 0.0) {
  test::Scene scene;
  scene.boxes.push_back({{wall_x_m, -8.0, 0.0}, {wall_x_m + 0.1, 8.0, 2.5}});
  StereoCalibration camera;
  const test::Rendering view = test::render(scene, camera, paper_mount(), core::Pose2{});
  ObstacleScanner scanner(params, camera, paper_mount());
  core::DepthScan scan;
  scanner.allocate(scan);
  const cv::Mat left = with_image ? blank_wall_image(view.left_depth, camera) : cv::Mat();
  scanner.compute(without_blank_pixels(view.left_depth, camera, floor_until_m, false), left, 0.0, 0, scan);
  return scan;
}

TEST(ObstacleScan, ABlankWallFacedHeadOnStandsWhereItsBaseIs) {
  // 1.4 m ahead of the camera: the floor's end gives nothing, the wall's base does.
  const core::DepthScan scan = scan_of_wall_faced_head_on(1.5, true);
  for (int x = 200; x < 440; x += 20) {
    const core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(x)];
    ASSERT_EQ(column.kind, Kind::obstacle) << "column " << x;
    EXPECT_NEAR(column.x_robot_m, 1.5, 0.02) << "column " << x;
    EXPECT_EQ(column.blank_wall, core::DepthScanColumn::BlankWall::base) << "column " << x;
    // ... on the column's own ray from the right camera (image x to the right is robot y < 0).
    const StereoCalibration camera;
    EXPECT_NEAR(std::atan2(column.y_robot_m - scan.origin_robot.y(), column.x_robot_m - scan.origin_robot.x()),
                -std::atan((x - camera.principal_x_px) / camera.focal_px), 0.01)
        << "column " << x;
  }
  EXPECT_EQ(scan_of_wall_faced_head_on(1.5, false).columns[320].kind, Kind::invalid);
  ObstacleScanParams off;
  off.wall_base_min_step_grey = 0.0;
  EXPECT_EQ(scan_of_wall_faced_head_on(1.5, true, off).columns[320].kind, Kind::invalid);
  // Beyond wall_base_within_m on the floor from the camera a step is no wall.
  ObstacleScanParams near_only;
  near_only.wall_base_within_m = 1.5;
  EXPECT_NE(scan_of_wall_faced_head_on(1.5, true, near_only).columns[40].kind, Kind::obstacle);  // 1.75 m away
  EXPECT_EQ(scan_of_wall_faced_head_on(1.7, true, near_only).columns[320].kind, Kind::invalid);
  EXPECT_NE(scan_of_wall_faced_head_on(3.7, true, {}, 2.5).columns[320].kind, Kind::obstacle);
}

// Farther than the floor-end rule reaches (blank_wall_within_m), the base still places the
// wall by its row's ray: a corridor's walls are seen at a slant from 2-3.5 m. There it
// needs floor matched before it: facing something nearer than the matcher can measure, no
// floor is matched and a step near the horizon is no wall's base (the clutter hall's rack).
TEST(ObstacleScan, ABlankWallsBaseIsFoundOutToItsOwnRangeBeyondMatchedFloor) {
  for (const double wall_x_m : {1.7, 2.5, 3.2}) {
    const core::DepthScan scan = scan_of_wall_faced_head_on(wall_x_m, true, {}, wall_x_m - 0.5);
    const core::DepthScanColumn& column = scan.columns[320];
    ASSERT_EQ(column.kind, Kind::obstacle) << "wall at " << wall_x_m << " m";
    EXPECT_NEAR(column.x_robot_m, wall_x_m, 0.03) << "wall at " << wall_x_m << " m";
    EXPECT_EQ(scan_of_wall_faced_head_on(wall_x_m, true).columns[320].kind, Kind::invalid)
        << "wall at " << wall_x_m << " m, no floor matched";
  }
}

// A step in the floor's brightness where stereo matched the floor on beyond it (a bright
// floor region: here the floor from 1.2 m on, matched up to 3 m) is no wall's base, even
// when the run above it is taken as blank (untextured fraction 0).
TEST(ObstacleScan, AWallBaseBeyondWhichStereoSeesFloorIsNoWall) {
  test::Scene scene;
  scene.boxes.push_back({{6.0, -8.0, 0.0}, {6.1, 8.0, 2.5}});
  StereoCalibration camera;
  const test::Rendering view = test::render(scene, camera, paper_mount(), core::Pose2{});
  cv::Mat left = blank_wall_image(view.left_depth, camera);
  for (int y = 0; y < left.rows; ++y) {
    for (int x = 0; x < left.cols; ++x) {
      if (view.left_depth.at<double>(y, x) > 1.2) left.at<std::uint8_t>(y, x) = 190;
    }
  }
  ObstacleScanParams params;
  params.blank_wall_untextured_fraction = 0.0;
  ObstacleScanner scanner(params, camera, paper_mount());
  core::DepthScan scan;
  scanner.allocate(scan);
  scanner.compute(without_blank_pixels(view.left_depth, camera, 3.0, false), left, 0.0, 0, scan);
  EXPECT_EQ(scan.columns[320].kind, Kind::free);
  EXPECT_NEAR(scan.columns[320].x_robot_m, 3.1, 0.05);
}

// The floor's matched part also ends where the matcher is confused on texture it could see
// (beside the edge of a near object the two cameras see differently: the clutter hall's
// dividing wall seen along its length), with open floor beyond. Nothing above that end was
// rejected for lack of texture, so it is no blank wall: the column stays free, and a later
// look may see past it.
TEST(ObstacleScan, AFloorEndingWhereStereoIsConfusedIsNoBlankWall) {
  const core::DepthScan confused = scan_of_wall(1.3, 0.0, 100.0, false, ObstacleScanParams{}, kInvalidDisparity);
  for (int x = 100; x < 540; x += 20) {
    const core::DepthScanColumn& column = confused.columns[static_cast<std::size_t>(x)];
    ASSERT_EQ(column.kind, Kind::free) << "column " << x;
    EXPECT_NEAR(column.x_robot_m, 1.3, 0.05) << "column " << x;  // free up to the floor's end
  }
  ObstacleScanParams any_end;
  any_end.blank_wall_untextured_fraction = 0.0;
  const core::DepthScan unchecked = scan_of_wall(1.3, 0.0, 100.0, false, any_end, kInvalidDisparity);
  EXPECT_EQ(unchecked.columns[320].kind, Kind::obstacle);
}

// Floor texture that fades 1.9 m from the camera under a blank ceiling: nothing is seen
// beyond, but the end is beyond blank_wall_within_m, so it is no wall.
TEST(ObstacleScan, FloorFadingBeyondTheBlankWallRangeIsFree) {
  const core::DepthScan scan = scan_of_wall(6.0, 0.0, 1.9, false);
  for (int x = 100; x < 540; x += 20) {
    EXPECT_EQ(scan.columns[static_cast<std::size_t>(x)].kind, Kind::free) << "column " << x;
  }
}

TEST(ObstacleScan, FloorTextureFadingBeforeAFarWallIsNoObstacle) {
  // A textured wall 4.9 m ahead, the floor measured up to 3 m.
  const core::DepthScan scan = scan_of_wall(5.0, 0.0, 3.0, true);
  for (int x = 100; x < 540; x += 20) {
    const core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(x)];
    // The wall is seen (above the floor's end), so it is the column's obstacle.
    ASSERT_EQ(column.kind, Kind::obstacle) << "column " << x;
    EXPECT_NEAR(column.x_robot_m, 5.0, 0.05) << "column " << x;
  }
  // With the wall's lower part above the robot's height only, what is seen beyond is not an
  // obstacle: the column is free up to where its floor texture ends.
  const core::DepthScan high = scan_of_wall(5.0, 1.3, 3.0, true);
  EXPECT_EQ(high.columns[320].kind, Kind::free);
  EXPECT_NEAR(high.columns[320].x_robot_m, 3.1, 0.05);  // depth 3 m from the camera, 0.1 m ahead
}

// A free column reports its end's range error, range * sigma_d / d: it grows with the square
// of the range (for the grid's free_end_sigmas, off by default: occupancy_grid.hpp).
TEST(ObstacleScan, AFreeColumnReportsItsEndsRangeError) {
  for (const double floor_until_m : {2.0, 3.0}) {
    // The floor seen up to floor_until_m of depth, under a wall above the robot (no obstacle).
    const core::DepthScan scan = scan_of_wall(5.0, 1.3, floor_until_m, true);
    const core::DepthScanColumn& column = scan.columns[320];
    ASSERT_EQ(column.kind, Kind::free);
    const double range = range_of(scan, column);
    EXPECT_NEAR(range, floor_until_m, 0.02);
    const double d = 400.0 * 0.1 / range;  // the paper's f B over the depth
    EXPECT_NEAR(column.end_range_sigma_m, range * 0.5 / d, 0.003) << floor_until_m;
  }
  EXPECT_EQ(scan_of_wall(1.3, 0.0, 100.0, false).columns[320].end_range_sigma_m, 0.0F);  // an obstacle
}

// Every matched pixel 6% too far (its disparity 6% too small), up to a blank wall 2.9 m from
// the camera: the floor points come out up to 3.6 cm below the floor, within its tolerance,
// and the free column would end 17 cm beyond the wall. Moved up their rays onto the floor,
// they end at the wall's base, give or take the wall's lowest centimetre (still matched here,
// and taken for floor: its ray meets the floor 2 per cent of the range behind the wall).
TEST(ObstacleScan, AFloorPointMeasuredBelowTheFloorIsMovedUpItsRayOntoIt) {
  test::Scene scene;
  scene.boxes.push_back({{3.0, -8.0, 0.0}, {3.1, 8.0, 2.5}});
  StereoCalibration camera;
  const test::Rendering view = test::render(scene, camera, paper_mount(), core::Pose2{});
  cv::Mat disparity = without_blank_pixels(view.left_depth, camera, 100.0, false);
  for (int y = 0; y < disparity.rows; ++y) {
    for (int x = 0; x < disparity.cols; ++x) {
      float& d = disparity.at<float>(y, x);
      if (d > 0.0F) d /= 1.06F;
    }
  }
  for (const bool onto_plane : {true, false}) {
    ObstacleScanParams params;
    params.floor_onto_plane = onto_plane;
    ObstacleScanner scanner(params, camera, paper_mount());
    core::DepthScan scan;
    scanner.allocate(scan);
    scanner.compute(disparity, 0.0, 0, scan);
    for (int x = 160; x < 480; x += 40) {
      const core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(x)];
      ASSERT_EQ(column.kind, Kind::free) << "column " << x;
      const double wall_range = 2.9 / std::cos(std::atan((x - camera.principal_x_px) / camera.focal_px));
      if (onto_plane) {
        EXPECT_LE(range_of(scan, column), wall_range * 1.02) << "column " << x;
        EXPECT_GE(range_of(scan, column), wall_range - 0.1) << "column " << x;
      } else {
        EXPECT_GE(range_of(scan, column), wall_range * 1.05) << "column " << x;
      }
    }
  }
}

TEST(ObstacleScan, AnObstacleThroughTheCameraHeightIsMarkedSo) {
  test::Scene scene;
  // A person-sized block (0 to 1.7 m) ahead to the right, a low box (0 to 0.5 m) to the left.
  scene.boxes.push_back({{1.5, -0.6, 0.0}, {1.8, -0.2, 1.7}});
  scene.boxes.push_back({{1.5, 0.2, 0.0}, {1.8, 0.6, 0.5}});
  ScanSetup setup;
  const core::DepthScan& scan = setup.run(scene);
  for (int x = 380; x < 420; ++x) {
    const core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(x)];
    ASSERT_EQ(column.kind, Kind::obstacle) << "column " << x;
    EXPECT_TRUE(column.obstacle_at_camera_height) << "column " << x;
  }
  for (int x = 220; x < 260; ++x) {
    const core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(x)];
    ASSERT_EQ(column.kind, Kind::obstacle) << "column " << x;
    EXPECT_FALSE(column.obstacle_at_camera_height) << "column " << x;
  }
}

TEST(ObstacleScan, TableTopBelowRobotHeightIsAnObstacleOverhangAboveIsNot) {
  test::Scene scene;
  // A table top (no legs) at 0.72-0.75 m: free floor under it, but the robot (1.2 m) cannot pass.
  scene.boxes.push_back({{2.0, -0.6, 0.72}, {2.8, 0.0, 0.75}});
  // A shelf above the robot's height to the left: not an obstacle.
  scene.boxes.push_back({{2.0, 0.1, 1.30}, {2.8, 0.8, 1.35}});
  ScanSetup setup;
  const core::DepthScan& scan = setup.run(scene);
  // Right of centre (table side, columns > 330), the front edge at x = 2.0 m.
  for (int x = 360; x < 420; ++x) {
    const core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(x)];
    ASSERT_EQ(column.kind, Kind::obstacle) << "column " << x;
    EXPECT_NEAR(column.x_robot_m, 2.0, 0.02);
  }
  // Left of centre (shelf side), free floor beyond the shelf.
  for (int x = 200; x < 280; ++x) {
    const core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(x)];
    ASSERT_EQ(column.kind, Kind::free) << "column " << x;
    EXPECT_GT(range_of(scan, column), 5.0);
  }
}

TEST(ObstacleScan, IsolatedMismatchesDoNotMakeObstacles) {
  const StereoCalibration camera;
  ObstacleScanner scanner(ObstacleScanParams{}, camera, paper_mount());
  core::DepthScan scan;
  scanner.allocate(scan);
  const test::Rendering view = test::render(test::Scene{}, camera, paper_mount(), core::Pose2{});
  cv::Mat disparity = disparity_from_depth(view.left_depth, camera);
  // Three wrong pixels in left column 140 claim a point 1 m ahead at camera height; with
  // d = 40 they belong to right column 100.
  for (int y = 230; y < 233; ++y) disparity.at<float>(y, 140) = 40.0F;
  scanner.compute(disparity, 0.0, 0, scan);
  EXPECT_EQ(scan.columns[100].kind, Kind::free);
  disparity.at<float>(233, 140) = 40.0F;  // the fourth (scan_min_obstacle_pixels) confirms it
  scanner.compute(disparity, 0.0, 0, scan);
  EXPECT_EQ(scan.columns[100].kind, Kind::obstacle);
}

// A pair whose right image shows the left image's pixels [x0, x1) x [y0, y1) at disparity d.
void show_at_disparity(const cv::Mat& left, cv::Mat& right, int x0, int x1, int y0, int y1, int d) {
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) right.at<std::uint8_t>(y, x - d) = left.at<std::uint8_t>(y, x);
  }
}

// Matches on a surface 0.45 m ahead (disparity 40 / 0.45 = 88.9 px, beyond the dense
// matcher's 63) over open floor, in holes of the dense disparities as a surface that near
// leaves. Three that agree, on a patch the right image shows at 89 px only, become their
// columns' obstacles. Left as they were: a match alone; three where the dense matcher found
// the floor; three on a texture repeating every 20 px, which also matches at 9, 29 and 49 px
// (the dense matcher leaves holes there for the ambiguity); and a match the dense matcher
// reaches. A scanner with near_min_matches 0 changes nothing.
TEST(ObstacleScan, NearMatchesThatAgreeAndMatchOnlyThatNearWhereTheDenseMatcherFoundLittleBecomeObstacles) {
  ObstacleScanParams params;
  params.near_min_matches = 3;
  const StereoCalibration camera;
  ObstacleScanner scanner(params, camera, paper_mount());
  const test::Rendering view = test::render(test::Scene{}, camera, paper_mount(), core::Pose2{});
  cv::Mat disparity = disparity_from_depth(view.left_depth, camera);
  cv::Mat left(camera.height_px, camera.width_px, CV_8UC1);
  cv::Mat right(camera.height_px, camera.width_px, CV_8UC1);
  cv::RNG(1).fill(left, cv::RNG::UNIFORM, 0, 256);
  cv::RNG(2).fill(right, cv::RNG::UNIFORM, 0, 256);
  const int near_d = 89;
  show_at_disparity(left, right, 290, 370, 225, 255, near_d);  // the near surface
  show_at_disparity(left, right, 612, 628, 225, 255, near_d);  // the match alone
  for (int y = 225; y < 255; ++y) {  // the repeated texture: period 20 px, seen at 9 (mod 20)
    const auto texture = [&left, y](int x) { return left.at<std::uint8_t>(y, 400 + x % 20); };
    for (int x = 500 - 1; x >= 400; --x) left.at<std::uint8_t>(y, x) = texture(x - 400);
    for (int u = 350; u < 500; ++u) right.at<std::uint8_t>(y, u) = texture(u + 9 - 400 + 20 * 10);
  }
  for (const cv::Rect hole : {cv::Rect(320, 225, 30, 30), cv::Rect(610, 225, 20, 30), cv::Rect(440, 225, 30, 30)}) {
    disparity(hole).setTo(kInvalidDisparity);
  }
  core::DepthScan dense_only;
  scanner.allocate(dense_only);
  scanner.compute(disparity, 0.0, 5, dense_only);
  core::DepthScan scan = dense_only;
  const auto d = static_cast<float>(near_d);
  const ObstacleScanner::NearMatch matches[] = {
      {330.0F, 240.0F, d}, {334.0F, 240.0F, d}, {338.0F, 240.0F, d},  // three that agree, only that near
      {620.0F, 240.0F, d},                                            // alone, 0.33 m from them
      {430.0F, 330.0F, d}, {434.0F, 330.0F, d}, {438.0F, 330.0F, d},  // where the floor was matched
      {450.0F, 240.0F, d}, {454.0F, 240.0F, d}, {458.0F, 240.0F, d},  // the repeated texture
      {200.0F, 300.0F, 20.0F},                                        // 2 m away: the dense matcher's
  };
  const std::size_t count = sizeof(matches) / sizeof(matches[0]);
  EXPECT_EQ(scanner.add_near_matches(matches, count, disparity, left, right, 0.0, scan), 3U);
  std::vector<std::size_t> near_columns;
  for (const float x_left : {330.0F, 334.0F, 338.0F}) {
    const auto column = static_cast<std::size_t>(std::lround(x_left - d));
    near_columns.push_back(column);
    const core::DepthScanColumn& near = scan.columns[column];
    ASSERT_EQ(dense_only.columns[column].kind, Kind::free);
    ASSERT_EQ(near.kind, Kind::obstacle) << column;
    EXPECT_NEAR(near.x_robot_m, 0.1 + 40.0 / near_d, 1e-3);
    EXPECT_TRUE(near.obstacle_at_camera_height);
    EXPECT_NEAR(near.measurable_from_m, range_of(scan, near), 1e-5);
    EXPECT_EQ(near.floor_visible_from_m, dense_only.columns[column].floor_visible_from_m);
  }
  for (std::size_t column = 0; column < scan.columns.size(); ++column) {
    if (std::find(near_columns.begin(), near_columns.end(), column) != near_columns.end()) continue;
    EXPECT_EQ(scan.columns[column].kind, dense_only.columns[column].kind) << column;
    EXPECT_EQ(scan.columns[column].x_robot_m, dense_only.columns[column].x_robot_m) << column;
  }
  ObstacleScanner off(ObstacleScanParams{}, camera, paper_mount());
  core::DepthScan untouched = dense_only;
  EXPECT_EQ(off.add_near_matches(matches, count, disparity, left, right, 0.0, untouched), 0U);
  for (std::size_t column = 0; column < scan.columns.size(); ++column) {
    EXPECT_EQ(untouched.columns[column].kind, dense_only.columns[column].kind) << column;
  }
}

TEST(ObstacleScan, PanTurnsTheScanInTheRobotFrame) {
  test::Scene scene;
  // A wall to the robot's left at y = 2 m.
  scene.boxes.push_back({{-3.0, 2.0, 0.0}, {3.0, 2.1, 1.0}});
  const StereoCalibration camera;
  const double pan = core::kPi / 2.0;
  ObstacleScanner scanner(ObstacleScanParams{}, camera, paper_mount());
  core::DepthScan scan;
  scanner.allocate(scan);
  const test::Rendering view = test::render(scene, camera, paper_mount(), core::Pose2{}, pan);
  scanner.compute(disparity_from_depth(view.left_depth, camera), pan, 0, scan);
  const core::DepthScanColumn& centre = scan.columns[320];
  ASSERT_EQ(centre.kind, Kind::obstacle);
  EXPECT_NEAR(centre.y_robot_m, 2.0, 0.02);
  // Columns are rays from the right camera, which pan keeps at the mount (x = 0.1 m).
  EXPECT_NEAR(centre.x_robot_m, 0.10, 0.02);
}

// The box and the table seen through the whole dense path (rendered images, block matcher).
TEST(ObstacleScan, BoxAndTableShowUpThroughTheDenseMatcher) {
  const StereoCalibration camera;
  test::Scene scene;
  scene.boxes.push_back({{1.5, 0.3, 0.0}, {1.7, 0.7, 0.10}});    // 10 cm box, left
  scene.boxes.push_back({{2.0, -0.9, 0.72}, {2.8, -0.3, 0.75}});  // table top, right
  scene.boxes.push_back({{5.0, -3.0, 0.0}, {5.1, 3.0, 2.5}});     // back wall
  const test::Rendering view = test::render(scene, camera, paper_mount(), core::Pose2{});
  DenseDisparityMatcher matcher(DenseDisparityParams{}, camera.width_px, camera.height_px);
  cv::Mat disparity;
  matcher.allocate_output(disparity);
  matcher.compute(view.frame.left, view.frame.right, disparity);
  ObstacleScanner scanner(ObstacleScanParams{}, camera, paper_mount());
  core::DepthScan scan;
  scanner.allocate(scan);
  scanner.compute(disparity, 0.0, 0, scan);
  // Right-image columns of the box's front face (y 0.3..0.7 m at x 1.5 m) and the table's
  // front edge (y -0.3..-0.9 m at x 2.0 m, only 3 cm high), 5 cm in from their ends. Stated
  // tolerance: the obstacle within 5 cm of the face on 90 % of the box's columns and 80 % of
  // the table's (a thin edge seen above the camera is the hardest case for a 7x7 window).
  const auto column_of = [&](double x, double y) {
    return static_cast<std::size_t>(std::lround(camera.principal_x_px - camera.focal_px * y / (x - 0.10)));
  };
  std::size_t box_hits = 0;
  std::size_t box_columns = 0;
  for (std::size_t x = column_of(1.5, 0.65); x <= column_of(1.5, 0.35); ++x) {
    ++box_columns;
    const auto& column = scan.columns[x];
    box_hits += column.kind == Kind::obstacle && std::fabs(column.x_robot_m - 1.5) < 0.05 ? 1U : 0U;
  }
  std::size_t table_hits = 0;
  std::size_t table_columns = 0;
  for (std::size_t x = column_of(2.0, -0.35); x <= column_of(2.0, -0.85); ++x) {
    ++table_columns;
    const auto& column = scan.columns[x];
    table_hits += column.kind == Kind::obstacle && std::fabs(column.x_robot_m - 2.0) < 0.05 ? 1U : 0U;
  }
  std::printf("box: %zu of %zu columns, table: %zu of %zu columns\n", box_hits, box_columns, table_hits, table_columns);
  EXPECT_GE(box_hits, box_columns * 9 / 10);
  EXPECT_GE(table_hits, table_columns * 8 / 10);
}

// The whole dense path on rendered images against the ground-truth scan.
TEST(ObstacleScan, RenderedViewAgreesWithGroundTruthDepth) {
  const StereoCalibration camera;
  const test::Scene scene = test::textured_room();
  const test::Rendering view = test::render(scene, camera, paper_mount(), core::Pose2{0.0, 0.0, 0.1});
  DenseDisparityMatcher matcher(DenseDisparityParams{}, camera.width_px, camera.height_px);
  cv::Mat disparity;
  matcher.allocate_output(disparity);
  matcher.compute(view.frame.left, view.frame.right, disparity);
  ObstacleScanner scanner(ObstacleScanParams{}, camera, paper_mount());
  core::DepthScan measured;
  core::DepthScan truth;
  scanner.allocate(measured);
  scanner.allocate(truth);
  const core::AllocationScope scope;
  scanner.compute(disparity, 0.0, 0, measured);
  EXPECT_EQ(scope.allocations(), 0U);
  scanner.compute(disparity_from_depth(view.left_depth, camera), 0.0, 0, truth);
  // Stated tolerance: kinds agree and ranges within 5 cm + 5 % (a 0.5 px disparity error at
  // 3 m is 4 %), on at least 90 % of the columns that the 64-disparity search can see.
  std::size_t compared = 0;
  std::size_t agree = 0;
  for (std::size_t x = 80; x < truth.columns.size() - 10; ++x) {
    ++compared;
    const auto& m = measured.columns[x];
    const auto& t = truth.columns[x];
    const double true_range = range_of(truth, t);
    if (m.kind == t.kind && std::fabs(range_of(measured, m) - true_range) <= 0.05 + 0.05 * true_range) {
      ++agree;
    }
  }
  EXPECT_GE(agree, compared * 9 / 10) << agree << " of " << compared;
}

}  // namespace
}  // namespace stereoscout::vision
