#include "stereoscout/core/geometry.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

namespace stereoscout::core {

double wrap_centred(double angle, double period) { return angle - period * std::floor(angle / period + 0.5); }

double principal_axis_angle(double sxx, double sxy, double syy) { return 0.5 * std::atan2(2.0 * sxy, sxx - syy); }

double wrap_angle(double radians) {
  if (!std::isfinite(radians)) {
    return radians;
  }
  double wrapped = std::fmod(radians, 2.0 * kPi);  // (-2pi, 2pi), exact
  if (wrapped <= -kPi) {
    wrapped += 2.0 * kPi;
  } else if (wrapped > kPi) {
    wrapped -= 2.0 * kPi;
  }
  return wrapped;
}

Pose2 Pose2::compose(const Pose2& other) const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return {x + c * other.x - s * other.y, y + s * other.x + c * other.y, wrap_angle(theta + other.theta)};
}

Pose2 Pose2::inverse() const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return {-c * x - s * y, s * x - c * y, wrap_angle(-theta)};
}

Pose2 Pose2::between(const Pose2& to) const { return inverse().compose(to); }

Eigen::Vector2d Pose2::transform_point(const Eigen::Vector2d& point) const {
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  return {x + c * point.x() - s * point.y(), y + s * point.x() + c * point.y()};
}

Eigen::Isometry3d Pose2::to_isometry3() const {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  transform.translation() = Eigen::Vector3d(x, y, 0.0);
  return transform;
}

Eigen::Matrix3d body_from_optical() {
  Eigen::Matrix3d rotation;
  // Columns: the optical x (right), y (down), z (forward) axes written in body coordinates.
  rotation << 0.0, 0.0, 1.0,  //
      -1.0, 0.0, 0.0,         //
      0.0, -1.0, 0.0;
  return rotation;
}

Eigen::Isometry3d robot_from_camera(const CameraMount& mount, double pan_rad) {
  // Tilt turns the camera about its body-aligned y axis (positive: nose down), pan about z.
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(mount.tilt_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d pan = Eigen::AngleAxisd(pan_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = pan * tilt * body_from_optical();
  transform.translation() = Eigen::Vector3d(mount.x_m, mount.y_m, mount.height_m);
  return transform;
}

Eigen::Matrix3d stereo_triangulation_jacobian(double focal_px, double baseline_m, double u_px, double v_px,
                                              double disparity_px) {
  const double b_over_d = baseline_m / disparity_px;
  const double b_over_d2 = b_over_d / disparity_px;
  Eigen::Matrix3d jacobian;
  jacobian << b_over_d, 0.0, -u_px * b_over_d2,  //
      0.0, b_over_d, -v_px * b_over_d2,          //
      0.0, 0.0, -focal_px * b_over_d2;
  return jacobian;
}

Eigen::Matrix3d symmetrize(const Eigen::Matrix3d& covariance) {
  return 0.5 * (covariance + covariance.transpose());
}

bool is_positive_definite(const Eigen::Matrix3d& covariance) {
  if (!covariance.allFinite()) {
    return false;
  }
  const Eigen::LLT<Eigen::Matrix3d> cholesky(covariance);
  return cholesky.info() == Eigen::Success;
}

double mahalanobis_squared(const Eigen::Vector3d& delta, const Eigen::Matrix3d& covariance) {
  const Eigen::LLT<Eigen::Matrix3d> cholesky(covariance);
  if (cholesky.info() != Eigen::Success) {
    return std::numeric_limits<double>::infinity();
  }
  const Eigen::Vector3d whitened = cholesky.matrixL().solve(delta);
  return whitened.squaredNorm();
}

Eigen::Matrix3d rotate_covariance(const Eigen::Matrix3d& rotation, const Eigen::Matrix3d& covariance) {
  return rotation * covariance * rotation.transpose();
}

}  // namespace stereoscout::core
