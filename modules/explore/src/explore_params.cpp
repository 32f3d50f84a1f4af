#include "stereoscout/explore/grid_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::explore {

ExploreParams ExploreParams::from_config(const core::ExploreConfig& explore, const core::RobotConfig& robot,
                                         const core::CameraConfig& camera, const core::VisionConfig& vision,
                                         int max_width, int max_height) {
  ExploreParams params;
  params.explore = explore;
  params.robot_radius_m = robot.radius_m;
  params.max_speed_mps = robot.max_speed_mps;
  params.max_turn_rate_rad_s = core::degrees_to_radians(robot.max_turn_rate_deg_s);
  params.has_pan_unit = camera.has_pan_unit;
  params.camera_forward_m = camera.mount_x_m;
  params.camera_baseline_m = camera.baseline_m;
  params.camera_half_fov_rad = std::atan(0.5 * camera.width_px / camera.focal_px);
  // The lowest image row looks down by half the vertical field of view plus the tilt.
  const double lowest_ray_rad =
      std::atan(0.5 * camera.height_px / camera.focal_px) + core::degrees_to_radians(camera.mount_tilt_deg);
  constexpr double kStraightDownRad = 0.5 * core::kPi;
  if (lowest_ray_rad <= 0.0) {
    params.camera_near_m = std::numeric_limits<double>::infinity();  // tilted up: it never sees the floor
  } else {
    params.camera_near_m = lowest_ray_rad >= kStraightDownRad ? 0.0 : camera.mount_height_m / std::tan(lowest_ray_rad);
  }
  const int largest_disparity_px = std::max(1, vision.dense_num_disparities - 1);
  params.camera_measurable_m = camera.focal_px * camera.baseline_m / largest_disparity_px;
  params.max_width = max_width;
  params.max_height = max_height;
  return params;
}

}  // namespace stereoscout::explore
