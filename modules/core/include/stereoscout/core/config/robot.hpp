#pragma once
// Config section `robot`: the platform's size and limits (paper section VII, Powerbot).
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

struct RobotConfig {
  double max_speed_mps = 0.12;
  double max_turn_rate_deg_s = 8.0;
  double radius_m = 0.35;
  double height_m = 1.2;
  double odometry_rate_hz = 5.4;
  double update_min_translation_m = 0.07;
  double update_min_rotation_deg = 1.0;
};

inline void describe(ConfigVisitor& v, RobotConfig& c) {
  v.begin_section("robot", "The robot's size and motion limits (paper: Powerbot, section VII).");
  v.number("max_speed_mps", c.max_speed_mps, {0.01, 2.0, "m/s", "Top translational speed the drive is commanded (paper 0.12)."});
  v.number("max_turn_rate_deg_s", c.max_turn_rate_deg_s, {0.5, 180.0, "deg/s", "Top turn rate (paper 8)."});
  v.number("radius_m", c.radius_m, {0.05, 2.0, "m", "Radius of the circle that covers the robot's footprint; the grid is inflated by it."});
  v.number("height_m", c.height_m, {0.1, 3.0, "m", "Height of the robot; obstacles above it do not block (2.5D scan)."});
  v.number("odometry_rate_hz", c.odometry_rate_hz, {0.5, 200.0, "Hz", "Rate of wheel odometry readings (paper about 5.4)."});
  v.number("update_min_translation_m", c.update_min_translation_m, {0.0, 5.0, "m", "An observation update runs once the robot moved farther than this (paper 0.07)."});
  v.number("update_min_rotation_deg", c.update_min_rotation_deg, {0.0, 180.0, "deg", "... or turned more than this (paper 1)."});
  v.end_section();
}

}  // namespace stereoscout::core
