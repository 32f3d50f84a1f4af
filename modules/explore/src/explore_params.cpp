#include "stereoscout/explore/grid_view.hpp"

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::explore {

ExploreParams ExploreParams::from_config(const core::ExploreConfig& explore, const core::RobotConfig& robot,
                                         const core::CameraConfig& camera, int max_width, int max_height) {
  ExploreParams params;
  params.explore = explore;
  params.robot_radius_m = robot.radius_m;
  params.max_speed_mps = robot.max_speed_mps;
  params.max_turn_rate_rad_s = core::degrees_to_radians(robot.max_turn_rate_deg_s);
  params.has_pan_unit = camera.has_pan_unit;
  params.max_width = max_width;
  params.max_height = max_height;
  return params;
}

}  // namespace stereoscout::explore
