#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/random.hpp"
#include "stereoscout/slam/manhattan_frame.hpp"
#include "stereoscout/slam/particle_filter.hpp"
#include "stereoscout/slam/wall_line.hpp"

namespace stereoscout::slam {
namespace {

using core::degrees_to_radians;
using core::radians_to_degrees;
using Column = core::DepthScanColumn;

// A wall in the robot frame: the line through `point` along `direction_rad`.
struct TestWall {
  Eigen::Vector2d point;
  double direction_rad;
};

// A scan of 640 columns over a 60 degree view from the origin, each column's ray ending at the
// nearest of `walls` (with `noise_m` along the ray), or invalid when it meets none.
core::DepthScan scan_of(const std::vector<TestWall>& walls, double noise_m = 0.0, double view_rad = 0.0) {
  core::DepthScan scan;
  scan.columns.resize(640);
  core::RandomStream noise(7, {core::stream_purpose::test, 0, 0});
  for (std::size_t i = 0; i < scan.columns.size(); ++i) {
    // Bearing order as in the camera: the leftmost column first.
    const double bearing = view_rad + degrees_to_radians(30.0 - 60.0 * static_cast<double>(i) / 639.0);
    const Eigen::Vector2d ray(std::cos(bearing), std::sin(bearing));
    double nearest = 1e9;
    for (const TestWall& wall : walls) {
      const Eigen::Vector2d along(std::cos(wall.direction_rad), std::sin(wall.direction_rad));
      const double denominator = ray.x() * along.y() - ray.y() * along.x();
      if (std::abs(denominator) < 1e-9) continue;
      const double t = (wall.point.x() * along.y() - wall.point.y() * along.x()) / denominator;
      if (t > 0.0) nearest = std::min(nearest, t);
    }
    Column& column = scan.columns[i];
    if (nearest > 100.0) continue;
    const double range = nearest + noise.gaussian(0.0, noise_m);
    column.kind = Column::Kind::obstacle;
    column.x_robot_m = static_cast<float>(range * ray.x());
    column.y_robot_m = static_cast<float>(range * ray.y());
  }
  return scan;
}

// The smaller angle between two line directions (lines, so modulo 180 degrees).
double line_angle_deg(double a_rad, double b_rad) {
  const double d = std::fmod(std::abs(a_rad - b_rad), core::kPi);
  return radians_to_degrees(std::min(d, core::kPi - d));
}

TEST(WallLine, AStraightWallGivesItsDirection) {
  const double direction = degrees_to_radians(110.0);
  const core::DepthScan scan = scan_of({{{2.0, 0.0}, direction}}, 0.01);
  WallLine line;
  ASSERT_TRUE(fit_wall_line(scan, WallLineParams{}, line));
  EXPECT_LT(line_angle_deg(line.direction_rad, direction), 0.5);
  EXPECT_GE(line.direction_rad, 0.0);
  EXPECT_LT(line.direction_rad, core::kPi);
  EXPECT_GT(line.length_m, 2.0);
  EXPECT_LT(line.rms_m, 0.02);
  EXPECT_EQ(line.points, 640);
}

TEST(WallLine, ACornerIsSplitAndTheLongerWallKept) {
  // Facing a corner: a wall across the view 2.5 m ahead, and a side wall 0.6 m to the right
  // that meets it; the side wall fills the right part of the view.
  const core::DepthScan scan = scan_of({{{2.5, 0.0}, degrees_to_radians(90.0)}, {{0.0, -0.6}, 0.0}});
  WallLine line;
  ASSERT_TRUE(fit_wall_line(scan, WallLineParams{}, line));
  EXPECT_LT(line_angle_deg(line.direction_rad, degrees_to_radians(90.0)), 0.5);
  EXPECT_LT(line.rms_m, 0.005);
  EXPECT_LT(line.points, 640);
}

TEST(WallLine, ShortNoisyOrFarRunsAreNoWall) {
  WallLineParams params;
  WallLine line;
  // 0.6 m of wall, the rest of the view open.
  core::DepthScan scan = scan_of({{{2.0, 0.0}, degrees_to_radians(90.0)}});
  for (Column& column : scan.columns) {
    if (std::abs(column.y_robot_m) > 0.3F) column.kind = Column::Kind::free;
  }
  EXPECT_FALSE(fit_wall_line(scan, params, line));
  // A ragged surface: 0.1 m of range noise.
  EXPECT_FALSE(fit_wall_line(scan_of({{{2.0, 0.0}, degrees_to_radians(90.0)}}, 0.1), params, line));
  // A straight wall beyond max_range_m.
  params.max_range_m = 1.5;
  EXPECT_FALSE(fit_wall_line(scan_of({{{2.0, 0.0}, degrees_to_radians(90.0)}}), params, line));
}

TEST(ManhattanFrame, LearnsTheAxesFromWallsAtRightAngles) {
  ManhattanFrame frame(8);
  const double walls_deg[] = {30.5, 120.0, -60.2, 29.6, 210.0, 119.8, 30.1, -149.9};
  for (const double wall : walls_deg) {
    EXPECT_FALSE(frame.fixed());
    frame.learn(degrees_to_radians(wall));
  }
  ASSERT_TRUE(frame.fixed());
  EXPECT_NEAR(radians_to_degrees(frame.axis_rad()), 30.0, 0.3);
  EXPECT_NEAR(radians_to_degrees(frame.offset(degrees_to_radians(122.0))), 2.0, 0.3);
  EXPECT_NEAR(radians_to_degrees(frame.offset(degrees_to_radians(-62.0))), -2.0, 0.3);
  EXPECT_NEAR(radians_to_degrees(frame.offset(degrees_to_radians(75.0))), -45.0 + 0.0, 0.3);
  frame.learn(degrees_to_radians(50.0));  // ignored once fixed
  EXPECT_NEAR(radians_to_degrees(frame.axis_rad()), 30.0, 0.3);
}

TEST(ManhattanFrame, WallsThatDoNotShareAxesStartTheLearningOver) {
  ManhattanFrame frame(4);
  for (const double wall : {0.0, 20.0, 40.0, 60.0}) frame.learn(degrees_to_radians(wall));
  EXPECT_FALSE(frame.fixed());
  EXPECT_EQ(frame.restarts(), 1u);
  for (const double wall : {-10.0, 80.0, 170.0, -100.0}) frame.learn(degrees_to_radians(wall));
  EXPECT_TRUE(frame.fixed());
  EXPECT_NEAR(radians_to_degrees(frame.axis_rad()), -10.0, 1e-6);
}

core::FilterConfig turning_config(double manhattan_sigma_deg) {
  core::FilterConfig config;
  config.particles = 200;
  config.particle_capacity = 200;
  config.landmark_node_capacity = 10000;
  config.landmark_estimate_capacity = 10000;
  config.trajectory_node_capacity = 100000;
  config.max_observations_per_update = 16;
  config.motion_noise_rotation_per_rad = 0.1;
  config.manhattan_heading_sigma_deg = manhattan_sigma_deg;
  config.manhattan_frame_walls = 5;
  return config;
}

// A robot turning in place in a room whose walls lie at 30 and 120 degrees, with no landmark
// in view; its odometry counts every turn 5% long. Each update it sees the wall its camera
// faces. Returns the estimate's heading error at the end, in degrees.
double heading_error_after_turning(ParticleFilter& filter, bool hand_walls) {
  const double step_rad = degrees_to_radians(9.0);
  filter.start(core::OdometryReading{}, core::Pose2{});
  core::OdometryReading odometry;
  double truth = 0.0;
  for (int step = 1; step <= 200; ++step) {
    truth += step_rad;
    odometry.timestamp_ns = static_cast<std::int64_t>(step) * 500000000;
    odometry.pose.theta = core::wrap_angle(odometry.pose.theta + 1.05 * step_rad);
    // The room's wall the robot faces, in the robot frame.
    const double wall_map = degrees_to_radians(120.0);
    WallLine wall;
    wall.direction_rad = core::wrap_angle(wall_map - truth);
    if (wall.direction_rad < 0.0) wall.direction_rad += core::kPi;
    wall.length_m = 2.0;
    filter.update(odometry, ObservationList{}, Eigen::Isometry3d::Identity(), hand_walls ? &wall : nullptr);
  }
  return std::abs(radians_to_degrees(core::wrap_angle(filter.estimate_pose().theta - core::wrap_angle(truth))));
}

TEST(ParticleFilter, WallsOnTheBuildingsAxesKeepTheHeadingWhereNoLandmarkIsInView) {
  ParticleFilter without(turning_config(0.0), core::CameraMount{}, 3);
  const double drifted = heading_error_after_turning(without, true);  // walls handed, but the key is off
  EXPECT_GT(drifted, 60.0);  // 5% of 1800 degrees: 90 degrees
  EXPECT_EQ(without.counters().manhattan_walls_learnt + without.counters().manhattan_walls_used, 0u);

  ParticleFilter with(turning_config(2.0), core::CameraMount{}, 3);
  const double kept = heading_error_after_turning(with, true);
  EXPECT_LT(kept, 2.5);  // the axes were learnt while the heading drifted 0.45 degrees a step
  EXPECT_TRUE(with.manhattan_frame().fixed());
  EXPECT_EQ(with.counters().manhattan_walls_learnt, 5u);
  EXPECT_GT(with.counters().manhattan_walls_used, 150u);
}

TEST(ParticleFilter, AWallOffTheBuildingsAxesWeighsNobody) {
  ParticleFilter filter(turning_config(2.0), core::CameraMount{}, 3);
  filter.start(core::OdometryReading{}, core::Pose2{});
  core::OdometryReading odometry;
  WallLine wall;
  wall.direction_rad = degrees_to_radians(90.0);
  for (int step = 1; step <= 5; ++step) {
    odometry.timestamp_ns = step * 500000000LL;
    filter.update(odometry, ObservationList{}, Eigen::Isometry3d::Identity(), &wall);
  }
  ASSERT_TRUE(filter.manhattan_frame().fixed());
  // Turn a little so that the particles' headings differ, then show a wall at 45 degrees.
  odometry.timestamp_ns = 6 * 500000000LL;
  odometry.pose.theta = 0.3;
  filter.update(odometry, ObservationList{}, Eigen::Isometry3d::Identity(), nullptr);
  std::vector<double> before;
  for (std::size_t i = 0; i < filter.particle_count(); ++i) before.push_back(filter.particle(i).log_weight);
  wall.direction_rad = degrees_to_radians(45.0) - 0.3;
  odometry.timestamp_ns = 7 * 500000000LL;
  filter.update(odometry, ObservationList{}, Eigen::Isometry3d::Identity(), &wall);
  EXPECT_EQ(filter.counters().manhattan_walls_off_axes, 1u);
  EXPECT_EQ(filter.counters().manhattan_walls_used, 0u);
  for (std::size_t i = 0; i < filter.particle_count(); ++i) EXPECT_EQ(filter.particle(i).log_weight, before[i]);
}

TEST(ParticleFilter, WeighingByWallsDoesNotTouchTheHeap) {
  ParticleFilter filter(turning_config(2.0), core::CameraMount{}, 3);
  filter.start(core::OdometryReading{}, core::Pose2{});
  const core::DepthScan scan = scan_of({{{2.0, 0.0}, degrees_to_radians(90.0)}}, 0.01);
  core::OdometryReading odometry;
  const core::AllocationScope scope;
  for (int step = 1; step <= 20; ++step) {
    odometry.timestamp_ns = step * 500000000LL;
    WallLine wall;
    const bool seen = fit_wall_line(scan, WallLineParams{}, wall);
    filter.update(odometry, ObservationList{}, Eigen::Isometry3d::Identity(), seen ? &wall : nullptr);
  }
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_EQ(filter.counters().manhattan_walls_learnt + filter.counters().manhattan_walls_used, 20u);
}

}  // namespace
}  // namespace stereoscout::slam
