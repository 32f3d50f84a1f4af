#include "stereoscout/slam/particle_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stereoscout/core/check.hpp"
#include "stereoscout/core/random.hpp"

namespace stereoscout::slam {
namespace {

std::size_t to_size(int value) { return static_cast<std::size_t>(value); }

// Stable insertion sort (no heap, keeps the given order within one id). Visiting landmarks in
// id order walks neighbouring paths of the tree one after the other, so the nodes they share
// are copied once and then found in cache.
void sort_by_landmark_id(core::FixedVector<RobotFrameObservation>& observations) {
  for (std::size_t i = 1; i < observations.size(); ++i) {
    const RobotFrameObservation moving = observations[i];
    std::size_t j = i;
    while (j > 0 && observations[j - 1].landmark_id > moving.landmark_id) {
      observations[j] = observations[j - 1];
      --j;
    }
    observations[j] = moving;
  }
}

}  // namespace

ParticleFilter::ParticleFilter(const core::FilterConfig& config, const core::CameraMount& camera_mount,
                               std::uint64_t seed, const StereoModel* stereo)
    : config_(config),
      camera_mount_(camera_mount),
      stereo_(stereo != nullptr ? *stereo : StereoModel{}),
      linearise_at_estimate_(config.linearise_at_estimate && stereo != nullptr),
      fuse_at_measurement_(linearise_at_estimate_ && !config.linearise_fusion),
      seed_(seed),
      motion_noise_(motion_noise_from_config(config)),
      landmarks_(to_size(config.landmark_node_capacity), to_size(config.landmark_estimate_capacity)),
      trajectory_(to_size(config.trajectory_node_capacity)),
      particles_a_(to_size(config.particle_capacity)),
      particles_b_(to_size(config.particle_capacity)),
      particles_(&particles_a_),
      spare_(&particles_b_),
      observations_(to_size(config.max_observations_per_update)),
      scratch_weights_(to_size(config.particle_capacity)),
      manhattan_frame_(config.manhattan_frame_walls) {
  STEREOSCOUT_CHECK(config.particles >= 1 && config.particles <= config.particle_capacity,
                    "filter.particles must be in [1, particle_capacity]");
  start(core::OdometryReading{});
  if (config.background_release) release_worker_ = std::make_unique<core::Worker>();
}

ParticleFilter::~ParticleFilter() {
  settle();
  set_estimate({});
  release_particles(*particles_);
}

void ParticleFilter::release_particles(core::FixedVector<Particle>& particles) {
  for (Particle& p : particles) {
    landmarks_.release(p.map);
    if (p.trajectory) {
      trajectory_.release(p.trajectory);
    }
  }
  particles.clear();
}

// The particles resampling dropped: their trajectory references now (the grid's roll-up walks
// the tree between updates), their maps on the release worker, which the next update waits
// for. Freeing a dead map's nodes is a walk of cache misses (a tenth of a run's CPU time), and
// between updates the second core mostly idles. The maps are released in the same order
// either way, so the pools' free lists, and every result, are the same.
void ParticleFilter::release_dropped(core::FixedVector<Particle>& dropped) {
  for (Particle& p : dropped) {
    if (p.trajectory) {
      trajectory_.release(p.trajectory);
      p.trajectory = {};
    }
  }
  if (release_worker_) {
    dropped_ = &dropped;
    release_worker_->start(&ParticleFilter::release_dropped_maps, this);
    return;
  }
  release_particles(dropped);
}

void ParticleFilter::release_dropped_maps(void* self) {
  auto* filter = static_cast<ParticleFilter*>(self);
  filter->release_particles(*filter->dropped_);  // their trajectories are released already
}

void ParticleFilter::settle() const {
  if (release_worker_) release_worker_->wait();
}

void ParticleFilter::start(const core::OdometryReading& odometry, const core::Pose2& initial_pose) {
  settle();
  release_particles(*particles_);
  const TrajectoryNodeHandle root = trajectory_.add({}, initial_pose, odometry.timestamp_ns, 0);
  STEREOSCOUT_CHECK(root, "filter.trajectory_node_capacity leaves no room for the first node");
  for (int i = 0; i < config_.particles; ++i) {
    Particle p;
    p.pose = initial_pose;
    p.trajectory = root;
    if (i > 0) {
      trajectory_.retain(root);
    }
    particles_->push_back(p);
  }
  last_odometry_ = odometry.pose;
  manhattan_frame_.reset();
  update_index_ = 1;  // the root is update 0
  ml_slot_ = 0;
  set_estimate(root);
}

void ParticleFilter::start(const core::OdometryReading& odometry, const core::Pose2& initial_pose,
                           const PriorLandmark* prior, std::size_t prior_count) {
  start(odometry, initial_pose);
  Particle& first = (*particles_)[0];
  for (std::size_t k = 0; k < prior_count; ++k) {
    MapNode* leaf = landmarks_.mutable_leaf(first.map, prior[k].landmark_id, 1);
    if (leaf == nullptr) {
      ++counters_.changes_refused_pool_full;
    } else if (leaf->estimates.size() >= to_size(config_.estimates_per_landmark)) {
      ++counters_.estimates_refused_list_full;
    } else {
      landmarks_.add_estimate(*leaf, prior[k].estimate);
    }
  }
  for (std::size_t slot = 1; slot < particles_->size(); ++slot) {
    (*particles_)[slot].map = first.map;
    landmarks_.retain(first.map);
  }
}

UpdateResult ParticleFilter::update(const core::OdometryReading& odometry, ObservationList observations,
                                    double pan_rad, const WallLine* wall) {
  return update(odometry, observations, core::robot_from_camera(camera_mount_, pan_rad), wall);
}

UpdateResult ParticleFilter::update(const core::OdometryReading& odometry, ObservationList observations,
                                    const Eigen::Isometry3d& robot_from_sensor, const WallLine* wall) {
  settle();  // the last resampling's dropped maps are back in the pools
  UpdateResult result;
  if (trajectory_.available() < particles_->size()) {
    // Defined degradation: no update; the odometry motion carries over to the next one.
    ++counters_.updates_refused_trajectory_full;
    result.status = {core::StatusCode::exhausted, "trajectory node pool full: update refused"};
    result.effective_sample_size = effective_sample_size();
    return result;
  }
  predict(last_odometry_.between(odometry.pose));
  last_odometry_ = odometry.pose;
  if (wall != nullptr && config_.manhattan_heading_sigma_deg > 0.0) weigh_by_wall(*wall);
  const std::size_t used = prepare_observations(observations, robot_from_sensor);
  const double weight_scale = observation_weight_scale(used);
  for (Particle& p : *particles_) {
    const PlanarTransform map_from_robot(p.pose);
    const MapFromSensor sensor =
        linearise_at_estimate_ ? map_from_sensor(map_from_robot, robot_from_sensor_) : MapFromSensor{};
    double log_likelihood = 0.0;
    for (std::size_t k = 0; k < used; ++k) {
      log_likelihood += observe(p, map_from_robot, sensor, observations_[k]);
    }
    p.log_weight += weight_scale * log_likelihood;
  }
  extend_trajectories(odometry.timestamp_ns);
  normalise_weights();
  ml_slot_ = best_slot();
  follow_estimate();
  result.effective_sample_size = effective_sample_size();
  if (result.effective_sample_size < config_.resample_ess_fraction * static_cast<double>(particles_->size())) {
    resample();
    result.resampled = true;
  }
  ++update_index_;
  ++counters_.updates;
  return result;
}

// The wall's direction in the map frame is the particle's heading plus its direction in the
// robot frame; a right heading puts it on one of the building's axes. The weighted mean
// heading decides whether the wall is one of the building's at all, so that a slanted box
// weighs nobody.
void ParticleFilter::weigh_by_wall(const WallLine& wall) {
  const double mean_heading = weighted_mean_pose().theta;
  if (!manhattan_frame_.fixed()) {
    manhattan_frame_.learn(mean_heading + wall.direction_rad);
    ++counters_.manhattan_walls_learnt;
    return;
  }
  if (std::abs(manhattan_frame_.offset(mean_heading + wall.direction_rad)) >
      core::degrees_to_radians(config_.manhattan_gate_deg)) {
    ++counters_.manhattan_walls_off_axes;
    return;
  }
  ++counters_.manhattan_walls_used;
  const double sigma = core::degrees_to_radians(config_.manhattan_heading_sigma_deg);
  for (Particle& p : *particles_) {
    const double offset = manhattan_frame_.offset(p.pose.theta + wall.direction_rad) / sigma;
    p.log_weight -= 0.5 * offset * offset;
  }
}

void ParticleFilter::predict(const core::Pose2& motion) {
  for (std::size_t slot = 0; slot < particles_->size(); ++slot) {
    core::RandomStream stream(seed_, {core::stream_purpose::motion_noise, update_index_,
                                      static_cast<std::uint32_t>(slot)});
    Particle& p = (*particles_)[slot];
    p.pose = p.pose.compose(sample_motion(motion, motion_noise_, stream));
  }
}

std::size_t ParticleFilter::prepare_observations(ObservationList observations,
                                                 const Eigen::Isometry3d& robot_from_sensor) {
  observations_.clear();
  robot_from_sensor_ = robot_from_sensor;
  for (std::size_t k = 0; k < observations.size; ++k) {
    const core::LandmarkObservation& observation = observations.data[k];
    if (!is_valid_observation(observation)) {
      ++counters_.observations_invalid;
      continue;
    }
    if (observations_.full()) {
      ++counters_.observations_dropped_overflow;
      continue;
    }
    RobotFrameObservation* added = observations_.emplace_back(to_robot_frame(observation, robot_from_sensor));
    if (linearise_at_estimate_) added->measured_pixel = project(stereo_, observation.point_camera);
    ++counters_.observations_used;
  }
  sort_by_landmark_id(observations_);
  return observations_.size();
}

double ParticleFilter::observation_weight_scale(std::size_t used) {
  const auto independent = static_cast<std::size_t>(std::max(0, config_.independent_observations));
  if (independent == 0 || used <= independent) return 1.0;
  ++counters_.updates_weighed_as_fewer;
  return static_cast<double>(independent) / static_cast<double>(used);
}

// Paper Algorithm 1 for one particle and one observation; returns its log-likelihood (eq. 7,
// the constant k dropped: it is the same for every particle). Linearised at the estimate the
// normaliser is that of S = H P H^T + diag(sigma^2) in pixel coordinates, still nearly the
// same for every particle; the map frame's S carries the square of the triangulation
// Jacobian's determinant as well, which is not the measurement's and must not be weighed
// (with it, the corridor drive of tests/unit/slam came out 1.7 % long).
double ParticleFilter::observe(Particle& particle, const PlanarTransform& map_from_robot, const MapFromSensor& sensor,
                               const RobotFrameObservation& observation) {
  const MapFrameObservation seen = to_map_frame(observation, map_from_robot);
  const MapNode* leaf = landmarks_.find_leaf(particle.map, observation.landmark_id);
  if (leaf == nullptr || leaf->estimates.empty()) {
    // A first sighting: every particle is in the same position, the weight is unchanged.
    MapNode* fresh = landmarks_.mutable_leaf(particle.map, observation.landmark_id, 1);
    if (fresh == nullptr) {
      ++counters_.changes_refused_pool_full;
      return 0.0;
    }
    landmarks_.add_estimate(*fresh, LandmarkEstimate{seen.point, seen.covariance, 1});
    ++counters_.estimates_added;
    return 0.0;
  }
  std::size_t best = 0;
  Innovation best_innovation;
  best_innovation.distance_squared = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < leaf->estimates.size(); ++i) {
    const LandmarkEstimate& estimate = landmarks_.estimate(leaf->estimates[i]);
    MapFrameObservation linearised;
    const Innovation candidate =
        linearise_at_estimate_ && at_estimate(stereo_, observation.measured_pixel, estimate.mean, sensor, linearised)
            ? innovation(estimate, linearised)
            : innovation(estimate, seen);
    if (candidate.distance_squared < best_innovation.distance_squared) {
      best_innovation = candidate;
      best = i;
    }
  }
  const double best_distance = best_innovation.distance_squared;
  double log_likelihood = -0.5 * best_distance;
  if (!(log_likelihood >= config_.min_log_likelihood)) {
    log_likelihood = config_.min_log_likelihood;
    ++counters_.log_likelihood_floored;
  }
  const bool in_gate = best_distance <= config_.association_gate_chi2;
  if (!in_gate && leaf->estimates.size() >= to_size(config_.estimates_per_landmark)) {
    ++counters_.estimates_refused_list_full;
    return log_likelihood;
  }
  MapNode* own = landmarks_.mutable_leaf(particle.map, observation.landmark_id, 1);
  if (own == nullptr) {
    ++counters_.changes_refused_pool_full;
    return log_likelihood;
  }
  if (in_gate) {
    LandmarkEstimate& fused = landmarks_.mutable_estimate(*own, best);
    ekf_update(fused, fuse_at_measurement_ ? innovation(fused, seen) : best_innovation);
    ++counters_.estimates_updated;
  } else {
    // Spatially distinct from every estimate of this identity: a new landmark (paper Fig. 1).
    landmarks_.add_estimate(*own, LandmarkEstimate{seen.point, seen.covariance, 1});
    ++counters_.estimates_added;
  }
  return log_likelihood;
}

