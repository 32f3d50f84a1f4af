#pragma once
// Config section `filter`: the Rao-Blackwellised particle filter (paper sections III, IV).
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

struct FilterConfig {
  int particles = 1000;
  int particle_capacity = 5000;
  double resample_ess_fraction = 0.5;
  double association_gate_chi2 = 11.345;
  double min_log_likelihood = -10.0;
  double motion_noise_translation_per_m = 0.05;
  double motion_noise_rotation_per_rad = 0.05;
  double motion_noise_rotation_per_m = 0.02;
  double motion_noise_translation_per_rad = 0.01;
};

inline void describe(ConfigVisitor& v, FilterConfig& c) {
  v.begin_section("filter", "Particle filter over landmark maps (paper III, IV).");
  v.integer_field("particles", c.particles, {1, 1000000, "", "Particles in the filter (paper 1000, up to 2000)."});
  v.integer_field("particle_capacity", c.particle_capacity, {1, 1000000, "", "Size of the particle pool fixed at start-up."});
  v.number("resample_ess_fraction", c.resample_ess_fraction, {0.0, 1.0, "", "Resample when the effective sample size falls below this fraction of the particles."});
  v.number("association_gate_chi2", c.association_gate_chi2, {0.1, 1000.0, "", "Mahalanobis gate for data association (3 DOF, 99%: 11.345)."});
  v.number("min_log_likelihood", c.min_log_likelihood, {-1000.0, 0.0, "", "Floor on one observation's log-likelihood, so one outlier cannot kill a particle."});
  v.number("motion_noise_translation_per_m", c.motion_noise_translation_per_m, {0.0, 2.0, "m/m", "Standard deviation of translation noise per metre driven."});
  v.number("motion_noise_rotation_per_rad", c.motion_noise_rotation_per_rad, {0.0, 2.0, "rad/rad", "Standard deviation of rotation noise per radian turned."});
  v.number("motion_noise_rotation_per_m", c.motion_noise_rotation_per_m, {0.0, 2.0, "rad/m", "Standard deviation of rotation noise per metre driven."});
  v.number("motion_noise_translation_per_rad", c.motion_noise_translation_per_rad, {0.0, 2.0, "m/rad", "Standard deviation of translation noise per radian turned."});
  v.require(c.particles <= c.particle_capacity, "particles", "must not exceed particle_capacity");
  v.end_section();
}

}  // namespace stereoscout::core
