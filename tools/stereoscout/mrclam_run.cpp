// Running the landmark filter over one MRCLAM robot and scoring its map (README: fit the best
// 2D rigid transform onto the true landmarks, report the RMSE; same for dead reckoning).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

#include "mrclam.hpp"
#include "stereoscout/slam/observation_model.hpp"
#include "stereoscout/slam/particle_filter.hpp"
#include "stereoscout/slam/slam_export.hpp"

namespace stereoscout::cli::mrclam {
namespace {

std::int64_t to_nanoseconds(double seconds) { return static_cast<std::int64_t>(std::llround(seconds * 1e9)); }

// Dead reckoning from commanded velocities: each command holds until the next row; a
// constant (v, w) moves the robot along a circular arc.
class OdometryIntegrator {
 public:
  explicit OdometryIntegrator(const std::vector<OdometryRow>& rows) : rows_(rows), time_s_(rows.front().time_s) {}

  core::Pose2 advance_to(double time_s) {
    while (time_s_ < time_s) {
      const bool has_next = next_ < rows_.size();
      const double until = has_next ? std::min(time_s, rows_[next_].time_s) : time_s;
      if (until > time_s_) {
        move(until - time_s_);
        time_s_ = until;
      }
      if (has_next && rows_[next_].time_s <= time_s_) {
        command_ = rows_[next_];
        ++next_;
      }
    }
    return pose_;
  }

 private:
  void move(double dt) {
    const double v = command_.forward_mps;
    const double w = command_.angular_rad_s;
    const double theta = pose_.theta;
    if (std::fabs(w) < 1e-9) {
      pose_.x += v * dt * std::cos(theta);
      pose_.y += v * dt * std::sin(theta);
    } else {
      pose_.x += v / w * (std::sin(theta + w * dt) - std::sin(theta));
      pose_.y += v / w * (std::cos(theta) - std::cos(theta + w * dt));
    }
    pose_.theta = core::wrap_angle(theta + w * dt);
  }

  const std::vector<OdometryRow>& rows_;
  std::size_t next_ = 0;
  OdometryRow command_;
  double time_s_;
  core::Pose2 pose_;
};

struct Fit {
  double angle = 0.0;
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();
};

Fit rigid_fit(const std::vector<Eigen::Vector2d>& from, const std::vector<Eigen::Vector2d>& to) {
  Eigen::Vector2d from_mean = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_mean = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < from.size(); ++i) {
    from_mean += from[i];
    to_mean += to[i];
  }
  from_mean /= static_cast<double>(from.size());
  to_mean /= static_cast<double>(to.size());
  double cross = 0.0;
  double dot = 0.0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector2d p = from[i] - from_mean;
    const Eigen::Vector2d q = to[i] - to_mean;
    cross += p.x() * q.y() - p.y() * q.x();
    dot += p.x() * q.x() + p.y() * q.y();
  }
  Fit fit;
  fit.angle = std::atan2(cross, dot);
  fit.translation = to_mean - Eigen::Rotation2Dd(fit.angle) * from_mean;
  return fit;
}

std::optional<double> trajectory_rmse(const std::vector<PoseRow>& estimated, const std::vector<PoseRow>& truth) {
  std::vector<Eigen::Vector2d> from;
  std::vector<Eigen::Vector2d> to;
  for (const PoseRow& row : estimated) {
    const auto after = std::lower_bound(truth.begin(), truth.end(), row.time_s,
                                        [](const PoseRow& r, double t) { return r.time_s < t; });
    if (after == truth.end() || after == truth.begin()) {
      continue;
    }
    const auto before = after - 1;
    const double span = after->time_s - before->time_s;
    const double a = span > 0.0 ? (row.time_s - before->time_s) / span : 0.0;
    from.push_back(row.pose.translation());
    to.push_back((1.0 - a) * before->pose.translation() + a * after->pose.translation());
  }
  if (from.size() < 2) {
    return std::nullopt;
  }
  return score_landmarks(from, to).rmse_m;
}

}  // namespace

