#pragma once
// Config section `dataset`: recorded stereo datasets without wheel odometry (KITTI odometry,
// platform/host_dataset). Their odometry is made from the ground-truth motion between frames
// with the same kind of noise the simulator gives its wheels (config/sim.hpp), so the noise
// keys mean exactly what sim.tile and sim.carpet mean (the struct is sim's OdometryNoiseConfig;
// the help texts speak of a dataset instead of a floor type).
#include "stereoscout/core/config.hpp"
#include "stereoscout/core/config/sim.hpp"

namespace stereoscout::core {

struct DatasetConfig {
  // A car's odometry on asphalt, on the order of the simulator's carpet: 2 cm/sqrt(m) random
  // distance error, 1 % scale error and 0.2 deg/m heading drift give about a metre and a
  // few degrees of error over the 60 m of the shared KITTI excerpt.
  OdometryNoiseConfig odometry{0.02, 0.02, 0.005, 0.01, 0.2};
  // KITTI's cameras are 1.65 m above the road (Geiger et al., IJRR 2013, Fig. 3).
  double camera_height_m = 1.65;
};

inline void describe(ConfigVisitor& v, DatasetConfig& c) {
  v.begin_section("dataset", "Recorded stereo datasets without wheel odometry (KITTI, platform/host_dataset): odometry is the ground-truth motion between frames with noise added, seeded by the run's seed.");
  v.number("camera_height_m", c.camera_height_m, {0.0, 10.0, "m", "Height of the dataset's reference camera above the ground (KITTI: 1.65 m); the camera is the robot's origin, looking forward, no tilt."});
  OdometryNoiseConfig& n = c.odometry;
  v.begin_section("odometry", "Noise of the odometry made from the ground truth; the keys mean what they mean in sim.tile (random walk in distance and heading, systematic scale error and heading drift).");
  v.number("translation_sigma_m_per_sqrt_m", n.translation_sigma_m_per_sqrt_m, {0.0, 1.0, "m/sqrt(m)", "Random distance error: standard deviation after 1 m travelled (grows with sqrt of distance)."});
  v.number("rotation_sigma_rad_per_sqrt_rad", n.rotation_sigma_rad_per_sqrt_rad, {0.0, 1.0, "rad/sqrt(rad)", "Random heading error per turned angle: standard deviation after 1 rad turned."});
  v.number("rotation_sigma_rad_per_sqrt_m", n.rotation_sigma_rad_per_sqrt_m, {0.0, 1.0, "rad/sqrt(m)", "Random heading error per distance travelled: standard deviation after 1 m."});
  v.number("scale_error", n.scale_error, {-0.5, 0.5, "", "Systematic distance error: odometry reports (1 + scale_error) times the distance travelled."});
  v.number("drift_deg_per_m", n.drift_deg_per_m, {-45.0, 45.0, "deg/m", "Systematic heading drift per metre travelled."});
  v.end_section();
  v.end_section();
}

}  // namespace stereoscout::core
