#include "stereoscout/core/odometry_noise.hpp"

#include <cmath>

namespace stereoscout::core {

Pose2 corrupt_motion(const Pose2& delta, const OdometryNoiseConfig& noise, RandomStream& random) {
  const double distance = std::hypot(delta.x, delta.y);
  const double turned = std::abs(delta.theta);
  const double distance_sigma = noise.translation_sigma_m_per_sqrt_m * std::sqrt(distance);
  const double rotation_sigma = std::sqrt(noise.rotation_sigma_rad_per_sqrt_rad * noise.rotation_sigma_rad_per_sqrt_rad * turned +
                                          noise.rotation_sigma_rad_per_sqrt_m * noise.rotation_sigma_rad_per_sqrt_m * distance);
  const double measured_distance = distance * (1.0 + noise.scale_error) + distance_sigma * random.gaussian();
  const double measured_rotation =
      delta.theta + degrees_to_radians(noise.drift_deg_per_m) * distance + rotation_sigma * random.gaussian();
  const double scale = distance > 0.0 ? measured_distance / distance : 0.0;
  return Pose2{delta.x * scale, delta.y * scale, wrap_angle(measured_rotation)};
}

}  // namespace stereoscout::core
