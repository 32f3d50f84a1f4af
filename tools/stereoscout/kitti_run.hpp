#pragma once
// `stereoscout slam --kitti`: the vision front end and the RBPF over a KITTI odometry folder
// played through host_dataset's Camera and Odometry (no exploration, no driving), every frame
// one observation update, scored against the ground truth when poses.txt is there.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "stereoscout/core/config/dataset.hpp"
#include "stereoscout/core/config/filter.hpp"
#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/host_dataset/kitti_sequence.hpp"

namespace stereoscout::cli::kitti {

// Seconds spent per stage, summed over the frames of a run.
struct StageTimes {
  double sift_s = 0.0;
  double stereo_matching_s = 0.0;
  double index_lookup_s = 0.0;  // descriptor index and triangulation
  double filter_update_s = 0.0;
};

struct RunOptions {
  core::VisionConfig vision;
  core::FilterConfig filter;
  core::DatasetConfig dataset;  // odometry noise, camera height
  std::uint64_t seed = 1;
  double rpe_segment_m = 10.0;
};

// Trajectory errors against the ground truth (of the filter, or of the odometry alone).
struct TrajectoryScore {
  double ate_rmse_m = 0.0;
  double rpe_per_m = 0.0;
};

struct RunResult {
  std::string trajectory_tum;
  std::string odometry_tum;
  std::string groundtruth_tum;  // empty without poses.txt
  std::string landmarks_ply;
  std::vector<std::string> warnings;  // skipped pairs, naming the file
  std::size_t frames = 0;             // updates made (one per frame)
  std::size_t frames_skipped = 0;     // pair unreadable: update with odometry only
  std::size_t frames_without_features = 0;
  std::size_t landmarks = 0;          // vertices of landmarks.ply
  std::uint64_t stereo_matches = 0;
  std::uint64_t observations = 0;          // identified landmarks handed to the filter
  std::uint64_t observations_matched = 0;  // their identity already in the ML particle's map
  std::uint32_t identities = 0;            // landmark ids the index handed out
  std::optional<TrajectoryScore> filter_score;
  std::optional<TrajectoryScore> odometry_score;
  std::uint64_t reobservations = 0;
  std::uint64_t reobservations_consistent = 0;
  std::uint64_t resamplings = 0;
  std::uint64_t updates_refused = 0;
  std::uint64_t changes_refused_pool_full = 0;
  std::size_t landmark_nodes_high_water = 0;
  StageTimes times;
  double matched_share() const {
    return observations == 0 ? 0.0 : static_cast<double>(observations_matched) / static_cast<double>(observations);
  }
  double reobservation_consistency() const {
    return reobservations == 0 ? 0.0 : static_cast<double>(reobservations_consistent) / static_cast<double>(reobservations);
  }
};

RunResult run_kitti_slam(const host_dataset::KittiSequence& sequence, const RunOptions& options);

}  // namespace stereoscout::cli::kitti