void ParticleFilter::extend_trajectories(std::int64_t timestamp_ns) {
  for (Particle& p : *particles_) {
    const TrajectoryNodeHandle node = trajectory_.add(p.trajectory, p.pose, timestamp_ns, update_index_);
    STEREOSCOUT_CHECK(node, "trajectory pool ran out after its room was checked");
    trajectory_.release(p.trajectory);  // the new node now holds the parent
    p.trajectory = node;
  }
}

void ParticleFilter::normalise_weights() {
  double best = -std::numeric_limits<double>::infinity();
  for (const Particle& p : *particles_) {
    best = p.log_weight > best ? p.log_weight : best;
  }
  for (Particle& p : *particles_) {
    p.log_weight -= best;
  }
}

std::size_t ParticleFilter::best_slot() const {
  std::size_t best = 0;
  for (std::size_t slot = 1; slot < particles_->size(); ++slot) {
    if ((*particles_)[slot].log_weight > (*particles_)[best].log_weight) {
      best = slot;  // strict: ties keep the lowest slot, so the choice is deterministic
    }
  }
  return best;
}

void ParticleFilter::follow_estimate() {
  const std::size_t none = particles_->size();
  std::size_t chosen = ml_slot_;
  if (config_.estimate_lineage_margin > 0.0 && estimate_node_) {
    std::size_t best_descendant = none;
    for (std::size_t slot = 0; slot < particles_->size(); ++slot) {
      const Particle& p = (*particles_)[slot];
      if ((best_descendant == none || p.log_weight > (*particles_)[best_descendant].log_weight) &&
          trajectory_.descends_from(p.trajectory, estimate_node_)) {
        best_descendant = slot;
      }
    }
    if (best_descendant != none && (*particles_)[best_descendant].log_weight >= -config_.estimate_lineage_margin) {
      chosen = best_descendant;
    }
  }
  const TrajectoryNodeHandle node = (*particles_)[chosen].trajectory;
  if (estimate_node_ && !trajectory_.descends_from(node, estimate_node_)) {
    const std::uint64_t depth = depth_to_common_ancestor(node, estimate_node_);
    ++counters_.estimate_lineage_switches;
    counters_.estimate_switch_depth_sum += depth;
    counters_.estimate_switch_depth_max = std::max(counters_.estimate_switch_depth_max, depth);
  }
  set_estimate(node);
}

