// The scores of `slam --kitti`: ATE after the best rigid fit, relative error per metre, and the
// re-observation identity check, on hand-made trajectories and points.
#include <gtest/gtest.h>

#include <cmath>

#include "kitti_metrics.hpp"

namespace stereoscout::cli::kitti {
namespace {

std::vector<core::Pose2> arc(int poses) {
  std::vector<core::Pose2> path;
  for (int k = 0; k < poses; ++k) path.push_back({std::sin(0.1 * k) * 10.0, (1.0 - std::cos(0.1 * k)) * 10.0, 0.1 * k});
  return path;
}

TEST(KittiMetrics, AteIgnoresARigidMotionOfTheWholeTrajectory) {
  const std::vector<core::Pose2> truth = arc(30);
  std::vector<core::Pose2> moved;
  const core::Pose2 offset{3.0, -2.0, 0.7};
  for (const core::Pose2& pose : truth) moved.push_back(offset.compose(pose));
  EXPECT_NEAR(planar_ate_rmse(moved, truth), 0.0, 1e-9);
  EXPECT_NEAR(relative_error_per_metre(moved, truth, 5.0), 0.0, 1e-9);
  // Stretched by 10 %: relative error 0.1 per metre on every segment.
  std::vector<core::Pose2> straight;
  std::vector<core::Pose2> stretched;
  for (int k = 0; k < 30; ++k) {
    straight.push_back({1.0 * k, 0.0, 0.0});
    stretched.push_back({1.1 * k, 0.0, 0.0});
  }
  EXPECT_NEAR(relative_error_per_metre(stretched, straight, 10.0), 0.1, 1e-12);
  // Shorter than one segment: the whole path is the segment.
  EXPECT_NEAR(relative_error_per_metre(stretched, straight, 100.0), 0.1, 1e-12);
  EXPECT_GT(planar_ate_rmse(stretched, straight), 0.5);
}

TEST(KittiMetrics, ReobservationsAgreeOnlyWhereTheTrueMotionPutsThem) {
  ReobservationCheck check(11.345);
  core::LandmarkObservation seen;
  seen.landmark_id = 7;
  seen.point_camera = Eigen::Vector3d(1.0, 0.5, 10.0);
  seen.covariance = Eigen::Matrix3d::Identity() * 0.01;
  check.observe(Eigen::Isometry3d::Identity(), &seen, 1);
  EXPECT_EQ(check.reobservations(), 0U);
  // The camera moved 2 m forward: the same world point is 2 m closer.
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.translation() = Eigen::Vector3d(0.0, 0.0, 2.0);
  core::LandmarkObservation again = seen;
  again.point_camera = Eigen::Vector3d(1.0, 0.5, 8.05);
  check.observe(moved, &again, 1);
  // A wrong identity: the same id on a point 1 m to the side.
  core::LandmarkObservation wrong = seen;
  wrong.point_camera = Eigen::Vector3d(2.0, 0.5, 8.0);
  check.observe(moved, &wrong, 1);
  EXPECT_EQ(check.reobservations(), 2U);
  EXPECT_EQ(check.consistent(), 1U);
  EXPECT_DOUBLE_EQ(check.consistency(), 0.5);
}

}  // namespace
}  // namespace stereoscout::cli::kitti
