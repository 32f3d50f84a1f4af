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
  moved.covariance = core::rotate_covariance(robot_from_sensor.linear(), observation.covariance);
  return moved;
}

PlanarTransform::PlanarTransform(const core::Pose2& pose) : translation(pose.x, pose.y, 0.0) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  rotation << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
}

MapFrameObservation to_map_frame(const RobotFrameObservation& observation, const PlanarTransform& map_from_robot) {
  MapFrameObservation moved;
  moved.point = map_from_robot.rotation * observation.point + map_from_robot.translation;
  moved.covariance = core::symmetrize(map_from_robot.rotation * observation.covariance *
                                      map_from_robot.rotation.transpose());
  return moved;
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

double association_distance_squared(const LandmarkEstimate& estimate, const MapFrameObservation& observation) {
  const Eigen::Matrix3d innovation_covariance = estimate.covariance + observation.covariance;
  return core::mahalanobis_squared(observation.point - estimate.mean, innovation_covariance);
}

void ekf_update(LandmarkEstimate& estimate, const MapFrameObservation& observation) {
  // With h(m) = R^T (m - t) and H = R^T, the gain P H^T (H P H^T + Q)^-1 moved into the map
  // frame is P (P + R Q R^T)^-1: the same update written where the estimate lives.
  const Eigen::Matrix3d innovation_covariance = estimate.covariance + observation.covariance;
  const Eigen::Matrix3d gain = estimate.covariance * innovation_covariance.inverse();
  estimate.mean += gain * (observation.point - estimate.mean);
  estimate.covariance = core::symmetrize((Eigen::Matrix3d::Identity() - gain) * estimate.covariance);
  ++estimate.observations;
}

bool is_valid_observation(const core::LandmarkObservation& observation) {
  return observation.point_camera.allFinite() && core::is_positive_definite(observation.covariance);
}

}  // namespace stereoscout::slam
