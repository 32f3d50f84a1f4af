#pragma once
// Config section `sim`: the simulated robot (platform/host_sim). The world itself comes from
// the world file named by run.world; this section holds the sensor and noise models.
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

// Wheel odometry noise on one floor type. Random parts grow with the square root of the
// distance (a random walk: variance proportional to distance or angle); systematic parts are
// a scale error of the wheel radius and a heading drift from unequal wheels.
struct OdometryNoiseConfig {
  double translation_sigma_m_per_sqrt_m = 0.0;
  double rotation_sigma_rad_per_sqrt_rad = 0.0;
  double rotation_sigma_rad_per_sqrt_m = 0.0;
  double scale_error = 0.0;
  double drift_deg_per_m = 0.0;
};

struct SimConfig {
  OdometryNoiseConfig tile{0.01, 0.02, 0.005, 0.0, 0.2};
  OdometryNoiseConfig carpet{0.03, 0.05, 0.015, -0.02, 0.8};
  double image_noise_sigma = 2.0;
  double exposure = 1.0;
  double step_s = 0.01;
  double floor_tolerance_m = 0.02;
  int odometry_queue = 64;
  int max_hits_per_column = 64;
  double near_miss_m = 0.03;
  double door_visit_reach_m = 0.15;
};

inline void describe_odometry_noise(ConfigVisitor& v, const char* floor, OdometryNoiseConfig& c) {
  v.begin_section(floor, "Odometry noise while the robot drives on this floor type.");
  v.number("translation_sigma_m_per_sqrt_m", c.translation_sigma_m_per_sqrt_m, {0.0, 1.0, "m/sqrt(m)", "Random distance error: standard deviation after 1 m driven (grows with sqrt of distance)."});
  v.number("rotation_sigma_rad_per_sqrt_rad", c.rotation_sigma_rad_per_sqrt_rad, {0.0, 1.0, "rad/sqrt(rad)", "Random heading error per turned angle: standard deviation after 1 rad turned."});
  v.number("rotation_sigma_rad_per_sqrt_m", c.rotation_sigma_rad_per_sqrt_m, {0.0, 1.0, "rad/sqrt(m)", "Random heading error per distance driven: standard deviation after 1 m."});
  v.number("scale_error", c.scale_error, {-0.5, 0.5, "", "Systematic distance error: odometry reports (1 + scale_error) times the distance driven."});
  v.number("drift_deg_per_m", c.drift_deg_per_m, {-45.0, 45.0, "deg/m", "Systematic heading drift per metre driven (unequal wheels)."});
  v.end_section();
}

inline void describe(ConfigVisitor& v, SimConfig& c) {
  v.begin_section("sim", "The simulated robot (platform/host_sim): odometry noise per floor type, image noise, exposure. The world file is run.world.");
  describe_odometry_noise(v, "tile", c.tile);
  describe_odometry_noise(v, "carpet", c.carpet);
  v.number("image_noise_sigma", c.image_noise_sigma, {0.0, 50.0, "gray levels", "Standard deviation of the additive sensor noise of each pixel."});
  v.number("exposure", c.exposure, {0.05, 20.0, "", "Exposure gain: radiance times exposure gives the gray level; bright regions (windows) saturate at 255."});
  v.number("step_s", c.step_s, {0.0005, 0.1, "s", "Longest integration step of the robot's kinematics and collision check."});
  v.number("floor_tolerance_m", c.floor_tolerance_m, {0.0, 0.5, "m", "Objects entirely below this height (thresholds, cables) do not block the robot and are free in the ground-truth map."});
  v.integer_field("odometry_queue", c.odometry_queue, {1, 100000, "", "Odometry readings the simulator holds until read; when full the oldest is dropped and counted."});
  v.integer_field("max_hits_per_column", c.max_hits_per_column, {4, 1024, "", "Surfaces the renderer keeps per image column (nearest first); more are counted and dropped."});
  v.number("near_miss_m", c.near_miss_m, {0.0, 0.5, "m", "A near miss (report.json near_misses): the robot's disc comes within this of a static obstacle and moves 2 cm farther clear again without touching it. An evaluation figure, not a model of the robot; 0 counts none."});
  v.number("door_visit_reach_m", c.door_visit_reach_m, {0.0, 2.0, "m", "A door visit (report.json door_visits): the robot's centre comes within its radius plus this of a doorway (the gap between the jambs of a world's opening that reaches the floor) and leaves again; each keeps the least clearance of the disc from a static obstacle meanwhile, and whether the robot crossed the door's line. Contacts and near misses are the tail of that spread, a few an hour; the clearances of every visit compare runs with fewer of them. An evaluation figure, not a model of the robot; 0 counts none."});
  v.end_section();
}

}  // namespace stereoscout::core
