// The scores of `slam --kitti`: ATE after the best rigid fit and relative error per metre, on
// hand-made trajectories (the identity check is tested with the vision module).
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

}  // namespace
}  // namespace stereoscout::cli::kitti
