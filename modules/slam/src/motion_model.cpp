#include "stereoscout/slam/motion_model.hpp"

#include <cmath>

namespace stereoscout::slam {

MotionNoise motion_noise_from_config(const core::FilterConfig& config) {
  MotionNoise noise;
  noise.translation_per_m = config.motion_noise_translation_per_m;
  noise.rotation_per_rad = config.motion_noise_rotation_per_rad;
  noise.rotation_per_m = config.motion_noise_rotation_per_m;
  noise.translation_per_rad = config.motion_noise_translation_per_rad;
  noise.translation_per_sqrt_m = config.motion_noise_translation_per_sqrt_m;
  noise.rotation_per_sqrt_rad = config.motion_noise_rotation_per_sqrt_rad;
  noise.rotation_per_sqrt_m = config.motion_noise_rotation_per_sqrt_m;
  return noise;
}

namespace {

// Without random-walk terms the linear sigma is returned untouched, so runs without them
// draw exactly what they drew before the terms existed.
double with_random_walk(double linear_sigma, double random_walk_variance) {
  if (random_walk_variance <= 0.0) return linear_sigma;
  return std::sqrt(linear_sigma * linear_sigma + random_walk_variance);
}

}  // namespace

core::Pose2 sample_motion(const core::Pose2& motion, const MotionNoise& noise, core::RandomStream& stream) {
  const double distance = std::sqrt(motion.x * motion.x + motion.y * motion.y);
  const double turn = std::fabs(motion.theta);
  const double translation_sigma = with_random_walk(
      noise.translation_per_m * distance + noise.translation_per_rad * turn,
      noise.translation_per_sqrt_m * noise.translation_per_sqrt_m * distance);
  const double rotation_sigma = with_random_walk(
      noise.rotation_per_rad * turn + noise.rotation_per_m * distance,
      noise.rotation_per_sqrt_rad * noise.rotation_per_sqrt_rad * turn +
          noise.rotation_per_sqrt_m * noise.rotation_per_sqrt_m * distance);
  // Draw order is fixed (x, y, theta) so a particle's sample is a pure function of its stream.
  const double noise_x = stream.gaussian(0.0, translation_sigma);
  const double noise_y = stream.gaussian(0.0, translation_sigma);
  const double noise_theta = stream.gaussian(0.0, rotation_sigma);
  return core::Pose2{motion.x + noise_x, motion.y + noise_y, core::wrap_angle(motion.theta + noise_theta)};
}

}  // namespace stereoscout::slam
