// One pass over a KITTI folder: per frame, the pair through the front end, the noisy odometry
// reading, one filter update; then the exported files and the scores.
#include "kitti_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include "kitti_metrics.hpp"
#include "stereoscout/host_dataset/dataset_odometry.hpp"
#include "stereoscout/host_dataset/kitti_camera.hpp"
#include "stereoscout/report/wall_stopwatch.hpp"
#include "stereoscout/slam/particle_filter.hpp"
#include "stereoscout/slam/slam_export.hpp"
#include "stereoscout/vision/front_end.hpp"
#include "stereoscout/vision/identity_check.hpp"
#include "stereoscout/vision/identity_gate.hpp"

namespace stereoscout::cli::kitti {
namespace {

vision::StereoCalibration stereo_calibration(const host_dataset::KittiCalibration& kitti) {
  vision::StereoCalibration calibration;
  calibration.focal_px = kitti.focal_px;
  calibration.principal_x_px = kitti.principal_x_px;
  calibration.principal_y_px = kitti.principal_y_px;
  calibration.baseline_m = kitti.baseline_m;
  calibration.width_px = kitti.width_px;
  calibration.height_px = kitti.height_px;
  return calibration;
}

// The reference (right) camera is the robot's origin, looking forward, level (KITTI's cameras
// are mounted level on the car); only its height is a dataset constant.
core::CameraMount kitti_mount(const core::DatasetConfig& dataset) {
  core::CameraMount mount;
  mount.height_m = dataset.camera_height_m;
  return mount;
}

// Identities the ML particle's map already holds, before this frame's update.
std::uint64_t count_known(const slam::ParticleFilter& filter, const core::FixedVector<core::LandmarkObservation>& list) {
  std::uint64_t known = 0;
  for (const core::LandmarkObservation& observation : list) {
    known += filter.landmarks().find_leaf(filter.ml_map(), observation.landmark_id) != nullptr ? 1U : 0U;
  }
  return known;
}

// The final ML particle's ancestry, one pose per frame it updated (the root is not a frame).
std::vector<std::pair<std::size_t, core::Pose2>> ml_path(const slam::ParticleFilter& filter,
                                                         const std::map<std::int64_t, std::size_t>& frame_of_time) {
  std::vector<std::pair<std::size_t, core::Pose2>> path;
  for (slam::TrajectoryNodeHandle at = filter.ml_trajectory_node(); at; at = filter.trajectory().parent(at)) {
    const slam::TrajectoryNode& node = filter.trajectory().get(at);
    const auto frame = frame_of_time.find(node.timestamp_ns);
    if (node.update_index == 0 || frame == frame_of_time.end()) continue;
    path.emplace_back(frame->second, node.pose);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

void score(const host_dataset::KittiSequence& sequence, const std::vector<core::Pose2>& truth,
           const std::vector<core::Pose2>& odometry_poses, const std::vector<std::pair<std::size_t, core::Pose2>>& path,
           const RunOptions& options, RunResult& result) {
  std::vector<core::Pose2> estimated;
  std::vector<core::Pose2> estimated_truth;
  std::ostringstream tum;
  for (const auto& [frame, pose] : path) {
    estimated.push_back(pose);
    estimated_truth.push_back(truth[frame]);
    tum << slam::tum_line(static_cast<std::int64_t>(std::llround(sequence.times_s[frame] * 1e9)), pose);
  }
  result.trajectory_tum = tum.str();
  result.filter_score = TrajectoryScore{planar_ate_rmse(estimated, estimated_truth),
                                        relative_error_per_metre(estimated, estimated_truth, options.rpe_segment_m)};
  result.odometry_score = TrajectoryScore{planar_ate_rmse(odometry_poses, truth),
                                          relative_error_per_metre(odometry_poses, truth, options.rpe_segment_m)};
}

}  // namespace

RunResult run_kitti_slam(const host_dataset::KittiSequence& sequence, const RunOptions& options) {
  using Clock = std::chrono::steady_clock;
  RunResult result;
  const std::vector<core::Pose2> truth = host_dataset::ground_truth_robot_poses(sequence);
  host_dataset::KittiCamera camera(sequence);
  host_dataset::DatasetOdometry odometry(truth, sequence.times_s, options.dataset.odometry, options.seed);
  const core::CameraMount mount = kitti_mount(options.dataset);
  report::WallStopwatch stopwatch;
  auto front_end = std::make_unique<vision::VisionFrontEnd>(options.vision, core::RobotConfig{},
                                                            stereo_calibration(sequence.calibration), mount);
  front_end->set_stopwatch(&stopwatch);
  const slam::StereoModel stereo{sequence.calibration.focal_px, sequence.calibration.principal_x_px,
                                 sequence.calibration.principal_y_px, sequence.calibration.baseline_m,
                                 options.vision.sigma_u_px,        options.vision.sigma_v_px,
                                 options.vision.sigma_d_px};
  auto filter = std::make_unique<slam::ParticleFilter>(options.filter, mount, options.seed, &stereo);
  core::FixedVector<core::LandmarkObservation> observations(front_end->max_observations());
  core::StereoFrame frame;
  frame.allocate(sequence.calibration.width_px, sequence.calibration.height_px);
  std::unique_ptr<vision::IdentityGate> gate;
  if (options.vision.identity_gate) {
    gate = std::make_unique<vision::IdentityGate>(vision::identity_gate_params_from_config(options.vision, options.filter));
  }
  vision::IdentityCheck check(vision::landmark_id_capacity(options.vision), options.filter.association_gate_chi2);
  std::vector<core::Pose2> odometry_poses;
  std::map<std::int64_t, std::size_t> frame_of_time;
  std::ostringstream odometry_tum;
  std::ostringstream truth_tum;
  core::OdometryReading reading;
  while (odometry.read(reading).ok()) {
    const std::size_t index = odometry_poses.size();
    if (index == 0) filter->start(reading);  // frame 0 is an update too (with zero motion)
    odometry_poses.push_back(reading.pose);
    frame_of_time.emplace(reading.timestamp_ns, index);
    odometry_tum << slam::tum_line(reading.timestamp_ns, reading.pose);
    truth_tum << slam::tum_line(reading.timestamp_ns, truth[index]);
    const core::Status captured = camera.capture(frame);
    observations.clear();
    if (!captured.ok()) {
      ++result.frames_skipped;
      result.warnings.push_back(camera.last_failed_path() + ": " + captured.message +
                                " (pair skipped; this frame's update uses odometry only)");
    } else {
      front_end->observe_landmarks(frame, observations);  // KittiCamera delivers the calibrated size
      const vision::FrontEndFrameStats& stats = front_end->last_frame_stats();
      result.times.sift_s += static_cast<double>(stats.sift_ns) * 1e-9;
      result.times.stereo_matching_s += static_cast<double>(stats.matching_ns) * 1e-9;
      result.times.index_lookup_s += static_cast<double>(stats.identify_ns) * 1e-9;
      result.stereo_matches += stats.stereo_matches;
      result.frames_without_features += stats.stereo_matches == 0 ? 1U : 0U;
      if (gate) gate->apply(reading.pose, reading.pose.to_isometry3() * core::robot_from_camera(mount, 0.0), observations);
      check.observe(host_dataset::right_camera_from_left(sequence.world_from_cam0[index], sequence.calibration.baseline_m),
                    observations.data(), observations.size());
    }
    result.observations += observations.size();
    result.observations_matched += count_known(*filter, observations);
    const Clock::time_point start = Clock::now();
    filter->update(reading, slam::ObservationList{observations.data(), observations.size()}, 0.0);
    result.times.filter_update_s += std::chrono::duration<double>(Clock::now() - start).count();
    ++result.frames;
  }
  score(sequence, truth, odometry_poses, ml_path(*filter, frame_of_time), options, result);
  result.odometry_tum = odometry_tum.str();
  result.groundtruth_tum = truth_tum.str();
  std::ostringstream ply;
  result.landmarks = slam::write_landmarks_ply(ply, filter->landmarks(), filter->ml_map(),
                                               static_cast<std::uint32_t>(options.filter.export_min_observations));
  result.landmarks_ply = ply.str();
  result.identities = static_cast<std::uint32_t>(front_end->index().stats().landmarks);
  result.reobservations = check.reobservations();
  result.reobservations_consistent = check.consistent();
  result.resamplings = filter->counters().resamplings;
  result.updates_refused = filter->counters().updates_refused_trajectory_full;
  result.changes_refused_pool_full = filter->counters().changes_refused_pool_full;
  result.landmark_nodes_high_water = filter->landmarks().node_stats().high_water;
  return result;
}

}  // namespace stereoscout::cli::kitti
