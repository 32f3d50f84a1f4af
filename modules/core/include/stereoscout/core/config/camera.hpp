#pragma once
// Config section `camera`: the rectified stereo head and where it sits on the robot.
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

struct CameraConfig {
  int width_px = 640;
  int height_px = 480;
  double focal_px = 400.0;
  double principal_x_px = 319.5;
  double principal_y_px = 239.5;
  double baseline_m = 0.10;
  double frame_rate_hz = 15.0;
  double mount_x_m = 0.10;
  double mount_y_m = 0.0;
  double mount_height_m = 0.6;
  double mount_tilt_deg = 0.0;
  bool has_pan_unit = true;
  double pan_rate_deg_s = 30.0;
};

inline void describe(ConfigVisitor& v, CameraConfig& c) {
  v.begin_section("camera", "The rectified stereo pair (right image is the reference, as in the paper) and its mount.");
  v.integer_field("width_px", c.width_px, {16, 4096, "px", "Image width."});
  v.integer_field("height_px", c.height_px, {16, 4096, "px", "Image height."});
  v.number("focal_px", c.focal_px, {10.0, 10000.0, "px", "Focal length f of the rectified pair."});
  v.number("principal_x_px", c.principal_x_px, {0.0, 4096.0, "px", "Principal point, column."});
  v.number("principal_y_px", c.principal_y_px, {0.0, 4096.0, "px", "Principal point, row."});
  v.number("baseline_m", c.baseline_m, {0.01, 2.0, "m", "Stereo baseline B (paper's Digiclops: 0.10)."});
  v.number("frame_rate_hz", c.frame_rate_hz, {0.5, 120.0, "Hz", "Rate at which stereo pairs are captured."});
  v.number("mount_x_m", c.mount_x_m, {-2.0, 2.0, "m", "Camera position forward of the robot's centre."});
  v.number("mount_y_m", c.mount_y_m, {-2.0, 2.0, "m", "Camera position left of the robot's centre."});
  v.number("mount_height_m", c.mount_height_m, {0.05, 3.0, "m", "Height of the optical centre above the floor."});
  v.number("mount_tilt_deg", c.mount_tilt_deg, {-45.0, 60.0, "deg", "Downward tilt of the optical axis. The paper assumes 0 (image columns perpendicular to the floor)."});
  v.boolean("has_pan_unit", c.has_pan_unit, "The camera sits on a pan unit; without one the robot turns in place for a 360-degree look.");
  v.number("pan_rate_deg_s", c.pan_rate_deg_s, {1.0, 360.0, "deg/s", "Turn rate of the pan unit."});
  v.require(c.principal_x_px < c.width_px, "principal_x_px", "must lie inside the image (below width_px)");
  v.require(c.principal_y_px < c.height_px, "principal_y_px", "must lie inside the image (below height_px)");
  v.end_section();
}

}  // namespace stereoscout::core
