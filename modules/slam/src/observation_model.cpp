#include "stereoscout/slam/observation_model.hpp"

#include <cmath>
#include <limits>

namespace stereoscout::slam {

core::CameraMount camera_mount_from_config(const core::CameraConfig& camera) {
  return core::CameraMount{camera.mount_x_m, camera.mount_y_m, camera.mount_height_m,
                           core::degrees_to_radians(camera.mount_tilt_deg)};
}

RobotFrameObservation to_robot_frame(const core::LandmarkObservation& observation,
                                     const Eigen::Isometry3d& robot_from_sensor) {
  RobotFrameObservation moved;
  moved.landmark_id = observation.landmark_id;
  moved.point = robot_from_sensor * observation.point_camera;
  moved.covariance = core::symmetrize(core::rotate_covariance(robot_from_sensor.linear(), observation.covariance));
  return moved;
}

PlanarTransform::PlanarTransform(const core::Pose2& pose)
    : cosine(std::cos(pose.theta)), sine(std::sin(pose.theta)), translation(pose.x, pose.y, 0.0) {}

MapFrameObservation to_map_frame(const RobotFrameObservation& observation, const PlanarTransform& map_from_robot) {
  const double c = map_from_robot.cosine;
  const double s = map_from_robot.sine;
  const Eigen::Vector3d& p = observation.point;
  const SymmetricMatrix3& q = observation.covariance;
  MapFrameObservation moved;
  moved.point = Eigen::Vector3d(c * p.x() - s * p.y(), s * p.x() + c * p.y(), p.z()) + map_from_robot.translation;
  // R Q R^T with R = [c -s 0; s c 0; 0 0 1]: first B = R2 Q2 on the x-y block, then B R2^T.
  const double b00 = c * q.xx - s * q.xy;
  const double b01 = c * q.xy - s * q.yy;
  const double b10 = s * q.xx + c * q.xy;
  const double b11 = s * q.xy + c * q.yy;
  moved.covariance = SymmetricMatrix3(b00 * c - b01 * s, b00 * s + b01 * c, c * q.xz - s * q.yz,
                                      b10 * s + b11 * c, s * q.xz + c * q.yz, q.zz);
  return moved;
}

StereoModel stereo_model_from_config(const core::CameraConfig& camera, const core::VisionConfig& vision) {
  return StereoModel{camera.focal_px,  camera.principal_x_px, camera.principal_y_px, camera.baseline_m,
                     vision.sigma_u_px, vision.sigma_v_px,     vision.sigma_d_px};
}

Eigen::Vector3d project(const StereoModel& stereo, const Eigen::Vector3d& point_camera) {
  const double inverse_depth = 1.0 / point_camera.z();
  return {stereo.focal_px * point_camera.x() * inverse_depth + stereo.principal_x_px,
          stereo.focal_px * point_camera.y() * inverse_depth + stereo.principal_y_px,
          stereo.focal_px * stereo.baseline_m * inverse_depth};
}

MapFromSensor map_from_sensor(const PlanarTransform& map_from_robot, const Eigen::Isometry3d& robot_from_sensor) {
  Eigen::Matrix3d turn;
  turn << map_from_robot.cosine, -map_from_robot.sine, 0.0, map_from_robot.sine, map_from_robot.cosine, 0.0, 0.0, 0.0,
      1.0;
  MapFromSensor sensor;
  sensor.rotation = turn * robot_from_sensor.linear();
  sensor.translation = turn * robot_from_sensor.translation() + map_from_robot.translation;
  return sensor;
}

bool at_estimate(const StereoModel& stereo, const Eigen::Vector3d& measured_pixel, const Eigen::Vector3d& estimate_mean,
                 const MapFromSensor& sensor, MapFrameObservation& linearised) {
  const Eigen::Vector3d p = sensor.rotation.transpose() * (estimate_mean - sensor.translation);
  if (!(p.z() > 0.0)) return false;
  const Eigen::Vector3d predicted = project(stereo, p);
  const Eigen::Matrix3d map_jacobian =
      sensor.rotation * core::stereo_triangulation_jacobian(stereo.focal_px, stereo.baseline_m,
                                                            predicted.x() - stereo.principal_x_px,
                                                            predicted.y() - stereo.principal_y_px, predicted.z());
  const Eigen::Vector3d variances(stereo.sigma_u_px * stereo.sigma_u_px, stereo.sigma_v_px * stereo.sigma_v_px,
                                  stereo.sigma_d_px * stereo.sigma_d_px);
  linearised.point = estimate_mean + map_jacobian * (measured_pixel - predicted);
  linearised.covariance = core::symmetrize(map_jacobian * variances.asDiagonal() * map_jacobian.transpose());
  return true;
}

core::LandmarkObservation range_bearing_observation(std::uint32_t landmark_id, double range_m, double bearing_rad,
                                                    double range_sigma_m, double bearing_sigma_rad,
                                                    double height_sigma_m) {
  const double c = std::cos(bearing_rad);
  const double s = std::sin(bearing_rad);
  Eigen::Matrix<double, 3, 2> jacobian;
  jacobian << c, -range_m * s, s, range_m * c, 0.0, 0.0;
  const Eigen::Matrix2d measurement_covariance =
      Eigen::Vector2d(range_sigma_m * range_sigma_m, bearing_sigma_rad * bearing_sigma_rad).asDiagonal();
  core::LandmarkObservation observation;
  observation.landmark_id = landmark_id;
  observation.point_camera = Eigen::Vector3d(range_m * c, range_m * s, 0.0);
  observation.covariance = core::symmetrize(jacobian * measurement_covariance * jacobian.transpose());
  observation.covariance(2, 2) = height_sigma_m * height_sigma_m;
  return observation;
}

Innovation innovation(const LandmarkEstimate& estimate, const MapFrameObservation& observation) {
  const SymmetricMatrix3& p = estimate.covariance;
  const SymmetricMatrix3& q = observation.covariance;
  const double a = p.xx + q.xx, b = p.xy + q.xy, c = p.xz + q.xz;  // S = P + C
  const double d = p.yy + q.yy, e = p.yz + q.yz, f = p.zz + q.zz;
  // Cofactors of S; S is positive definite iff its leading minors a, ad - b^2, det are.
  const double cofactor_xx = d * f - e * e;
  const double cofactor_xy = c * e - b * f;
  const double cofactor_xz = b * e - c * d;
  const double minor2 = a * d - b * b;
  const double determinant = a * cofactor_xx + b * cofactor_xy + c * cofactor_xz;
  Innovation result;
  result.delta = observation.point - estimate.mean;
  if (!(a > 0.0 && minor2 > 0.0 && determinant > 0.0)) {
    result.distance_squared = std::numeric_limits<double>::infinity();
    return result;
  }
  const double scale = 1.0 / determinant;
  SymmetricMatrix3& w = result.inverse_covariance;
  w = SymmetricMatrix3(cofactor_xx * scale, cofactor_xy * scale, cofactor_xz * scale, (a * f - c * c) * scale,
                       (b * c - a * e) * scale, minor2 * scale);
  const double x = result.delta.x(), y = result.delta.y(), z = result.delta.z();
  result.distance_squared = w.xx * x * x + w.yy * y * y + w.zz * z * z +
                            2.0 * (w.xy * x * y + w.xz * x * z + w.yz * y * z);
  return result;
}

double association_distance_squared(const LandmarkEstimate& estimate, const MapFrameObservation& observation) {
  return innovation(estimate, observation).distance_squared;
}

void ekf_update(LandmarkEstimate& estimate, const Innovation& innovation) {
  // With h(m) = R^T (m - t) and H = R^T, the gain P H^T (H P H^T + Q)^-1 moved into the map
  // frame is K = P (P + R Q R^T)^-1 = P S^-1: the same update written where the estimate
  // lives. The new covariance P - K P is symmetric; only its upper triangle is computed.
  // Plain 3x3 arrays: this runs once per particle and observation, and the small Eigen
  // products were not inlined.
  const SymmetricMatrix3& c = estimate.covariance;
  const SymmetricMatrix3& w = innovation.inverse_covariance;
  const double p[3][3] = {{c.xx, c.xy, c.xz}, {c.xy, c.yy, c.yz}, {c.xz, c.yz, c.zz}};
  const double s[3][3] = {{w.xx, w.xy, w.xz}, {w.xy, w.yy, w.yz}, {w.xz, w.yz, w.zz}};
  const double delta[3] = {innovation.delta.x(), innovation.delta.y(), innovation.delta.z()};
  double gain[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      gain[i][j] = p[i][0] * s[0][j] + p[i][1] * s[1][j] + p[i][2] * s[2][j];
    }
  }
  for (int i = 0; i < 3; ++i) {
    estimate.mean[i] += gain[i][0] * delta[0] + gain[i][1] * delta[1] + gain[i][2] * delta[2];
  }
  const auto reduced = [&](int i, int j) {
    return p[i][j] - (gain[i][0] * p[0][j] + gain[i][1] * p[1][j] + gain[i][2] * p[2][j]);
  };
  estimate.covariance = SymmetricMatrix3(reduced(0, 0), reduced(0, 1), reduced(0, 2), reduced(1, 1), reduced(1, 2),
                                         reduced(2, 2));
  ++estimate.observations;
}

void ekf_update(LandmarkEstimate& estimate, const MapFrameObservation& observation) {
  ekf_update(estimate, innovation(estimate, observation));
}

bool is_valid_observation(const core::LandmarkObservation& observation) {
  return observation.point_camera.allFinite() && core::is_positive_definite(observation.covariance);
}

}  // namespace stereoscout::slam
