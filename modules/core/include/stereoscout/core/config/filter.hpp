#pragma once
// Config section `filter`: the Rao-Blackwellised particle filter (paper sections III, IV).
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

struct FilterConfig {
  int particles = 1000;
  int particle_capacity = 5000;
  double resample_ess_fraction = 0.5;
  // The maps of the particles resampling dropped are released on a thread of their own.
  bool background_release = true;
  double association_gate_chi2 = 11.345;
  double min_log_likelihood = -10.0;
  bool linearise_at_estimate = false;
  bool linearise_fusion = true;
  double motion_noise_translation_per_m = 0.05;
  double motion_noise_rotation_per_rad = 0.05;
  double motion_noise_rotation_per_m = 0.02;
  double motion_noise_translation_per_rad = 0.01;
  double motion_noise_translation_per_sqrt_m = 0.0;
  double motion_noise_rotation_per_sqrt_rad = 0.0;
  double motion_noise_rotation_per_sqrt_m = 0.0;
  int landmark_node_capacity = 4000000;
  int landmark_estimate_capacity = 4000000;
  int trajectory_node_capacity = 1000000;
  int estimates_per_landmark = 4;
  int max_observations_per_update = 1000;
  int export_min_observations = 4;
  double estimate_lineage_margin = 0.0;
  int independent_observations = 0;
  double manhattan_heading_sigma_deg = 0.0;
  double manhattan_gate_deg = 10.0;
  int manhattan_frame_walls = 5;
  double manhattan_wall_min_length_m = 1.0;
  double manhattan_wall_max_range_m = 3.0;
  double manhattan_wall_max_rms_m = 0.03;
  double manhattan_wall_max_gap_m = 0.15;
};

