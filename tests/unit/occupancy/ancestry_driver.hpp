#pragma once
// A small deterministic stand-in for the particle filter's ancestry: N particles, each
// holding its newest TrajectoryTree node; every update gives each particle a child node
// (odometry step plus noise), accumulates random log-weights, resamples systematically when
// the effective sample size drops below half, and names the best-weight particle the ML one.
// That gives the branching and ML switches of a real run without landmarks. Random scans
// come from the same seed. No heap use after construction.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "stereoscout/core/messages.hpp"
#include "stereoscout/core/random.hpp"
#include "stereoscout/slam/trajectory_tree.hpp"

namespace stereoscout::occupancy::testing {

struct DriverSettings {
  std::size_t particles = 20;
  std::uint64_t seed = 1;
  double step_m = 0.07;              // paper: an update every 7 cm
  double turn_rad = 0.05;
  double motion_noise_m = 0.01;
  double weight_noise = 1.0;         // spread of i.i.d. per-update log-likelihoods
  // > 0: the log-likelihood also scores each particle's distance to the true (noise-free)
  // path, as landmark observations do, so good lineages stay good (a real filter's genealogy).
  double likelihood_sigma_m = 0.0;
  double likelihood_sigma_rad = 0.02;
  double resample_fraction = 0.5;    // resample when ESS < fraction * N
};

class AncestryDriver {
 public:
  AncestryDriver(slam::TrajectoryTree& tree, const DriverSettings& settings)
      : tree_(tree),
        settings_(settings),
        nodes_(settings.particles),
        scratch_(settings.particles),
        log_weights_(settings.particles, 0.0),
        scratch_weights_(settings.particles, 0.0) {}

  ~AncestryDriver() { release_all(); }

  void start(const core::Pose2& pose) {
    const slam::TrajectoryNodeHandle root = tree_.add({}, pose, 0, 0);
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      if (i > 0) tree_.retain(root);
      nodes_[i] = root;
    }
    update_index_ = 0;
    ml_ = 0;
    truth_ = pose;
  }

  void step() {
    ++update_index_;
    truth_ = truth_.compose(core::Pose2{settings_.step_m, 0.0, settings_.turn_rad});
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      core::RandomStream random(settings_.seed, {core::stream_purpose::test, update_index_, static_cast<std::uint32_t>(i)});
      const core::Pose2 parent = tree_.get(nodes_[i]).pose;
      const core::Pose2 motion{settings_.step_m + random.gaussian(0.0, settings_.motion_noise_m),
                               random.gaussian(0.0, settings_.motion_noise_m),
                               settings_.turn_rad + random.gaussian(0.0, 0.01)};
      const slam::TrajectoryNodeHandle child =
          tree_.add(nodes_[i], parent.compose(motion), static_cast<std::int64_t>(update_index_) * 1000, update_index_);
      tree_.release(nodes_[i]);
      nodes_[i] = child;
      log_weights_[i] += random.gaussian(0.0, settings_.weight_noise) + path_log_likelihood(tree_.get(child).pose);
    }
    choose_ml();
    if (effective_sample_size() < settings_.resample_fraction * static_cast<double>(nodes_.size())) resample();
  }

  // A scan of `columns` columns fanned over +-30 degrees, 10 % invalid, 30 % free.
  void make_scan(core::DepthScan& scan, std::size_t columns) const {
    core::RandomStream random(settings_.seed, {core::stream_purpose::test + 1, update_index_, 0});
    scan.timestamp_ns = static_cast<std::int64_t>(update_index_) * 1000;
    scan.origin_robot = {0.1, 0.0};
    scan.columns.resize(columns);
    for (std::size_t c = 0; c < columns; ++c) {
      const double bearing = -0.52 + 1.04 * (static_cast<double>(c) + 0.5) / static_cast<double>(columns);
      const double range = random.uniform(0.4, 3.0);
      const double kind = random.uniform();
      core::DepthScanColumn& column = scan.columns[c];
      column.x_robot_m = static_cast<float>(0.1 + range * std::cos(bearing));
      column.y_robot_m = static_cast<float>(range * std::sin(bearing));
      column.kind = kind < 0.1 ? core::DepthScanColumn::Kind::invalid
                    : kind < 0.4 ? core::DepthScanColumn::Kind::free
                                 : core::DepthScanColumn::Kind::obstacle;
    }
  }

  void release_all() {
    for (slam::TrajectoryNodeHandle& node : nodes_) {
      if (node) tree_.release(node);
      node = {};
    }
  }

  slam::TrajectoryNodeHandle ml_node() const { return nodes_[ml_]; }
  const slam::TrajectoryNodeHandle* nodes() const { return nodes_.data(); }
  std::size_t count() const { return nodes_.size(); }
  std::uint32_t update_index() const { return update_index_; }
  std::uint64_t resamplings() const { return resamplings_; }

  // Forces the ML particle (tests of ML switches).
  void set_ml(std::size_t particle) { ml_ = particle; }

 private:
  void choose_ml() {
    ml_ = static_cast<std::size_t>(std::max_element(log_weights_.begin(), log_weights_.end()) - log_weights_.begin());
  }

  double path_log_likelihood(const core::Pose2& pose) const {
    if (settings_.likelihood_sigma_m <= 0.0) return 0.0;
    const core::Pose2 error = truth_.between(pose);
    const double position = (error.x * error.x + error.y * error.y) /
                            (settings_.likelihood_sigma_m * settings_.likelihood_sigma_m);
    const double heading = error.theta * error.theta / (settings_.likelihood_sigma_rad * settings_.likelihood_sigma_rad);
    return -0.5 * (position + heading);
  }

  double effective_sample_size() const {
    const double best = log_weights_[ml_];
    double sum = 0.0;
    double sum_squares = 0.0;
    for (const double log_weight : log_weights_) {
      const double w = std::exp(log_weight - best);
      sum += w;
      sum_squares += w * w;
    }
    return sum * sum / sum_squares;
  }

  // Systematic resampling; the ML particle's lineage is kept in the ML slot.
  void resample() {
    ++resamplings_;
    core::RandomStream random(settings_.seed, {core::stream_purpose::test + 2, update_index_, 0});
    const double best = log_weights_[ml_];
    double total = 0.0;
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      scratch_weights_[i] = std::exp(log_weights_[i] - best);
      total += scratch_weights_[i];
    }
    const double spacing = total / static_cast<double>(nodes_.size());
    double pointer = random.uniform() * spacing;
    double cumulative = scratch_weights_[0];
    std::size_t source = 0;
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      while (pointer > cumulative && source + 1 < nodes_.size()) cumulative += scratch_weights_[++source];
      scratch_[i] = nodes_[source];
      tree_.retain(scratch_[i]);
      pointer += spacing;
    }
    const slam::TrajectoryNodeHandle ml = nodes_[ml_];
    tree_.retain(ml);
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      tree_.release(nodes_[i]);
      nodes_[i] = scratch_[i];
      log_weights_[i] = 0.0;
    }
    tree_.release(nodes_[ml_]);
    nodes_[ml_] = ml;  // the ML particle survives resampling (its weight was the best)
  }

  slam::TrajectoryTree& tree_;
  DriverSettings settings_;
  std::vector<slam::TrajectoryNodeHandle> nodes_;
  std::vector<slam::TrajectoryNodeHandle> scratch_;
  std::vector<double> log_weights_;
  std::vector<double> scratch_weights_;
  std::uint32_t update_index_ = 0;
  std::size_t ml_ = 0;
  core::Pose2 truth_;
  std::uint64_t resamplings_ = 0;
};

}  // namespace stereoscout::occupancy::testing
