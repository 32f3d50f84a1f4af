#include "stereoscout/vision/identity_check.hpp"

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::vision {

IdentityCheck::IdentityCheck(std::size_t capacity, double gate_chi2, double floor_below_m)
    : gate_chi2_(gate_chi2), floor_below_m_(floor_below_m), stored_(capacity) {}

void IdentityCheck::observe(const Eigen::Isometry3d& world_from_camera, const core::LandmarkObservation* observations,
                            std::size_t count) {
  const Eigen::Matrix3d rotation = world_from_camera.linear();
  for (std::size_t k = 0; k < count; ++k) {
    const core::LandmarkObservation& observation = observations[k];
    if (observation.landmark_id == 0 || observation.landmark_id > stored_.size()) {
      ++past_capacity_;
      continue;
    }
    Stored& stored = stored_[observation.landmark_id - 1];
    const Eigen::Vector3d point_world = world_from_camera * observation.point_camera;
    const Eigen::Matrix3d covariance_world = core::rotate_covariance(rotation, observation.covariance);
    if (!stored.seen) {
      // A NaN floor height compares false: nothing is on the floor.
      stored = Stored{point_world, covariance_world, true, point_world.z() < floor_below_m_};
      ++first_sightings_;
      continue;
    }
    // Comparing in the world frame equals moving the stored estimate into the current camera
    // (a rigid motion leaves the Mahalanobis distance unchanged).
    const Eigen::Vector3d delta = point_world - stored.mean_world;
    const Eigen::Matrix3d innovation = stored.covariance_world + covariance_world;
    ++reobservations_;
    floor_reobservations_ += stored.on_floor ? 1U : 0U;
    if (core::mahalanobis_squared(delta, innovation) > gate_chi2_) continue;
    ++consistent_;
    floor_consistent_ += stored.on_floor ? 1U : 0U;
    // Kalman fusion of the consistent sighting (the filter's EKF update with H = I).
    const Eigen::Matrix3d gain = stored.covariance_world * innovation.inverse();
    stored.mean_world += gain * delta;
    stored.covariance_world = core::symmetrize((Eigen::Matrix3d::Identity() - gain) * stored.covariance_world);
  }
}

}  // namespace stereoscout::vision