inline void describe(ConfigVisitor& v, FilterConfig& c) {
  v.begin_section("filter", "Particle filter over landmark maps (paper III, IV).");
  v.integer_field("particles", c.particles, {1, 1000000, "", "Particles in the filter (paper 1000, up to 2000)."});
  v.integer_field("particle_capacity", c.particle_capacity, {1, 1000000, "", "Size of the particle pool fixed at start-up."});
  v.number("resample_ess_fraction", c.resample_ess_fraction, {0.0, 1.0, "", "Resample when the effective sample size falls below this fraction of the particles."});
  v.boolean("background_release", c.background_release, "Release the landmark maps of the particles resampling dropped on a thread of their own, between one update and the next (the next update, and anything that reads the landmarks, waits for it), in the same order as in the update: the pools, and so every result, are as without it. Off: one thread fewer, and the update does the release itself.");
  v.number("association_gate_chi2", c.association_gate_chi2, {0.1, 1000.0, "", "Mahalanobis gate for data association (3 DOF, 99%: 11.345)."});
  v.boolean("linearise_at_estimate", c.linearise_at_estimate, "Compare a stereo observation with a landmark estimate the textbook EKF's way: its (u, v, d) against the estimate's projection, with the covariance J S J^T at the estimate rather than at the noisy measurement (the same update as an EKF in pixel coordinates). At the measurement, sightings measured too near weigh more (C grows as range^4 along the ray), landmarks are mapped short of the robots that saw them, and with exact odometry a 30 m straight drive comes out 1.5 % short (tests/unit/slam); linearised it keeps its length. Stereo only: other sensors (MRCLAM) are always compared at the measurement. Over the whole stack it kept the trajectory's scale (k along x 1.004 where the pose held) but office seeds 1-4 fell to 78.5% on the mean with 11 static contacts against 96.9% and 3 (docs/results.md, sixty-fourth session), so off: the paper's C at the measurement. Not in the paper.");
  v.boolean("linearise_fusion", c.linearise_fusion, "With linearise_at_estimate: the landmark's EKF update is linearised at the estimate too. Off: only the weights, the gate and the choice among a landmark's estimates are, and the update is the paper's, at the measurement. On a synthetic corridor (tests/unit/slam) the fusion makes the shortfall: linearised alone it gives a 30 m drive 1.0029 of its length, the weights alone 0.9820. In the whole stack it is the other way round: on office seeds 7-10 the weights alone gave k along x 0.990-1.009 (1.000 on the median), the fusion alone 0.976-0.994 as at the measurement, and the fusion linearised lost the pose on seed 7 leaving the first room. The weights alone gave 92.6% on the mean against the default's 91.8%, but 5 static contacts against 4, and seeds 7 and 9 0.5 m off at the building's east end; lab seeds 1 and 2 kept k 0.980 and 0.992 with twice the default's ATE (docs/results.md, seventy-sixth session), so linearise_at_estimate stays off. On: the sixty-fourth session's form, both linearised.");
  v.number("min_log_likelihood", c.min_log_likelihood, {-1000.0, 0.0, "", "Floor on one observation's log-likelihood, so one outlier cannot kill a particle. At the gate's -chi2/2 (-5.6725) an observation outside the gate would weigh every particle alike: office seed 1 kept its pose, but the office's coverage fell and MRCLAM robot 1 lost its map on two seeds of three, whose identities are right and whose observations outside the gate say the pose is wrong (docs/results.md), so -10."});
  v.number("motion_noise_translation_per_m", c.motion_noise_translation_per_m, {0.0, 2.0, "m/m", "Standard deviation of translation noise per metre driven."});
  v.number("motion_noise_rotation_per_rad", c.motion_noise_rotation_per_rad, {0.0, 2.0, "rad/rad", "Standard deviation of rotation noise per radian turned."});
  v.number("motion_noise_rotation_per_m", c.motion_noise_rotation_per_m, {0.0, 2.0, "rad/m", "Standard deviation of rotation noise per metre driven."});
  v.number("motion_noise_translation_per_rad", c.motion_noise_translation_per_rad, {0.0, 2.0, "m/rad", "Standard deviation of translation noise per radian turned."});
  v.number("motion_noise_translation_per_sqrt_m", c.motion_noise_translation_per_sqrt_m, {0.0, 2.0, "m/sqrt(m)", "Translation noise that grows as a random walk: its variance is this squared per metre driven, added to the variance of the per-metre terms. Wheel odometry's error adds up over many small steps as a random walk, and the per-metre terms, sized for one update's motion, give a particle cloud that spreads too slowly over the many short updates of a slow robot. Measured at the simulator's carpet values on every world and KITTI (docs/results.md): the clutter hall's three seeds all past 95%, but the office's coverage 12 points lower on the mean and the mean ATE higher on every world, so off by default. 0: off."});
  v.number("motion_noise_rotation_per_sqrt_rad", c.motion_noise_rotation_per_sqrt_rad, {0.0, 2.0, "rad/sqrt(rad)", "Rotation noise as a random walk: variance this squared per radian turned, added as above. 0: off."});
  v.number("motion_noise_rotation_per_sqrt_m", c.motion_noise_rotation_per_sqrt_m, {0.0, 2.0, "rad/sqrt(m)", "Rotation noise as a random walk: variance this squared per metre driven, added as above. 0: off."});
  v.integer_field("landmark_node_capacity", c.landmark_node_capacity, {1, 1000000000, "", "Nodes of the shared landmark trees of all particles (FastSLAM tree, O(N log K)); when short, a particle's change to one landmark is refused and counted."});
  v.integer_field("landmark_estimate_capacity", c.landmark_estimate_capacity, {1, 1000000000, "", "3D Gaussian landmark estimates shared by all particles; when short, the new estimate or update is refused and counted."});
  v.integer_field("trajectory_node_capacity", c.trajectory_node_capacity, {1, 1000000000, "", "Nodes of the particles' ancestry tree (one per particle per update, freed when no particle descends from them); when fewer than `particles` are free the update is refused and counted, and the motion carries over to the next."});
  v.integer_field("estimates_per_landmark", c.estimates_per_landmark, {1, 4, "", "Spatially distinct estimates one landmark identity may hold (paper Fig. 1); further distinct sightings are refused and counted."});
  v.integer_field("max_observations_per_update", c.max_observations_per_update, {1, 100000, "", "Landmark observations one update takes; more are dropped and counted."});
  v.integer_field("export_min_observations", c.export_min_observations, {1, 1000000, "", "An estimate goes into landmarks.ply once it has fused this many observations (4: seen more than 3 times)."});
  v.number("estimate_lineage_margin", c.estimate_lineage_margin, {0.0, 100.0, "", "The particle the grid and the explorer follow (the estimate) stays on the lineage it followed while a particle descending from it has a log-weight within this of the best; otherwise, and at 0, it is the ML particle (paper V). The ML particle after a resampling is the one whose single update was likeliest, often of another lineage a few centimetres away, and the grid follows it: a wall held, then a gap. Counted either way in report.json's filter.estimate_lineage_switches. At 10, four changes in five fewer and half the grids held, but no better coverage or fewer contacts on eight runs (docs/results.md), so 0."});
  v.integer_field("independent_observations", c.independent_observations, {0, 100000, "", "An update with more observations than this weighs its particles as if it had this many: the sum of their log-likelihoods is scaled by this number over theirs. Eq. 7 takes the observations of one frame as independent, but their errors share the frame's (the stereo calibration, the pose they were seen from), and 200 of them weighed as independent leave one particle of 1000 at each update, the cloud narrower than the estimate's error. Every observation still updates its landmark. 0: every observation independent (paper eq. 7). At 30 office seed 1 kept its pose, but the coverage fell on all six office seeds (docs/results.md), so 0."});
  v.number("manhattan_heading_sigma_deg", c.manhattan_heading_sigma_deg, {0.0, 90.0, "deg", "Assume the building's walls meet at right angles (a Manhattan world) and weigh every particle by how far the straightest wall of the update's obstacle scan, turned by the particle's heading, lies from the nearest of the building's axes: a Gaussian of this standard deviation. It bounds the heading's drift where no landmark is in view (turning in front of blank walls) without a gyro. The axes are learnt from the first manhattan_frame_walls walls. Not in the paper. At 2 the walls fit within 0.6 degrees of the truth and office seed 1 kept its pose, but the office's coverage fell to 91.8% on the mean against 97.8% and the heading's error at the explorer's events was no smaller (docs/results.md), so 0 (off)."});
  v.number("manhattan_gate_deg", c.manhattan_gate_deg, {0.0, 45.0, "deg", "A wall further than this from the nearest axis at the estimate's heading is not one of the building's (a slanted box, a wall off the grid): not used, counted in report.json's filter.manhattan_walls_off_axes."});
  v.integer_field("manhattan_frame_walls", c.manhattan_frame_walls, {1, 100000, "", "Walls from the start (at the estimate's heading, still exact there) whose circular mean modulo 90 degrees fixes the building's axes; when they do not agree (resultant below 0.9) the count starts again."});
  v.number("manhattan_wall_min_length_m", c.manhattan_wall_min_length_m, {0.1, 20.0, "m", "Shortest straight run of scan points taken for a wall."});
  v.number("manhattan_wall_max_range_m", c.manhattan_wall_max_range_m, {0.5, 20.0, "m", "Scan points farther than this from the camera are left out of the wall fit (stereo's range error grows with the square of the range)."});
  v.number("manhattan_wall_max_rms_m", c.manhattan_wall_max_rms_m, {0.001, 1.0, "m", "Largest root-mean-square distance of a wall's points from its fitted line; a run is split at its point farthest from its chord while that lies more than three times this off."});
  v.number("manhattan_wall_max_gap_m", c.manhattan_wall_max_gap_m, {0.01, 5.0, "m", "Neighbouring scan columns farther apart than this end a run of wall points."});
  v.require(c.particles <= c.particle_capacity, "particles", "must not exceed particle_capacity");
  v.end_section();
}

}  // namespace stereoscout::core
