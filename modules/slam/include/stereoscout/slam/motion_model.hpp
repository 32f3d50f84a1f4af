#pragma once
// The proposal distribution: the odometry motion model (paper eq. 5-6, q = p(s_t | s_t-1, u_t)).
// The odometry's motion between two updates is perturbed by zero-mean Gaussian noise whose
// standard deviation grows with the distance driven and the angle turned, and whose variance
// may also grow with them as a random walk's (config filter.motion_noise_*), then composed
// onto the particle's pose.

#include "stereoscout/core/config/filter.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/random.hpp"

namespace stereoscout::slam {

struct MotionNoise {
  double translation_per_m = 0.0;
  double rotation_per_rad = 0.0;
  double rotation_per_m = 0.0;
  double translation_per_rad = 0.0;
  // Random-walk terms: variance per metre or radian, as standard deviation per square root.
  double translation_per_sqrt_m = 0.0;
  double rotation_per_sqrt_rad = 0.0;
  double rotation_per_sqrt_m = 0.0;
};

MotionNoise motion_noise_from_config(const core::FilterConfig& config);

// A sample of the true motion given the odometry's `motion` (in the robot frame at the
// previous update). Draws exactly three Gaussians from `stream`.
core::Pose2 sample_motion(const core::Pose2& motion, const MotionNoise& noise, core::RandomStream& stream);

}  // namespace stereoscout::slam
