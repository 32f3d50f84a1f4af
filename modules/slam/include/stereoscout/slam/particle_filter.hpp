#pragma once
// The Rao-Blackwellised particle filter over landmark maps (paper III, IV).
//
// One update, given the newest odometry reading and the landmark observations of that moment:
//   1. proposal: every particle samples its motion from the odometry motion model, with the
//      stream (seed, {motion_noise, update_index, particle slot});
//   2. observation update (paper Algorithm 1): per particle and observation, the most likely
//      estimate in the identity's list (Mahalanobis distance, gated) is EKF-updated, after
//      path copying of whatever the particle shares; no estimate in the gate adds a new one;
//      the weight gains the observation's log-likelihood (eq. 7 in log space, floored; the
//      sum scaled down when there are more than filter.independent_observations);
//   3. ancestry: every particle gets a trajectory node (pose, time, update index);
//   3a. with filter.manhattan_heading_sigma_deg, the update's wall (wall_line.hpp), if any,
//      weighs every particle by how far its heading puts the wall from the building's axes
//      (manhattan_frame.hpp); until the axes are learnt the wall only teaches them;
//   4. resampling: systematic, when the effective sample size falls below the configured
//      fraction, with the stream (seed, {resampling, update_index, 0}).
// All memory is reserved in the constructor; update() does not touch the heap.

#include <cstddef>
#include <cstdint>
#include <memory>

#include <Eigen/Geometry>

#include "stereoscout/core/config/filter.hpp"
#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/core/status.hpp"
#include "stereoscout/core/worker.hpp"
#include "stereoscout/slam/landmark_map.hpp"
#include "stereoscout/slam/manhattan_frame.hpp"
#include "stereoscout/slam/motion_model.hpp"
#include "stereoscout/slam/observation_model.hpp"
#include "stereoscout/slam/trajectory_tree.hpp"
#include "stereoscout/slam/wall_line.hpp"

namespace stereoscout::slam {

struct Particle {
  core::Pose2 pose;
  double log_weight = 0.0;  // normalised so the best particle has 0 after every update
  LandmarkMap map;
  TrajectoryNodeHandle trajectory;
};

// One landmark of a map the filter starts from (start with a prior).
struct PriorLandmark {
  std::uint32_t landmark_id = 0;
  LandmarkEstimate estimate;
};

// A view of the observations of one update (no ownership, no copy).
struct ObservationList {
  const core::LandmarkObservation* data = nullptr;
  std::size_t size = 0;
};

struct FilterCounters {
  std::uint64_t updates = 0;
  std::uint64_t updates_refused_trajectory_full = 0;
  std::uint64_t resamplings = 0;
  std::uint64_t observations_used = 0;            // per update, not per particle
  std::uint64_t observations_invalid = 0;         // non-finite point or covariance not PD
  std::uint64_t observations_dropped_overflow = 0;  // beyond max_observations_per_update
  std::uint64_t estimates_added = 0;              // per particle
  std::uint64_t estimates_updated = 0;            // per particle
  std::uint64_t estimates_refused_list_full = 0;  // identity already holds estimates_per_landmark
  std::uint64_t changes_refused_pool_full = 0;    // landmark pools short (see LandmarkStore)
  std::uint64_t log_likelihood_floored = 0;       // observation likelihoods raised to the floor
  std::uint64_t updates_weighed_as_fewer = 0;     // more observations than filter.independent_observations
  // The estimate's lineage (estimate_node()): updates whose estimate does not descend from
  // the previous update's, and how many updates back their common ancestor lay (summed, max).
  std::uint64_t estimate_lineage_switches = 0;
  std::uint64_t estimate_switch_depth_sum = 0;
  std::uint64_t estimate_switch_depth_max = 0;
  // Walls handed to update() (filter.manhattan_heading_sigma_deg): learnt into the building's
  // axes, used to weigh the particles, or too far off the axes to be one of the building's.
  std::uint64_t manhattan_walls_learnt = 0;
  std::uint64_t manhattan_walls_used = 0;
  std::uint64_t manhattan_walls_off_axes = 0;
};

struct UpdateResult {
  core::Status status;
  double effective_sample_size = 0.0;
  bool resampled = false;
};

class ParticleFilter {
 public:
  // `stereo`: the camera's measurement model, needed by filter.linearise_at_estimate (without
  // it every observation is compared at its measured point).
  ParticleFilter(const core::FilterConfig& config, const core::CameraMount& camera_mount, std::uint64_t seed,
                 const StereoModel* stereo = nullptr);
  ~ParticleFilter();

  ParticleFilter(const ParticleFilter&) = delete;
  ParticleFilter& operator=(const ParticleFilter&) = delete;

  // Places every particle at `initial_pose` with an empty map; `odometry` is the reading the
  // first update's motion is measured from. Releases whatever an earlier run held.
  void start(const core::OdometryReading& odometry, const core::Pose2& initial_pose = {});
  // The same, every particle starting from one shared copy of a known map (a resumed mission,
  // a benchmark's steady state): the map is built once and all particles hold it.
  void start(const core::OdometryReading& odometry, const core::Pose2& initial_pose, const PriorLandmark* prior,
             std::size_t prior_count);

