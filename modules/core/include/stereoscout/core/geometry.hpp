#pragma once
// Geometry shared by every module.
//
// Frames (docs/architecture.md, "Frames"):
//   map / odom / robot (body): x forward, y left, z up; poses in SE(2) on the floor plane.
//   camera (optical): x right, y down, z forward, origin at the right camera's centre, as in
//   the stereo equations of the paper (eq. 3). The camera sits on the robot at a mount
//   offset and may turn on a pan unit about the robot's z axis.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace stereoscout::core {

inline constexpr double kPi = 3.14159265358979323846;

// Wraps an angle to (-pi, pi].
double wrap_angle(double radians);
// Brings `angle` into [-period/2, period/2): with period pi, the turn between two lines.
double wrap_centred(double angle, double period);
// The direction (radians, in [-pi/2, pi/2]) of the principal axis of 2-D points whose second
// moments about their mean are sxx, sxy, syy (any common scale): the total-least-squares line.
double principal_axis_angle(double sxx, double sxy, double syy);
constexpr double degrees_to_radians(double degrees) { return degrees * (kPi / 180.0); }
constexpr double radians_to_degrees(double radians) { return radians * (180.0 / kPi); }

// A robot pose (or a motion) in SE(2).
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;  // radians, kept in (-pi, pi] by every operation below

  // this * other: `other` expressed in this pose's frame, moved into the outer frame.
  Pose2 compose(const Pose2& other) const;
  Pose2 inverse() const;
  // The motion from this pose to `to`, expressed in this pose's frame: inverse() * to.
  Pose2 between(const Pose2& to) const;
  Eigen::Vector2d transform_point(const Eigen::Vector2d& point) const;
  Eigen::Vector2d translation() const { return {x, y}; }
  // The same pose as a 3D rigid transform (rotation about z, z = 0).
  Eigen::Isometry3d to_isometry3() const;
};

// Where the camera sits on the robot (config camera.mount_*).
struct CameraMount {
  double x_m = 0.0;       // forward of the robot's centre
  double y_m = 0.0;       // left of the robot's centre
  double height_m = 1.0;  // above the floor
  double tilt_rad = 0.0;  // positive looks down
};

// Rotation from the optical frame (x right, y down, z forward) to a body-aligned frame
// (x forward, y left, z up).
Eigen::Matrix3d body_from_optical();

// Transform taking points in the camera's optical frame to the robot frame, for a camera on
// `mount` turned by `pan_rad` about the robot's z axis (counter-clockwise positive).
Eigen::Isometry3d robot_from_camera(const CameraMount& mount, double pan_rad);

// The Jacobian of stereo triangulation (x, y, z) = (u B / d, v B / d, f B / d) with respect to
// (u, v, d), u and v measured from the principal point (paper eq. 4): a stereo point's
// covariance is J diag(sigma_u^2, sigma_v^2, sigma_d^2) J^T.
Eigen::Matrix3d stereo_triangulation_jacobian(double focal_px, double baseline_m, double u_px, double v_px,
                                              double disparity_px);

// Covariance helpers.
Eigen::Matrix3d symmetrize(const Eigen::Matrix3d& covariance);
bool is_positive_definite(const Eigen::Matrix3d& covariance);
// Squared Mahalanobis distance of `delta` under `covariance`; +infinity when the covariance
// is not positive definite.
double mahalanobis_squared(const Eigen::Vector3d& delta, const Eigen::Matrix3d& covariance);
// Covariance of R x for x with covariance C: R C R^T.
Eigen::Matrix3d rotate_covariance(const Eigen::Matrix3d& rotation, const Eigen::Matrix3d& covariance);

}  // namespace stereoscout::core
