#include <gtest/gtest.h>

#include <cmath>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::core {
namespace {

constexpr double kTolerance = 1e-12;

TEST(WrapAngle, MapsIntoHalfOpenInterval) {
  EXPECT_NEAR(wrap_angle(0.0), 0.0, kTolerance);
  EXPECT_NEAR(wrap_angle(kPi), kPi, kTolerance);
  EXPECT_NEAR(wrap_angle(-kPi), kPi, kTolerance);  // -pi maps to +pi
  EXPECT_NEAR(wrap_angle(3.0 * kPi / 2.0), -kPi / 2.0, kTolerance);
  EXPECT_NEAR(wrap_angle(-3.0 * kPi / 2.0), kPi / 2.0, kTolerance);
  EXPECT_NEAR(wrap_angle(20.0 * kPi + 0.1), 0.1, 1e-12);
  EXPECT_TRUE(std::isnan(wrap_angle(std::nan(""))));
}

// With period pi: the turn between two lines, which have no direction.
TEST(WrapCentred, BringsTheTurnBetweenTwoLinesWithinAQuarterTurn) {
  EXPECT_NEAR(wrap_centred(0.1, kPi), 0.1, 1e-12);
  EXPECT_NEAR(wrap_centred(kPi - 0.1, kPi), -0.1, 1e-12);
  EXPECT_NEAR(wrap_centred(-kPi + 0.1, kPi), 0.1, 1e-12);
  EXPECT_NEAR(wrap_centred(0.5 * kPi, kPi), -0.5 * kPi, 1e-12);  // half-open: [-period/2, period/2)
  EXPECT_NEAR(wrap_centred(0.3 + 2.0 * kPi, 0.5 * kPi), 0.3, 1e-12);
}

// Points along a line at 30 degrees, spread a little across it: the axis is the line's.
TEST(PrincipalAxisAngle, IsTheDirectionOfTheLineThePointsLieAlong) {
  const Eigen::Vector2d along(std::cos(degrees_to_radians(30.0)), std::sin(degrees_to_radians(30.0)));
  const Eigen::Vector2d across(-along.y(), along.x());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (int i = -10; i <= 10; ++i) {
    const Eigen::Vector2d point = 0.1 * i * along + (i % 2 == 0 ? 0.01 : -0.01) * across;
    scatter += point * point.transpose();
  }
  EXPECT_NEAR(principal_axis_angle(scatter(0, 0), scatter(0, 1), scatter(1, 1)), degrees_to_radians(30.0), 1e-3);
  // A vertical line: the axis at a quarter turn (either sign is the same line).
  EXPECT_NEAR(std::abs(principal_axis_angle(0.0, 0.0, 1.0)), 0.5 * kPi, 1e-12);
}

TEST(Pose2, ComposeThenInverseIsIdentity) {
  const Pose2 a{1.0, 2.0, 0.5};
  const Pose2 identity = a.compose(a.inverse());
  EXPECT_NEAR(identity.x, 0.0, kTolerance);
  EXPECT_NEAR(identity.y, 0.0, kTolerance);
  EXPECT_NEAR(identity.theta, 0.0, kTolerance);
}

TEST(Pose2, ComposeMovesInTheRotatedFrame) {
  const Pose2 facing_left{1.0, 1.0, kPi / 2.0};
  const Pose2 moved = facing_left.compose({2.0, 0.0, kPi / 2.0});  // 2 m forward, turn left
  EXPECT_NEAR(moved.x, 1.0, kTolerance);
  EXPECT_NEAR(moved.y, 3.0, kTolerance);
  EXPECT_NEAR(moved.theta, kPi, kTolerance);
}

TEST(Pose2, BetweenRecoversTheRelativeMotion) {
  const Pose2 a{0.3, -1.2, 2.9};
  const Pose2 motion{0.07, 0.01, 0.4};
  const Pose2 b = a.compose(motion);
  const Pose2 recovered = a.between(b);
  EXPECT_NEAR(recovered.x, motion.x, kTolerance);
  EXPECT_NEAR(recovered.y, motion.y, kTolerance);
  EXPECT_NEAR(recovered.theta, motion.theta, kTolerance);  // across the +-pi seam
}

TEST(Pose2, TransformPointAndIsometryAgree) {
  const Pose2 pose{2.0, -1.0, 0.7};
  const Eigen::Vector2d point(0.5, 1.5);
  const Eigen::Vector2d planar = pose.transform_point(point);
  const Eigen::Vector3d spatial = pose.to_isometry3() * Eigen::Vector3d(point.x(), point.y(), 0.4);
  EXPECT_NEAR(planar.x(), spatial.x(), kTolerance);
  EXPECT_NEAR(planar.y(), spatial.y(), kTolerance);
  EXPECT_NEAR(spatial.z(), 0.4, kTolerance);
}

TEST(CameraFrames, OpticalAxisLooksForwardAndImageDownIsWorldDown) {
  const CameraMount mount{0.1, 0.0, 1.0, 0.0};
  const Eigen::Isometry3d robot_camera = robot_from_camera(mount, 0.0);
  const Eigen::Vector3d ahead = robot_camera * Eigen::Vector3d(0.0, 0.0, 2.0);  // 2 m along optical z
  EXPECT_NEAR(ahead.x(), 2.1, kTolerance);
  EXPECT_NEAR(ahead.y(), 0.0, kTolerance);
  EXPECT_NEAR(ahead.z(), 1.0, kTolerance);
  const Eigen::Vector3d right_down = robot_camera.linear() * Eigen::Vector3d(1.0, 1.0, 0.0);
  EXPECT_NEAR(right_down.y(), -1.0, kTolerance);  // image right is robot right (-y)
  EXPECT_NEAR(right_down.z(), -1.0, kTolerance);  // image down is down
}

TEST(CameraFrames, PanAndTiltTurnTheOpticalAxis) {
  const CameraMount tilted{0.0, 0.0, 1.0, degrees_to_radians(30.0)};
  const Eigen::Vector3d axis = robot_from_camera(tilted, 0.0).linear() * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(axis.z(), -0.5, kTolerance);  // looks 30 degrees down
  const Eigen::Vector3d panned = robot_from_camera({}, kPi / 2.0).linear() * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(panned.y(), 1.0, kTolerance);  // pan +90: looks left
}

TEST(Covariance, MahalanobisAndDefiniteness) {
  Eigen::Matrix3d covariance = Eigen::Vector3d(4.0, 1.0, 0.25).asDiagonal();
  EXPECT_TRUE(is_positive_definite(covariance));
  EXPECT_NEAR(mahalanobis_squared(Eigen::Vector3d(2.0, 1.0, 0.5), covariance), 3.0, kTolerance);
  Eigen::Matrix3d singular = Eigen::Matrix3d::Zero();
  singular(0, 0) = 1.0;
  EXPECT_FALSE(is_positive_definite(singular));
  EXPECT_TRUE(std::isinf(mahalanobis_squared(Eigen::Vector3d::Ones(), singular)));
  Eigen::Matrix3d with_nan = covariance;
  with_nan(1, 1) = std::nan("");
  EXPECT_FALSE(is_positive_definite(with_nan));
}

TEST(Covariance, RotationPreservesMahalanobisDistance) {
  Eigen::Matrix3d covariance;
  covariance << 2.0, 0.3, 0.1, 0.3, 1.0, 0.2, 0.1, 0.2, 0.5;
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d delta(0.4, -0.7, 1.1);
  EXPECT_NEAR(mahalanobis_squared(rotation * delta, rotate_covariance(rotation, covariance)),
              mahalanobis_squared(delta, covariance), 1e-10);
  Eigen::Matrix3d lopsided = covariance;
  lopsided(0, 1) += 0.2;
  const Eigen::Matrix3d symmetric = symmetrize(lopsided);
  EXPECT_DOUBLE_EQ(symmetric(0, 1), symmetric(1, 0));
  EXPECT_DOUBLE_EQ(symmetric(0, 1), 0.4);
}

}  // namespace
}  // namespace stereoscout::core