  // One update with stereo observations in the camera's optical frame, the camera on the
  // configured mount turned by `pan_rad`; `wall`: the straightest wall of the same moment's
  // scan, or null (used only with filter.manhattan_heading_sigma_deg).
  UpdateResult update(const core::OdometryReading& odometry, ObservationList observations, double pan_rad,
                      const WallLine* wall = nullptr);
  // The same for any sensor: observations are points in the frame `robot_from_sensor` maps
  // into the robot frame (identity for a sensor at the robot's centre, as in MRCLAM).
  UpdateResult update(const core::OdometryReading& odometry, ObservationList observations,
                      const Eigen::Isometry3d& robot_from_sensor, const WallLine* wall = nullptr);

  std::size_t particle_count() const { return particles_->size(); }
  const Particle& particle(std::size_t slot) const { return (*particles_)[slot]; }

  // The maximum-likelihood particle: the best weight of the last update (carried through
  // resampling to one of its copies).
  std::size_t ml_slot() const { return ml_slot_; }
  const Particle& ml_particle() const { return particle(ml_slot_); }
  core::Pose2 ml_pose() const { return ml_particle().pose; }
  TrajectoryNodeHandle ml_trajectory_node() const { return ml_particle().trajectory; }
  const LandmarkMap& ml_map() const { return ml_particle().map; }
  // The particle the rest of the stack follows (the grid, the explorer's pose): the ML
  // particle, or with filter.estimate_lineage_margin the best particle descending from the
  // previous update's estimate while its log-weight is within the margin of the best. Chosen
  // before resampling; the node is retained, so it stays valid when resampling left no copy
  // of its particle (the next update then follows the ML particle).
  TrajectoryNodeHandle estimate_node() const { return estimate_node_; }
  core::Pose2 estimate_pose() const { return trajectory_.get(estimate_node_).pose; }
  core::Pose2 weighted_mean_pose() const;
  double effective_sample_size() const;
  std::uint32_t update_index() const { return update_index_; }

  // Waits for a release of dropped maps still running (filter.background_release).
  const LandmarkStore& landmarks() const {
    settle();
    return landmarks_;
  }
  TrajectoryTree& trajectory() { return trajectory_; }
  const TrajectoryTree& trajectory() const { return trajectory_; }
  const FilterCounters& counters() const { return counters_; }
  const core::FilterConfig& config() const { return config_; }
  const ManhattanFrame& manhattan_frame() const { return manhattan_frame_; }

 private:
  void release_particles(core::FixedVector<Particle>& particles);
  void release_dropped(core::FixedVector<Particle>& dropped);
  static void release_dropped_maps(void* self);
  void settle() const;
  void predict(const core::Pose2& motion);
  std::size_t prepare_observations(ObservationList observations, const Eigen::Isometry3d& robot_from_sensor);
  // What one update's summed log-likelihoods are scaled by (filter.independent_observations).
  double observation_weight_scale(std::size_t used);
  // Step 3a: learns the building's axes from `wall`, or weighs the particles by it.
  void weigh_by_wall(const WallLine& wall);
  double observe(Particle& particle, const PlanarTransform& map_from_robot, const MapFromSensor& sensor,
                 const RobotFrameObservation& observation);
  void extend_trajectories(std::int64_t timestamp_ns);
  void normalise_weights();
  std::size_t best_slot() const;
  // Sets estimate_node_ from this update's nodes and weights, and counts a change of lineage.
  void follow_estimate();
  // Updates from `older`'s back to the newest node both descend from.
  std::uint32_t depth_to_common_ancestor(TrajectoryNodeHandle newer, TrajectoryNodeHandle older) const;
  void set_estimate(TrajectoryNodeHandle node);
  void resample();

  core::FilterConfig config_;
  core::CameraMount camera_mount_;
  StereoModel stereo_;
  bool linearise_at_estimate_ = false;  // filter.linearise_at_estimate with a StereoModel
  bool fuse_at_measurement_ = false;    // linearised weights, the paper's fusion (filter.linearise_fusion off)
  Eigen::Isometry3d robot_from_sensor_ = Eigen::Isometry3d::Identity();  // of this update
  std::uint64_t seed_;
  MotionNoise motion_noise_;
  LandmarkStore landmarks_;
  TrajectoryTree trajectory_;
  core::FixedVector<Particle> particles_a_;
  core::FixedVector<Particle> particles_b_;
  core::FixedVector<Particle>* particles_;  // current generation
  core::FixedVector<Particle>* spare_;      // the next one, built by resampling
  core::FixedVector<RobotFrameObservation> observations_;
  core::FixedVector<double> scratch_weights_;
  core::Pose2 last_odometry_;
  std::uint32_t update_index_ = 0;
  std::size_t ml_slot_ = 0;
  TrajectoryNodeHandle estimate_node_;  // retained
  ManhattanFrame manhattan_frame_;
  FilterCounters counters_;
  // filter.background_release: releases *spare_'s maps after a resampling. Last, so that it
  // is destroyed (its job waited for) before the pools the job works on.
  std::unique_ptr<core::Worker> release_worker_;
  core::FixedVector<Particle>* dropped_ = nullptr;  // what it releases
};

}  // namespace stereoscout::slam