std::uint32_t ParticleFilter::depth_to_common_ancestor(TrajectoryNodeHandle newer, TrajectoryNodeHandle older) const {
  const std::uint32_t older_index = trajectory_.get(older).update_index;
  while (newer && older && newer != older) {
    if (trajectory_.get(newer).update_index >= trajectory_.get(older).update_index) {
      newer = trajectory_.parent(newer);
    } else {
      older = trajectory_.parent(older);
    }
  }
  return older ? older_index - trajectory_.get(older).update_index : older_index;
}

void ParticleFilter::set_estimate(TrajectoryNodeHandle node) {
  if (node) trajectory_.retain(node);
  if (estimate_node_) trajectory_.release(estimate_node_);
  estimate_node_ = node;
}

double ParticleFilter::effective_sample_size() const {
  double sum = 0.0;
  double sum_squares = 0.0;
  for (const Particle& p : *particles_) {
    const double w = std::exp(p.log_weight);
    sum += w;
    sum_squares += w * w;
  }
  return sum_squares > 0.0 ? sum * sum / sum_squares : 0.0;
}

core::Pose2 ParticleFilter::weighted_mean_pose() const {
  double sum = 0.0;
  double x = 0.0;
  double y = 0.0;
  double cosine = 0.0;
  double sine = 0.0;
  for (const Particle& p : *particles_) {
    const double w = std::exp(p.log_weight);
    sum += w;
    x += w * p.pose.x;
    y += w * p.pose.y;
    cosine += w * std::cos(p.pose.theta);
    sine += w * std::sin(p.pose.theta);
  }
  return core::Pose2{x / sum, y / sum, std::atan2(sine, cosine)};
}

