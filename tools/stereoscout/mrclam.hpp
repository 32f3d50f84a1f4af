#pragma once
// The UTIAS MRCLAM dataset (Leung et al., IJRR 2011) as input to the landmark filter, and the
// scoring of a run: ../shared/data/mrclam/README.md describes the files. Host tool code: it
// reads whole files into vectors and may allocate freely; the filter it drives does not.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "stereoscout/core/config/filter.hpp"
#include "stereoscout/core/geometry.hpp"

namespace stereoscout::cli::mrclam {

struct OdometryRow {
  double time_s = 0.0;
  double forward_mps = 0.0;
  double angular_rad_s = 0.0;
};

struct MeasurementRow {
  double time_s = 0.0;
  int barcode = 0;
  double range_m = 0.0;
  double bearing_rad = 0.0;
};

struct LandmarkTruth {
  int subject = 0;
  double x_m = 0.0;
  double y_m = 0.0;
};

struct PoseRow {
  double time_s = 0.0;
  core::Pose2 pose;
};

struct Dataset {
  std::vector<OdometryRow> odometry;
  std::vector<MeasurementRow> measurements;
  std::vector<int> subject_of_barcode;  // indexed by barcode; 0 = unknown barcode
  std::vector<LandmarkTruth> landmarks;
  std::string landmark_truth_file;      // the corrected file when one is present
  std::vector<PoseRow> groundtruth;     // empty without RobotN_Groundtruth.dat
};

// Reads one robot of a dataset folder. On a missing or malformed file returns false with
// `error` naming the file (and line).
bool load_dataset(const std::string& folder, int robot, Dataset& dataset, std::string& error);

// Subjects 1-5 are the robots; their barcodes are not landmarks.
inline constexpr int kFirstLandmarkSubject = 6;

// MRCLAM's odometry is the commanded velocity, not measured wheel motion, so the proposal
// needs far more noise than the paper robot's encoders (config filter.motion_noise_*): these
// replace those four config values. Chosen on Dataset1 (docs/results.md).
struct RunOptions {
  core::FilterConfig filter;
  std::uint64_t seed = 1;
  double noise_translation_per_m = 0.3;
  double noise_rotation_per_rad = 0.3;
  double noise_rotation_per_m = 0.3;
  double noise_translation_per_rad = 0.1;
  double range_sigma_m = 0.15;
  double bearing_sigma_rad = 0.1;
  double height_sigma_m = 0.01;
  double duration_s = 0.0;  // > 0: only this prefix of the log
};

struct MapScore {
  double rmse_m = 0.0;
  std::size_t mapped = 0;
  std::vector<double> residuals_m;  // per landmark, subject order
  std::vector<int> subjects;
};

struct RunResult {
  std::string trajectory_tum;
  std::string odometry_tum;
  std::string landmarks_ply;
  MapScore filter_map;
  MapScore dead_reckoning_map;
  std::optional<double> ate_rmse_m;
  core::Pose2 final_ml_pose;    // the filter's frame (its own origin, not the Vicon frame)
  core::Pose2 final_mean_pose;
  std::uint64_t updates = 0;
  std::uint64_t resamplings = 0;
  std::uint64_t measurements_used = 0;
  std::uint64_t robot_measurements_dropped = 0;
  std::uint64_t unknown_barcodes_dropped = 0;
  std::uint64_t updates_refused = 0;
  std::uint64_t changes_refused_pool_full = 0;
  std::size_t landmark_nodes_high_water = 0;
  std::size_t trajectory_nodes_high_water = 0;
  double filter_seconds = 0.0;
};

RunResult run_landmark_slam(const Dataset& dataset, const RunOptions& options);

// Best 2D rigid fit of `estimated` onto `truth` (paired), then the RMSE and residuals.
MapScore score_landmarks(const std::vector<Eigen::Vector2d>& estimated, const std::vector<Eigen::Vector2d>& truth);

}  // namespace stereoscout::cli::mrclam
