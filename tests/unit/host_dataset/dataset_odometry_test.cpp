// Odometry made from ground truth: exact without noise, the systematic terms as configured,
// the random terms of the right size, and reproducible per seed.
#include <gtest/gtest.h>

#include <cmath>

#include "stereoscout/core/odometry_noise.hpp"
#include "stereoscout/host_dataset/dataset_odometry.hpp"

namespace stereoscout::host_dataset {
namespace {

std::vector<core::Pose2> straight_line(int frames, double step_m) {
  std::vector<core::Pose2> poses;
  for (int k = 0; k < frames; ++k) poses.push_back({step_m * k, 0.0, 0.0});
  return poses;
}

std::vector<double> frame_times(std::size_t frames) {
  std::vector<double> times;
  for (std::size_t k = 0; k < frames; ++k) times.push_back(0.1 * static_cast<double>(k));
  return times;
}

std::vector<core::Pose2> read_all(DatasetOdometry& odometry) {
  std::vector<core::Pose2> poses;
  core::OdometryReading reading;
  while (odometry.read(reading).ok()) poses.push_back(reading.pose);
  return poses;
}

TEST(DatasetOdometry, WithoutNoiseItIsTheGroundTruth) {
  std::vector<core::Pose2> truth = {{0.0, 0.0, 0.0}, {1.0, 0.2, 0.1}, {2.0, 0.5, 0.3}, {2.5, 1.5, 1.2}};
  DatasetOdometry odometry(truth, frame_times(truth.size()), core::OdometryNoiseConfig{}, 7);
  core::OdometryReading reading;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    ASSERT_TRUE(odometry.read(reading).ok());
    EXPECT_EQ(reading.sequence, k);
    EXPECT_EQ(reading.timestamp_ns, static_cast<std::int64_t>(std::llround(0.1 * static_cast<double>(k) * 1e9)));
    EXPECT_NEAR(reading.pose.x, truth[k].x, 1e-12);
    EXPECT_NEAR(reading.pose.y, truth[k].y, 1e-12);
    EXPECT_NEAR(reading.pose.theta, truth[k].theta, 1e-12);
  }
  EXPECT_EQ(odometry.read(reading).code, core::StatusCode::not_available);
}

TEST(DatasetOdometry, SystematicScaleAndDrift) {
  core::OdometryNoiseConfig noise;
  noise.scale_error = 0.05;
  noise.drift_deg_per_m = 1.0;
  DatasetOdometry odometry(straight_line(11, 1.0), frame_times(11), noise, 1);
  const std::vector<core::Pose2> poses = read_all(odometry);
  ASSERT_EQ(poses.size(), 11U);
  // 10 steps of 1.05 m, each turning 1 deg more after it is driven.
  EXPECT_NEAR(poses.back().theta, core::degrees_to_radians(10.0), 1e-12);
  double distance = 0.0;
  for (std::size_t k = 1; k < poses.size(); ++k) distance += (poses[k].translation() - poses[k - 1].translation()).norm();
  EXPECT_NEAR(distance, 10.5, 1e-9);
}

TEST(DatasetOdometry, RandomWalkHasTheConfiguredSpreadAndIsSeeded) {
  core::OdometryNoiseConfig noise;
  noise.translation_sigma_m_per_sqrt_m = 0.1;
  noise.rotation_sigma_rad_per_sqrt_m = 0.02;
  // Over 100 frames of 1 m: distance sigma 0.1 * sqrt(100) = 1 m, heading sigma 0.2 rad.
  double sum_squares_distance = 0.0;
  double sum_squares_heading = 0.0;
  const int runs = 200;
  for (int seed = 0; seed < runs; ++seed) {
    DatasetOdometry odometry(straight_line(101, 1.0), frame_times(101), noise, static_cast<std::uint64_t>(seed));
    const std::vector<core::Pose2> poses = read_all(odometry);
    double distance = 0.0;
    for (std::size_t k = 1; k < poses.size(); ++k) {
      distance += (poses[k].translation() - poses[k - 1].translation()).norm();
    }
    sum_squares_distance += (distance - 100.0) * (distance - 100.0);
    sum_squares_heading += poses.back().theta * poses.back().theta;
  }
  EXPECT_NEAR(std::sqrt(sum_squares_distance / runs), 1.0, 0.15);
  EXPECT_NEAR(std::sqrt(sum_squares_heading / runs), 0.2, 0.03);

  DatasetOdometry first(straight_line(20, 1.0), frame_times(20), noise, 42);
  DatasetOdometry again(straight_line(20, 1.0), frame_times(20), noise, 42);
  DatasetOdometry other(straight_line(20, 1.0), frame_times(20), noise, 43);
  const core::Pose2 a = read_all(first).back();
  const core::Pose2 b = read_all(again).back();
  const core::Pose2 c = read_all(other).back();
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.theta, b.theta);
  EXPECT_NE(a.x, c.x);
}

TEST(DatasetOdometry, NoMotionNoNoise) {
  core::OdometryNoiseConfig noise{0.1, 0.1, 0.1, 0.1, 5.0};
  core::RandomStream random(3, {core::stream_purpose::dataset_odometry, 1, 0});
  const core::Pose2 still = core::corrupt_motion(core::Pose2{}, noise, random);
  EXPECT_EQ(still.x, 0.0);
  EXPECT_EQ(still.y, 0.0);
  EXPECT_EQ(still.theta, 0.0);
}

}  // namespace
}  // namespace stereoscout::host_dataset
