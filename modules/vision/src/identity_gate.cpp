#include "stereoscout/vision/identity_gate.hpp"

#include <cmath>

namespace stereoscout::vision {

IdentityGateParams identity_gate_params_from_config(const core::VisionConfig& vision, const core::FilterConfig& filter) {
  IdentityGateParams params;
  params.identities = static_cast<std::size_t>(vision.index_capacity);
  params.instances = static_cast<std::size_t>(vision.identity_gate_instances);
  params.instances_per_identity = static_cast<std::size_t>(vision.identity_gate_instances_per_identity);
  params.gate_chi2 = filter.association_gate_chi2;
  params.translation_per_m = filter.motion_noise_translation_per_m;
  params.translation_per_rad = filter.motion_noise_translation_per_rad;
  params.rotation_per_m = filter.motion_noise_rotation_per_m;
  params.rotation_per_rad = filter.motion_noise_rotation_per_rad;
  return params;
}

std::size_t landmark_id_capacity(const core::VisionConfig& vision) {
  return static_cast<std::size_t>(vision.identity_gate ? vision.identity_gate_instances : vision.index_capacity);
}

IdentityGate::IdentityGate(const IdentityGateParams& params)
    : params_(params), first_instance_(params.identities, kNone), instances_(params.instances) {}

void IdentityGate::advance_odometer(const core::Pose2& odometry) {
  if (has_odometry_) {
    const core::Pose2 step = last_odometry_.between(odometry);
    odometer_m_ += step.translation().norm();
    odometer_rad_ += std::abs(step.theta);
  }
  last_odometry_ = odometry;
  has_odometry_ = true;
}

// The odometry's error since the instance's last sighting, at a point `range_m` from the robot:
// its translation error plus its heading error swung through that range (horizontal only).
double IdentityGate::drift_variance(const Instance& instance, double range_m) const {
  const double driven_m = odometer_m_ - instance.odometer_m;
  const double turned_rad = odometer_rad_ - instance.odometer_rad;
  const double translation_m = params_.translation_per_m * driven_m + params_.translation_per_rad * turned_rad;
  const double heading_rad = params_.rotation_per_m * driven_m + params_.rotation_per_rad * turned_rad;
  const double swing_m = heading_rad * range_m;
  return translation_m * translation_m + swing_m * swing_m;
}

std::uint32_t IdentityGate::nearest_instance(std::uint32_t identity, const Eigen::Vector3d& point,
                                             const Eigen::Matrix3d& covariance, double range_m,
                                             std::size_t& count) const {
  std::uint32_t best = kNone;
  double best_distance = params_.gate_chi2;
  count = 0;
  for (std::uint32_t k = first_instance_[identity - 1]; k != kNone; k = instances_[k].next) {
    ++count;
    const Instance& instance = instances_[k];
    Eigen::Matrix3d innovation = instance.covariance + covariance;
    const double drift = drift_variance(instance, range_m);
    innovation(0, 0) += drift;
    innovation(1, 1) += drift;
    const double distance = core::mahalanobis_squared(point - instance.point, innovation);
    if (distance <= best_distance) {  // ties: the later instance, the one nearer in time
      best_distance = distance;
      best = k;
    }
  }
  return best;
}

std::uint32_t IdentityGate::place(std::uint32_t identity, const Eigen::Vector3d& point,
                                  const Eigen::Matrix3d& covariance, double range_m) {
  if (identity == 0 || identity > first_instance_.size()) {
    ++stats_.dropped_unknown_identity;
    return kNone;
  }
  std::size_t count = 0;
  std::uint32_t slot = nearest_instance(identity, point, covariance, range_m, count);
  if (slot != kNone) {
    ++stats_.joined;
  } else if (count >= params_.instances_per_identity) {
    ++stats_.dropped_identity_full;
    return kNone;
  } else if (instances_.full()) {
    ++stats_.dropped_pool_full;
    return kNone;
  } else {
    slot = static_cast<std::uint32_t>(instances_.size());
    Instance* created = instances_.emplace_back();
    created->next = first_instance_[identity - 1];  // newest first
    first_instance_[identity - 1] = slot;
    ++stats_.instances_created;
    if (count > 0) ++stats_.split;
  }
  Instance& instance = instances_[slot];
  instance.point = point;
  instance.covariance = covariance;
  instance.odometer_m = odometer_m_;
  instance.odometer_rad = odometer_rad_;
  return slot;
}

void IdentityGate::apply(const core::Pose2& odometry, const Eigen::Isometry3d& odometry_from_camera,
                         core::FixedVector<core::LandmarkObservation>& observations) {
  advance_odometer(odometry);
  const Eigen::Matrix3d rotation = odometry_from_camera.linear();
  std::size_t kept = 0;
  for (std::size_t k = 0; k < observations.size(); ++k) {
    core::LandmarkObservation& observation = observations[k];
    ++stats_.observations;
    const Eigen::Vector3d point = odometry_from_camera * observation.point_camera;
    const double range_m = (point.head<2>() - odometry.translation()).norm();
    const std::uint32_t slot =
        place(observation.landmark_id, point, core::rotate_covariance(rotation, observation.covariance), range_m);
    if (slot == kNone) continue;
    observation.landmark_id = slot + 1;
    if (kept != k) observations[kept] = observation;
    ++kept;
  }
  while (observations.size() > kept) observations.pop_back();
}

}  // namespace stereoscout::vision
