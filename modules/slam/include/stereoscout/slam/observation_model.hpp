#pragma once
// The observation model shared by every sensor: a landmark observation is a 3D point with a
// covariance in some sensor frame. Stereo gives one directly (paper eq. 3-4: C = J S J^T);
// a range/bearing sensor on the floor plane (MRCLAM) gives one through the same Jacobian
// approach (range_bearing_observation). Landmark estimates live in the map frame, so the
// observation is moved into it with the particle's pose; the rotation is exact (the pose is a
// sample, not an estimate), which makes the map-frame EKF below identical to the textbook one
// with H = R^T.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "stereoscout/core/config/camera.hpp"
#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/slam/landmark_map.hpp"

namespace stereoscout::slam {

// Where config section `camera` puts the camera on the robot (the filter's stereo update turns
// it by the pan angle of each frame).
core::CameraMount camera_mount_from_config(const core::CameraConfig& camera);

// An observation moved into the robot frame (done once per update, for all particles).
struct RobotFrameObservation {
  std::uint32_t landmark_id = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  SymmetricMatrix3 covariance;
  Eigen::Vector3d measured_pixel = Eigen::Vector3d::Zero();  // (u, v, d) with a StereoModel
};

// The same observation in the map frame of one particle.
struct MapFrameObservation {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  SymmetricMatrix3 covariance;
};

RobotFrameObservation to_robot_frame(const core::LandmarkObservation& observation,
                                     const Eigen::Isometry3d& robot_from_sensor);
// A particle's pose as a 3D transform (rotation about z), made once per particle and update.
struct PlanarTransform {
  explicit PlanarTransform(const core::Pose2& pose);
  double cosine;
  double sine;
  Eigen::Vector3d translation;
};

// Moves the point and rotates the covariance (R C R^T) about z; the closed form of the
// planar rotation touches only the entries it changes.
MapFrameObservation to_map_frame(const RobotFrameObservation& observation, const PlanarTransform& map_from_robot);

// The stereo camera as a measurement model: a point p of the camera frame is seen at
// (u, v, d) = (f x / z + cx, f y / z + cy, f B / z) in the right image, with independent
// noise sigma_u, sigma_v, sigma_d (paper eq. 3 inverted; the noise of eq. 4).
struct StereoModel {
  double focal_px = 0.0;
  double principal_x_px = 0.0;
  double principal_y_px = 0.0;
  double baseline_m = 0.0;
  double sigma_u_px = 0.0;
  double sigma_v_px = 0.0;
  double sigma_d_px = 0.0;
};
StereoModel stereo_model_from_config(const core::CameraConfig& camera, const core::VisionConfig& vision);
Eigen::Vector3d project(const StereoModel& stereo, const Eigen::Vector3d& point_camera);

// Where one particle puts the sensor: its rotation and origin in the map frame.
struct MapFromSensor {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};
MapFromSensor map_from_sensor(const PlanarTransform& map_from_robot, const Eigen::Isometry3d& robot_from_sensor);

// The stereo observation linearised at the estimate (the textbook EKF, filter.linearise_at_estimate):
// with p the estimate's mean in the camera frame and J the Jacobian of eq. 3 at project(p),
// the innovation J (measured - project(p)) with covariance J S J^T, both moved into the map
// frame and returned as an observation at mean + innovation. An EKF in (u, v, d) with
// H = dproject/dp is the same update, because J is the inverse of dproject/dp: the Mahalanobis
// distance and the gain are unchanged by the invertible change of coordinates. The
// covariance is the one at the estimate, not at the noisy measurement, so a sighting measured
// too near no longer counts more than one measured too far. False when the estimate is not in
// front of the camera (then the caller keeps the observation at the measurement).
bool at_estimate(const StereoModel& stereo, const Eigen::Vector3d& measured_pixel, const Eigen::Vector3d& estimate_mean,
                 const MapFromSensor& sensor, MapFrameObservation& linearised);

// A range/bearing measurement on the floor plane turned into a point observation in the
// sensor frame (x forward, y left, z up): p = (r cos b, r sin b, 0), covariance J S J^T with
// J the Jacobian of p in (r, b) and S = diag(range_sigma^2, bearing_sigma^2), plus
// height_sigma^2 on z so the 3x3 covariance is positive definite (landmarks at z = 0).
core::LandmarkObservation range_bearing_observation(std::uint32_t landmark_id, double range_m, double bearing_rad,
                                                    double range_sigma_m, double bearing_sigma_rad,
                                                    double height_sigma_m);

// The innovation of an observation against one estimate: delta = z - mean, the inverse of
// S = P + C (estimate plus measurement) and the squared Mahalanobis distance
// delta^T S^-1 delta, +infinity if S is not positive definite. The gate uses the distance;
// the EKF update of the chosen estimate reuses the inverse instead of inverting S again.
struct Innovation {
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();
  SymmetricMatrix3 inverse_covariance;
  double distance_squared = 0.0;
};
Innovation innovation(const LandmarkEstimate& estimate, const MapFrameObservation& observation);

double association_distance_squared(const LandmarkEstimate& estimate, const MapFrameObservation& observation);

// EKF update of an estimate by an observation of it (paper III: "updated using the EKF"),
// given the innovation of that observation against this estimate (finite distance).
void ekf_update(LandmarkEstimate& estimate, const Innovation& innovation);
void ekf_update(LandmarkEstimate& estimate, const MapFrameObservation& observation);

// A valid observation has a finite point and a positive definite covariance.
bool is_valid_observation(const core::LandmarkObservation& observation);

}  // namespace stereoscout::slam