MapScore score_landmarks(const std::vector<Eigen::Vector2d>& estimated, const std::vector<Eigen::Vector2d>& truth) {
  MapScore score;
  score.mapped = estimated.size();
  if (estimated.size() < 2) {
    return score;
  }
  const Fit fit = rigid_fit(estimated, truth);
  const Eigen::Rotation2Dd rotation(fit.angle);
  double sum = 0.0;
  for (std::size_t i = 0; i < estimated.size(); ++i) {
    const double residual = (rotation * estimated[i] + fit.translation - truth[i]).norm();
    score.residuals_m.push_back(residual);
    sum += residual * residual;
  }
  score.rmse_m = std::sqrt(sum / static_cast<double>(estimated.size()));
  return score;
}

RunResult run_landmark_slam(const Dataset& dataset, const RunOptions& options) {
  RunResult result;
  std::vector<MeasurementRow> measurements = dataset.measurements;
  std::stable_sort(measurements.begin(), measurements.end(),
                   [](const MeasurementRow& a, const MeasurementRow& b) { return a.time_s < b.time_s; });
  const double start_s = dataset.odometry.front().time_s;
  const double stop_s = options.duration_s > 0.0 ? start_s + options.duration_s : 1e300;

  core::FilterConfig filter_config = options.filter;
  filter_config.motion_noise_translation_per_m = options.noise_translation_per_m;
  filter_config.motion_noise_rotation_per_rad = options.noise_rotation_per_rad;
  filter_config.motion_noise_rotation_per_m = options.noise_rotation_per_m;
  filter_config.motion_noise_translation_per_rad = options.noise_translation_per_rad;
  filter_config.motion_noise_translation_per_sqrt_m = 0.0;
  filter_config.motion_noise_rotation_per_sqrt_rad = 0.0;
  filter_config.motion_noise_rotation_per_sqrt_m = 0.0;
  auto filter = std::make_unique<slam::ParticleFilter>(filter_config, core::CameraMount{}, options.seed);
  OdometryIntegrator odometry(dataset.odometry);
  filter->start(core::OdometryReading{to_nanoseconds(start_s), 0, {}});
  std::vector<Eigen::Vector2d> dead_reckoning_landmark(64, Eigen::Vector2d::Zero());
  std::vector<bool> dead_reckoning_seen(64, false);
  std::vector<core::LandmarkObservation> observations;
  std::ostringstream odometry_tum;
  odometry_tum << slam::tum_line(to_nanoseconds(start_s), {});

  const auto clock_start = std::chrono::steady_clock::now();
  std::size_t i = 0;
  std::uint64_t sequence = 0;
  while (i < measurements.size() && measurements[i].time_s <= stop_s) {
    const double time_s = measurements[i].time_s;
    observations.clear();
    const core::Pose2 odometry_pose = odometry.advance_to(std::max(time_s, start_s));
    for (; i < measurements.size() && measurements[i].time_s == time_s; ++i) {
      const MeasurementRow& m = measurements[i];
      const auto barcode = static_cast<std::size_t>(m.barcode);
      const int subject = barcode < dataset.subject_of_barcode.size() ? dataset.subject_of_barcode[barcode] : 0;
      if (subject == 0 || subject >= 64) {
        ++result.unknown_barcodes_dropped;
        continue;
      }
      if (subject < kFirstLandmarkSubject) {
        ++result.robot_measurements_dropped;
        continue;
      }
      observations.push_back(slam::range_bearing_observation(static_cast<std::uint32_t>(subject), m.range_m,
                                                             m.bearing_rad, options.range_sigma_m,
                                                             options.bearing_sigma_rad, options.height_sigma_m));
      const auto s = static_cast<std::size_t>(subject);
      if (!dead_reckoning_seen[s]) {
        dead_reckoning_seen[s] = true;
        dead_reckoning_landmark[s] = odometry_pose.transform_point(observations.back().point_camera.head<2>());
      }
    }
    if (observations.empty() || time_s < start_s) {
      continue;
    }
    const core::OdometryReading reading{to_nanoseconds(time_s), ++sequence, odometry_pose};
    const slam::UpdateResult update = filter->update(
        reading, slam::ObservationList{observations.data(), observations.size()}, Eigen::Isometry3d::Identity());
    if (!update.status.ok()) {
      continue;
    }
    result.measurements_used += observations.size();
    odometry_tum << slam::tum_line(reading.timestamp_ns, odometry_pose);
  }
  result.filter_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();

  std::ostringstream trajectory;
  slam::write_tum_trajectory(trajectory, filter->trajectory(), filter->ml_trajectory_node());
  result.trajectory_tum = trajectory.str();
  result.odometry_tum = odometry_tum.str();
  std::ostringstream ply;
  slam::write_landmarks_ply(ply, filter->landmarks(), filter->ml_map(),
                            static_cast<std::uint32_t>(options.filter.export_min_observations));
  result.landmarks_ply = ply.str();

  // Score: per true landmark, the filter's best-observed estimate (if it passed the export
  // threshold) and the dead-reckoning placement.
  std::vector<Eigen::Vector2d> filter_points, filter_truth, dr_points, dr_truth;
  for (const LandmarkTruth& truth : dataset.landmarks) {
    const Eigen::Vector2d true_point(truth.x_m, truth.y_m);
    const slam::MapNode* leaf =
        filter->landmarks().find_leaf(filter->ml_map(), static_cast<std::uint32_t>(truth.subject));
    const slam::LandmarkEstimate* best = nullptr;
    for (std::size_t k = 0; leaf != nullptr && k < leaf->estimates.size(); ++k) {
      const slam::LandmarkEstimate& e = filter->landmarks().estimate(leaf->estimates[k]);
      if (best == nullptr || e.observations > best->observations) {
        best = &e;
      }
    }
    if (best != nullptr && best->observations >= static_cast<std::uint32_t>(options.filter.export_min_observations)) {
      filter_points.push_back(best->mean.head<2>());
      filter_truth.push_back(true_point);
      result.filter_map.subjects.push_back(truth.subject);
    }
    if (truth.subject < 64 && dead_reckoning_seen[static_cast<std::size_t>(truth.subject)]) {
      dr_points.push_back(dead_reckoning_landmark[static_cast<std::size_t>(truth.subject)]);
      dr_truth.push_back(true_point);
      result.dead_reckoning_map.subjects.push_back(truth.subject);
    }
  }
  const std::vector<int> filter_subjects = result.filter_map.subjects;
  const std::vector<int> dr_subjects = result.dead_reckoning_map.subjects;
  result.filter_map = score_landmarks(filter_points, filter_truth);
  result.filter_map.subjects = filter_subjects;
  result.dead_reckoning_map = score_landmarks(dr_points, dr_truth);
  result.dead_reckoning_map.subjects = dr_subjects;
  if (!dataset.groundtruth.empty()) {
    std::vector<PoseRow> estimated_path;  // the final ML particle's ancestry, oldest last
    for (slam::TrajectoryNodeHandle at = filter->ml_trajectory_node(); at; at = filter->trajectory().parent(at)) {
      const slam::TrajectoryNode& node = filter->trajectory().get(at);
      estimated_path.push_back({static_cast<double>(node.timestamp_ns) * 1e-9, node.pose});
    }
    std::reverse(estimated_path.begin(), estimated_path.end());
    result.ate_rmse_m = trajectory_rmse(estimated_path, dataset.groundtruth);
  }
  result.final_ml_pose = filter->ml_pose();
  result.final_mean_pose = filter->weighted_mean_pose();
  result.updates = filter->counters().updates;
  result.resamplings = filter->counters().resamplings;
  result.updates_refused = filter->counters().updates_refused_trajectory_full;
  result.changes_refused_pool_full = filter->counters().changes_refused_pool_full;
  result.landmark_nodes_high_water = filter->landmarks().node_stats().high_water;
  result.trajectory_nodes_high_water = filter->trajectory().stats().high_water;
  return result;
}

}  // namespace stereoscout::cli::mrclam