// Systematic (low-variance) resampling: one uniform offset, N evenly spaced pointers.
void ParticleFilter::resample() {
  core::FixedVector<Particle>& current = *particles_;
  core::FixedVector<Particle>& next = *spare_;
  const std::size_t n = current.size();
  scratch_weights_.clear();
  double total = 0.0;
  for (const Particle& p : current) {
    total += std::exp(p.log_weight);
    scratch_weights_.push_back(total);  // cumulative
  }
  core::RandomStream stream(seed_, {core::stream_purpose::resampling, update_index_, 0});
  const double step = total / static_cast<double>(n);
  double pointer = stream.uniform() * step;
  std::size_t source = 0;
  std::size_t new_ml_slot = n;
  next.clear();
  for (std::size_t k = 0; k < n; ++k) {
    while (source + 1 < n && scratch_weights_[source] <= pointer) {
      ++source;
    }
    Particle copy = current[source];
    copy.log_weight = 0.0;
    landmarks_.retain(copy.map);
    trajectory_.retain(copy.trajectory);
    if (source == ml_slot_ && new_ml_slot == n) {
      new_ml_slot = k;
    }
    next.push_back(copy);
    pointer += step;
  }
  release_dropped(current);
  particles_ = &next;
  spare_ = &current;
  // The ML particle has the largest weight, so systematic resampling always keeps it.
  ml_slot_ = new_ml_slot < n ? new_ml_slot : 0;
  ++counters_.resamplings;
}

}  // namespace stereoscout::slam
